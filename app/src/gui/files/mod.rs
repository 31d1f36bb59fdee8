//! The file workflow: new, open, save and save as, saving the image,
//! choosing a reference; asking "save changes?" before unsaved work is
//! replaced or closed; native file dialogs, or a typed path where there are
//! none; and the messages of what failed.
//!
//! [`FileWorkflow`] is the workflow's own state, kept in the app; [`Files`]
//! is that state at work on the parts of the app it reads and changes. What
//! only the app can do (put another document in place, load a reference
//! into the error plot) comes back as an [`Outcome`].

pub mod dialogs;
mod modals;

use super::doc::document::Document;
use super::settings::Settings;
use super::viewport::screenshot;
use crate::io::output::Provenance;
use dialogs::{DialogKind, DialogResult, Dialogs};
use renderer::Camera;
use renderer::progressive::RenderedFrame;
use scene::Scene;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What waits for the user's answer to "save changes?".
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    /// Open this file.
    Open(PathBuf),
    /// Ask for a file to open.
    OpenDialog,
    /// Start a new scene.
    New,
    /// Close the window.
    Close,
}

/// What a step of the workflow leaves for the app to do.
#[must_use]
pub enum Outcome {
    /// Nothing.
    Done,
    /// Put this document in place of the open one (new or opened).
    Replace(Box<Document>),
    /// Load this reference image for the live error plot.
    LoadReference(PathBuf),
    /// Make the environment map in this file the sky's.
    LoadSkyMap(PathBuf),
}

/// The workflow's state between frames.
#[derive(Default)]
pub struct FileWorkflow {
    /// The open file dialog, if any.
    dialogs: Dialogs,
    /// An action waiting for "save changes?".
    pub guard: Option<Pending>,
    /// An action to carry out once a Save As dialog has saved.
    after_save: Option<Pending>,
    /// Closing the window was confirmed.
    pub allow_close: bool,
    /// A message for the user (a failed open or save), shown until dismissed.
    pub message: Option<String>,
    /// A passing note ("Saved …"), shown in the status bar for
    /// [`NOTE_DURATION`] from when it was made.
    note: Option<(String, Instant)>,
    /// A path typed by the user when no file dialog is available.
    pub path_prompt: Option<(DialogKind, String)>,
}

/// How long a note stays in the status bar.
pub const NOTE_DURATION: Duration = Duration::from_secs(5);

impl FileWorkflow {
    /// Shows `text` in the status bar for a few seconds.
    pub fn note(&mut self, text: String) {
        self.note = Some((text, Instant::now()));
    }

    /// The note to show now, and for how much longer.
    pub fn current_note(&self) -> Option<(&str, Duration)> {
        let (text, at) = self.note.as_ref()?;
        let left = NOTE_DURATION.checked_sub(at.elapsed())?;
        Some((text.as_str(), left))
    }

    /// Holds a close of the window asked for with unsaved changes, to ask
    /// first ("save changes?"), unless closing was already confirmed.
    pub fn hold_close(&mut self, ctx: &egui::Context, doc: &Document) {
        if ctx.input(|i| i.viewport().close_requested()) && !self.allow_close && doc.is_modified() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.guard = Some(Pending::Close);
        }
    }
}

/// The file workflow at work on the app's document and settings, with the
/// image on screen (what Save Image writes).
pub struct Files<'a> {
    /// The workflow's state.
    pub flow: &'a mut FileWorkflow,
    /// The open document.
    pub doc: &'a mut Document,
    /// Recent files and the last folder.
    pub settings: &'a mut Settings,
    /// The frame on screen.
    pub frame: Option<&'a RenderedFrame>,
    /// The camera of the newest prepared world.
    pub camera: Option<&'a Camera>,
}

