//! Editing one light: name, kind-specific placement, colour and intensity.

use super::widgets;
use scene::{Light, LightKind};

/// Draws the editor for `light`; true when something changed.
pub fn show(ui: &mut egui::Ui, light: &mut Light) -> bool {
    let mut changed = false;
    egui::Grid::new("light-editor")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            ui.label("Name");
            let mut name = light.name.clone().unwrap_or_default();
            if ui.text_edit_singleline(&mut name).changed() {
                light.name = (!name.trim().is_empty()).then_some(name);
                changed = true;
            }
            ui.end_row();
            match &mut light.kind {
                LightKind::Point { position } => {
                    changed |= widgets::vec3_row(ui, "Position", position, 0.05);
                }
                LightKind::Directional { direction } => {
                    changed |= widgets::vec3_row(ui, "Direction", direction, 0.01);
                }
                LightKind::Ambient => {
                    ui.label("Ambient");
                    ui.weak("radiance from every direction, unshadowed");
                    ui.end_row();
                }
            }
            ui.label("Colour");
            ui.horizontal(|ui| changed |= widgets::color(ui, &mut light.color));
            ui.end_row();
            ui.label(match light.kind {
                LightKind::Point { .. } => "Intensity (W/sr)",
                LightKind::Directional { .. } => "Irradiance (W/m²)",
                LightKind::Ambient => "Radiance",
            });
            changed |= ui
                .add(
                    widgets::drag(&mut light.intensity)
                        .speed(0.05)
                        .range(0.0..=1e6)
                        .prefix("intensity "),
                )
                .changed();
            ui.end_row();
        });
    changed
}

/// The list label of a light.
pub fn label(light: &Light, index: usize) -> String {
    light.name.clone().unwrap_or_else(|| {
        let kind = match light.kind {
            LightKind::Point { .. } => "point light",
            LightKind::Directional { .. } => "directional light",
            LightKind::Ambient => "ambient light",
        };
        format!("{kind} {}", index + 1)
    })
}
