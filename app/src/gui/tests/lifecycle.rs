//! The window's life around a render in progress: opening another scene,
//! resizing every frame, and closing mid-render, which must leave no thread
//! of the app behind.

use super::load::{
    assert_shows_the_document, harness_discarding_textures, knot_app, wait_for_newest,
};
use super::own_process::{in_own_process, test_path};
use super::process_probe::{thread_count, threads_named, threads_settle_to};
use super::{harness, seed_app, seed_path, settle};
use crate::gui::RaylabApp;
use crate::gui::commands::Command;
use egui_kittest::Harness;
use renderer::progressive::Step;
use std::time::{Duration, Instant};

/// The render worker's thread name.
const WORKER: &str = "raylab-render";

/// The generated knot's triangles.
const KNOT: usize = crate::bench::scene_spec::KNOT_TRIANGLES;

/// Steps until a full pass of the newest job is on screen: the tracer is
/// then refining, not previewing.
fn wait_for_a_pass(h: &mut Harness<'static, RaylabApp>) {
    let started = Instant::now();
    while !(super::load::shows_newest(h)
        && matches!(
            h.state().session.frame.as_ref().map(|f| f.step),
            Some(Step::Passes { .. })
        ))
    {
        assert!(started.elapsed() < Duration::from_secs(60), "no full pass");
        std::thread::sleep(Duration::from_millis(2));
        h.step();
    }
}

#[test]
fn opening_another_scene_mid_render_shows_the_new_scene() {
    let mut h = harness_discarding_textures(knot_app(KNOT, None));
    wait_for_a_pass(&mut h);
    let seed = seed_path();
    let ctx = h.ctx.clone();
    let opened = Instant::now();
    h.state_mut().run(&ctx, Command::OpenPath(seed.clone()));
    assert_eq!(h.state().doc.path.as_deref(), Some(seed.as_path()));
    h.state_mut().doc.state.render.target_spp = Some(1);
    let knot = h.state().session.generation;
    h.step();
    assert!(
        h.state().session.generation > knot,
        "the opened scene is submitted"
    );
    wait_for_newest(&mut h);
    eprintln!(
        "the opened scene's first frame after {:.0} ms",
        opened.elapsed().as_secs_f64() * 1e3
    );
    assert_shows_the_document(&h);
    settle(&mut h);
    assert_shows_the_document(&h);
}

#[test]
fn resizing_the_window_every_frame_while_rendering_is_harmless() {
    let mut h = Harness::builder()
        .with_size(egui::Vec2::new(1200.0, 800.0))
        .wgpu()
        .build_ui_state(
            |ui, app: &mut RaylabApp| app.show(ui),
            knot_app(KNOT, Some(16)),
        );
    wait_for_newest(&mut h);
    // Sizes from a tiny window to a large one, in a fixed pseudo-random order.
    let mut x: u32 = 12345;
    for frame in 0..300 {
        x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        let (w, hh) = (40 + (x >> 8) % 1560, 30 + (x >> 20) % 970);
        h.set_size(egui::Vec2::new(w as f32, hh as f32));
        h.step();
        if frame % 50 == 0 {
            let image = h.render().expect("the window renders at any size");
            assert_eq!(image.width(), w);
        }
    }
    h.set_size(egui::Vec2::new(1200.0, 800.0));
    settle(&mut h);
    assert_shows_the_document(&h);
}

/// Opens the knot, lets it render until a full pass is shown, and drops
/// the harness (the app and its session) while the tracer is refining;
/// returns how long dropping took.
fn drop_mid_render() -> Duration {
    let mut h = harness_discarding_textures(knot_app(KNOT, None));
    wait_for_a_pass(&mut h);
    assert_eq!(threads_named(WORKER), 1, "one render worker");
    let dropping = Instant::now();
    drop(h);
    dropping.elapsed()
}

#[test]
fn closing_the_window_mid_render_leaves_no_thread_behind() {
    let name = test_path(
        module_path!(),
        "closing_the_window_mid_render_leaves_no_thread_behind",
    );
    if !in_own_process(&name, Duration::from_secs(300)) {
        return;
    }
    // Start rayon's pool and whatever else starts once per process.
    rayon::broadcast(|_| ());
    drop_mid_render();
    let before = thread_count();
    let took = drop_mid_render();
    let after = threads_settle_to(before, Duration::from_secs(10));
    eprintln!(
        "closing mid-render took {:.0} ms; threads {before} → {after}",
        took.as_secs_f64() * 1e3
    );
    assert_eq!(
        threads_named(WORKER),
        0,
        "the render worker outlived the app"
    );
    assert_eq!(after, before, "threads leaked");
    assert!(
        took < Duration::from_secs(5),
        "closing waited {took:?} for the render"
    );
}

/// A binary glTF of one triangle with these corners.
fn triangle_glb(corners: [[f32; 3]; 3]) -> Vec<u8> {
    let bin: Vec<u8> = corners
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    let min: [f32; 3] =
        std::array::from_fn(|k| corners.iter().map(|c| c[k]).fold(f32::MAX, f32::min));
    let max: [f32; 3] =
        std::array::from_fn(|k| corners.iter().map(|c| c[k]).fold(f32::MIN, f32::max));
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [{"buffer": 0, "byteLength": bin.len()}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": min, "max": max}],
    });
    let mut json = json.to_string().into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut glb = Vec::with_capacity(total);
    for word in [0x4654_6c67, 2, total as u32, json.len() as u32, 0x4e4f_534a] {
        glb.extend_from_slice(&u32::to_le_bytes(word));
    }
    glb.extend_from_slice(&json);
    for word in [bin.len() as u32, 0x004e_4942] {
        glb.extend_from_slice(&u32::to_le_bytes(word));
    }
    glb.extend_from_slice(&bin);
    glb
}

#[test]
fn reopening_a_scene_whose_model_changed_on_disk_shows_the_new_model() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (scene_path, model_path) = (dir.path().join("s.xml"), dir.path().join("m.glb"));
    std::fs::write(
        &scene_path,
        r#"<scene><camera eye="0 0 5" toward="0 0 -1" width="48" height="32"/><mesh src="m.glb"/></scene>"#,
    )
    .expect("write the scene");
    let mut h = harness(seed_app(48, 32));
    let ctx = h.ctx.clone();
    let open = |h: &mut Harness<'static, RaylabApp>, corners| {
        std::fs::write(&model_path, triangle_glb(corners)).expect("write the model");
        h.state_mut()
            .run(&ctx, Command::OpenPath(scene_path.clone()));
        h.step();
        settle(h);
        assert_shows_the_document(h);
    };
    open(
        &mut h,
        [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
    );
    let before = h
        .state()
        .session
        .frame
        .as_ref()
        .expect("a frame")
        .linear_image()
        .into_owned();
    // The same scene file, its model re-exported with the triangle turned over.
    open(
        &mut h,
        [[-1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, -1.0, 0.0]],
    );
    assert_ne!(
        *h.state()
            .session
            .frame
            .as_ref()
            .expect("a frame")
            .linear_image(),
        before
    );
}
