//! `raylab bench`: responsiveness figures of the window, measured headless.

use crate::cli::{BenchArgs, BenchKind};
use crate::gui::bench::{self, quantile};
use anyhow::Result;
use std::path::PathBuf;
use std::time::Duration;

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Runs the benchmark `args` asks for and prints its figures.
pub fn run(args: &BenchArgs, default_scene: PathBuf) -> Result<()> {
    match args.which {
        BenchKind::Interactive => interactive(args, default_scene),
        BenchKind::DebugView => debug_view(args, default_scene),
    }
}

fn line(name: &str, values: &mut [Duration]) {
    println!(
        "{name:<34} median {:>7.1} ms   p95 {:>7.1} ms   max {:>7.1} ms",
        ms(quantile(values, 0.5)),
        ms(quantile(values, 0.95)),
        ms(quantile(values, 1.0)),
    );
}

fn debug_view(args: &BenchArgs, default_scene: PathBuf) -> Result<()> {
    let path = args.scene.clone().unwrap_or(default_scene);
    let mut scene = scene::read_file(&path)?;
    scene.camera.width = args.width;
    scene.camera.height = args.height;
    renderer::World::from_scene(&scene)?;
    let size = [1600u32, 900];
    let gpu = crate::gui::headless_gpu::HeadlessGpu::new(size)?;
    println!(
        "{} at {}×{}, debug view {} in a {}×{} window drawn by {}, {} frames, {} tracer threads",
        path.display(),
        args.width,
        args.height,
        if args.hide_debug_view {
            "hidden"
        } else {
            "shown"
        },
        size[0],
        size[1],
        gpu.adapter(),
        args.frames,
        rayon::current_num_threads()
    );
    let mut report = bench::debug_view(
        scene,
        Some(path),
        args.frames,
        !args.hide_debug_view,
        &gpu,
        egui::vec2(size[0] as f32, size[1] as f32),
    )?;
    line("UI thread per frame", &mut report.ui);
    line("whole frame, GPU finished", &mut report.whole);
    println!("(target: whole frame < 16 ms while the tracer runs)");
    Ok(())
}

fn interactive(args: &BenchArgs, default_scene: PathBuf) -> Result<()> {
    let path = args.scene.clone().unwrap_or(default_scene);
    let mut scene = scene::read_file(&path)?;
    scene.camera.width = args.width;
    scene.camera.height = args.height;
    renderer::World::from_scene(&scene)?;
    let threads = rayon::current_num_threads();
    println!(
        "{} at {}×{}, {} edits of θ, {threads} tracer threads",
        path.display(),
        args.width,
        args.height,
        args.edits
    );
    let mut report = bench::interactive(scene, Some(path), args.edits);
    if report.to_full_pass.len() < args.edits as usize {
        anyhow::bail!(
            "only {} of {} edits reached a full pass within 10 s",
            report.to_full_pass.len(),
            args.edits
        );
    }
    line("edit → first preview on screen", &mut report.to_preview);
    line(
        "  of which the render thread",
        &mut report.preview_handed_over,
    );
    line("edit → first full pass on screen", &mut report.to_full_pass);
    line("UI frame time while rendering", &mut report.frame_times);
    println!(
        "({} UI frames; targets: preview ≤ 16 ms, full pass ≤ 150 ms, UI frame < 16 ms)",
        report.frame_times.len()
    );
    Ok(())
}
