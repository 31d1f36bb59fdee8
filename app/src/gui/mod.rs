//! The desktop window: menu bar, camera and render panel, scene panel, the
//! progressively refined image and a status bar. The UI thread never
//! renders: after every edit it snapshots the scene for the progressive
//! session and shows the newest frame the session hands back.
//!
//! Where things are:
//! - `app`: [`RaylabApp`], the layout of a frame, and every command carried
//!   out in one place;
//! - `commands`: everything the user can ask, from the menu bar, the
//!   toolbar, buttons, keys and dropped files;
//! - `session`: the render session kept in step with the document;
//! - `inspector`: the inspected pixel, its ray tree and the inspector panel
//!   (docked under the image);
//! - `files`: new, open, save, dialogs and "save changes?"; `settings`:
//!   what is remembered between runs;
//! - `crash_recovery`: autosave, and the offer of a crashed run's work;
//! - `doc`: the document (scene, settings, undo, edits, autosave and
//!   recovery files), without egui;
//! - `panels`: the panels around the image, the status bar, the help;
//! - `viewport`: the image, its legend, picking, camera moves, screenshots;
//! - `debug_view`: the 3D debug view;
//! - `startup`: the scene the window opens on, or the error why not;
//! - `bench`: the window's benchmarks, driven headless; `tests`: its
//!   headless UI tests.

mod app;
pub mod bench;
mod commands;
mod crash_recovery;
mod debug_view;
mod doc;
mod files;
mod inspector;
mod panels;
mod session;
mod settings;
pub mod startup;
mod viewport;
pub mod worker_priority;

#[cfg(test)]
mod tests;

pub use app::RaylabApp;
pub use doc::document::Document;
pub use doc::recovery::default_dir as recovery_dir;
