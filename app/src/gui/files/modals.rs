//! The file workflow's three modals: "save changes?", a message until it
//! is dismissed, and the path prompt where no file dialog can be shown.

use super::dialogs::DialogKind;
use super::{FileWorkflow, Files, Outcome, Pending};
use std::path::{Path, PathBuf};

impl Files<'_> {
    /// "Save changes?" for the action waiting in the guard.
    pub fn guard_modal(&mut self, ctx: &egui::Context) -> Outcome {
        let Some(pending) = self.flow.guard.clone() else {
            return Outcome::Done;
        };
        let what = match &pending {
            Pending::Close => "closing",
            Pending::New => "starting a new scene",
            Pending::Open(_) | Pending::OpenDialog => "opening another scene",
        };
        let mut answer = None;
        egui::Modal::new(egui::Id::unique("unsaved-changes")).show(ctx, |ui| {
            ui.heading("Unsaved changes");
            ui.label(format!(
                "Save the changes to {} before {what}?",
                self.doc.display_name()
            ));
            ui.horizontal(|ui| {
                if ui.button("Save").clicked() {
                    answer = Some("save");
                }
                if ui.button("Don't save").clicked() {
                    answer = Some("discard");
                }
                if ui.button("Cancel").clicked() {
                    answer = Some("cancel");
                }
            });
        });
        match answer {
            Some("save") => {
                self.flow.guard = None;
                match self.doc.path.clone() {
                    Some(path) => {
                        if self.save_scene(&path) {
                            return self.proceed(ctx, pending);
                        }
                    }
                    None => {
                        self.flow.after_save = Some(pending);
                        self.start_dialog(ctx, DialogKind::SaveScene);
                    }
                }
            }
            Some("discard") => {
                self.flow.guard = None;
                return self.proceed(ctx, pending);
            }
            Some(_) => self.flow.guard = None,
            None => {}
        }
        Outcome::Done
    }
}

impl FileWorkflow {
    /// A message (failed open or save) until dismissed.
    pub fn message_modal(&mut self, ctx: &egui::Context) {
        let Some(message) = &self.message else {
            return;
        };
        let mut dismissed = false;
        egui::Modal::new(egui::Id::unique("message")).show(ctx, |ui| {
            ui.set_max_width(520.0);
            ui.label(message.as_str());
            dismissed = ui.button("OK").clicked();
        });
        if dismissed {
            self.message = None;
        }
    }

    /// Where no native dialog is available: type the file's path. Returns
    /// the path once entered.
    pub fn path_prompt_modal(&mut self, ctx: &egui::Context) -> Option<(DialogKind, PathBuf)> {
        let (kind, text) = self.path_prompt.as_mut()?;
        let kind = *kind;
        let mut answer = None;
        egui::Modal::new(egui::Id::unique("path-prompt")).show(ctx, |ui| {
            ui.label(match kind {
                DialogKind::Open => "Open scene file:",
                DialogKind::SaveScene => "Save scene as:",
                DialogKind::SaveImage => "Save image as (.png or .exr):",
                DialogKind::Reference => "Reference image (linear .exr):",
                DialogKind::SkyMap => "Environment map (.exr or .hdr):",
            });
            ui.weak("No file dialog is available here (xdg-desktop-portal or zenity).");
            let edit = ui.add(egui::TextEdit::singleline(text).desired_width(480.0));
            // No dialog to confirm it: replacing a file is said, and the button says it.
            let saving = matches!(kind, DialogKind::SaveScene | DialogKind::SaveImage);
            let replaces = saving && Path::new(text.trim()).is_file();
            if replaces {
                ui.colored_label(
                    ui.visuals().warn_fg_color,
                    "This file exists: Replace overwrites it.",
                );
            }
            let entered =
                edit.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) && !replaces;
            ui.horizontal(|ui| {
                let ok = if replaces { "Replace" } else { "OK" };
                if ui.button(ok).clicked() || entered {
                    answer = Some(true);
                }
                if ui.button("Cancel").clicked() {
                    answer = Some(false);
                }
            });
        });
        match answer {
            Some(true) => {
                let path = self
                    .path_prompt
                    .take()
                    .map(|(_, t)| PathBuf::from(t.trim()));
                path.filter(|p| !p.as_os_str().is_empty())
                    .map(|path| (kind, path))
            }
            Some(false) => {
                self.path_prompt = None;
                self.after_save = None;
                None
            }
            None => None,
        }
    }
}
