//! The view transform: exposure, then a tone curve, from linear radiance to
//! display values in [0, 1] (which [`super::srgb`] encodes). Applied where
//! pictures are made for the screen or a PNG, never to the film or an EXR.

use glam::Vec3;
use scene::{Tonemap, View};

/// `c` as `view` shows it, before sRGB encoding: scaled by 2^exposure, then
/// through the view's curve. The identity view returns `c` itself.
#[inline]
pub fn apply(view: View, c: Vec3) -> Vec3 {
    if view.is_identity() {
        return c;
    }
    let scaled = c * view.scale();
    match view.tonemap {
        // The sRGB encoding clamps.
        Tonemap::Clamp => scaled,
        Tonemap::Neutral => pbr_neutral(scaled),
    }
}

/// F₉₀, the Fresnel reflectance at normal incidence of common (ior 1.5)
/// materials: the toe's offset.
const F90: f32 = 0.04;
/// K_s: where highlight compression starts.
const START_COMPRESSION: f32 = 0.8 - F90;
/// K_d: how fast compressed highlights desaturate.
const DESATURATION: f32 = 0.15;

/// The Khronos PBR Neutral tone mapper, as its specification defines it
/// (KhronosGroup/ToneMapping, `PBR_Neutral/README.md`): linear Rec. 709 in
/// (negatives and NaN taken as 0), linear Rec. 709 in [0, 1] out. An
/// offset f (0.04 once the darkest channel reaches 0.08, less below) comes
/// off every channel — the specification expects a PBR material's
/// specular reflection to add it back — so a grey of 0.4 shows as 0.36;
/// past K_s = 0.76 the peak is compressed toward white along the hue,
/// and desaturated as it nears it. An infinite channel is white, the limit.
pub fn pbr_neutral(c: Vec3) -> Vec3 {
    // max also maps NaN to 0.
    let c = c.max(Vec3::ZERO);
    let x = c.min_element();
    let f = if x <= 2.0 * F90 {
        x - x * x / (4.0 * F90)
    } else {
        F90
    };
    let c = c - Vec3::splat(f);
    let p = c.max_element();
    if p <= START_COMPRESSION {
        return c;
    }
    if p == f32::INFINITY {
        // p_n → 1 and g → 0: the curve's limit is white (∞ · 0 would be NaN).
        return Vec3::ONE;
    }
    let d = 1.0 - START_COMPRESSION;
    let p_n = 1.0 - d * d / (p + d - START_COMPRESSION);
    let g = 1.0 / (DESATURATION * (p - p_n) + 1.0);
    c * (p_n / p * g) + Vec3::splat(p_n * (1.0 - g))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The specification's formulas in f64, written out independently.
    fn neutral_f64(c: [f64; 3]) -> [f64; 3] {
        let (f90, ks, kd) = (0.04, 0.8 - 0.04, 0.15);
        let x = c[0].min(c[1]).min(c[2]);
        let f = if x <= 2.0 * f90 {
            x - x * x / (4.0 * f90)
        } else {
            f90
        };
        let p = (c[0] - f).max(c[1] - f).max(c[2] - f);
        if p <= ks {
            return c.map(|v| v - f);
        }
        let p_n = 1.0 - (1.0 - ks) * (1.0 - ks) / (p + 1.0 - 2.0 * ks);
        let g = 1.0 / (kd * (p - p_n) + 1.0);
        c.map(|v| (v - f) * p_n / p * g + p_n * (1.0 - g))
    }

    fn colours() -> impl Iterator<Item = Vec3> {
        (0..4000).map(|k| {
            let h = |s: u32| {
                let x = (k as u32).wrapping_mul(0x9e37_79b9) ^ s;
                let x = (x ^ (x >> 15)).wrapping_mul(0x2c1b_3c6d);
                (x ^ (x >> 12)) as f32 / u32::MAX as f32
            };
            // Up to 2⁶ above white, a quarter of them dark.
            let scale = if k % 4 == 0 { 0.1 } else { (6.0 * h(4)).exp2() };
            Vec3::new(h(1), h(2), h(3)) * scale
        })
    }

    /// Ours is the specification's, to f32 rounding.
    #[test]
    fn neutral_follows_the_specification() {
        for c in colours() {
            let ours = pbr_neutral(c);
            let theirs = neutral_f64(c.to_array().map(f64::from));
            for (a, b) in ours.to_array().into_iter().zip(theirs) {
                assert!(
                    (f64::from(a) - b).abs() < 2e-6,
                    "{c}: {ours} against {theirs:?}"
                );
            }
        }
    }

    /// Every output lies in [0, 1]; a grey stays grey; brighter in, brighter out.
    #[test]
    fn neutral_maps_into_the_display_range_keeping_grey_and_order() {
        let extremes = [
            Vec3::splat(1e30),
            Vec3::splat(f32::NAN),
            Vec3::splat(-1.0),
            Vec3::new(f32::INFINITY, 0.5, 0.5),
        ];
        for c in colours().chain(extremes) {
            let out = pbr_neutral(c);
            assert!(
                out.cmpge(Vec3::ZERO).all() && out.cmple(Vec3::ONE).all(),
                "{c}: {out}"
            );
        }
        assert_eq!(pbr_neutral(Vec3::new(f32::INFINITY, 0.5, 0.5)), Vec3::ONE);
        let mut last = -1.0;
        for k in 0..2000 {
            let grey = k as f32 * 0.01;
            let out = pbr_neutral(Vec3::splat(grey));
            assert!(out.x == out.y && out.y == out.z, "{grey}: {out}");
            assert!(out.x > last, "{grey}: {} after {last}", out.x);
            last = out.x;
        }
    }

    /// +1 EV doubles the radiance the curve sees; the identity view changes
    /// nothing, bit for bit.
    #[test]
    fn a_stop_of_exposure_doubles_the_radiance() {
        let up = View {
            exposure: 1.0,
            tonemap: Tonemap::Clamp,
        };
        let neutral = View {
            exposure: 1.0,
            tonemap: Tonemap::Neutral,
        };
        for c in colours() {
            assert_eq!(apply(up, c), 2.0 * c);
            assert_eq!(apply(neutral, c), pbr_neutral(2.0 * c));
            assert_eq!(apply(View::default(), c).to_array(), c.to_array());
        }
    }
}
