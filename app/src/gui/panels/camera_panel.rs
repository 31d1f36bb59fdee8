//! The camera panel: the lecture's inputs P0, t, u, θ, d, w, h as editable
//! values, and its derived quantities r, ρ, H_d, W_d, C00 read-only.

use super::widgets::{self, vec3_row};
use glam::Vec3;
use renderer::Camera;
use scene::Scene;

/// A read-only vector.
fn vec3_value(ui: &mut egui::Ui, label: &str, v: Vec3) {
    ui.label(label);
    ui.monospace(format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z));
    ui.end_row();
}

/// Draws the panel for `scene.camera`, showing the prepared `camera`'s
/// values where the scene leaves them to defaults; true when the user changed something.
pub fn show(ui: &mut egui::Ui, scene: &mut Scene, camera: Option<&Camera>) -> bool {
    let mut changed = false;
    let cam = &mut scene.camera;
    ui.heading("Camera");
    egui::Grid::new("camera-inputs")
        .num_columns(2)
        .show(ui, |ui| {
            let mut eye = cam.eye.or(camera.map(|c| c.p0)).unwrap_or_default();
            let mut toward = cam.toward.or(camera.map(|c| c.t)).unwrap_or(Vec3::NEG_Z);
            let moved = vec3_row(ui, "P0 (eye)", &mut eye, 0.05);
            let turned = vec3_row(ui, "t (toward)", &mut toward, 0.01);
            if moved || turned {
                // Fix both, so moving the eye does not re-aim an automatic camera.
                cam.eye = Some(eye);
                cam.toward = Some(toward);
                changed = true;
            }
            changed |= vec3_row(ui, "u (up)", &mut cam.up, 0.01);

            ui.label("θ (half-height, °)");
            changed |= ui
                .add(egui::Slider::new(&mut cam.theta_deg, 0.5..=89.5).text("θ"))
                .changed();
            ui.end_row();

            ui.label("d (view window)");
            let mut d = cam.d.or(camera.map(|c| c.d)).unwrap_or(1.0);
            ui.horizontal(|ui| {
                if ui
                    .add(
                        widgets::drag(&mut d)
                            .speed(0.05)
                            .range(1e-4..=1e6)
                            .prefix("d "),
                    )
                    .changed()
                {
                    cam.d = Some(d);
                    changed = true;
                }
                if cam.d.is_some() && ui.small_button("h / (2 tan θ)").clicked() {
                    cam.d = None;
                    changed = true;
                }
            });
            ui.end_row();
            ui.label("");
            ui.small("d only moves the view window along t: the image does not change.");
            ui.end_row();

            ui.label("w × h (pixels)");
            ui.horizontal(|ui| {
                let max = scene::Camera::MAX_SIZE;
                changed |= ui
                    .add(widgets::drag(&mut cam.width).range(1..=max).prefix("w "))
                    .changed();
                ui.label("×");
                changed |= ui
                    .add(widgets::drag(&mut cam.height).range(1..=max).prefix("h "))
                    .changed();
            });
            ui.end_row();
        });

    if let Some(c) = camera {
        ui.separator();
        ui.label("Derived (lecture)");
        egui::Grid::new("camera-derived")
            .num_columns(2)
            .show(ui, |ui| {
                vec3_value(ui, "r = t × u", c.r);
                ui.label("ρ = w / h");
                ui.monospace(format!("{:.4}", c.rho));
                ui.end_row();
                ui.label("H_d = 2 d tan θ");
                ui.monospace(format!("{:.4}", c.h_d));
                ui.end_row();
                ui.label("W_d = ρ H_d");
                ui.monospace(format!("{:.4}", c.w_d));
                ui.end_row();
                vec3_value(ui, "C00", c.c00);
            });
    }
    changed
}
