//! PNG charts the command line writes (plotters): each chart owns the types
//! it draws; the font and colours they share are in [`style`].

pub mod chart;
pub mod stability;
pub mod style;
