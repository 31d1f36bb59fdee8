//! The image in the middle of the window: the texture with its zoom and
//! pan, the legend of the display mode, the orbit maths behind camera moves
//! by mouse, and saving or copying what is shown.

pub mod image_view;
pub mod legend;
pub mod navigation;
pub mod screenshot;
