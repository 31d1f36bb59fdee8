//! `raylab bench`: ray-tracing throughput (any scene, or the suite of
//! generated scenes), and the window's responsiveness measured headless.

use super::args::BenchArgs;
use crate::bench::headless_gpu::HeadlessGpu;
use crate::bench::{export, scene_spec, trace};
use crate::gui::bench;
use crate::io::stdout::say;
use anyhow::Result;
use renderer::diagnostics::quantile::quantile_by;
use std::path::{Path, PathBuf};
use std::time::Duration;

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Runs the benchmark `args` asks for and prints its figures.
pub fn run(args: &BenchArgs, default_scene: PathBuf) -> Result<()> {
    let measures_a_scene = !matches!(args.which.as_str(), "interactive" | "debug-view" | "suite");
    if args.export.is_some() && !measures_a_scene {
        anyhow::bail!(
            "--export goes with a scene to measure (e.g. `raylab bench knot --export DIR`), not with `{}`",
            args.which
        );
    }
    match args.which.as_str() {
        "interactive" => interactive(args, &default_scene),
        "debug-view" => debug_view(args, &default_scene),
        "suite" => suite(args.json, &default_scene),
        spec => {
            let (scene, label) = scene_spec::load(spec, &default_scene)?;
            let scene = trace::sized(scene, args.width, args.height);
            let exported = match &args.export {
                Some(dir) => {
                    let manifest = export::export(&scene, &label, dir)?;
                    eprintln!(
                        "exported {} triangles, {} primary and {} incoherent rays to {}",
                        manifest.triangles,
                        manifest.primary.count,
                        manifest.incoherent.as_ref().map_or(0, |r| r.count),
                        dir.display()
                    );
                    Some((dir, manifest))
                }
                None => None,
            };
            let figures = trace::measure(scene, &label, None, None)?;
            if let Some((dir, mut manifest)) = exported {
                manifest.raylab = Some(figures.clone());
                export::write_manifest(dir, &manifest)?;
            }
            if args.json {
                say!("{}", serde_json::to_string_pretty(&figures)?);
            } else {
                trace::print_table(&figures);
            }
            Ok(())
        }
    }
}

/// The report: the million-triangle knot at 1920×1080, ten thousand
/// spheres, the seed scene at 1280×720, and the scaling table.
fn suite(json: bool, seed: &Path) -> Result<()> {
    let runs: [(&str, Option<(u32, u32)>); 3] = [
        ("knot", Some((1920, 1080))),
        ("spheres", None),
        ("seed", Some((1280, 720))),
    ];
    let mut scenes = Vec::new();
    for (spec, size) in runs {
        let (scene, label) = scene_spec::load(spec, seed)?;
        let figures = trace::measure(scene, &label, size.map(|s| s.0), size.map(|s| s.1))?;
        if !json {
            trace::print_table(&figures);
            say!("");
        }
        scenes.push(figures);
    }
    let scaling = trace::scaling()?;
    if json {
        let report = serde_json::json!({ "scenes": scenes, "scaling": scaling });
        say!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        trace::print_scaling(&scaling);
    }
    Ok(())
}

/// The scene of a window benchmark at its size (1280×720 unless given).
fn window_scene(args: &BenchArgs, seed: &Path) -> Result<(scene::Scene, String, Option<PathBuf>)> {
    let spec = args
        .scene
        .clone()
        .unwrap_or_else(|| seed.display().to_string());
    let (mut scene, label) = scene_spec::load(&spec, seed)?;
    scene.camera.width = args.width.unwrap_or(1280);
    scene.camera.height = args.height.unwrap_or(720);
    let world = renderer::World::from_scene(&scene)?;
    renderer::film::image_memory::check_world_fits(&world)?;
    let path = Path::new(&spec);
    Ok((scene, label, path.exists().then(|| path.to_path_buf())))
}

