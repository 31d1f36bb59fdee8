//! `raylab render`: a scene to an image file, no window.

use super::args::{AovArg, RenderArgs};
use super::interrupt;
use super::prepare::{UserError, prepare};
use super::progress::Progress;
use crate::io::output::{Format, Provenance, write_exr, write_png, write_png_srgb8};
use crate::io::stdout::say;
use anyhow::Result;
use renderer::display::Display;
use renderer::display::DisplayImage;
use renderer::display::image::{Source, aov_image, display_image};
use renderer::film::aov::{self, Aov};
use renderer::{Film, Region};
use scene::View;
use std::time::{Duration, Instant};

/// The view a PNG is written with: the scene's `<view>`, with what
/// `--exposure` and `--tonemap` set instead.
fn view_of(args: &RenderArgs, scene: View) -> Result<View> {
    let exposure = args.exposure.unwrap_or(scene.exposure);
    if !(exposure.abs() <= View::MAX_EXPOSURE) {
        return Err(UserError(format!(
            "--exposure {exposure}: the exposure must be a number of stops from -{max} to {max}",
            max = View::MAX_EXPOSURE
        ))
        .into());
    }
    Ok(View {
        exposure,
        tonemap: args.tonemap.map_or(scene.tonemap, Into::into),
    })
}

/// What `raylab render` did: how long the render took, and how many of the
/// passes asked for were traced (fewer when Ctrl+C stopped it).
pub struct Rendered {
    /// The render's time, without loading the scene or writing the image.
    pub elapsed: Duration,
    /// Passes (samples per pixel) traced and written.
    pub passes: u32,
    /// Passes asked for (`--spp`).
    pub requested: u32,
}

/// Renders `args.scene` to `args.output`.
pub fn run(args: &RenderArgs) -> Result<Rendered> {
    let format = Format::from_path(&args.output).map_err(|e| UserError(e.to_string()))?;
    let (world, options, scene_view) = prepare(&args.scene)?;
    let view = view_of(args, scene_view)?;
    let (w, h) = (world.camera.w, world.camera.h);
    let split = Split::of(args, w, h, options.adaptive.is_some())?;

    // A bad reference is an error before the render, not after it.
    let reference = match &args.reference {
        Some(path) => {
            let image = renderer::diagnostics::reference_image::read_exr_rgb(path)?;
            image.check_size(path, w, h)?;
            Some(image)
        }
        None => None,
    };
    let start = Instant::now();
    let provenance_of = |passes| {
        let provenance = Provenance::of_render(&world.camera, Some(&args.scene.scene), passes);
        let provenance = split.record(provenance, passes);
        match args.aov {
            AovArg::Variance => provenance.with_display(Display::Variance),
            AovArg::Cost => provenance.with_display(Display::Cost),
            AovArg::Spp => provenance.with_display(Display::SamplesPerPixel),
            _ => provenance,
        }
    };
    match aov_of(args.aov) {
        None => {
            let (film, passes) = render_passes(&world, &options, &split, args.spp)?;
            let elapsed = start.elapsed();
            let provenance = provenance_of(passes);
            if film.discarded() > 0 {
                eprintln!(
                    "warning: {} samples were NaN or infinite and were left out",
                    film.discarded()
                );
            }
            let pixels = film.linear();
            if let (Some(path), Some(reference)) = (&args.reference, &reference) {
                let flip = super::chart::flip::FlipReference::new(&reference.pixels, w, h);
                say!(
                    "relMSE {:.4e}, RMSE {:.4e}, FLIP {:.4} against {}",
                    renderer::diagnostics::metrics::rel_mse(&pixels, &reference.pixels),
                    renderer::diagnostics::metrics::rmse(&pixels, &reference.pixels),
                    flip.mean_error(&pixels),
                    path.display()
                );
            }
            let diagnostic = match args.aov {
                AovArg::Variance => Some((Display::Variance, "variance")),
                AovArg::Cost => Some((Display::Cost, "cost")),
                AovArg::Spp => Some((Display::SamplesPerPixel, "spp")),
                _ => None,
            };
            match (format, diagnostic) {
                (Format::Png, None) => {
                    let provenance = provenance.clone().with_view(view);
                    write_png(&args.output, w, h, &pixels, view, &provenance)?
                }
                (Format::Exr, None) => {
                    let values: Vec<f32> = pixels.iter().flat_map(|p| p.to_array()).collect();
                    write_exr(&args.output, w, h, &["R", "G", "B"], &values, &provenance)?
                }
                (Format::Png, Some((display, _))) => {
                    let shown = display_image(display, view, Source::Film(&film), &pixels, None);
                    write_png_srgb8(&args.output, w, h, &rgb_bytes(&shown), &provenance)?
                }
                (Format::Exr, Some((display, channel))) => {
                    let values = match display {
                        // One pass has no variance estimate: zero throughout.
                        Display::Variance => film
                            .relative_variance()
                            .unwrap_or_else(|| vec![0.0; pixels.len()]),
                        Display::SamplesPerPixel => {
                            film.samples_per_pixel().iter().map(|&n| n as f32).collect()
                        }
                        _ => film.cost_per_sample(),
                    };
                    write_exr(&args.output, w, h, &[channel], &values, &provenance)?
                }
            }
            Ok(Rendered {
                elapsed,
                passes,
                requested: split.passes(args.spp),
            })
        }
        Some(kind) => {
            let values = aov::render_aov(&world, kind, options.method);
            let elapsed = start.elapsed();
            let provenance = provenance_of(1);
            match format {
                Format::Png => {
                    let shown = aov_image(kind, &values);
                    write_png_srgb8(&args.output, w, h, &rgb_bytes(&shown), &provenance)?
                }
                Format::Exr => {
                    let names: &[&str] = match kind {
                        Aov::Depth => &["Z"],
                        Aov::Object => &["id"],
                        Aov::Normal | Aov::Albedo => &["R", "G", "B"],
                    };
                    write_exr(&args.output, w, h, names, &values, &provenance)?
                }
            }
            Ok(Rendered {
                elapsed,
                passes: 1,
                requested: 1,
            })
        }
    }
}

