//! `raylab render`: a scene to an image file, no window.

use crate::cli::{AovArg, RenderArgs};
use crate::output::{Format, Provenance, write_exr, write_png};
use anyhow::Result;
use renderer::aov::{self, Aov};
use renderer::{Film, RenderOptions, World};
use std::time::{Duration, Instant};

/// A failure the user can fix, reported as one line with exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UserError(pub String);

/// Renders `args.scene` to `args.output`; returns the time the render took.
pub fn run(args: &RenderArgs) -> Result<Duration> {
    let format = Format::from_path(&args.output).map_err(|e| UserError(e.to_string()))?;
    let mut scene = scene::read_file(&args.scene).map_err(|e| UserError(e.to_string()))?;
    if let Some(w) = args.width {
        scene.camera.width = w;
    }
    if let Some(h) = args.height {
        scene.camera.height = h;
    }
    let world = World::from_scene(&scene)
        .map_err(|e| UserError(format!("{}: {e}", args.scene.display())))?;
    let options = RenderOptions {
        method: args.method.into(),
        max_depth: args.max_depth,
        seed: args.seed,
    };
    let (w, h) = (world.camera.w, world.camera.h);
    let provenance = Provenance::of_render(&world.camera, Some(&args.scene), args.spp);
    let start = Instant::now();
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
            match format {
                Format::Png => write_png(&args.output, w, h, &pixels, &provenance)?,
                Format::Exr => {
                    let values: Vec<f32> = pixels.iter().flat_map(|p| p.to_array()).collect();
                    write_exr(&args.output, w, h, &["R", "G", "B"], &values, &provenance)?
                }
            }
            Ok(elapsed)
        }
        Some(kind) => {
            let values = aov::render_aov(&world, kind, options.method);
            let elapsed = start.elapsed();
            match format {
                Format::Png => write_png(
                    &args.output,
                    w,
                    h,
                    &aov::visualize(kind, &values),
                    &provenance,
                )?,
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

fn aov_of(arg: AovArg) -> Option<Aov> {
    match arg {
        AovArg::Color => None,
        AovArg::Depth => Some(Aov::Depth),
        AovArg::Normal => Some(Aov::Normal),
        AovArg::Albedo => Some(Aov::Albedo),
        AovArg::Object => Some(Aov::Object),
    }
}
