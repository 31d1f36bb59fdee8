//! `raylab bench interactive`: the window's own code driven headless by an
//! egui context, timing what a user feels — from an edit to the first
//! preview on screen and to the first full-resolution pass — and the UI
//! thread's frame time while the tracer keeps every core busy; and
//! `raylab bench debug-view`, whole frames with the 3D debug view shown.
//!
//! These benchmarks live with the window, not in `crate::bench`, because
//! they drive the app's own state (its session, inspector and debug view);
//! `cli/bench.rs` runs them and prints their figures.

mod wake;

use super::RaylabApp;
use renderer::integrator::Integrator;
use renderer::progressive::Step;
use scene::{Geometry, Scene, Shape};
use std::path::PathBuf;
use std::time::{Duration, Instant};
use wake::RepaintWake;

/// An edit `interactive` makes: the kinds a user makes most, in turn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EditKind {
    /// θ, the half-height angle, as a drag in the camera panel.
    Theta,
    /// The eye turned about the point it looks at, as a drag in the image.
    Orbit,
    /// An object's colour, as a colour picker.
    Color,
    /// A sphere or box moved, as a drag of its position.
    Move,
}

impl EditKind {
    /// Every kind, in the order `interactive` takes them.
    pub const ALL: [EditKind; 4] = [
        EditKind::Theta,
        EditKind::Orbit,
        EditKind::Color,
        EditKind::Move,
    ];

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            EditKind::Theta => "θ",
            EditKind::Orbit => "orbit",
            EditKind::Color => "colour",
            EditKind::Move => "move",
        }
    }
}

/// What one run measured.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Each timed edit's kind, in the order made (parallel to the timings).
    pub kinds: Vec<EditKind>,
    /// Edit → the frame that first shows a preview of the new job.
    pub to_preview: Vec<Duration>,
    /// Edit → the frame that first shows a full pass of the new job.
    pub to_full_pass: Vec<Duration>,
    /// Edit → the render thread handing over that first preview.
    pub preview_handed_over: Vec<Duration>,
    /// Edit → the render thread handing over that first full pass.
    pub pass_handed_over: Vec<Duration>,
    /// CPU time of every UI frame (layout and tessellation) while rendering.
    pub frame_times: Vec<Duration>,
}

/// How long one display frame lasts at 60 Hz: the UI loop's pace.
const FRAME: Duration = Duration::from_micros(16_667);

/// Makes edit number `edit`, of kind `kind`, to the app's scene as the panel
/// or a drag in the image would. Returns false when the scene has nothing
/// that kind applies to (no sphere or box to move, no object to colour).
fn make_edit(app: &mut RaylabApp, kind: EditKind, edit: u32) -> bool {
    let step = (edit % 5) as f32;
    let sign = if edit.is_multiple_of(2) { 1.0 } else { -1.0 };
    match kind {
        EditKind::Theta => app.doc.state.scene.camera.theta_deg = 24.0 + step,
        EditKind::Orbit => {
            let Some(prepared) = &app.session.prepared else {
                return false;
            };
            let camera = &prepared.world.camera;
            let view = super::viewport::navigation::OrbitView {
                eye: camera.p0,
                target: camera.p0 + camera.t * camera.p0.length().max(1.0),
                up: camera.u,
            }
            .orbit(0.02 * sign, 0.0);
            let Some((eye, toward)) = view.as_stored() else {
                return false;
            };
            let stored = &mut app.doc.state.scene.camera;
            stored.eye = Some(eye);
            stored.toward = Some(toward);
        }
        EditKind::Color => {
            let Some(object) = app.doc.state.scene.objects.first_mut() else {
                return false;
            };
            object.params.color = Some(glam::Vec3::new(0.2 + 0.15 * step, 0.5, 0.8 - 0.1 * step));
        }
        EditKind::Move => {
            let Some(prepared) = &app.session.prepared else {
                return false;
            };
            let placed = prepared
                .resolved
                .objects
                .iter()
                .enumerate()
                .find_map(|(k, o)| match o.geometry {
                    Geometry::Sphere { center, .. } | Geometry::Box { center, .. } => {
                        Some((k, center))
                    }
                    _ => None,
                });
            let Some((k, at)) = placed else {
                return false;
            };
            let to = at + glam::Vec3::new(0.05 * sign, 0.0, 0.0);
            match &mut app.doc.state.scene.objects[k].shape {
                Shape::Sphere { center, .. } | Shape::Box { center, .. } => *center = Some(to),
                _ => return false,
            }
        }
    }
    true
}

/// Runs `edits` edits, of each [`EditKind`] in turn that the scene offers,
/// on `scene` traced by `integrator`, and times each until its first full
/// pass.
pub fn interactive(
    scene: Scene,
    path: Option<PathBuf>,
    integrator: Integrator,
    edits: u32,
) -> Report {
    let ctx = egui::Context::default();
    let wake = RepaintWake::of(&ctx);
    let mut app = RaylabApp::new(scene, path);
    app.doc.state.render.target_spp = None; // refine forever: the tracer never idles
    app.doc.state.render.integrator = integrator;
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
        // Not measured; and the spinner shown before the first frame asks
        // for a repaint every frame, which would make `wake` spin.
        std::thread::sleep(Duration::from_millis(1));
    }
    let mut report = Report::default();
    let mut next_kind = 0;
    for edit in 0..edits {
        // The next kind of edit that applies here.
        let mut made = None;
        for _ in 0..EditKind::ALL.len() {
            let kind = EditKind::ALL[next_kind % EditKind::ALL.len()];
            next_kind += 1;
            if make_edit(&mut app, kind, edit) {
                made = Some(kind);
                break;
            }
        }
        let Some(made) = made else {
            break;
        };
        // Then frames, as the display would run them.
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
                    report.pass_handed_over.extend(shown.map(|(_, t)| t));
                    report.kinds.push(made);
                    break;
                }
                _ => {}
            }
            // Sleep as the window does: until the tracer hands over a step
            // (its repaint request), or a frame at most.
            wake.sleep(FRAME.saturating_sub(took));
        }
        // Let the tracer keep both cores busy for a while before the next edit.
        let busy = Instant::now() + Duration::from_millis(300);
        while Instant::now() < busy {
            let took = frame(&mut app);
            report.frame_times.push(took);
            wake.sleep(FRAME.saturating_sub(took));
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
/// the image on every core (or, with `idle_tracer`, after it has finished
/// one pass and stopped).
pub fn debug_view(
    scene: Scene,
    path: Option<PathBuf>,
    frames: u32,
    show_debug: bool,
    idle_tracer: bool,
    gpu: &crate::bench::headless_gpu::HeadlessGpu,
    size: egui::Vec2,
) -> anyhow::Result<DebugViewReport> {
    let ctx = egui::Context::default();
    let mut app = RaylabApp::new(scene, path).with_gpu(Some(gpu.render_state.clone()));
    app.doc.state.render.target_spp = if idle_tracer { Some(1) } else { None };
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
