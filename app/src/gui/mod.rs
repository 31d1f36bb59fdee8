//! The desktop window: a camera panel, the progressively refined image and a
//! status bar. The UI thread never renders: it submits a scene snapshot to
//! the progressive session after every edit and shows the newest frame.

mod camera_panel;
mod image_view;
mod status_bar;

use renderer::progressive::{Job, ProgressiveRenderer, RenderedFrame};
use renderer::{RenderOptions, World};
use scene::Scene;
use std::path::PathBuf;
use std::sync::Arc;

/// Samples per pixel the window refines to before it stops.
const DEFAULT_TARGET_SPP: u32 = 64;

/// The application state: the edited scene, its render session and what is shown.
pub struct RaylabApp {
    /// The scene being edited.
    scene: Scene,
    /// Where the scene came from.
    path: Option<PathBuf>,
    /// The render session; started on the first frame, when a context exists.
    session: Option<ProgressiveRenderer>,
    /// The prepared copy of the newest valid scene (camera values for the panel).
    world: Option<Arc<World>>,
    /// The generation of the newest submitted job.
    generation: u64,
    /// The image view (one texture, updated in place).
    image: image_view::ImageView,
    /// The newest frame's step and timings, for the status bar.
    shown: Option<status_bar::Shown>,
    /// Why the scene cannot be rendered as edited, if it can't.
    error: Option<String>,
    /// Refinement target and pause, as set in the status bar.
    controls: status_bar::Controls,
    /// True when the scene changed since the last submit.
    dirty: bool,
}

impl RaylabApp {
    /// An app showing `scene` (loaded from `path`).
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Self {
        Self {
            scene,
            path,
            session: None,
            world: None,
            generation: 0,
            image: image_view::ImageView::default(),
            shown: None,
            error: None,
            controls: status_bar::Controls {
                target_spp: DEFAULT_TARGET_SPP,
                paused: false,
            },
            dirty: true,
        }
    }

    /// Prepares the scene and hands it to the session; a scene that cannot be
    /// rendered keeps the last image and shows why.
    fn submit(&mut self, ctx: &egui::Context) {
        self.dirty = false;
        let session = self.session.get_or_insert_with(|| {
            let ctx = ctx.clone();
            ProgressiveRenderer::new(move || ctx.request_repaint())
        });
        match World::from_scene(&self.scene) {
            Ok(world) => {
                let world = Arc::new(world);
                self.world = Some(Arc::clone(&world));
                self.generation = session.submit(Job {
                    world,
                    options: RenderOptions::default(),
                    target_spp: Some(self.controls.target_spp),
                });
                self.error = None;
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Shows the newest finished frame, if one arrived.
    fn receive(&mut self, ctx: &egui::Context) {
        let Some(frame): Option<RenderedFrame> = self.session.as_ref().and_then(|s| s.take_frame())
        else {
            return;
        };
        self.image.show_frame(ctx, &frame);
        self.shown = Some(status_bar::Shown::of(&frame));
    }

    /// Draws the whole window into `ui`.
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.receive(&ctx);

        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| {
                if status_bar::controls(ui, &mut self.controls)
                    && let Some(session) = &self.session
                {
                    session.set_paused(self.controls.paused);
                    session.set_target_spp(Some(self.controls.target_spp));
                }
                status_bar::show(
                    ui,
                    self.shown.as_ref(),
                    self.error.as_deref(),
                    self.controls.target_spp,
                );
            });
        });
        egui::Panel::left("camera").resizable(true).show(ui, |ui| {
            if let Some(path) = &self.path {
                ui.label(path.display().to_string());
                ui.separator();
            }
            let camera = self.world.as_ref().map(|w| w.camera);
            if camera_panel::show(ui, &mut self.scene, camera.as_ref()) {
                self.dirty = true;
            }
        });
        egui::CentralPanel::default().show(ui, |ui| self.image.ui(ui));
        // Edits made anywhere in this frame restart the render once, at its end.
        if self.dirty {
            self.submit(&ctx);
        }
    }
}

impl eframe::App for RaylabApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}

#[cfg(test)]
mod tests;
