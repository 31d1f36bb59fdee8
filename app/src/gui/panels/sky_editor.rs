//! Editing the sky: its colour (a constant sky's radiance, or a map's
//! tint), its strength, its environment map (chosen in a file dialog, or
//! removed) and the map's rotation.

use super::widgets;
use crate::gui::doc::edits::Action;
use scene::Sky;

/// Draws the editor for `sky`; true when a field changed, and the action a
/// button asks for (choosing a map file).
pub fn show(ui: &mut egui::Ui, sky: &mut Sky) -> (bool, Option<Action>) {
    let mut changed = false;
    let mut action = None;
    egui::Grid::new("sky-editor")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            ui.label(if sky.map.is_some() { "Tint" } else { "Colour" });
            ui.horizontal(|ui| changed |= widgets::color(ui, &mut sky.color));
            ui.end_row();
            ui.label("Strength");
            changed |= ui
                .add(
                    widgets::drag(&mut sky.strength)
                        .speed(0.01)
                        .range(0.0..=1e6)
                        .prefix("× "),
                )
                .on_hover_text("multiplies the whole sky's radiance (Mitsuba's envmap scale)")
                .changed();
            ui.end_row();
            ui.label("Map");
            ui.horizontal(|ui| match &sky.map {
                Some(map) => {
                    // The file's name; its path as the scene names it on hover.
                    let image = &map.image;
                    ui.label(file_name(&map.src)).on_hover_text(format!(
                        "{}\n{} × {} pixels",
                        map.src, image.width, image.height
                    ));
                }
                None => {
                    ui.weak("none: a constant colour");
                }
            });
            ui.end_row();
            ui.label("");
            ui.horizontal(|ui| {
                if ui
                    .button("Choose map…")
                    .on_hover_text("an equirectangular HDR image (.exr or .hdr)")
                    .clicked()
                {
                    action = Some(Action::ChooseSkyMap);
                }
                if ui
                    .add_enabled(sky.map.is_some(), egui::Button::new("Remove map"))
                    .clicked()
                {
                    sky.map = None;
                    changed = true;
                }
            });
            ui.end_row();
            if sky.map.is_some() {
                changed |= widgets::vec3_row(ui, "Rotate (°)", &mut sky.rotate, 1.0);
            }
        });
    (changed, action)
}

/// The list label of the sky.
pub fn label(sky: &Sky) -> String {
    match &sky.map {
        Some(map) => format!("sky: {}", file_name(&map.src)),
        None => "sky".to_string(),
    }
}

/// The last component of a map's path (a built-in map's whole name).
fn file_name(src: &str) -> String {
    std::path::Path::new(src)
        .file_name()
        .map_or_else(|| src.to_string(), |n| n.to_string_lossy().into_owned())
}
