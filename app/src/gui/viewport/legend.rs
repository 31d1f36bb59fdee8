//! The display mode's legend, drawn over the bottom-left corner of the
//! image: the mode, its colour ramp with the value range and unit, and a
//! one-line note (misses, special cases). Only draws; every number comes
//! with the frame from the render thread.

use renderer::display::{Display, Legend, ScalarRange, Scale};

/// Width of the ramp bar, in points.
const BAR_WIDTH: f32 = 220.0;
/// Height of the ramp bar, in points.
const BAR_HEIGHT: f32 = 12.0;
/// Flat-coloured steps the bar is painted with.
const BAR_STEPS: usize = 48;

/// A value for a legend label: few digits, scientific when tiny or huge.
pub fn format_value(v: f32) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".to_owned()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.2e}")
    } else if a >= 100.0 || v.fract() == 0.0 {
        format!("{v:.0}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.4}")
    }
}

/// Draws `legend` over the bottom-left corner of `view`; nothing for the colour.
pub fn show(ui: &mut egui::Ui, view: egui::Rect, legend: &Legend) {
    if legend.display == Display::Color {
        return;
    }
    egui::Area::new(egui::Id::unique("display-legend"))
        .order(egui::Order::Foreground)
        .pivot(egui::Align2::LEFT_BOTTOM)
        .fixed_pos(view.left_bottom() + egui::vec2(8.0, -8.0))
        .constrain_to(view)
        .interactable(false)
        .show(ui.ctx(), |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(BAR_WIDTH + 40.0);
                ui.strong(legend.display.label());
                if let Some(range) = legend.range {
                    let scale = match range.scale {
                        Scale::Linear => "",
                        Scale::Log => ", log scale",
                    };
                    if range.min == range.max {
                        // One value throughout: a bar would suggest a range.
                        ui.label(format!("{} {}", format_value(range.max), range.unit));
                    } else {
                        ramp_bar(ui, range);
                        ui.weak(format!("{}{scale}", range.unit));
                    }
                }
                if !legend.note.is_empty() {
                    ui.weak(&legend.note);
                }
            });
        });
}

/// The ramp as a bar, with its minimum under the left end and its maximum
/// under the right end.
fn ramp_bar(ui: &mut egui::Ui, range: ScalarRange) {
    let (bar, _) = ui.allocate_exact_size(egui::vec2(BAR_WIDTH, BAR_HEIGHT), egui::Sense::hover());
    let step = bar.width() / BAR_STEPS as f32;
    for k in 0..BAR_STEPS {
        let t = k as f32 / (BAR_STEPS - 1) as f32;
        let [r, g, b] = range.ramp.srgb8(t);
        let x = bar.left() + k as f32 * step;
        let cell = egui::Rect::from_min_max(
            egui::pos2(x, bar.top()),
            egui::pos2(x + step + 0.5, bar.bottom()),
        );
        ui.painter()
            .rect_filled(cell, 0.0, egui::Color32::from_rgb(r, g, b));
    }
    ui.horizontal(|ui| {
        ui.set_width(BAR_WIDTH);
        ui.label(format_value(range.min));
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.label(format_value(range.max));
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_read_short() {
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(64.0), "64");
        assert_eq!(format_value(3.25), "3.25");
        assert_eq!(format_value(0.015625), "0.0156");
        assert_eq!(format_value(2.5e-7), "2.50e-7");
        assert_eq!(format_value(1234.5), "1234");
    }
}