fn line(name: &str, values: &mut [Duration]) {
    let mut quantile = |q| quantile_by(values, q, Duration::cmp).unwrap_or(Duration::ZERO);
    say!(
        "{name:<34} median {:>7.1} ms   p95 {:>7.1} ms   max {:>7.1} ms",
        ms(quantile(0.5)),
        ms(quantile(0.95)),
        ms(quantile(1.0)),
    );
}

fn debug_view(args: &BenchArgs, seed: &Path) -> Result<()> {
    // As in the window: the tracer below the UI.
    crate::gui::worker_priority::lower_tracer_priority();
    let (scene, label, path) = window_scene(args, seed)?;
    let size = [1600u32, 900];
    let gpu = HeadlessGpu::new(size)?;
    say!(
        "{label} at {}×{}, debug view {} in a {}×{} window drawn by {}, {} frames, {} tracer threads {}",
        scene.camera.width,
        scene.camera.height,
        if args.hide_debug_view {
            "hidden"
        } else {
            "shown"
        },
        size[0],
        size[1],
        gpu.adapter(),
        args.frames,
        rayon::current_num_threads(),
        match (
            args.idle_tracer,
            crate::gui::worker_priority::tracer_priority_lowered()
        ) {
            (true, _) => "idle (one pass, then none)",
            (false, true) => "running, at low priority",
            (false, false) => "running, at normal priority",
        }
    );
    let mut report = bench::debug_view(
        scene,
        path,
        args.frames,
        !args.hide_debug_view,
        args.idle_tracer,
        &gpu,
        egui::vec2(size[0] as f32, size[1] as f32),
    )?;
    line("UI thread per frame", &mut report.ui);
    line("whole frame, GPU finished", &mut report.whole);
    say!("(target: whole frame < 16 ms while the tracer runs)");
    Ok(())
}

fn interactive(args: &BenchArgs, seed: &Path) -> Result<()> {
    // As in the window: the tracer below the UI.
    crate::gui::worker_priority::lower_tracer_priority();
    let (scene, label, path) = window_scene(args, seed)?;
    let threads = rayon::current_num_threads();
    let integrator = renderer::integrator::Integrator::from(args.integrator);
    say!(
        "{label} at {}×{}, {:?}, {} edits (θ, orbit, colour, move in turn), {threads} tracer threads{}",
        scene.camera.width,
        scene.camera.height,
        integrator,
        args.edits,
        if crate::gui::worker_priority::tracer_priority_lowered() {
            " at low priority"
        } else {
            " at normal priority"
        }
    );
    let mut report = bench::interactive(scene, path, integrator, args.edits);
    if report.to_full_pass.len() < args.edits as usize {
        anyhow::bail!(
            "only {} of {} edits reached a full pass within 10 s",
            report.to_full_pass.len(),
            args.edits
        );
    }
    line(
        "edit → first preview on screen",
        &mut report.to_preview.clone(),
    );
    line(
        "  of which the render thread",
        &mut report.preview_handed_over,
    );
    line(
        "edit → first full pass on screen",
        &mut report.to_full_pass.clone(),
    );
    line("  of which the render thread", &mut report.pass_handed_over);
    for kind in bench::EditKind::ALL {
        let of_kind = |times: &[Duration]| -> Vec<Duration> {
            times
                .iter()
                .zip(&report.kinds)
                .filter(|&(_, &k)| k == kind)
                .map(|(&t, _)| t)
                .collect()
        };
        let (mut preview, mut full) = (of_kind(&report.to_preview), of_kind(&report.to_full_pass));
        if !preview.is_empty() {
            line(&format!("  {}: preview", kind.name()), &mut preview);
            line(&format!("  {}: full pass", kind.name()), &mut full);
        }
    }
    line("UI frame time while rendering", &mut report.frame_times);
    say!(
        "({} UI frames; targets: preview p95 ≤ 16 ms, full pass median ≤ 150 ms, UI frame < 16 ms)",
        report.frame_times.len()
    );
    Ok(())
}
