//! Native file dialogs (rfd), run off the UI thread: one at a time, and
//! said to be unavailable when it answers too quickly to have been shown.

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
    /// Pick an environment map (HDR, latitude-longitude) for the sky.
    SkyMap,
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
                DialogKind::SkyMap => dialog
                    .add_filter("HDR environment map (OpenEXR, Radiance)", &["exr", "hdr"])
                    .add_filter("any file", &["*"])
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
