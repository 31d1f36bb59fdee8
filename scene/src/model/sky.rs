//! The sky: radiance arriving from every direction no object blocks — a
//! constant colour, or an HDR environment map in latitude-longitude form
//! turned by `rotate` and tinted by `color`; either scaled by `strength`.

use glam::Vec3;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

/// `<sky color=… map=… rotate=… strength=…>`: what the scene sees where no
/// object is.
#[derive(Clone, Debug, PartialEq)]
pub struct Sky {
    /// Linear RGB radiance of a constant sky; with a map, the tint the map's
    /// radiance is multiplied by (white by default).
    pub color: Vec3,
    /// An equirectangular HDR image around the scene, if any.
    pub map: Option<SkyMap>,
    /// Degrees about x, then y, then z, that turn the map (as a box turns).
    pub rotate: Vec3,
    /// A factor on the whole sky's radiance (1 by default; Mitsuba's
    /// `envmap` calls it `scale`): brighter or dimmer without touching the
    /// tint's hue.
    pub strength: f32,
}

impl Sky {
    /// A constant sky of radiance `color`.
    pub fn constant(color: Vec3) -> Sky {
        Sky {
            color,
            map: None,
            rotate: Vec3::ZERO,
            strength: 1.0,
        }
    }

    /// No light at all from the background: black.
    pub fn black() -> Sky {
        Sky::constant(Vec3::ZERO)
    }

    /// raylab's neutral studio environment ([`STUDIO_MAP`]), untinted and
    /// unturned: what a glTF model opened on its own is lit by when it
    /// brings no lights.
    pub fn studio() -> Sky {
        Sky {
            color: Vec3::ONE,
            map: Some(SkyMap {
                src: STUDIO_MAP.to_string(),
                image: studio_image(),
            }),
            rotate: Vec3::ZERO,
            strength: 1.0,
        }
    }

    /// The factor every direction's radiance is multiplied by: the colour
    /// (a constant sky's radiance, or a map's tint) times the strength.
    pub fn scale(&self) -> Vec3 {
        self.color * self.strength
    }
}

/// The name of the built-in studio environment in `<sky map=…>`: a grey
/// gradient (a light ceiling, a darker floor) with one soft, bright
/// softbox above and in front of the model, to its left
/// ([`STUDIO_KEY_DIRECTION`]). Not a file: it is made by raylab.
pub const STUDIO_MAP: &str = "raylab:studio";

/// The direction from the scene toward the studio's softbox (unit length).
pub const STUDIO_KEY_DIRECTION: Vec3 = Vec3::new(-0.4472136, 0.7745967, 0.4472136);

/// The studio environment's image, made once and shared.
pub fn studio_image() -> Arc<EnvImage> {
    static STUDIO: OnceLock<Arc<EnvImage>> = OnceLock::new();
    STUDIO
        .get_or_init(|| {
            let (width, height) = (128u32, 64u32);
            let mut texels = Vec::with_capacity((width * height) as usize);
            for y in 0..height {
                let theta = std::f32::consts::PI * y as f32 / (height - 1) as f32;
                for x in 0..width {
                    let phi = std::f32::consts::TAU * (x as f32 + 0.5) / width as f32;
                    // Mitsuba's layout: θ from +y, φ from −z toward +x.
                    let d = Vec3::new(
                        theta.sin() * phi.sin(),
                        theta.cos(),
                        -theta.sin() * phi.cos(),
                    );
                    let up = d.y;
                    let gradient = if up >= 0.0 {
                        0.45 + 0.4 * up.powf(0.6)
                    } else {
                        0.15 + 0.3 * (1.0 + up).powi(4)
                    };
                    // The softbox: 3.5 inside 12°, fading out by 24°.
                    let angle = d
                        .dot(STUDIO_KEY_DIRECTION)
                        .clamp(-1.0, 1.0)
                        .acos()
                        .to_degrees();
                    let softbox = 3.5 * ((24.0 - angle) / 12.0).clamp(0.0, 1.0);
                    texels.push([gradient + softbox; 3]);
                }
            }
            Arc::new(EnvImage {
                path: PathBuf::from(STUDIO_MAP),
                width,
                height,
                texels,
            })
        })
        .clone()
}

/// An environment map as the scene file names it, with its decoded image.
#[derive(Clone, Debug)]
pub struct SkyMap {
    /// The path as written in the scene file (relative to it, or absolute).
    pub src: String,
    /// The decoded image, shared by every copy of the scene.
    pub image: Arc<EnvImage>,
}

impl PartialEq for SkyMap {
    /// Equal when named alike and holding the same pixels (the same shared
    /// image, as every edit of a scene keeps, is not compared texel by texel).
    fn eq(&self, other: &SkyMap) -> bool {
        self.src == other.src
            && (Arc::ptr_eq(&self.image, &other.image) || *self.image == *other.image)
    }
}

/// A decoded latitude-longitude HDR image: linear RGB, row 0 at the top
/// (the direction +y before `rotate`), column 0 starting at the azimuth of
/// −z and going toward +x, as Mitsuba 3's `envmap` lays it out.
#[derive(Clone, Debug, PartialEq)]
pub struct EnvImage {
    /// The file it was read from.
    pub path: PathBuf,
    /// Width in pixels (azimuth φ from 0 to 2π).
    pub width: u32,
    /// Height in pixels (polar angle θ from 0 at +y to π at −y).
    pub height: u32,
    /// Linear RGB radiance, `width × height`, row by row from the top; every
    /// value finite and non-negative.
    pub texels: Vec<[f32; 3]>,
}

impl EnvImage {
    /// The texel at column `x`, row `y`.
    pub fn texel(&self, x: u32, y: u32) -> [f32; 3] {
        self.texels[y as usize * self.width as usize + x as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_studio_is_neutral_bright_above_and_shared() {
        let image = studio_image();
        assert!(Arc::ptr_eq(&image, &studio_image()));
        assert!(
            image
                .texels
                .iter()
                .all(|t| t[0] == t[1] && t[1] == t[2] && t[0] > 0.0)
        );
        // The top row is brighter than the bottom one; the softbox is brightest.
        let (top, bottom) = (image.texel(0, 0)[0], image.texel(0, image.height - 1)[0]);
        assert!(top > 2.0 * bottom, "{top} vs {bottom}");
        let brightest = image.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
        assert!(brightest > 3.5, "{brightest}");
        assert!((STUDIO_KEY_DIRECTION.length() - 1.0).abs() < 1e-6);
    }
}
