//! Keeping the render session in step with the document. The UI thread
//! never renders: after every edit it snapshots the scene, prepares its
//! render copy and hands it to the progressive renderer's thread, and it
//! shows the newest frame that thread hands back.

use super::doc::document::{EditState, rebase_file_sources};
use renderer::display::Display;
use renderer::progressive::{Job, ProgressiveRenderer, RenderedFrame};
use renderer::{RenderOptions, World};
use scene::{ResolvedScene, Scene, View};
use std::path::Path;
use std::sync::Arc;

/// A scene snapshot and the render copy prepared from it.
pub struct Prepared {
    /// Every default decided (placement, camera, lights).
    pub resolved: ResolvedScene,
    /// The immutable render copy the session renders.
    pub world: Arc<World>,
}

/// The render session as the window sees it: what it was last given, the
/// world prepared from the newest valid scene, and the newest frame.
pub struct SessionSync {
    /// The render session; started on the first frame, when a context exists.
    progressive: Option<ProgressiveRenderer>,
    /// The prepared copy of the newest valid scene.
    pub prepared: Option<Prepared>,
    /// What the session was last given: the scene and the options.
    pub submitted: Option<(Scene, RenderOptions)>,
    /// The target spp the session was last given.
    submitted_target: Option<Option<u32>>,
    /// The display mode the session was last given.
    submitted_display: Display,
    /// The view transform (exposure, tone curve) the session was last given.
    submitted_view: View,
    /// The generation of the newest submitted job.
    pub generation: u64,
    /// The newest frame on screen.
    pub frame: Option<RenderedFrame>,
    /// Why the scene cannot be rendered as edited, if it can't.
    pub error: Option<String>,
    /// Refinement is paused.
    pub paused: bool,
}

impl Default for SessionSync {
    fn default() -> Self {
        Self {
            progressive: None,
            prepared: None,
            submitted: None,
            submitted_target: None,
            submitted_display: Display::Color,
            submitted_view: View::default(),
            generation: 0,
            frame: None,
            error: None,
            paused: false,
        }
    }
}

impl SessionSync {
    /// Hands `state`'s scene to the session when it or the options changed
    /// since the last submit, and `display` when it changed; a scene that
    /// cannot be rendered keeps the last image and says why. A scene that
    /// differs only as saving it to `saved_to` (the document's file) rewrote
    /// its file names goes on rendering. True when a new world was prepared
    /// (and submitted).
    pub fn submit_if_changed(
        &mut self,
        ctx: &egui::Context,
        state: &EditState,
        saved_to: Option<&Path>,
        display: Display,
    ) -> bool {
        let options = state.render.options();
        let target = state.render.target_spp;
        let unchanged = self.submitted.as_ref().is_some_and(|(scene, o)| {
            *o == options
                && (scene.renders_like(&state.scene)
                    || saved_to
                        .is_some_and(|path| saved_as(scene, path).renders_like(&state.scene)))
        });
        if unchanged && let Some((scene, _)) = &mut self.submitted {
            // Saved elsewhere: the same files, named from the new folder.
            scene.clone_from(&state.scene);
        }
        let session = self.progressive.get_or_insert_with(|| {
            let ctx = ctx.clone();
            ProgressiveRenderer::new(move || ctx.request_repaint())
        });
        if self.submitted_display != display {
            session.set_display(display);
            self.submitted_display = display;
        }
        // How the picture is shown changes no sample: the frame on screen
        // is shown again, the render goes on.
        if self.submitted_view != state.scene.view {
            session.set_view(state.scene.view);
            self.submitted_view = state.scene.view;
        }
        if unchanged {
            if self.submitted_target != Some(target) {
                session.set_target_spp(target);
                self.submitted_target = Some(target);
            }
            return false;
        }
        self.submitted = Some((state.scene.clone(), options));
        self.submitted_target = Some(target);
        // Free the workers first: the world's BVH builds run on them.
        session.cancel();
        let prepared = scene::resolve(&state.scene)
            .map_err(renderer::RenderError::from)
            .and_then(|resolved| {
                let world = World::new(&resolved)?;
                renderer::film::image_memory::check_world_fits(&world)?;
                Ok(Prepared {
                    resolved,
                    world: Arc::new(world),
                })
            });
        match prepared {
            Ok(prepared) => {
                self.generation = session.submit(Job {
                    world: Arc::clone(&prepared.world),
                    options,
                    target_spp: target,
                });
                self.prepared = Some(prepared);
                self.error = None;
                true
            }
            Err(e) => {
                self.error = Some(e.to_string());
                false
            }
        }
    }

    /// Forgets what the session was given, so that the next check submits
    /// the document even when it compares equal to the scene on screen
    /// (meshes compare by file name, and a file may have changed on disk).
    pub fn forget_submitted(&mut self) {
        self.submitted = None;
    }

    /// Takes the newest finished frame, if one arrived, to be shown.
    pub fn receive(&mut self) -> Option<&RenderedFrame> {
        let frame = self.progressive.as_ref().and_then(|s| s.take_frame())?;
        Some(self.frame.insert(frame))
    }

    /// Pauses refinement, or resumes it.
    pub fn toggle_pause(&mut self) {
        self.paused = !self.paused;
        if let Some(session) = &self.progressive {
            session.set_paused(self.paused);
        }
    }

    /// Samples per pixel of the frame on screen, when it shows the current scene.
    pub fn shown_spp(&self) -> u32 {
        match self.frame.as_ref().map(|f| (f.generation, f.step)) {
            Some((generation, renderer::progressive::Step::Passes { spp }))
                if generation == self.generation =>
            {
                spp
            }
            _ => 0,
        }
    }
}

/// `scene` as saving it to `path` writes it: its model and map files named
/// from `path`'s folder. A save changes the scene only so; the render of a
/// scene just saved elsewhere goes on.
fn saved_as(scene: &Scene, path: &Path) -> Scene {
    let mut scene = scene.clone();
    rebase_file_sources(&mut scene, path);
    scene
}
