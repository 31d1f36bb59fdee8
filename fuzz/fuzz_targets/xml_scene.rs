//! Fuzzes the XML scene reader, `scene::read_str`.
//!
//! Property: for any UTF-8 text the reader returns, never panics, and
//! - an error is one line, `fuzz.xml:LINE:COL: message`, whose line and column
//!   lie inside the text (a column may point just past its line's last
//!   character), with a non-empty message: the check of
//!   `scene/tests/no_panic.rs`;
//! - an accepted scene, written back with `scene::write_string`, reads again
//!   to the same scene (load → save → load, as `scene/tests/round_trip.rs`
//!   checks for generated scenes).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    match scene::read_str(text, "fuzz.xml") {
        Err(e) => check_error(text, &e),
        Ok(scene) => {
            let written = scene::write_string(&scene);
            match scene::read_str(&written, "fuzz.xml") {
                Ok(again) => assert_eq!(again, scene, "round trip changed the scene:\n{written}"),
                Err(e) => panic!("the written scene does not read back: {e}\n{written}"),
            }
        }
    }
});

/// The error is one line pointing inside `text`.
fn check_error(text: &str, e: &scene::SceneError) {
    let shown = e.to_string();
    assert!(!shown.contains('\n'), "error spans lines: {shown:?}");
    assert!(shown.starts_with("fuzz.xml:"), "error without the file: {shown:?}");
    let lines: Vec<&str> = text.split('\n').collect();
    assert!(e.line >= 1 && e.line <= lines.len(), "line of {shown:?}");
    let width = lines[e.line - 1].chars().count();
    assert!(e.column >= 1 && e.column <= width + 1, "column of {shown:?}");
    assert!(!e.message.is_empty(), "empty message");
}