impl Files<'_> {
    /// Carries out `pending` now, or first asks about unsaved changes.
    pub fn guarded(&mut self, ctx: &egui::Context, pending: Pending) -> Outcome {
        if self.doc.is_modified() {
            self.flow.guard = Some(pending);
            Outcome::Done
        } else {
            self.proceed(ctx, pending)
        }
    }

    /// Carries out an action that no longer needs to ask.
    fn proceed(&mut self, ctx: &egui::Context, pending: Pending) -> Outcome {
        match pending {
            Pending::Open(path) => self.open(&path),
            Pending::OpenDialog => {
                self.start_dialog(ctx, DialogKind::Open);
                Outcome::Done
            }
            Pending::New => Outcome::Replace(Box::new(Document::new(
                Scene::default(),
                None,
                self.doc.state.render,
            ))),
            Pending::Close => {
                // Closing without saving discards the changes; `on_exit`
                // removes the recovery file of a close allowed here.
                self.flow.allow_close = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                Outcome::Done
            }
        }
    }

    /// Reads the scene file at `path`, to replace the document; a file that
    /// cannot be read leaves the current document as it is and says why.
    fn open(&mut self, path: &Path) -> Outcome {
        match Document::open(path, self.doc.state.render) {
            Ok(doc) => {
                let warnings = model_warnings_text(&doc.state.scene);
                self.settings.remember(path);
                if !warnings.is_empty() {
                    self.flow.message = Some(format!("Loaded, but raylab ignored:\n\n{warnings}"));
                }
                Outcome::Replace(Box::new(doc))
            }
            Err(e) => {
                self.flow.message = Some(format!("Cannot open the scene.\n\n{e}"));
                Outcome::Done
            }
        }
    }

    /// Saves to the document's file, or asks where when it has none.
    pub fn save(&mut self, ctx: &egui::Context) {
        match self.doc.path.clone() {
            Some(path) => {
                self.save_scene(&path);
            }
            None => self.start_dialog(ctx, DialogKind::SaveScene),
        }
    }

    /// Saves the scene to `path`; true when it was saved.
    fn save_scene(&mut self, path: &Path) -> bool {
        match self.doc.save_as(path) {
            Ok(()) => {
                self.settings.remember(path);
                self.flow.note(format!("Saved {}", path.display()));
                true
            }
            Err(e) => {
                self.flow.message = Some(format!(
                    "Cannot save {}: {e}\n\nThe file on disk is unchanged; the changes are \
                     still unsaved.",
                    path.display()
                ));
                false
            }
        }
    }

    /// Writes the image on screen to `path`.
    pub fn save_image(&mut self, path: &Path) {
        let (Some(frame), Some(camera)) = (self.frame, self.camera) else {
            return;
        };
        let provenance = Provenance::of_render(
            camera,
            self.doc.path.as_deref(),
            screenshot::spp_of(frame.step),
        );
        match screenshot::save(path, frame, &provenance) {
            Ok(()) => {
                self.settings.last_folder = path.parent().map(Path::to_path_buf);
                self.flow
                    .note(format!("Saved the image to {}", path.display()));
            }
            Err(e) => self.flow.message = Some(format!("Cannot save the image: {e:#}")),
        }
    }

    /// The folder a file dialog starts in: the scene's, else the last one used.
    fn dialog_folder(&self) -> Option<PathBuf> {
        self.doc
            .folder()
            .map(Path::to_path_buf)
            .or_else(|| self.settings.last_folder.clone())
    }

    /// The file name a save dialog of `kind` suggests in `folder`. An
    /// image's is free there (`seed-64spp.png`, else `seed-64spp-2.png`, …),
    /// so accepting the suggestion never replaces an earlier image.
    fn suggested_name(&self, kind: DialogKind, folder: Option<&Path>) -> Option<String> {
        match kind {
            DialogKind::Open | DialogKind::Reference | DialogKind::SkyMap => None,
            DialogKind::SaveScene => Some(self.doc.scene_file_name()),
            DialogKind::SaveImage => self.frame.map(|f| {
                let name = self.doc.display_name();
                let name = screenshot::default_file_name(&name, f.step, f.legend.display);
                let free = crate::io::output_path::free_file(
                    &folder.unwrap_or(Path::new(".")).join(&name),
                );
                free.file_name()
                    .map_or(name, |n| n.to_string_lossy().into_owned())
            }),
        }
    }

    /// Opens a native file dialog of `kind` in the scene's or the last
    /// folder. The system's save dialog (the xdg portal's, or zenity's with
    /// --confirm-overwrite) asks before replacing a file.
    pub fn start_dialog(&mut self, ctx: &egui::Context, kind: DialogKind) {
        let folder = self.dialog_folder();
        let name = self.suggested_name(kind, folder.as_deref());
        self.flow.dialogs.start(ctx, kind, folder.as_deref(), name);
    }

    /// Asks for the path of a file of `kind` by typing, where no file dialog
    /// can be shown; a save starts from the name a dialog would suggest.
    pub fn prompt_for_path(&mut self, kind: DialogKind) {
        let start = match kind {
            DialogKind::Open | DialogKind::SkyMap => String::new(),
            _ => {
                let folder = self.dialog_folder();
                let name = self.suggested_name(kind, folder.as_deref());
                match (folder, name) {
                    (Some(f), Some(n)) => f.join(n).display().to_string(),
                    (Some(f), None) => format!("{}/", f.display()),
                    (None, n) => n.unwrap_or_default(),
                }
            }
        };
        self.flow.path_prompt = Some((kind, start));
    }

    /// The file chosen in a dialog that closed, if one was; a dialog that
    /// could not be shown becomes the path prompt.
    pub fn poll_dialogs(&mut self) -> Option<(DialogKind, PathBuf)> {
        match self.flow.dialogs.poll() {
            Some(DialogResult::Chosen(kind, path)) => return Some((kind, path)),
            Some(DialogResult::Unavailable(kind)) => self.prompt_for_path(kind),
            Some(DialogResult::Cancelled) => self.flow.after_save = None,
            None => {}
        }
        None
    }

    /// Acts on a file chosen in a dialog or typed into the path prompt.
    pub fn chosen(&mut self, ctx: &egui::Context, kind: DialogKind, path: PathBuf) -> Outcome {
        match kind {
            DialogKind::Open => self.open(&path),
            DialogKind::SaveScene => {
                let saved = self.save_scene(&path);
                // What waited for this save goes ahead only if it succeeded.
                match self.flow.after_save.take() {
                    Some(pending) if saved => self.proceed(ctx, pending),
                    _ => Outcome::Done,
                }
            }
            DialogKind::SaveImage => {
                self.save_image(&path);
                Outcome::Done
            }
            DialogKind::Reference => Outcome::LoadReference(path),
            DialogKind::SkyMap => Outcome::LoadSkyMap(path),
        }
    }
}

/// What the scene's model files use that raylab ignores, one line each
/// (empty when nothing was ignored).
fn model_warnings_text(scene: &Scene) -> String {
    scene
        .model_warnings()
        .into_iter()
        .flat_map(|(src, warnings)| warnings.into_iter().map(move |w| format!("{src}: {w}")))
        .collect::<Vec<_>>()
        .join("\n")
}
