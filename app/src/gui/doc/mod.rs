//! The document behind the window, without egui: the scene being edited
//! with its render settings and undo history, the structural edits, and the
//! autosave and recovery files that keep unsaved work safe from a crash.

pub mod autosave;
pub mod change;
pub mod document;
pub mod edits;
pub mod history;
pub mod recovery;
