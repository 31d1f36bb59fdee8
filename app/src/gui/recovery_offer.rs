//! The offer, on the first start after a crash, to restore the work that
//! was autosaved: which file, when, and Restore or Discard.

use super::doc::recovery::{self, Left};
use std::path::Path;
use std::time::SystemTime;

/// The user's answer to the offer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// Open the recovered scene as an unsaved document.
    Restore,
    /// Delete the recovery file.
    Discard,
}

/// Shows the offer for `left` (`now` being the time); the answer once given.
pub fn show(ctx: &egui::Context, left: &Left, now: SystemTime) -> Option<Answer> {
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
