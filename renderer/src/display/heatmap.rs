//! Scalar images through a colour ramp, for the depth, variance and cost
//! display modes: the range is the values' own (finite) minimum and maximum,
//! linear or logarithmic; non-finite values are misses, painted black.

use super::colormap::Ramp;
use super::{Display, DisplayImage, Legend, ScalarRange, Scale};
use rayon::prelude::*;

/// Shown for a miss in a heatmap (viridis never reaches black).
pub const MISS: [u8; 4] = [0, 0, 0, 255];

/// The finite values' minimum and maximum (`None` when there are none),
/// and the smallest positive one.
fn finite_range(values: &[f32]) -> Option<(f32, f32, f32)> {
    values
        .par_iter()
        .filter(|v| v.is_finite())
        .fold(
            || None,
            |acc: Option<(f32, f32, f32)>, &v| {
                let positive = if v > 0.0 { v } else { f32::INFINITY };
                Some(match acc {
                    None => (v, v, positive),
                    Some((lo, hi, p)) => (lo.min(v), hi.max(v), p.min(positive)),
                })
            },
        )
        .reduce(
            || None,
            |a, b| match (a, b) {
                (Some(a), Some(b)) => Some((a.0.min(b.0), a.1.max(b.1), a.2.min(b.2))),
                (a, None) => a,
                (None, b) => b,
            },
        )
}

/// A scalar image through the viridis ramp from its finite minimum to its
/// maximum (log scale: from the smallest positive value, but at most
/// `decades` decades below the maximum); non-finite values (misses) black.
pub fn heatmap(
    display: Display,
    values: &[f32],
    scale: Scale,
    decades: Option<f32>,
    unit: &'static str,
    note: String,
) -> DisplayImage {
    let ramp = Ramp::Viridis;
    let Some((lo, hi, smallest_positive)) = finite_range(values) else {
        let srgba8 = vec![MISS; values.len()];
        let legend = Legend {
            display,
            range: None,
            note,
        };
        return DisplayImage { srgba8, legend };
    };
    let (scale, lo) = match scale {
        Scale::Log if hi > 0.0 => (
            Scale::Log,
            decades.map_or(smallest_positive, |d| {
                smallest_positive.max(hi * 10f32.powf(-d))
            }),
        ),
        // All zero: nothing to take a logarithm of.
        _ => (Scale::Linear, lo),
    };
    let t_of = |v: f32| -> f32 {
        match scale {
            // One value throughout: the ramp's end, unless it is zero.
            _ if hi <= lo => {
                if v > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
            Scale::Linear => (v - lo) / (hi - lo),
            Scale::Log if v <= lo => 0.0,
            Scale::Log => (v / lo).ln() / (hi / lo).ln(),
        }
    };
    let srgba8 = values
        .par_iter()
        .map(|&v| {
            if v.is_finite() {
                let [r, g, b] = ramp.srgb8(t_of(v));
                [r, g, b, 255]
            } else {
                MISS
            }
        })
        .collect();
    DisplayImage {
        srgba8,
        legend: Legend {
            display,
            range: Some(ScalarRange {
                ramp,
                min: lo,
                max: hi,
                scale,
                unit,
            }),
            note,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_heatmap_spans_the_finite_values_and_paints_misses_black() {
        let values = [2.0, f32::INFINITY, 4.0, 3.0];
        let image = heatmap(
            Display::Depth,
            &values,
            Scale::Linear,
            None,
            "α",
            String::new(),
        );
        let range = image.legend.range.expect("a range");
        assert_eq!((range.min, range.max), (2.0, 4.0));
        let at = |t: f32| {
            let [r, g, b] = Ramp::Viridis.srgb8(t);
            [r, g, b, 255]
        };
        assert_eq!(image.srgba8, vec![at(0.0), MISS, at(1.0), at(0.5)]);
    }

    #[test]
    fn a_log_heatmap_keeps_zero_at_the_start_and_spans_at_most_four_decades() {
        let values = [0.0, 1e-9, 1e-2, 1.0];
        let image = heatmap(
            Display::Variance,
            &values,
            Scale::Log,
            Some(4.0),
            "",
            String::new(),
        );
        let range = image.legend.range.expect("a range");
        assert_eq!(range.scale, Scale::Log);
        assert_eq!(range.max, 1.0);
        assert!((range.min - 1e-4).abs() < 1e-9, "{}", range.min);
        let start = Ramp::Viridis.srgb8(0.0);
        assert_eq!(image.srgba8[0][..3], start);
        assert_eq!(image.srgba8[1][..3], start);
        assert_eq!(image.srgba8[2][..3], Ramp::Viridis.srgb8(0.5));
    }

    #[test]
    fn all_zero_values_show_the_ramp_start() {
        let image = heatmap(
            Display::Variance,
            &[0.0; 3],
            Scale::Log,
            Some(4.0),
            "",
            String::new(),
        );
        assert!(
            image
                .srgba8
                .iter()
                .all(|p| p[..3] == Ramp::Viridis.srgb8(0.0))
        );
        let range = image.legend.range.expect("a range");
        assert_eq!((range.min, range.max), (0.0, 0.0));
    }
}
