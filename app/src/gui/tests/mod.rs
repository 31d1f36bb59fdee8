//! The window's headless tests (egui_kittest, and wgpu on lavapipe where
//! they render), and what they share: the seed scene at a small size, the
//! harness, and stepping until the render settles.

mod lifecycle;
mod load;
mod overwrite;
mod own_process;
mod process_probe;
mod recovery;
mod window;

use crate::gui::RaylabApp;
use crate::gui::doc::history::History;
use egui_kittest::Harness;
use renderer::progressive::Step;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The lecture's seed scene, shipped in assets/scenes.
pub fn seed_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml")
}

/// An app on the seed scene at `width` × `height`, refining to 2 spp, with
/// nothing to undo.
pub fn seed_app(width: u32, height: u32) -> RaylabApp {
    let path = seed_path();
    let mut scene = scene::read_file(&path).expect("the seed scene loads");
    scene.camera.width = width;
    scene.camera.height = height;
    let mut app = RaylabApp::new(scene, Some(path));
    app.doc.state.render.target_spp = Some(2);
    // The history starts from the adjusted state.
    app.doc.history = History::new(&app.doc.state);
    app
}

/// A 1200 × 800 headless window showing `app`.
pub fn harness(app: RaylabApp) -> Harness<'static, RaylabApp> {
    Harness::builder()
        .with_size(egui::Vec2::new(1200.0, 800.0))
        .build_ui_state(|ui, app: &mut RaylabApp| app.show(ui), app)
}

/// Steps the UI until the target spp of the newest job is on screen.
pub fn settle(h: &mut Harness<'static, RaylabApp>) {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        h.step();
        let target = h.state().doc.state.render.target_spp.unwrap_or(1);
        let frame = h.state().session.frame.as_ref();
        if frame.is_some_and(|f| {
            f.generation == h.state().session.generation && f.step == Step::Passes { spp: target }
        }) {
            return;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    panic!(
        "the render did not settle; shown {:?}",
        h.state().session.frame.as_ref().map(|f| f.step)
    );
}

/// Steps twice: a new window, menu or modal is measured invisibly on its first frame.
pub fn step_shown(h: &mut Harness<'static, RaylabApp>) {
    h.step();
    h.step();
}
