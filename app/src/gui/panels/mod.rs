//! The panels around the image: the camera and render settings, the scene
//! with its object, light and sky editors, the live error plot, the status bar,
//! the help window, and the widgets they share.

pub mod camera_panel;
pub mod error_plot;
pub mod help;
pub mod light_editor;
pub mod object_editor;
pub mod render_panel;
pub mod scene_panel;
pub mod sky_editor;
pub mod status_bar;
pub mod widgets;
