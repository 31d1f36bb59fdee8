//! Turning byte offsets into `line:column` positions and errors.

use crate::SceneError;

/// The text being read and its label; makes [`SceneError`]s at byte offsets.
pub(crate) struct Locator<'t> {
    /// The text (after any byte-order mark); every offset is relative to it.
    pub text: &'t str,
    /// The file label used in messages.
    pub file: &'t str,
}

impl<'t> Locator<'t> {
    /// The byte offset of `part` in the text, if `part` is a slice of it.
    pub fn offset_of(&self, part: &str) -> Option<usize> {
        let base = self.text.as_ptr() as usize;
        let at = part.as_ptr() as usize;
        (at >= base && at + part.len() <= base + self.text.len()).then(|| at - base)
    }

    /// The 1-based line and column (in characters) of a byte offset, clamped
    /// to the text.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let mut end = offset.min(self.text.len());
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let before = self.text.get(..end).unwrap_or("");
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before.get(line_start..).unwrap_or("").chars().count() + 1;
        (line, column)
    }

    /// An error at a byte offset.
    pub fn error(&self, offset: usize, message: impl Into<String>) -> SceneError {
        let (line, column) = self.line_column(offset);
        SceneError {
            file: self.file.to_owned(),
            line,
            column,
            message: message.into(),
        }
    }

    /// "line L, column C" of an offset, for messages that refer to another place.
    pub fn describe(&self, offset: usize) -> String {
        let (line, column) = self.line_column(offset);
        format!("line {line}, column {column}")
    }
}
