//! The image in the middle of the window: the texture with its zoom and
//! pan, the legend of the display mode, picking the object under a pixel,
//! moving the camera by mouse (and the orbit maths behind it), and saving or
//! copying what is shown.

pub mod camera_drag;
pub mod image_view;
pub mod legend;
pub mod navigation;
pub mod picking;
pub mod screenshot;
