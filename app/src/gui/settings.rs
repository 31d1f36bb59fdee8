//! What the window remembers between runs (eframe persistence): recent
//! files and the last folder.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// How many recent files are remembered.
const MAX_RECENT: usize = 10;

/// What the window remembers between runs (eframe persistence).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// Recently opened or saved scene files, newest first.
    pub recent: Vec<PathBuf>,
    /// The folder of the last file opened or saved.
    pub last_folder: Option<PathBuf>,
}

impl Settings {
    /// The key the settings are stored under.
    pub const KEY: &'static str = "raylab-settings";

    /// Puts `path` first in the recent list and remembers its folder.
    pub fn remember(&mut self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.recent.retain(|p| *p != path);
        self.recent.insert(0, path.clone());
        self.recent.truncate(MAX_RECENT);
        self.last_folder = path.parent().map(Path::to_path_buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recent_files_are_newest_first_without_repeats_and_bounded() {
        let mut s = Settings::default();
        for i in 0..15 {
            s.remember(Path::new(&format!("/scenes/{i}.xml")));
        }
        s.remember(Path::new("/scenes/12.xml"));
        assert_eq!(s.recent.len(), MAX_RECENT);
        assert_eq!(s.recent[0], Path::new("/scenes/12.xml"));
        assert_eq!(s.recent[1], Path::new("/scenes/14.xml"));
        assert_eq!(s.recent.iter().filter(|p| p.ends_with("12.xml")).count(), 1);
        assert_eq!(s.last_folder.as_deref(), Some(Path::new("/scenes")));
    }
}
