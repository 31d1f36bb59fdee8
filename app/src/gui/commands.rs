//! Everything the user can ask of the window, from the menu bar, the
//! toolbar, a button, a keyboard shortcut or a dropped file, as one enum
//! the app carries out in one place.

use super::doc::edits::Action;
use super::panels::scene_panel;
use egui::{Key, KeyboardShortcut, Modifiers};
use renderer::display::Display;
use std::path::PathBuf;

/// A command from the menu bar, the toolbar, a button, a shortcut or a dropped file.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Start a new, empty scene.
    New,
    /// Ask for a scene file to open.
    Open,
    /// Open this scene file.
    OpenPath(PathBuf),
    /// Save to the document's file (or ask where).
    Save,
    /// Ask where to save the scene.
    SaveAs,
    /// Ask where to save the rendered image.
    SaveImage,
    /// Ask for a reference image for the live error plot.
    LoadReference,
    /// Copy the rendered image to the clipboard.
    CopyImage,
    /// Close the window.
    Quit,
    /// Undo the last edit.
    Undo,
    /// Redo the last undone edit.
    Redo,
    /// A structural scene edit.
    Edit(Action),
    /// Show the image in this display mode.
    Display(Display),
    /// Show the next display mode.
    NextDisplay,
    /// Fit the image into the view.
    Fit,
    /// Show the image at 100 %.
    ActualSize,
    /// Pause refinement, or resume it.
    TogglePause,
    /// Show or hide the help overlay.
    ToggleHelp,
    /// Show or hide the 3D debug view.
    ToggleDebugView,
}

const fn ctrl(key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(Modifiers::COMMAND, key)
}

const fn ctrl_shift(key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(Modifiers::COMMAND.plus(Modifiers::SHIFT), key)
}

/// Shortcuts with Ctrl, checked first (longest modifiers first so
/// Ctrl+Shift+Z is not taken for Ctrl+Z).
const SHORTCUTS: [(KeyboardShortcut, fn() -> Command); 9] = [
    (ctrl_shift(Key::Z), || Command::Redo),
    (ctrl_shift(Key::S), || Command::SaveAs),
    (ctrl(Key::Y), || Command::Redo),
    (ctrl(Key::Z), || Command::Undo),
    (ctrl(Key::S), || Command::Save),
    (ctrl(Key::O), || Command::Open),
    (ctrl(Key::N), || Command::New),
    (ctrl(Key::E), || Command::SaveImage),
    (ctrl(Key::Q), || Command::Quit),
];

/// Single keys, active only while no text field has the keyboard.
const KEYS: [(Key, fn() -> Command); 7] = [
    (Key::F, || Command::Fit),
    (Key::M, || Command::NextDisplay),
    (Key::Num1, || Command::ActualSize),
    (Key::H, || Command::ToggleHelp),
    (Key::G, || Command::ToggleDebugView),
    (Key::Delete, || Command::Edit(Action::Delete)),
    (Key::D, || Command::Edit(Action::Duplicate)),
];

/// The commands asked for by keyboard this frame (the keys are consumed).
pub fn from_keyboard(ctx: &egui::Context) -> Vec<Command> {
    let typing = ctx.text_edit_focused();
    ctx.input_mut(|input| {
        let mut commands = Vec::new();
        for (shortcut, command) in SHORTCUTS {
            if input.consume_shortcut(&shortcut) {
                commands.push(command());
            }
        }
        if !typing {
            for (key, command) in KEYS {
                if input.consume_key(Modifiers::NONE, key) {
                    commands.push(command());
                }
            }
        }
        commands
    })
}

/// The file dropped on the window this frame, to open (the first, if several).
pub fn from_dropped_files(ctx: &egui::Context) -> Option<Command> {
    let dropped: Vec<PathBuf> = ctx.input(|i| {
        i.raw
            .dropped_files
            .iter()
            .map(|f| f.path().to_path_buf())
            .filter(|p| !p.as_os_str().is_empty())
            .collect()
    });
    dropped.into_iter().next().map(Command::OpenPath)
}

/// The toolbar above the image (`debug_shown`: the 3D debug view is
/// shown); returns the command chosen, if any.
pub fn toolbar(ui: &mut egui::Ui, debug_shown: bool) -> Option<Command> {
    let mut shown = debug_shown;
    let toggled = ui
        .horizontal(|ui| {
            ui.toggle_value(&mut shown, "3D debug view")
                .on_hover_text(
                    "The camera, the view window with C00 and its pixel grid, and the \
                     inspected pixel's rays in 3D (G)",
                )
                .clicked()
        })
        .inner;
    toggled.then_some(Command::ToggleDebugView)
}

