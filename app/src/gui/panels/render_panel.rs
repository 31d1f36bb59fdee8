//! Integrator settings: integrator, intersection method, depth, samples per pixel.

use super::widgets;
use crate::gui::doc::document::RenderSettings;
use renderer::integrator::Integrator;
use renderer::integrator::adaptive::Adaptive;
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

            ui.label("Adaptive");
            ui.horizontal(|ui| {
                let mut on = settings.adaptive.is_some();
                if ui
                    .checkbox(&mut on, "stop converged pixels")
                    .on_hover_text(
                        "after 16 passes, a pixel whose relative error (and its neighbours') \
                         is below the threshold gets no more samples; the \
                         'Samples per pixel' view shows where they went",
                    )
                    .changed()
                {
                    settings.adaptive = on.then(Adaptive::default);
                    changed = true;
                }
                if let Some(adaptive) = &mut settings.adaptive {
                    let mut percent = adaptive.threshold * 100.0;
                    if ui
                        .add(
                            egui::DragValue::new(&mut percent)
                                .range(0.1..=50.0)
                                .speed(0.05)
                                .prefix("error < ")
                                .suffix(" %"),
                        )
                        .changed()
                    {
                        adaptive.threshold = percent / 100.0;
                        changed = true;
                    }
                }
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

            if settings.integrator == Integrator::Whitted {
                ui.label("Min weight");
                changed |= ui
                    .add(
                        widgets::drag(&mut settings.min_weight)
                            .range(0.0..=1.0)
                            .speed(0.0005)
                            .max_decimals(4),
                    )
                    .on_hover_text(
                        "a reflection or refraction whose weight in the pixel is below this \
                         is not traced but sees the background (adaptive tree depth); \
                         0 traces every bounce to the max depth",
                    )
                    .changed();
                ui.end_row();
            }

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
