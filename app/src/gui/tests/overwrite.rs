//! Headless UI tests (egui_kittest): saving an image never replaces an
//! existing file unasked.

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