/// A menu item with its shortcut shown beside it.
fn item(ui: &mut egui::Ui, label: &str, shortcut: Option<KeyboardShortcut>, enabled: bool) -> bool {
    let mut button = egui::Button::new(label);
    if let Some(s) = shortcut {
        button = button.shortcut_text(ui.ctx().format_shortcut(&s));
    }
    ui.add_enabled(enabled, button).clicked()
}

/// What the menu bar needs to know to enable its items.
pub struct MenuState<'a> {
    /// Recent scene files.
    pub recent: &'a [PathBuf],
    /// Undo has something to do.
    pub can_undo: bool,
    /// Redo has something to do.
    pub can_redo: bool,
    /// What Undo would undo ("θ", "orbit"), when known.
    pub undo_name: Option<&'a str>,
    /// What Redo would redo, when known.
    pub redo_name: Option<&'a str>,
    /// An image is on screen.
    pub has_image: bool,
    /// Something is selected.
    pub has_selection: bool,
    /// The display mode chosen.
    pub display: Display,
}

/// The menu bar; returns the command chosen, if any.
pub fn menu_bar(ui: &mut egui::Ui, state: &MenuState) -> Option<Command> {
    let mut chosen = None;
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            let mut pick = |c: Command| chosen = Some(c);
            if item(ui, "New", Some(ctrl(Key::N)), true) {
                pick(Command::New);
            }
            if item(ui, "Open…", Some(ctrl(Key::O)), true) {
                pick(Command::Open);
            }
            ui.menu_button("Open Recent", |ui| {
                if state.recent.is_empty() {
                    ui.weak("no recent files");
                }
                for path in state.recent {
                    if ui.button(path.display().to_string()).clicked() {
                        pick(Command::OpenPath(path.clone()));
                    }
                }
            });
            ui.separator();
            if item(ui, "Save", Some(ctrl(Key::S)), true) {
                pick(Command::Save);
            }
            if item(ui, "Save As…", Some(ctrl_shift(Key::S)), true) {
                pick(Command::SaveAs);
            }
            ui.separator();
            let save_image = match state.display {
                Display::Color => "Save Image…",
                _ => "Save Image (as shown)…",
            };
            if item(ui, save_image, Some(ctrl(Key::E)), state.has_image) {
                pick(Command::SaveImage);
            }
            if item(ui, "Copy Image", None, state.has_image) {
                pick(Command::CopyImage);
            }
            ui.separator();
            if item(ui, "Quit", Some(ctrl(Key::Q)), true) {
                pick(Command::Quit);
            }
        });
        ui.menu_button("Edit", |ui| {
            let named = |verb: &str, name: Option<&str>| match name {
                Some(name) => format!("{verb} {name}"),
                None => verb.to_owned(),
            };
            if item(ui, &named("Undo", state.undo_name), Some(ctrl(Key::Z)), state.can_undo) {
                chosen = Some(Command::Undo);
            }
            if item(ui, &named("Redo", state.redo_name), Some(ctrl_shift(Key::Z)), state.can_redo) {
                chosen = Some(Command::Redo);
            }
            ui.separator();
            ui.menu_button("Add", |ui| {
                if let Some(action) = scene_panel::add_menu(ui) {
                    chosen = Some(Command::Edit(action));
                }
            });
            if item(ui, "Duplicate (D)", None, state.has_selection) {
                chosen = Some(Command::Edit(Action::Duplicate));
            }
            if item(ui, "Delete (Del)", None, state.has_selection) {
                chosen = Some(Command::Edit(Action::Delete));
            }
        });
        ui.menu_button("View", |ui| {
            if item(ui, "Fit image (F)", None, true) {
                chosen = Some(Command::Fit);
            }
            if item(ui, "Image at 100 % (1)", None, true) {
                chosen = Some(Command::ActualSize);
            }
            if item(ui, "3D debug view (G)", None, true) {
                chosen = Some(Command::ToggleDebugView);
            }
            ui.menu_button("Display (M)", |ui| {
                for display in Display::ALL {
                    if ui.radio(state.display == display, display.label()).clicked() {
                        chosen = Some(Command::Display(display));
                    }
                }
                ui.separator();
                ui.weak("Save Image writes the picture shown as PNG;\nEXR always holds the linear colour.");
            });
            if item(ui, "Mouse and keys help (H)", None, true) {
                chosen = Some(Command::ToggleHelp);
            }
        });
    });
    chosen
}
