//! The help window: the mouse and keyboard bindings.

use crate::gui::viewport::navigation;

/// The mouse and keys window, while `open`.
pub fn window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Mouse and keys")
        .open(open)
        .collapsible(false)
        .resizable(false)
        .show(ctx, |ui| {
            egui::Grid::new("help")
                .num_columns(2)
                .striped(true)
                .show(ui, |ui| {
                    for (input, effect) in navigation::HELP {
                        ui.strong(*input);
                        ui.label(*effect);
                        ui.end_row();
                    }
                });
        });
}
