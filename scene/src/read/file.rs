//! Reading a scene from a file.

use super::position::Locator;
use super::read_str;
use crate::{Scene, SceneError};
use std::path::Path;

/// The largest scene file raylab reads (64 MiB; scenes are small, meshes
/// live in model files): anything longer is refused before it is read whole.
pub const MAX_SCENE_BYTES: usize = 64 << 20;

/// Reads and parses a scene file; a file that cannot be read (or is not
/// UTF-8) is an error at 1:1 (or at the first invalid byte) saying why.
pub fn read_file(path: &Path) -> Result<Scene, SceneError> {
    let label = path.display().to_string();
    let error = |line, column, message| SceneError {
        file: label.clone(),
        line,
        column,
        message,
    };
    let bytes =
        crate::bounded_read::read_limited(path, MAX_SCENE_BYTES).map_err(|e| error(1, 1, e))?;
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => {
            let valid = e
                .as_bytes()
                .get(..e.utf8_error().valid_up_to())
                .unwrap_or(&[]);
            let prefix = String::from_utf8_lossy(valid);
            let (line, column) = Locator {
                text: &prefix,
                file: &label,
            }
            .line_column(prefix.len());
            return Err(error(
                line,
                column,
                "the file is not valid UTF-8 text".into(),
            ));
        }
    };
    read_str(&text, &label)
}
