//! Integrator settings: integrator, intersection method, depth, samples per pixel.

use super::document::RenderSettings;
use super::widgets;
use renderer::integrator::Integrator;
use renderer::{Method, Sampling};

/// Samples per pixel offered when the user turns a target back on.
const DEFAULT_TARGET: u32 = 64;

/// Draws the settings; true when one changed.
pub fn show(ui: &mut egui::Ui, settings: &mut RenderSettings) -> bool {
    let mut changed = false;
    ui.heading("Rendering");
    egui::Grid::new("render-settings")
        .num_columns(2)
        .show(ui, |ui| {
            ui.label("Integrator");
            ui.horizontal(|ui| {
                changed |= ui
                    .radio_value(&mut settings.integrator, Integrator::Whitted, "Whitted")
                    .on_hover_text(
                        "point and directional lights, ambient light, perfect mirrors and glass",
                    )
                    .changed();
                changed |= ui
                    .radio_value(&mut settings.integrator, Integrator::Path, "path")
                    .on_hover_text(
                        "physically based path tracing: emissive shapes, the sky, indirect light; \
                         no ambient term",
                    )
                    .changed();
            });
            ui.end_row();

            ui.label("Intersections");
            ui.horizontal(|ui| {
                changed |= ui
                    .radio_value(&mut settings.method, Method::Robust, "robust")
                    .on_hover_text("Ray Tracing Gems ch. 7 sphere, watertight triangle")
                    .changed();
                changed |= ui
                    .radio_value(&mut settings.method, Method::Lecture, "lecture")
                    .on_hover_text("the lecture's formulas exactly")
                    .changed();
            });
            ui.end_row();

            ui.label("Samples");
            ui.horizontal(|ui| {
                changed |= ui
                    .radio_value(&mut settings.sampling, Sampling::Independent, "independent")
                    .on_hover_text("independent random numbers for every sample")
                    .changed();
                changed |= ui
                    .radio_value(&mut settings.sampling, Sampling::Sobol, "Sobol")
                    .on_hover_text(
                        "Owen-scrambled Sobol points: each pixel's samples spread evenly over \
                         the pixel, the lights and the first bounce's directions",
                    )
                    .changed();
            });
            ui.end_row();

            ui.label("Max depth");
            changed |= ui
                .add(widgets::drag(&mut settings.max_depth).range(0..=64).prefix(
                    match settings.integrator {
                        Integrator::Whitted => "bounces ",
                        Integrator::Path => "path segments ",
                    },
                ))
                .on_hover_text(match settings.integrator {
                    Integrator::Whitted => "reflection/refraction bounces after the first hit",
                    Integrator::Path => {
                        "the longest path, counted as Mitsuba counts max_depth: \
                         1 = emitters seen directly, 2 = direct lighting"
                    }
                })
                .changed();
            ui.end_row();

            ui.label("Samples per pixel");
            ui.horizontal(|ui| {
                let mut forever = settings.target_spp.is_none();
                if ui.checkbox(&mut forever, "until stopped").changed() {
                    settings.target_spp = (!forever).then_some(DEFAULT_TARGET);
                    changed = true;
                }
                if let Some(target) = &mut settings.target_spp {
                    changed |= ui
                        .add(widgets::drag(target).range(1..=65536).prefix("target spp "))
                        .changed();
                }
            });
            ui.end_row();
        });
    changed
}
