//! The scene panel: the objects and lights, the buttons that add, duplicate
//! and delete them, and the editor of the selected one.

use super::{light_editor, object_editor, sky_editor};
use crate::gui::doc::edits::{Action, Selection};
use scene::{BaseMaterial, LightKind, ResolvedScene, Scene, Shape};

/// The light kinds offered by "Add light", with their menu labels.
const LIGHT_KINDS: [(&str, LightKind); 3] = [
    (
        "Point light",
        LightKind::Point {
            position: scene::defaults::LIGHT_POSITION,
        },
    ),
    (
        "Directional light",
        LightKind::Directional {
            direction: scene::defaults::LIGHT_DIRECTION,
        },
    ),
    ("Ambient light", LightKind::Ambient),
];

/// The "Add" menu's items; also used by the menu bar.
pub fn add_menu(ui: &mut egui::Ui) -> Option<Action> {
    let mut action = None;
    // A <mesh> needs a file; it comes in with File > Open or a scene's <mesh src>.
    for tag in Shape::TAGS
        .into_iter()
        .filter(|t| Shape::default_for_tag(t).is_some())
    {
        if ui.button(tag).clicked() {
            action = Some(Action::AddObject(tag));
        }
    }
    ui.separator();
    for (label, kind) in LIGHT_KINDS {
        if ui.button(label).clicked() {
            action = Some(Action::AddLight(kind));
        }
    }
    if ui
        .button("Sky")
        .on_hover_text("a constant colour or an HDR environment map around the scene")
        .clicked()
    {
        action = Some(Action::AddSky);
    }
    action
}

/// Every material an object may use: the built-ins, then the scene's own.
fn material_names(scene: &Scene) -> Vec<String> {
    BaseMaterial::ALL
        .iter()
        .map(|m| m.name().to_owned())
        .chain(scene.materials.iter().map(|m| m.name.clone()))
        .collect()
}

/// Draws the panel; field edits change `scene` directly, structural ones are
/// returned as an [`Action`]. True in `.0` when a field changed.
pub fn show(
    ui: &mut egui::Ui,
    scene: &mut Scene,
    resolved: Option<&ResolvedScene>,
    selection: &mut Selection,
) -> (bool, Option<Action>) {
    let mut action = None;
    ui.heading("Scene");
    ui.horizontal(|ui| {
        ui.menu_button("Add", |ui| action = add_menu(ui).or(action));
        let any = *selection != Selection::None;
        if ui
            .add_enabled(any, egui::Button::new("Duplicate"))
            .clicked()
        {
            action = Some(Action::Duplicate);
        }
        if ui.add_enabled(any, egui::Button::new("Delete")).clicked() {
            action = Some(Action::Delete);
        }
    });
    ui.label(egui::RichText::new("Objects").weak());
    // Only the rows in view are laid out: a scene may hold ten thousand objects.
    let row_height = ui.spacing().interact_size.y;
    egui::ScrollArea::vertical()
        .id_salt("scene-list")
        .max_height(220.0)
        .auto_shrink([false, true])
        .show_rows(ui, row_height, scene.objects.len(), |ui, rows| {
            for i in rows {
                let object = &scene.objects[i];
                let name = object.name.clone().unwrap_or_else(|| {
                    resolved.and_then(|r| r.objects.get(i)).map_or_else(
                        || format!("{} {}", object.shape.tag(), i + 1),
                        |o| o.name.clone(),
                    )
                });
                let selected = *selection == Selection::Object(i);
                if ui.selectable_label(selected, name).clicked() {
                    *selection = Selection::Object(i);
                }
            }
        });
    egui::ScrollArea::vertical()
        .id_salt("light-list")
        .max_height(120.0)
        .show(ui, |ui| {
            ui.label(egui::RichText::new("Lights").weak());
            if scene.lights.is_empty() {
                // Resolving adds default lights only to a scene nothing else lights.
                if resolved.is_none_or(|r| !r.lights.is_empty()) {
                    ui.weak("none: a default key light and ambient light");
                } else {
                    ui.weak("none: lit by its emissive objects or sky");
                }
            }
            for (i, light) in scene.lights.iter().enumerate() {
                let selected = *selection == Selection::Light(i);
                if ui
                    .selectable_label(selected, light_editor::label(light, i))
                    .clicked()
                {
                    *selection = Selection::Light(i);
                }
            }
            if let Some(sky) = &scene.sky {
                let selected = *selection == Selection::Sky;
                if ui
                    .selectable_label(selected, sky_editor::label(sky))
                    .clicked()
                {
                    *selection = Selection::Sky;
                }
            }
        });
    ui.separator();
    let names = material_names(scene);
    let changed = match selection.valid_in(scene) {
        Selection::Object(i) => {
            let resolved = resolved.and_then(|r| r.objects.get(i));
            object_editor::show(ui, &mut scene.objects[i], resolved, &names)
        }
        Selection::Light(i) => light_editor::show(ui, &mut scene.lights[i]),
        Selection::Sky => match &mut scene.sky {
            Some(sky) => {
                let (changed, asked) = sky_editor::show(ui, sky);
                action = asked.or(action);
                changed
            }
            None => false,
        },
        Selection::None => {
            ui.weak("Select an object, light or the sky to edit it (or click it in the image).");
            false
        }
    };
    (changed, action)
}
