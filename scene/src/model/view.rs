//! How the picture is shown: the exposure and the view transform from
//! linear radiance to the display. A display setting saved with the scene
//! (`<view>`), never part of what is rendered: changing it changes no
//! sample.

/// The exposure and view transform a scene is shown with.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct View {
    /// Exposure in stops (EV): linear radiance is scaled by 2^exposure
    /// before the curve. 0 shows it as rendered.
    pub exposure: f32,
    /// The curve from scaled radiance to display values in [0, 1].
    pub tonemap: Tonemap,
}

impl View {
    /// The largest exposure either way, in stops: ±2²⁰ in brightness.
    pub const MAX_EXPOSURE: f32 = 20.0;

    /// The factor 2^exposure that scales linear radiance.
    pub fn scale(self) -> f32 {
        self.exposure.exp2()
    }

    /// True when the picture is shown as rendered: no exposure, clamped.
    pub fn is_identity(self) -> bool {
        self == View::default()
    }
}

/// A view transform's curve: how radiance above display white is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Tonemap {
    /// Each channel clamped to [0, 1]: exact up to white, highlights clip.
    #[default]
    Clamp,
    /// Khronos PBR Neutral: below 0.76, colours less a small offset (up
    /// to 0.04, which a PBR material's specular adds back); above, highlights
    /// compressed toward white and desaturated, hues kept.
    Neutral,
}

impl Tonemap {
    /// Every curve, in menu order.
    pub const ALL: [Tonemap; 2] = [Tonemap::Clamp, Tonemap::Neutral];

    /// Its name in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Tonemap::Clamp => "clamp",
            Tonemap::Neutral => "neutral",
        }
    }

    /// The curve named `name` (as [`Tonemap::name`] gives it).
    pub fn from_name(name: &str) -> Option<Tonemap> {
        Tonemap::ALL.into_iter().find(|t| t.name() == name)
    }

    /// What it is called in menus.
    pub fn label(self) -> &'static str {
        match self {
            Tonemap::Clamp => "Clamp",
            Tonemap::Neutral => "Khronos PBR Neutral",
        }
    }
}
