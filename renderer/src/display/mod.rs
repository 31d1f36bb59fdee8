//! What the image view shows: the final colour or one of the diagnostic
//! modes, and the legend that explains a mode's colours. Everything here
//! runs on the render thread, so that showing a frame costs the UI a copy.
//!
//! [`image`] makes a mode's picture from a film or a preview; [`heatmap`]
//! maps scalars through a [`colormap`]; [`srgb`] encodes linear radiance to
//! the 8-bit sRGB of every picture raylab shows or writes.

pub mod colormap;
pub mod heatmap;
pub mod image;
pub mod srgb;
pub mod view;

use crate::film::aov::Aov;
use colormap::Ramp;

/// A way of showing the render: the final colour, what the primary ray
/// through P_ij sees, or where the tracer spends its samples and its work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Display {
    /// The final colour (the accumulated radiance, sRGB).
    #[default]
    Color,
    /// α to the first hit along v_ij, as a heatmap.
    Depth,
    /// The geometric normal at the first hit, ½n + ½ as RGB.
    Normal,
    /// The material's albedo at the first hit.
    Albedo,
    /// One colour per object hit.
    ObjectId,
    /// Samples per pixel so far.
    SamplesPerPixel,
    /// The relative variance of each pixel's mean, as a heatmap (log scale).
    Variance,
    /// Shape tests per sample, as a heatmap.
    Cost,
}

impl Display {
    /// Every mode, in menu order.
    pub const ALL: [Display; 8] = [
        Display::Color,
        Display::Depth,
        Display::Normal,
        Display::Albedo,
        Display::ObjectId,
        Display::SamplesPerPixel,
        Display::Variance,
        Display::Cost,
    ];

    /// The name shown in menus.
    pub fn label(self) -> &'static str {
        match self {
            Display::Color => "Colour",
            Display::Depth => "Depth α",
            Display::Normal => "Normal",
            Display::Albedo => "Albedo",
            Display::ObjectId => "Object id",
            Display::SamplesPerPixel => "Samples per pixel",
            Display::Variance => "Variance (relative)",
            Display::Cost => "Cost (shape tests)",
        }
    }

    /// The AOV a mode shows, for the modes that show one.
    pub fn aov(self) -> Option<Aov> {
        match self {
            Display::Depth => Some(Aov::Depth),
            Display::Normal => Some(Aov::Normal),
            Display::Albedo => Some(Aov::Albedo),
            Display::ObjectId => Some(Aov::Object),
            Display::Color | Display::SamplesPerPixel | Display::Variance | Display::Cost => None,
        }
    }

    /// The mode after this one in menu order, wrapping around (for a shortcut).
    pub fn next(self) -> Display {
        let k = Display::ALL.iter().position(|&d| d == self).unwrap_or(0);
        Display::ALL[(k + 1) % Display::ALL.len()]
    }
}

/// How values are spread along a ramp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// `min` at the start, `max` at the end, evenly in between.
    Linear,
    /// Evenly in log(value); values at or below `min` (zero too) at the start.
    Log,
}

/// The mapping of a scalar mode: `min` at the ramp's start, `max` at its end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalarRange {
    /// The colour ramp.
    pub ramp: Ramp,
    /// The value at the ramp's start.
    pub min: f32,
    /// The value at the ramp's end.
    pub max: f32,
    /// Linear or logarithmic.
    pub scale: Scale,
    /// The values' unit, e.g. "α (scene units)".
    pub unit: &'static str,
}

/// What a frame's colours mean, for the UI to draw beside the image.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The mode shown.
    pub display: Display,
    /// The value range and ramp of a scalar heatmap; `None` for the others.
    pub range: Option<ScalarRange>,
    /// One line explaining the colours (misses, special cases).
    pub note: String,
}

/// A mode's picture: opaque 8-bit sRGB RGBA row by row from the top, and its legend.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayImage {
    /// The pixels.
    pub srgba8: Vec<[u8; 4]>,
    /// What the colours mean.
    pub legend: Legend,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_visits_every_mode_once_and_wraps() {
        let mut d = Display::Color;
        let mut seen = Vec::new();
        for _ in 0..Display::ALL.len() {
            seen.push(d);
            d = d.next();
        }
        assert_eq!(seen, Display::ALL);
        assert_eq!(d, Display::Color);
    }
}
