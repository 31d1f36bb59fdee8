//! Perceptual colour ramps for scalar heatmaps (depth, variance, cost).
//!
//! Viridis is kept as nine control points (matplotlib's viridis at
//! t = 0, 1/8 … 1, 8-bit sRGB) with linear interpolation in between: close
//! to the full 256-entry table, perceptually uniform, readable in grey and
//! by the colour-blind, and no dependency for one small table.

/// A colour ramp from t = 0 to t = 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ramp {
    /// Dark purple through teal and green to yellow.
    Viridis,
}

/// Viridis at t = k / 8, 8-bit sRGB.
const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 45, 123],
    [59, 82, 139],
    [44, 114, 142],
    [33, 145, 140],
    [40, 174, 128],
    [94, 201, 98],
    [173, 220, 48],
    [253, 231, 37],
];

impl Ramp {
    /// The 8-bit sRGB colour at `t`, clamped to [0, 1] (NaN gives t = 0).
    pub fn srgb8(self, t: f32) -> [u8; 3] {
        let points = match self {
            Ramp::Viridis => &VIRIDIS,
        };
        let t = if t > 0.0 { t.min(1.0) } else { 0.0 };
        let x = t * (points.len() - 1) as f32;
        let k = (x as usize).min(points.len() - 2);
        let f = x - k as f32;
        let (a, b) = (points[k], points[k + 1]);
        std::array::from_fn(|c| {
            (f32::from(a[c]) + f * (f32::from(b[c]) - f32::from(a[c]))).round() as u8
        })
    }

    /// A short name for the legend.
    pub fn name(self) -> &'static str {
        match self {
            Ramp::Viridis => "viridis",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_and_control_points_are_the_table() {
        assert_eq!(Ramp::Viridis.srgb8(0.0), VIRIDIS[0]);
        assert_eq!(Ramp::Viridis.srgb8(1.0), VIRIDIS[8]);
        assert_eq!(Ramp::Viridis.srgb8(0.5), VIRIDIS[4]);
        assert_eq!(Ramp::Viridis.srgb8(-3.0), VIRIDIS[0]);
        assert_eq!(Ramp::Viridis.srgb8(f32::NAN), VIRIDIS[0]);
        assert_eq!(Ramp::Viridis.srgb8(7.0), VIRIDIS[8]);
    }

    #[test]
    fn brightness_rises_along_the_ramp() {
        let luma = |[r, g, b]: [u8; 3]| {
            0.2126 * f32::from(r) + 0.7152 * f32::from(g) + 0.0722 * f32::from(b)
        };
        let mut last = -1.0;
        for k in 0..=64 {
            let y = luma(Ramp::Viridis.srgb8(k as f32 / 64.0));
            assert!(y > last, "step {k}: {y} after {last}");
            last = y;
        }
    }
}
