//! Editing one object: its name, shape parameters, placement, material and
//! the material's parameters.

use super::widgets;
use glam::Vec3;
use scene::{BaseMaterial, Geometry, MaterialParams, Object, Shape};

/// Where the layout put an unplaced shape's anchor (centre or base).
pub fn resolved_anchor(geometry: &Geometry) -> Option<Vec3> {
    match *geometry {
        Geometry::Sphere { center, .. }
        | Geometry::Box { center, .. }
        | Geometry::Torus { center, .. } => Some(center),
        Geometry::Cylinder { base, .. } | Geometry::Cone { base, .. } => Some(base),
        Geometry::Mesh {
            world_from_model, ..
        } => Some(world_from_model.w_axis.truncate()),
        Geometry::Triangle { .. } | Geometry::Plane { .. } => None,
    }
}

/// Draws the editor for `object`; `resolved` is its prepared geometry and
/// `material_names` every material it may use. True when something changed.
pub fn show(
    ui: &mut egui::Ui,
    object: &mut Object,
    resolved: Option<&scene::ResolvedObject>,
    material_names: &[String],
) -> bool {
    let mut changed = false;
    egui::Grid::new("object-editor")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            ui.label("Name");
            let mut name = object.name.clone().unwrap_or_default();
            let hint = resolved.map(|r| r.name.as_str()).unwrap_or("");
            if ui
                .add(egui::TextEdit::singleline(&mut name).hint_text(hint))
                .changed()
            {
                object.name = (!name.trim().is_empty()).then_some(name);
                changed = true;
            }
            ui.end_row();
            let anchor = resolved.and_then(|r| resolved_anchor(&r.geometry));
            changed |= shape_rows(ui, &mut object.shape, anchor);
        });
    ui.separator();
    ui.label(egui::RichText::new("Material").strong());
    let inherited = resolved.map(|r| r.material);
    changed |= material(ui, object, inherited, material_names);
    changed
}

/// The rows for the shape's own parameters.
fn shape_rows(ui: &mut egui::Ui, shape: &mut Shape, anchor: Option<Vec3>) -> bool {
    let mut changed = false;
    match shape {
        Shape::Sphere { center, radius } => {
            changed |= widgets::anchor_row(ui, "Centre C", center, anchor);
            changed |= widgets::length_row(ui, "r", radius);
        }
        Shape::Box {
            center,
            size,
            rotate,
        } => {
            changed |= widgets::anchor_row(ui, "Centre", center, anchor);
            changed |= widgets::vec3_row(ui, "Size", size, 0.02);
            *size = size.max(Vec3::splat(1e-3));
            changed |= widgets::vec3_row(ui, "Rotate (°)", rotate, 1.0);
        }
        Shape::Cylinder {
            base,
            radius,
            height,
            rotate,
        }
        | Shape::Cone {
            base,
            radius,
            height,
            rotate,
        } => {
            changed |= widgets::anchor_row(ui, "Base", base, anchor);
            changed |= widgets::length_row(ui, "radius", radius);
            changed |= widgets::length_row(ui, "height", height);
            changed |= widgets::vec3_row(ui, "Rotate (°)", rotate, 1.0);
        }
        Shape::Torus {
            center,
            major,
            minor,
            rotate,
        } => {
            changed |= widgets::anchor_row(ui, "Centre", center, anchor);
            changed |= widgets::length_row(ui, "R", major);
            changed |= widgets::length_row(ui, "r", minor);
            changed |= widgets::vec3_row(ui, "Rotate (°)", rotate, 1.0);
        }
        Shape::Triangle { t0, t1, t2 } => {
            changed |= widgets::vec3_row(ui, "t0", t0, 0.02);
            changed |= widgets::vec3_row(ui, "t1", t1, 0.02);
            changed |= widgets::vec3_row(ui, "t2", t2, 0.02);
        }
        Shape::Plane { point, normal } => {
            changed |= widgets::vec3_row(ui, "Point s", point, 0.02);
            changed |= widgets::vec3_row(ui, "Normal n", normal, 0.01);
        }
        Shape::Floor { y } => {
            ui.label("Height y");
            changed |= ui.add(widgets::drag(y).speed(0.02).prefix("y ")).changed();
            ui.end_row();
        }
        Shape::Mesh {
            source,
            translate,
            rotate,
            scale,
        } => {
            ui.label("File");
            ui.label(&source.src).on_hover_text(format!(
                "{}\n{} triangles drawn",
                source.model.path.display(),
                source.model.drawn_triangles()
            ));
            ui.end_row();
            changed |= widgets::anchor_row(ui, "Translate", translate, anchor);
            changed |= widgets::vec3_row(ui, "Rotate (°)", rotate, 1.0);
            changed |= widgets::vec3_row(ui, "Scale", scale, 0.01);
            *scale = scale.max(Vec3::splat(1e-4));
        }
    }
    changed
}

/// The material choice and the per-object overrides of its parameters.
fn material(
    ui: &mut egui::Ui,
    object: &mut Object,
    inherited: Option<scene::Material>,
    material_names: &[String],
) -> bool {
    let mut changed = false;
    let current = object
        .material
        .clone()
        .unwrap_or_else(|| BaseMaterial::Matte.name().to_owned());
    egui::ComboBox::from_label("material")
        .selected_text(&current)
        .show_ui(ui, |ui| {
            for name in material_names {
                if ui.selectable_label(*name == current, name).clicked() && *name != current {
                    object.material = Some(name.clone());
                    changed = true;
                }
            }
        });
    // The resolved material: unset parameters show the material's own values.
    let base = inherited.unwrap_or_else(|| scene::materials::builtin(BaseMaterial::Matte));
    let MaterialParams {
        color,
        ior,
        shininess,
        specular,
        reflectivity,
        roughness,
        emission,
    } = &mut object.params;
    egui::Grid::new("material-params")
        .num_columns(2)
        .show(ui, |ui| {
            changed |= widgets::optional_row(ui, "colour", color, base.color, widgets::color);
            changed |=
                widgets::optional_row(ui, "emission", emission, base.emission, widgets::color);
            changed |= widgets::optional_row(ui, "specular", specular, base.specular, |ui, v| {
                ui.add(egui::Slider::new(v, 0.0..=1.0)).changed()
            });
            changed |= widgets::optional_row(
                ui,
                "shininess",
                shininess,
                base.shininess.max(1.0),
                |ui, v| {
                    ui.add(egui::Slider::new(v, 1.0..=2000.0).logarithmic(true))
                        .changed()
                },
            );
            changed |= widgets::optional_row(
                ui,
                "reflectivity",
                reflectivity,
                base.reflectivity,
                |ui, v| ui.add(egui::Slider::new(v, 0.0..=1.0)).changed(),
            );
            changed |= widgets::optional_row(ui, "IOR", ior, base.ior, |ui, v| {
                ui.add(egui::Slider::new(v, 1.0..=3.0)).changed()
            });
            changed |=
                widgets::optional_row(ui, "roughness", roughness, base.roughness, |ui, v| {
                    ui.add(egui::Slider::new(v, 0.0..=1.0))
                        .on_hover_text(
                            "mirror, metal, glass: GGX microfacets, α = roughness² (path tracer)",
                        )
                        .changed()
                });
        });
    changed
}
