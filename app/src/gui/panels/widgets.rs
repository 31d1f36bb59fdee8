//! Small editing widgets shared by the panels. Each returns true when the
//! user changed the value.

use glam::Vec3;

/// A drag value whose typed text must be a number the scene format accepts:
/// "NaN", "inf" or 1e30 typed into a field is refused, so the scene never
/// holds a value its own file could not be read back with.
pub fn drag<Num: egui::emath::Numeric>(value: &mut Num) -> egui::DragValue<'_> {
    egui::DragValue::new(value).custom_parser(|text| {
        let max = f64::from(scene::MAX_MAGNITUDE);
        text.trim().parse::<f64>().ok().filter(|v| v.abs() <= max)
    })
}

/// Three drag values for a vector, labelled x, y, z.
pub fn vec3(ui: &mut egui::Ui, v: &mut Vec3, speed: f32) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        for (axis, c) in ["x", "y", "z"]
            .into_iter()
            .zip([&mut v.x, &mut v.y, &mut v.z])
        {
            changed |= ui
                .add(
                    drag(c)
                        .speed(speed)
                        .range(-scene::MAX_MAGNITUDE..=scene::MAX_MAGNITUDE)
                        .prefix(format!("{axis} ")),
                )
                .changed();
        }
    });
    changed
}

/// A grid row: `label`, then three drag values.
pub fn vec3_row(ui: &mut egui::Ui, label: &str, v: &mut Vec3, speed: f32) -> bool {
    ui.label(label);
    let changed = vec3(ui, v, speed);
    ui.end_row();
    changed
}

/// A grid row with a positive length (drag value clamped to > 0).
pub fn length_row(ui: &mut egui::Ui, label: &str, value: &mut f32) -> bool {
    ui.label(label);
    let changed = ui
        .add(
            drag(value)
                .speed(0.01)
                .range(1e-3..=1e5)
                .prefix(format!("{label} ")),
        )
        .changed();
    ui.end_row();
    changed
}

/// A grid row for a position that may be left to the automatic layout:
/// a checkbox "auto", and the vector when it is set. `resolved` is where
/// the layout put it, used as the start value when the user unticks auto.
pub fn anchor_row(
    ui: &mut egui::Ui,
    label: &str,
    anchor: &mut Option<Vec3>,
    resolved: Option<Vec3>,
) -> bool {
    ui.label(label);
    let mut changed = false;
    ui.vertical(|ui| {
        let mut automatic = anchor.is_none();
        if ui
            .checkbox(&mut automatic, "on the floor, in a row (auto)")
            .changed()
        {
            *anchor = if automatic {
                None
            } else {
                Some(resolved.unwrap_or_default())
            };
            changed = true;
        }
        if let Some(v) = anchor {
            changed |= vec3(ui, v, 0.02);
        } else if let Some(v) = resolved {
            ui.weak(format!("({:.2}, {:.2}, {:.2})", v.x, v.y, v.z));
        }
    });
    ui.end_row();
    changed
}

/// A linear-RGB colour button with a picker, plus its hex value.
pub fn color(ui: &mut egui::Ui, c: &mut Vec3) -> bool {
    let mut rgb = c.to_array();
    let changed = egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed();
    if changed {
        *c = Vec3::from(rgb).max(Vec3::ZERO);
    }
    // The file's exact form (a hex byte triple, else full floats) on hover;
    // three decimals in the panel, so a picked colour does not widen it.
    let exact = scene::color::format_color(*c);
    let short = if exact.starts_with('#') {
        exact.clone()
    } else {
        format!("{:.3} {:.3} {:.3}", c.x, c.y, c.z)
    };
    ui.weak(short).on_hover_text(exact);
    changed
}

/// A grid row for an optional parameter: a checkbox that overrides the
/// inherited value, and `edit` for the value. Without the override the
/// inherited value is shown, and editing it sets the override (ticking the
/// box first is not needed).
pub fn optional_row<T: Copy>(
    ui: &mut egui::Ui,
    label: &str,
    value: &mut Option<T>,
    inherited: T,
    edit: impl FnOnce(&mut egui::Ui, &mut T) -> bool,
) -> bool {
    let mut set = value.is_some();
    let mut changed = ui.checkbox(&mut set, label).changed();
    if changed {
        *value = set.then_some(inherited);
    }
    ui.horizontal(|ui| match value {
        Some(v) => changed |= edit(ui, v),
        None => {
            let mut shown = inherited;
            if edit(ui, &mut shown) {
                *value = Some(shown);
                changed = true;
            }
        }
    });
    ui.end_row();
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui_kittest::Harness;
    use egui_kittest::kittest::Queryable;

    #[test]
    fn editing_an_inherited_value_overrides_it_without_ticking_its_box() {
        let mut h = Harness::new_ui_state(
            |ui, value: &mut Option<f32>| {
                egui::Grid::new("rows").show(ui, |ui| {
                    optional_row(ui, "specular", value, 0.25, |ui, v| {
                        ui.add(egui::Slider::new(v, 0.0..=1.0).text("amount"))
                            .changed()
                    });
                });
            },
            None,
        );
        h.run();
        h.get_by_role_and_label(egui::accesskit::Role::Slider, "amount")
            .set_value_accesskit(0.75);
        h.run();
        assert_eq!(*h.state(), Some(0.75), "the edit became the override");
        // Unticking the box goes back to the inherited value.
        h.get_by_label("specular").click();
        h.run();
        assert_eq!(*h.state(), None);
    }

    /// The picker's popup lays out every label with a font that has its
    /// glyphs: egui's test harness panics on a missing glyph ("📋", the copy
    /// button beside "U8", needs egui's emoji fonts).
    #[test]
    fn the_colour_pickers_popup_has_a_glyph_for_every_label() {
        let mut h = Harness::new_ui_state(
            |ui, c: &mut Vec3| {
                color(ui, c);
            },
            Vec3::new(0.8, 0.2, 0.1),
        );
        h.run();
        h.get_by_role(egui::accesskit::Role::ColorWell).click();
        h.run();
        assert!(h.query_by_label("U8").is_some(), "the popup is open");
        assert!(h.query_by_label("📋").is_some(), "its copy button is there");
    }
}
