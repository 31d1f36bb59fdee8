//! `raylab render`: a scene to an image file, no window.

use super::args::{AovArg, RenderArgs};
use super::prepare::{UserError, prepare};
use crate::io::output::{Format, Provenance, write_exr, write_png, write_png_srgb8};
use anyhow::Result;
use renderer::Film;
use renderer::display::Display;
use renderer::display::DisplayImage;
use renderer::display::image::{Source, aov_image, display_image};
use renderer::film::aov::{self, Aov};
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

/// Renders `args.scene` to `args.output`; returns the time the render took.
pub fn run(args: &RenderArgs) -> Result<Duration> {
    let format = Format::from_path(&args.output).map_err(|e| UserError(e.to_string()))?;
    let (world, options, scene_view) = prepare(&args.scene)?;
    let view = view_of(args, scene_view)?;
    let (w, h) = (world.camera.w, world.camera.h);
    let provenance = Provenance::of_render(&world.camera, Some(&args.scene.scene), args.spp);
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
    let provenance = match args.aov {
        AovArg::Variance => provenance.with_display(Display::Variance),
        AovArg::Cost => provenance.with_display(Display::Cost),
        AovArg::Spp => provenance.with_display(Display::SamplesPerPixel),
        _ => provenance,
    };
    match aov_of(args.aov) {
        None => {
            let film = Film::render(&world, &options, args.spp);
            let elapsed = start.elapsed();
            if film.discarded() > 0 {
                eprintln!(
                    "warning: {} samples were NaN or infinite and were left out",
                    film.discarded()
                );
            }
            let pixels = film.linear();
            if let (Some(path), Some(reference)) = (&args.reference, &reference) {
                let flip = super::chart::flip::FlipReference::new(&reference.pixels, w, h);
                println!(
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
            Ok(elapsed)
        }
        Some(kind) => {
            let values = aov::render_aov(&world, kind, options.method);
            let elapsed = start.elapsed();
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
            Ok(elapsed)
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

fn aov_of(arg: AovArg) -> Option<Aov> {
    match arg {
        AovArg::Color | AovArg::Variance | AovArg::Cost | AovArg::Spp => None,
        AovArg::Depth => Some(Aov::Depth),
        AovArg::Normal => Some(Aov::Normal),
        AovArg::Albedo => Some(Aov::Albedo),
        AovArg::Object => Some(Aov::Object),
    }
}
