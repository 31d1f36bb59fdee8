//! Errors that point at the place in a scene file where the problem is.

use std::fmt;

/// A problem in a scene file, shown as `FILE:LINE:COL: what is wrong and what was expected`.
///
/// The shown error is always one line: control characters in the file name
/// or the message (a newline in an end tag's name, say) are shown escaped,
/// and a message that quotes a huge value is shortened (see [`elide`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}:{line}:{column}: {}", OneLine(file), elide(.message))]
pub struct SceneError {
    /// The file's path as the user gave it (or a label such as `<string>`).
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
    /// What is wrong and what was expected.
    pub message: String,
}

/// A problem with a scene as a whole (no file position), e.g. a scene built in
/// code that names a material nobody defined.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct InvalidScene(pub String);

/// Shows text on one line: control characters (newlines, tabs, NUL…), which
/// may come from the file being read, are written as escapes (`\n`).
pub(crate) struct OneLine<'a>(pub &'a str);

impl fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_default())?;
            } else {
                write!(f, "{c}")?;
            }
        }
        Ok(())
    }
}

/// The longest message shown whole, in characters.
const SHOWN_CHARS: usize = 300;

/// `message` on one line ([`OneLine`]) and at most about [`SHOWN_CHARS`]
/// characters: a longer one (it quotes a 100 000-digit number, say) keeps its
/// start and its end, which says what was expected, and counts what it leaves out.
pub fn elide(message: &str) -> String {
    let one_line = OneLine(message).to_string();
    let count = one_line.chars().count();
    if count <= SHOWN_CHARS {
        return one_line;
    }
    let (head, tail) = (SHOWN_CHARS * 2 / 3, SHOWN_CHARS / 4);
    let start: String = one_line.chars().take(head).collect();
    let end: String = one_line.chars().skip(count - tail).collect();
    format!(
        "{start}…[{} characters left out]…{end}",
        count - head - tail
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_shown_escaped() {
        assert_eq!(OneLine("a\nb\r\tc\0é").to_string(), "a\\nb\\r\\tc\\u{0}é");
    }

    #[test]
    fn an_end_tag_name_with_a_newline_gives_a_one_line_error() {
        // Found by fuzzing (xml_scene): the end tag's name, shown in the
        // message, was "\n".
        let e = crate::read_str("</\n>", "fuzz.xml").expect_err("no <scene>");
        let shown = e.to_string();
        assert!(!shown.contains('\n'), "{shown:?}");
        assert!(shown.starts_with("fuzz.xml:1:1: "), "{shown:?}");
        assert!(shown.contains("</\\n>"), "{shown:?}");
    }

    #[test]
    fn long_messages_keep_their_start_and_end_on_one_line() {
        let long = format!(
            "radius got \"{}\" (it must be finite)\nsecond",
            "9".repeat(10_000)
        );
        let shown = elide(&long);
        assert!(shown.chars().count() < SHOWN_CHARS + 40, "{shown}");
        assert!(shown.starts_with("radius got \"999"), "{shown}");
        assert!(shown.ends_with("(it must be finite)\\nsecond"), "{shown}");
        assert!(!shown.contains('\n'));
        assert_eq!(elide("short"), "short");
    }

    #[test]
    fn a_model_whose_file_name_has_a_newline_gives_a_one_line_error() {
        let e = crate::load_model_bytes(b"not json".to_vec(), std::path::Path::new("a\nb.gltf"))
            .expect_err("not glTF");
        let shown = e.to_string();
        assert!(!shown.contains('\n'), "{shown:?}");
        assert!(shown.starts_with("a\\nb.gltf: "), "{shown:?}");
    }
}
