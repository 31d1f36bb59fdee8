//! PLACEHOLDER (being written): the XML scene reader.
use crate::{Scene, SceneError};
use std::path::Path;
/// Parses scene XML; `file` labels error messages.
pub fn read_str(_text: &str, file: &str) -> Result<Scene, SceneError> {
    Err(SceneError { file: file.into(), line: 1, column: 1, message: "reader not written yet".into() })
}
/// Reads and parses a scene file.
pub fn read_file(path: &Path) -> Result<Scene, SceneError> {
    let label = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SceneError { file: label.clone(), line: 1, column: 1, message: format!("cannot read the file: {e}") })?;
    read_str(&text, &label)
}
