//! `raylab bench interactive`: the window's own code driven headless by an
//! egui context, timing what a user feels — from an edit to the first
//! preview on screen and to the first full-resolution pass — and the UI
//! thread's frame time while the tracer keeps every core busy; and
//! `raylab bench debug-view`, whole frames with the 3D debug view shown.
//!
//! These benchmarks live with the window, not in `crate::bench`, because
//! they drive the app's own state (its session, inspector and debug view);
//! `cli/bench.rs` runs them and prints their figures.

use super::RaylabApp;
use renderer::progressive::Step;
use scene::Scene;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What one run measured.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Edit → the frame that first shows a preview of the new job.
    pub to_preview: Vec<Duration>,
    /// Edit → the frame that first shows a full pass of the new job.
    pub to_full_pass: Vec<Duration>,
    /// Edit → the render thread handing over that first preview.
    pub preview_handed_over: Vec<Duration>,
    /// CPU time of every UI frame (layout and tessellation) while rendering.
    pub frame_times: Vec<Duration>,
}

/// How long one display frame lasts at 60 Hz: the UI loop's pace.
const FRAME: Duration = Duration::from_micros(16_667);

/// Runs `edits` θ edits on `scene` and times each until its first full pass.
pub fn interactive(scene: Scene, path: Option<PathBuf>, edits: u32) -> Report {
    let ctx = egui::Context::default();
    let mut app = RaylabApp::new(scene, path);
    app.doc.state.render.target_spp = None; // refine forever: the tracer never idles
    let input = || egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(1920.0, 1080.0),
        )),
        ..Default::default()
    };
    let frame = |app: &mut RaylabApp| -> Duration {
        let start = Instant::now();
        let mut output = ctx.run_ui(input(), |ui| app.show(ui));
        let _ = ctx.tessellate(output.shapes, output.pixels_per_point);
        // No GPU here: the texture uploads are what egui-wgpu would do with these.
        output.textures_delta.clear();
        start.elapsed()
    };
    // Warm up: the first job, rendered to a few passes.
    let warm_up = Instant::now() + Duration::from_secs(5);
    while Instant::now() < warm_up
        && !matches!(app.session.frame.as_ref().map(|f| f.step), Some(Step::Passes { spp }) if spp >= 2)
    {
        frame(&mut app);
        std::thread::sleep(Duration::from_millis(1));
    }
    let mut report = Report::default();
    for edit in 0..edits {
        // Edit θ as a drag in the panel would, then run frames as the display would.
        app.doc.state.scene.camera.theta_deg = 24.0 + (edit % 5) as f32;
        let edited = Instant::now();
        let mut preview = None;
        let deadline = edited + Duration::from_secs(10);
        while Instant::now() < deadline {
            let took = frame(&mut app);
            report.frame_times.push(took);
            let shown = app
                .session
                .frame
                .as_ref()
                .filter(|f| f.generation == app.session.generation)
                .map(|f| (f.step, f.since_submit));
            match shown.map(|(step, _)| step) {
                Some(Step::Preview { .. }) if preview.is_none() => {
                    preview = Some(edited.elapsed());
                    report.preview_handed_over.extend(shown.map(|(_, t)| t));
                }
                Some(Step::Passes { .. }) => {
                    report
                        .to_preview
                        .push(preview.unwrap_or_else(|| edited.elapsed()));
                    report.to_full_pass.push(edited.elapsed());
                    break;
                }
                _ => {}
            }
            // Wait for the next frame, or less when the tracer asks to repaint.
            std::thread::sleep(FRAME.saturating_sub(took).min(Duration::from_millis(1)));
        }
        // Let the tracer keep both cores busy for a while before the next edit.
        let busy = Instant::now() + Duration::from_millis(300);
        while Instant::now() < busy {
            let took = frame(&mut app);
            report.frame_times.push(took);
            std::thread::sleep(FRAME.saturating_sub(took));
        }
    }
    report
}

/// What `raylab bench debug-view` measured.
#[derive(Clone, Debug, Default)]
pub struct DebugViewReport {
    /// The UI thread's part of each frame: layout and the drawing.
    pub ui: Vec<Duration>,
    /// Whole frames: the UI, tessellation, buffer and texture uploads, the
    /// debug view's 3D pass and egui's pass, until the GPU has finished.
    pub whole: Vec<Duration>,
}

/// Runs `frames` display frames of the window with the debug view shown (or,
/// to compare, hidden), the
/// centre pixel inspected (its rays drawn) and the observer turning a little
/// every frame so the 3D view is redrawn each time, while the tracer refines
/// the image on every core.
pub fn debug_view(
    scene: Scene,
    path: Option<PathBuf>,
    frames: u32,
    show_debug: bool,
    gpu: &crate::bench::headless_gpu::HeadlessGpu,
    size: egui::Vec2,
) -> anyhow::Result<DebugViewReport> {
    let ctx = egui::Context::default();
    let mut app = RaylabApp::new(scene, path).with_gpu(Some(gpu.render_state.clone()));
    app.doc.state.render.target_spp = None;
    app.show_debug = show_debug;
    let input = || egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size)),
        ..Default::default()
    };
    let frame = |app: &mut RaylabApp, report: Option<&mut DebugViewReport>| {
        let start = Instant::now();
        let output = ctx.run_ui(input(), |ui| app.show(ui));
        let ui = start.elapsed();
        let drawn = gpu.draw(&ctx, output);
        if let Some(report) = report {
            report.ui.push(ui);
            report.whole.push(start.elapsed());
        }
        drawn
    };
    let warm_up = Instant::now() + Duration::from_secs(10);
    while Instant::now() < warm_up
        && !matches!(
            app.session.frame.as_ref().map(|f| f.step),
            Some(Step::Passes { .. })
        )
    {
        frame(&mut app, None)?;
        std::thread::sleep(Duration::from_millis(5));
    }
    if let Some(prepared) = &app.session.prepared {
        let camera = &prepared.world.camera;
        let method = app.doc.state.render.method;
        app.inspector
            .inspect([camera.w / 2, camera.h / 2], false, Some(prepared), method);
    }
    let mut report = DebugViewReport::default();
    for _ in 0..frames {
        app.debug.orbit(0.01, 0.0);
        frame(&mut app, Some(&mut report))?;
        let took = report.whole.last().copied().unwrap_or_default();
        std::thread::sleep(FRAME.saturating_sub(took));
    }
    Ok(report)
}