/// A display picture's RGB bytes, three per pixel.
fn rgb_bytes(image: &DisplayImage) -> Vec<u8> {
    image
        .srgba8
        .iter()
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect()
}

/// A render's share of a split one: a rectangle of pixels (`--crop`), a
/// range of sample indices (`--samples`), both, or the whole.
struct Split {
    region: Option<Region>,
    samples: Option<std::ops::Range<u32>>,
}

impl Split {
    /// The split `args` asks for in a `w` × `h` image; an error for a
    /// rectangle outside it or empty, for a split of an adaptive render
    /// (its samples per pixel are not known in advance) and for an AOV.
    fn of(args: &RenderArgs, w: u32, h: u32, adaptive: bool) -> Result<Split> {
        let region = match args.crop.as_deref() {
            None => None,
            Some(&[x0, y0, x1, y1]) => {
                if !(x0 < x1 && y0 < y1 && x1 <= w && y1 <= h) {
                    return Err(UserError(format!(
                        "--crop {x0} {y0} {x1} {y1}: the rectangle must hold a pixel and lie \
                         inside the {w}×{h} image (X1 ≤ {w}, Y1 ≤ {h}; X1 and Y1 are excluded)"
                    ))
                    .into());
                }
                Some(Region { x0, y0, x1, y1 })
            }
            Some(other) => {
                return Err(UserError(format!("--crop takes 4 numbers, got {other:?}")).into());
            }
        };
        let split = Split {
            region,
            samples: args.samples.clone(),
        };
        if split.is_split() && adaptive {
            return Err(UserError(
                "--crop and --samples cannot split an --adaptive render: \
                 how many samples a pixel gets depends on the whole render"
                    .into(),
            )
            .into());
        }
        if split.is_split() && aov_of(args.aov).is_some() {
            return Err(UserError(
                "--crop and --samples split the colour image (--aov color, variance, cost, spp)"
                    .into(),
            )
            .into());
        }
        Ok(split)
    }

    fn is_split(&self) -> bool {
        self.region.is_some() || self.samples.is_some()
    }

    /// How many passes: the range's length, else `spp`.
    fn passes(&self, spp: u32) -> u32 {
        self.samples.as_ref().map_or(spp, |r| r.end - r.start)
    }

    /// A film of `w` × `h` for this share.
    fn film(&self, w: u32, h: u32) -> Film {
        let film = Film::new(w, h).from_sample(self.samples.as_ref().map_or(0, |r| r.start));
        match self.region {
            Some(region) => film.in_region(region),
            None => film,
        }
    }

    /// `provenance` with the share recorded (for `raylab merge`), after
    /// `passes` passes.
    fn record(&self, mut provenance: Provenance, passes: u32) -> Provenance {
        if self.is_split() {
            let first = self.samples.as_ref().map_or(0, |r| r.start);
            provenance.entries.push((
                "raylab:samples".to_owned(),
                format!("{first}..{}", first + passes),
            ));
            if let Some(r) = self.region {
                provenance.entries.push((
                    "raylab:region".to_owned(),
                    format!("{} {} {} {}", r.x0, r.y0, r.x1, r.y1),
                ));
            }
        }
        provenance
    }
}

/// The passes of `split` (or `spp` of the whole) of `world` on one film,
/// with a progress bar on a terminal; Ctrl+C stops it after the pass under
/// way (the film then holds the passes done). An error when it is stopped
/// before the first pass is done.
fn render_passes(
    world: &renderer::World,
    options: &renderer::RenderOptions,
    split: &Split,
    spp: u32,
) -> Result<(Film, u32)> {
    interrupt::catch();
    let spp = split.passes(spp);
    let progress = Progress::new(u64::from(spp), "passes");
    let mut film = split.film(world.camera.w, world.camera.h);
    let mut passes = 0;
    while passes < spp && !interrupt::requested() {
        film.add_pass(world, options);
        passes += 1;
        progress.step();
    }
    progress.finish();
    if passes == 0 {
        return Err(UserError(
            "stopped (Ctrl+C) before the first pass was done: nothing written".into(),
        )
        .into());
    }
    Ok((film, passes))
}

fn aov_of(arg: AovArg) -> Option<Aov> {
    match arg {
        AovArg::Color | AovArg::Variance | AovArg::Cost | AovArg::Spp => None,
        AovArg::Depth => Some(Aov::Depth),
        AovArg::Normal => Some(Aov::Normal),
        AovArg::Albedo => Some(Aov::Albedo),
        AovArg::Object => Some(Aov::Object),
    }
}
