//! Keeping unsaved work safe from a crash: while the document has unsaved
//! changes it is autosaved to this run's recovery file (see
//! [`super::doc::autosave`]), and on the first start after a crash the work
//! that run autosaved is offered back: which file, when, and Restore or
//! Discard.

use super::doc::autosave::{self, Autosave};
use super::doc::document::{Document, RenderSettings};
use super::doc::recovery::{self, Left};
use std::path::Path;
use std::time::{Instant, SystemTime};

/// This run's autosave and the crashed runs' work still to offer.
#[derive(Default)]
pub struct CrashRecovery {
    /// Writes the unsaved scene to a recovery file; `None`: no recovery.
    autosave: Option<Autosave>,
    /// Recovery files of crashed runs still to offer, newest first.
    left_behind: Vec<Left>,
}

/// The user's answer to the offer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Answer {
    /// Open the recovered scene as an unsaved document.
    Restore,
    /// Delete the recovery file.
    Discard,
}

impl CrashRecovery {
    /// Autosaves unsaved changes to a recovery file in `dir` (see
    /// [`recovery`]) and offers what crashed runs left there.
    pub fn in_dir(dir: &Path) -> Self {
        Self {
            left_behind: recovery::left_behind(dir),
            autosave: Some(Autosave::new(dir, autosave::INTERVAL)),
        }
    }

    /// Autosaves `doc` when due at `now`, and asks for a repaint when the
    /// next autosave is due (nothing else may wake the UI by then). Returns
    /// the error of a write that failed, to be told once.
    pub fn autosave_at(
        &mut self,
        ctx: &egui::Context,
        now: Instant,
        doc: &Document,
    ) -> Option<String> {
        let autosave = self.autosave.as_mut()?;
        let poll = autosave.poll(now, doc);
        if let Some(delay) = poll.again_in {
            ctx.request_repaint_after(delay);
        }
        poll.error
    }

    /// The offer to restore a crashed run's work. After a Restore the
    /// others wait for the next start (restoring one more would replace
    /// it). Returns the restored document, with `render` settings, once
    /// the user chose Restore (or why it could not be read); its recovery
    /// file becomes this run's.
    pub fn offer(
        &mut self,
        ctx: &egui::Context,
        render: RenderSettings,
    ) -> Option<Result<Document, String>> {
        let left = self.left_behind.first().cloned()?;
        match show_offer(ctx, &left, SystemTime::now())? {
            Answer::Restore => {
                self.left_behind.clear();
                Some(self.restore(&left, render))
            }
            Answer::Discard => {
                self.left_behind.remove(0);
                let _ = std::fs::remove_file(&left.file);
                None
            }
        }
    }

    /// The recovered scene of `left` as an unsaved document of the file it
    /// belongs to; its recovery file becomes this run's.
    fn restore(&mut self, left: &Left, render: RenderSettings) -> Result<Document, String> {
        match recovery::read(&left.file) {
            Ok((scene, source)) => {
                let doc = Document::recovered(scene.clone(), source.clone(), render);
                if let Some(autosave) = &mut self.autosave {
                    autosave.adopt(&left.file, (scene, source));
                }
                Ok(doc)
            }
            Err(e) => Err(format!("Cannot restore the autosaved work.\n\n{e}")),
        }
    }

    /// At exit: a clean one (nothing unsaved, or the user chose not to
    /// save) leaves nothing to recover; an exit forced past unsaved changes
    /// keeps the file.
    pub fn on_exit(&mut self, clean: bool) {
        if let Some(autosave) = self.autosave.as_mut().filter(|_| clean) {
            autosave.remove();
        }
    }
}

/// Shows the offer for `left` (`now` being the time); the answer once given.
fn show_offer(ctx: &egui::Context, left: &Left, now: SystemTime) -> Option<Answer> {
    let what = match &left.source {
        Some(path) => format!(
            "{} (in {})",
            path.file_name()
                .map_or_else(|| path.display().to_string(), |n| n.display().to_string()),
            path.parent().unwrap_or(Path::new("")).display()
        ),
        None => "a new, unnamed scene".to_owned(),
    };
    let mut answer = None;
    egui::Modal::new(egui::Id::unique("recovery-offer")).show(ctx, |ui| {
        ui.set_max_width(520.0);
        ui.heading("Restore unsaved work?");
        ui.label(format!(
            "raylab did not close normally. Unsaved changes to {what} were autosaved {}.",
            recovery::age(now, left.autosaved)
        ));
        ui.weak(format!("Recovery file: {}", left.file.display()));
        ui.horizontal(|ui| {
            if ui.button("Restore").clicked() {
                answer = Some(Answer::Restore);
            }
            if ui.button("Discard").clicked() {
                answer = Some(Answer::Discard);
            }
        });
    });
    answer
}
