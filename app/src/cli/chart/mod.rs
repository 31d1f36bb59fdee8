//! `raylab chart`: speed against accuracy. Renders a scene progressively
//! with each method, records the time and the error against a reference
//! after every pass up to 16, then each time the passes have grown by an
//! eighth (measuring slows the pass after it:
//! [`renderer::diagnostics::convergence::next_measurement`]), and writes the
//! curves as CSV and as a log–log PNG chart.

pub(crate) mod flip;

use super::args::{ChartArgs, ChartMethod};
use super::prepare::UserError;
use crate::cli::progress::Progress;
use crate::io::stdout::say;
use crate::plot::chart::{Curve, write_chart};
use anyhow::{Context, Result};
use flip::FlipReference;
use glam::Vec3;
use renderer::diagnostics::convergence::{Budget, converge, time_to_reach};
use renderer::diagnostics::reference_image::read_exr_rgb;
use renderer::integrator::Integrator;
use renderer::integrator::adaptive::Adaptive;
use renderer::{Film, Method, RenderOptions, Sampling, World};
use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

/// The options a method renders with.
fn options_of(method: ChartMethod, max_depth: u32, seed: u64) -> RenderOptions {
    let path = RenderOptions {
        integrator: Integrator::Path,
        max_depth,
        seed,
        ..RenderOptions::default()
    };
    let whitted = RenderOptions {
        integrator: Integrator::Whitted,
        ..path
    };
    match method {
        ChartMethod::Path => path,
        ChartMethod::PathSobol => RenderOptions {
            sampling: Sampling::Sobol,
            ..path
        },
        ChartMethod::PathAdaptive => RenderOptions {
            adaptive: Some(Adaptive::default()),
            ..path
        },
        ChartMethod::PathLecture => RenderOptions {
            method: Method::Lecture,
            ..path
        },
        ChartMethod::Whitted => whitted,
        ChartMethod::WhittedLecture => RenderOptions {
            method: Method::Lecture,
            ..whitted
        },
    }
}

/// Runs the command; returns the paths written.
pub fn run(args: &ChartArgs) -> Result<Vec<PathBuf>> {
    let scene = scene::read_any(&args.scene).map_err(|e| UserError(e.to_string()))?;
    let world = World::from_scene(&scene)
        .and_then(|world| renderer::film::image_memory::check_world_fits(&world).map(|()| world))
        .map_err(|e| UserError(format!("{}: {e}", args.scene.display())))?;
    let (w, h) = (world.camera.w, world.camera.h);
    let reference = match &args.reference {
        Some(path) => {
            let image = read_exr_rgb(path).map_err(|e| UserError(e.to_string()))?;
            image
                .check_size(path, w, h)
                .map_err(|e| UserError(e.to_string()))?;
            eprintln!("reference: {}", path.display());
            image.pixels
        }
        None => {
            let seconds = 4.0 * args.seconds;
            eprintln!(
                "no --reference: rendering raylab's own path-traced reference for {seconds:.0} s"
            );
            own_reference(&world, args.max_depth, seconds)
        }
    };
    let flip = FlipReference::new(&reference, w, h);
    let budget = Budget {
        time: Duration::from_secs_f64(args.seconds),
        max_spp: args.max_spp,
    };
    let mut curves = Vec::new();
    let progress = Progress::new(args.methods.len() as u64, "methods");
    for &method in &args.methods {
        let name = method.name();
        progress.say(name);
        let options = options_of(method, args.max_depth, args.seed);
        let (points, _) = converge(
            &world,
            &options,
            &reference,
            budget,
            Some(&|image: &[Vec3]| flip.mean_error(image)),
        );
        if let Some(last) = points.last() {
            let reach = |target| {
                time_to_reach(&points, target)
                    .map_or_else(|| "not reached".to_owned(), |t| format!("{t:.2} s"))
            };
            progress.suspend(|| {
                say!(
                    "{name:>16}: {} spp ({:.1} on average) in {:.2} s, relMSE {:.3e}, FLIP {:.4}; \
                     to 1e-2: {}, to 1e-3: {}",
                    last.spp,
                    last.mean_spp,
                    last.seconds,
                    last.rel_mse,
                    last.perceptual.unwrap_or(f64::NAN),
                    reach(1e-2),
                    reach(1e-3)
                )
            });
        }
        progress.step();
        curves.push(Curve { name, points });
    }
    progress.finish();
    let (csv, png) = crate::io::output_path::csv_and_png(args.output.as_deref(), "chart");
    write_csv(&csv, &curves)?;
    let title = format!(
        "{} ({w}×{h}): error against time",
        args.scene.file_name().map_or_else(
            || args.scene.display().to_string(),
            |n| n.to_string_lossy().into()
        )
    );
    write_chart(&png, &title, &curves)?;
    Ok(vec![csv, png])
}

/// A long path-traced render to measure against when no reference is given.
fn own_reference(world: &World, max_depth: u32, seconds: f64) -> Vec<glam::Vec3> {
    let options = RenderOptions {
        integrator: Integrator::Path,
        max_depth,
        // A seed no charted method uses, so that its noise is independent.
        seed: u64::MAX,
        ..Default::default()
    };
    let mut film = Film::new(world.camera.w, world.camera.h);
    let start = std::time::Instant::now();
    while start.elapsed().as_secs_f64() < seconds {
        film.add_pass(world, &options);
    }
    film.linear()
}

/// One row per method and pass: method, spp (passes), mean_spp, seconds,
/// rel_mse, rmse, flip (LDR-FLIP's mean).
fn write_csv(path: &std::path::Path, curves: &[Curve]) -> Result<()> {
    let mut out = String::from("method,spp,mean_spp,seconds,rel_mse,rmse,flip\n");
    for curve in curves {
        for p in &curve.points {
            out.push_str(&format!(
                "{},{},{:.3},{:.6},{:.6e},{:.6e},{:.6e}\n",
                curve.name,
                p.spp,
                p.mean_spp,
                p.seconds,
                p.rel_mse,
                p.rmse,
                p.perceptual.unwrap_or(f64::NAN)
            ));
        }
    }
    let mut file =
        std::fs::File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    file.write_all(out.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))
}
