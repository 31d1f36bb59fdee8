//! Helpers shared by the error tests.
#![allow(dead_code)]

use scene::{SceneError, read_str};

/// Reads `text`, which must fail; returns the error.
pub fn fail(text: &str) -> SceneError {
    match read_str(text, "bad.xml") {
        Ok(s) => panic!("expected an error, got {s:?}\n--- input ---\n{text}"),
        Err(e) => e,
    }
}

/// Asserts that `text` fails at `line:column` with a message containing `phrase`.
#[track_caller]
pub fn assert_error(text: &str, line: usize, column: usize, phrase: &str) {
    let e = fail(text);
    assert_eq!(
        (e.line, e.column),
        (line, column),
        "position of: {e}\n--- input ---\n{text}"
    );
    assert!(
        e.message.contains(phrase),
        "message {:?} lacks {phrase:?}",
        e.message
    );
    assert_eq!(e.file, "bad.xml");
}

/// A scene whose second line is `line` (between `<scene>` and `</scene>` lines).
pub fn in_scene(line: &str) -> String {
    format!("<scene>\n{line}\n</scene>\n")
}
