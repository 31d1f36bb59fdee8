//! Turning what the render thread holds (the colour, the film's per-pixel
//! statistics, a preview's samples, an AOV) into the 8-bit picture of a
//! [`Display`] mode and its [`Legend`]. Runs on the render thread, so that
//! showing any mode costs the UI only a texture copy.

use super::colormap::Ramp;
use super::heatmap::heatmap;
use super::srgb::srgba8_of_linear;
use super::{Display, DisplayImage, Legend, ScalarRange, Scale};
use crate::film::Film;
use crate::film::aov::{Aov, visualize};
use crate::film::preview::PreviewSamples;
use glam::Vec3;
use scene::View;

/// Shown where a mode has nothing to show yet (variance of one sample).
const UNAVAILABLE: [u8; 4] = [48, 48, 48, 255];
/// The span of the variance heatmap: max / min at most 10^this (relative
/// variances below that are as good as zero on screen).
const VARIANCE_DECADES: f32 = 4.0;

/// What the render thread holds of the current job.
#[derive(Clone, Copy, Debug)]
pub enum Source<'a> {
    /// A coarse preview (one sample per block).
    Preview(&'a PreviewSamples),
    /// The film after one or more full passes.
    Film(&'a Film),
}

impl Source<'_> {
    /// The pixels of the image.
    fn pixel_count(self) -> usize {
        let (w, h) = match self {
            Source::Preview(p) => p.size(),
            Source::Film(f) => (f.width(), f.height()),
        };
        w as usize * h as usize
    }
}

/// The colour legend's note: the view it is shown through, then sRGB.
fn color_note(view: View) -> String {
    if view.is_identity() {
        "the final colour, sRGB".into()
    } else {
        format!(
            "the final colour at {:+} EV, {}, sRGB",
            view.exposure,
            view.tonemap.label()
        )
    }
}

/// The picture of `display` from `source`: `color` is its linear colour
/// at the source's resolution (a preview's one value per block, in the
/// order of [`PreviewSamples::finite_values`]; a film's every pixel), `aov`
/// the mode's AOV at full resolution (computed by the caller for the AOV modes);
/// `view` the exposure and curve the colour is shown with (the other modes ignore it).
pub fn display_image(
    display: Display,
    view: View,
    source: Source,
    color: &[Vec3],
    aov: Option<&[f32]>,
) -> DisplayImage {
    let len = source.pixel_count();
    match (display, display.aov(), aov) {
        (Display::Color, ..) => DisplayImage {
            srgba8: match source {
                // Each sample converted once, then repeated over its block.
                Source::Preview(p) => p.blocks(&srgba8_of_linear(color, view)),
                Source::Film(_) => srgba8_of_linear(color, view),
            },
            legend: Legend {
                display,
                range: None,
                note: color_note(view),
            },
        },
        (_, Some(kind), Some(values)) => aov_image(kind, values),
        (_, Some(_), None) => uniform(display, len, UNAVAILABLE, None, "not computed".into()),
        (Display::SamplesPerPixel, ..) => samples_per_pixel(source, len),
        (Display::Variance, ..) => match source {
            Source::Film(film) => match film.relative_variance() {
                Some(values) => heatmap(
                    display,
                    &values,
                    Scale::Log,
                    Some(VARIANCE_DECADES),
                    "relative: Var[mean] / mean²",
                    "log scale; zero variance at the ramp's start".into(),
                ),
                None => uniform(display, len, UNAVAILABLE, None, "needs two passes".into()),
            },
            Source::Preview(p) => uniform(
                display,
                len,
                UNAVAILABLE,
                None,
                format!(
                    "preview ({}×{} blocks): no variance yet",
                    p.stride(),
                    p.stride()
                ),
            ),
        },
        (Display::Cost, ..) => {
            let (values, note) = match source {
                Source::Film(film) => (
                    film.cost_per_sample(),
                    "mean over the pixel's samples; shadow rays stop at the first occluder".into(),
                ),
                Source::Preview(p) => (
                    p.tests_image(),
                    format!("preview: the one sample of each {0}×{0} block", p.stride()),
                ),
            };
            heatmap(
                display,
                &values,
                Scale::Linear,
                None,
                "shape tests / sample",
                note,
            )
        }
        // Every AOV mode is matched above.
        (_, None, _) => uniform(display, len, UNAVAILABLE, None, String::new()),
    }
}

/// An AOV's picture: depth as a heatmap over log α (an infinite floor's far
/// α would leave a linear ramp nothing for the near objects), the others as
/// [`visualize`] does.
pub fn aov_image(aov: Aov, values: &[f32]) -> DisplayImage {
    let (display, note) = match aov {
        Aov::Depth => {
            return heatmap(
                Display::Depth,
                values,
                Scale::Log,
                None,
                "α (scene units)",
                "α to the first hit along v_ij; black: miss".into(),
            );
        }
        Aov::Normal => (
            Display::Normal,
            "½n + ½: +x red, +y green, +z blue; black: miss",
        ),
        Aov::Albedo => (Display::Albedo, "the material's colour; black: miss"),
        Aov::Object => (
            Display::ObjectId,
            "one colour per object (hover shows the name); black: miss",
        ),
    };
    DisplayImage {
        srgba8: srgba8_of_linear(&visualize(aov, values), View::default()),
        legend: Legend {
            display,
            range: None,
            note: note.into(),
        },
    }
}

/// Samples per pixel: the same everywhere unless adaptive sampling stopped
/// some pixels, then a heatmap of each pixel's count.
fn samples_per_pixel(source: Source, len: usize) -> DisplayImage {
    let (spp, note) = match source {
        Source::Film(film) => {
            let counts = film.samples_per_pixel();
            let (min, max) = counts
                .iter()
                .fold((u32::MAX, 0), |(lo, hi), &n| (lo.min(n), hi.max(n)));
            if min < max {
                let values: Vec<f32> = counts.iter().map(|&n| n as f32).collect();
                return heatmap(
                    Display::SamplesPerPixel,
                    &values,
                    Scale::Linear,
                    None,
                    "samples / pixel",
                    format!(
                        "adaptive: {:.1} on average; a pixel stops once its error is below the threshold",
                        film.mean_spp()
                    ),
                );
            }
            (
                film.passes() as f32,
                "every pixel: one sample per pass".to_owned(),
            )
        }
        Source::Preview(p) => {
            let stride = p.stride();
            (
                1.0 / (stride * stride) as f32,
                format!("preview: one sample per {stride}×{stride} block"),
            )
        }
    };
    let [r, g, b] = Ramp::Viridis.srgb8(1.0);
    let range = ScalarRange {
        ramp: Ramp::Viridis,
        min: spp,
        max: spp,
        scale: Scale::Linear,
        unit: "samples / pixel",
    };
    uniform(
        Display::SamplesPerPixel,
        len,
        [r, g, b, 255],
        Some(range),
        note,
    )
}

/// Every pixel the same colour.
fn uniform(
    display: Display,
    len: usize,
    color: [u8; 4],
    range: Option<ScalarRange>,
    note: String,
) -> DisplayImage {
    DisplayImage {
        srgba8: vec![color; len],
        legend: Legend {
            display,
            range,
            note,
        },
    }
}
