//! Native file dialogs (rfd) run off the UI thread, and the settings kept
//! between runs: recent files and the last folder.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// What a file dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DialogKind {
    /// Pick a scene file to open.
    Open,
    /// Pick where to save the scene.
    SaveScene,
    /// Pick where to save the rendered image.
    SaveImage,
    /// Pick a reference image (linear EXR) for the live error plot.
    Reference,
}

/// A dialog that answered too quickly to have been shown: no dialog service.
const UNANSWERED: Duration = Duration::from_millis(150);

/// The one file dialog that may be open, run on its own thread.
#[derive(Default)]
pub struct Dialogs {
    pending: Option<(DialogKind, Instant, mpsc::Receiver<Option<PathBuf>>)>,
}

/// The result of a finished dialog.
#[derive(Clone, Debug, PartialEq)]
pub enum DialogResult {
    /// The user chose this file.
    Chosen(DialogKind, PathBuf),
    /// The user cancelled.
    Cancelled,
    /// No dialog could be shown (no portal or zenity on this system).
    Unavailable(DialogKind),
}

impl Dialogs {
    /// True while a dialog is open.
    pub fn is_open(&self) -> bool {
        self.pending.is_some()
    }

    /// Opens a dialog of `kind` in `folder`, suggesting `file_name` when saving.
    pub fn start(
        &mut self,
        ctx: &egui::Context,
        kind: DialogKind,
        folder: Option<&Path>,
        file_name: Option<String>,
    ) {
        if self.is_open() {
            return;
        }
        let (send, receive) = mpsc::sync_channel(1);
        let folder = folder.map(Path::to_path_buf);
        let ctx = ctx.clone();
        std::thread::spawn(move || {
            let mut dialog = rfd::FileDialog::new();
            if let Some(folder) = folder {
                dialog = dialog.set_directory(folder);
            }
            if let Some(name) = file_name {
                dialog = dialog.set_file_name(name);
            }
            let chosen = match kind {
                DialogKind::Open => dialog
                    .add_filter("raylab scene or glTF model", &["xml", "gltf", "glb"])
                    .add_filter("any file", &["*"])
                    .pick_file(),
                DialogKind::SaveScene => dialog.add_filter("raylab scene", &["xml"]).save_file(),
                DialogKind::Reference => dialog
                    .add_filter("OpenEXR image (linear float)", &["exr"])
                    .pick_file(),
                DialogKind::SaveImage => dialog
                    .add_filter("PNG image (8-bit sRGB)", &["png"])
                    .add_filter("OpenEXR image (linear float)", &["exr"])
                    .save_file(),
            };
            let _ = send.send(chosen);
            ctx.request_repaint();
        });
        self.pending = Some((kind, Instant::now(), receive));
    }

    /// The dialog's result once it has closed.
    pub fn poll(&mut self) -> Option<DialogResult> {
        let (kind, started, receive) = self.pending.as_ref()?;
        let result = match receive.try_recv() {
            Ok(Some(path)) => DialogResult::Chosen(*kind, path),
            Ok(None) if started.elapsed() < UNANSWERED => DialogResult::Unavailable(*kind),
            Ok(None) | Err(mpsc::TryRecvError::Disconnected) => DialogResult::Cancelled,
            Err(mpsc::TryRecvError::Empty) => return None,
        };
        self.pending = None;
        Some(result)
    }
}

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
