//! Errors that point at the place in a scene file where the problem is.

use std::fmt;

/// A problem in a scene file, shown as `FILE:LINE:COL: what is wrong and what was expected`.
///
/// The shown error is always one line: control characters in the file name
/// or the message (a newline in an end tag's name, say) are shown escaped.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}:{line}:{column}: {}", OneLine(file), OneLine(message))]
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
}
