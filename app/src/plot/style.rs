//! What every chart shares: egui's own Ubuntu font (so that no system font
//! is needed) and the line colours.

use plotters::prelude::*;
use std::sync::Once;

/// Line colours, distinct on white (Tableau 10's first colours).
pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

/// Registers the chart font once per process.
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is egui's; failing to parse it would be a bug in the build.
        if plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            epaint_default_fonts::UBUNTU_LIGHT,
        )
        .is_err()
        {
            eprintln!("warning: the chart font could not be loaded; labels may be missing");
        }
    });
}
