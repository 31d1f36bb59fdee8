//! Headless UI tests (egui_kittest): the window's behaviour without a display.

use super::RaylabApp;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use renderer::progressive::Step;
use std::time::{Duration, Instant};

fn seed_app(width: u32, height: u32) -> RaylabApp {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml");
    let mut scene = scene::read_file(&path).expect("the seed scene loads");
    scene.camera.width = width;
    scene.camera.height = height;
    let mut app = RaylabApp::new(scene, Some(path));
    app.controls.target_spp = 2;
    app
}

fn harness(app: RaylabApp) -> Harness<'static, RaylabApp> {
    Harness::builder()
        .with_size(egui::Vec2::new(1000.0, 700.0))
        .build_ui_state(|ui, app: &mut RaylabApp| app.show(ui), app)
}

/// Steps the UI until the target spp of the newest job is on screen.
fn settle(h: &mut Harness<'static, RaylabApp>) {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        h.step();
        if h.state().shown.map(|s| s.step)
            == Some(Step::Passes {
                spp: h.state().controls.target_spp,
            })
        {
            return;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    panic!(
        "the render did not settle; shown {:?}",
        h.state().shown.map(|s| s.step)
    );
}

#[test]
fn window_refines_the_seed_scene_and_shows_the_lecture_values() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    assert!(h.state().generation >= 1);
    h.get_by_label("C00");
    h.get_by_label("2 / 2 spp");
}

#[test]
fn editing_theta_in_the_panel_starts_a_new_render_with_the_new_angle() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let before = h.state().generation;
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "θ")
        .set_value_accesskit(40.0);
    h.step();
    assert_eq!(h.state().scene.camera.theta_deg, 40.0);
    assert!(h.state().generation > before, "an edit submits a new job");
    settle(&mut h);
}

#[test]
fn a_degenerate_camera_keeps_the_last_image_and_says_why() {
    let mut h = harness(seed_app(64, 48));
    settle(&mut h);
    let before = h.state().generation;
    h.state_mut().scene.camera.up = glam::Vec3::ZERO;
    h.state_mut().dirty = true;
    h.step();
    assert_eq!(h.state().generation, before, "no job for an invalid scene");
    h.step(); // the status bar shows the error from the next frame on
    h.get_by_label("camera: the up vector u is zero or not finite");
    assert!(h.state().shown.is_some(), "the last image stays");
}

#[test]
fn raising_the_target_spp_refines_the_same_image_further() {
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let generation = h.state().generation;
    h.get_by_label_contains("target spp")
        .set_value_accesskit(4.0);
    h.step();
    assert_eq!(h.state().controls.target_spp, 4);
    settle(&mut h);
    assert_eq!(h.state().generation, generation, "no restart");
}
