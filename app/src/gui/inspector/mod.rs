//! The pixel inspector: the inspected pixel and the inspector window.

pub mod panel;
pub mod pixel;
