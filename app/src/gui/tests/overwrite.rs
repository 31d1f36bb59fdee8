//! Headless UI tests (egui_kittest): saving an image never replaces an
//! existing file unasked, and a save says where it went.

use super::{harness, seed_app, settle, step_shown};
use crate::gui::files::dialogs::DialogKind;
use egui_kittest::kittest::Queryable;

#[test]
fn the_suggested_image_name_is_free_and_saving_it_keeps_the_earlier_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32));
    h.state_mut().doc.path = Some(dir.path().join("seed.xml"));
    settle(&mut h);
    let earlier = dir.path().join("seed-2spp.png");
    std::fs::write(&earlier, "an earlier image").expect("write");
    // No file dialog here: the path prompt starts from the suggestion.
    h.state_mut().files().prompt_for_path(DialogKind::SaveImage);
    let free = dir.path().join("seed-2spp-2.png");
    assert_eq!(
        h.state().files.path_prompt,
        Some((DialogKind::SaveImage, free.display().to_string()))
    );
    step_shown(&mut h);
    h.get_by_label("OK").click();
    h.step();
    assert_eq!(h.state().files.message, None);
    assert_eq!(
        std::fs::read_to_string(&earlier).expect("read"),
        "an earlier image"
    );
    let written = image::open(&free).expect("a PNG").to_rgb8();
    assert_eq!(written.dimensions(), (48, 32));
    // The status bar says where it went, for a few seconds.
    step_shown(&mut h);
    let note = format!("Saved the image to {}", free.display());
    assert!(
        h.query_by_label(&note).is_some(),
        "the status bar shows {note:?}"
    );
}

#[test]
fn saving_the_scene_says_so_in_the_status_bar() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let path = dir.path().join("mine.xml");
    h.state_mut().files.path_prompt = Some((DialogKind::SaveScene, path.display().to_string()));
    step_shown(&mut h);
    h.get_by_label("OK").click();
    step_shown(&mut h);
    assert!(path.is_file(), "the scene was written");
    let note = format!("Saved {}", path.display());
    assert!(
        h.query_by_label(&note).is_some(),
        "the status bar shows {note:?}"
    );
}

#[test]
fn typing_the_name_of_an_existing_image_asks_to_replace_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut h = harness(seed_app(48, 32));
    settle(&mut h);
    let existing = dir.path().join("shot.png");
    std::fs::write(&existing, "an earlier image").expect("write");
    h.state_mut().files.path_prompt = Some((DialogKind::SaveImage, existing.display().to_string()));
    step_shown(&mut h);
    h.get_by_label("This file exists: Replace overwrites it.");
    assert!(h.query_by_label("OK").is_none());
    h.get_by_label("Replace").click();
    h.step();
    image::open(&existing).expect("replaced by a PNG, as asked");
}

#[test]
fn saving_a_scene_to_another_folder_keeps_its_render_going() {
    // sky.xml names its map "sky_map.exr" beside it; saved elsewhere, the
    // scene names the same file by its absolute path. Same samples: the
    // render must not start over.
    let sky = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/reference/sky.xml");
    let mut scene = scene::read_file(&sky).expect("sky.xml loads");
    (scene.camera.width, scene.camera.height) = (48, 32);
    let mut app = crate::gui::RaylabApp::new(scene, Some(sky));
    app.doc.state.render.target_spp = Some(2);
    app.doc.history = crate::gui::doc::history::History::new(&app.doc.state);
    let mut h = harness(app);
    settle(&mut h);
    let generation = h.state().session.generation;
    let before = h.state().doc.state.scene.clone();
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("sky-copy.xml");
    h.state_mut().files.path_prompt = Some((DialogKind::SaveScene, path.display().to_string()));
    step_shown(&mut h);
    h.get_by_label("OK").click();
    step_shown(&mut h);
    assert!(path.is_file(), "the scene was written");
    assert_ne!(
        h.state().doc.state.scene,
        before,
        "the map is named from the new folder"
    );
    assert_eq!(
        h.state().session.generation,
        generation,
        "the same job goes on"
    );
}
