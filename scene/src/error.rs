//! Errors that point at the place in a scene file where the problem is.

/// A problem in a scene file, shown as `FILE:LINE:COL: what is wrong and what was expected`
/// (one line; a message that quotes a huge value is shortened, see [`elide`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{column}: {}", elide(.message))]
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

/// The longest message shown whole, in characters.
const SHOWN_CHARS: usize = 300;

/// `message` on one line and at most about [`SHOWN_CHARS`] characters: a
/// longer one (it quotes a 100 000-digit number, say) keeps its start and its
/// end, which says what was expected, and counts what it leaves out.
pub fn elide(message: &str) -> String {
    let one_line = message.replace(['\n', '\r'], " ");
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
    fn long_messages_keep_their_start_and_end_on_one_line() {
        let long = format!(
            "radius got \"{}\" (it must be finite)\nsecond",
            "9".repeat(10_000)
        );
        let shown = elide(&long);
        assert!(shown.chars().count() < SHOWN_CHARS + 40, "{shown}");
        assert!(shown.starts_with("radius got \"999"), "{shown}");
        assert!(shown.ends_with("(it must be finite) second"), "{shown}");
        assert!(!shown.contains('\n'));
        assert_eq!(elide("short"), "short");
    }
}
