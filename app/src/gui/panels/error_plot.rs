//! The live error plot: with a reference image loaded, each finished pass's
//! relative MSE against it, plotted against the time since the render
//! started (log–log, egui_plot), so the image's convergence is visible as it
//! refines.

use renderer::diagnostics::metrics::rel_mse;
use renderer::diagnostics::reference_image::LinearImage;
use renderer::progressive::{RenderedFrame, Step};
use std::path::PathBuf;

/// A reference image and the error of each pass of the current render against it.
#[derive(Default)]
pub struct ErrorPlot {
    /// The reference and the file it came from.
    reference: Option<(PathBuf, LinearImage)>,
    /// The render generation the points belong to.
    generation: u64,
    /// (seconds since submit, samples per pixel, relative MSE) per pass.
    points: Vec<(f64, u32, f64)>,
    /// Why the last frame could not be compared, if it could not.
    mismatch: Option<String>,
}

impl ErrorPlot {
    /// Measures against `image`, read from `path`, from the next pass on.
    pub fn set_reference(&mut self, path: PathBuf, image: LinearImage) {
        *self = Self {
            reference: Some((path, image)),
            ..Self::default()
        };
    }

    /// Forgets the reference.
    pub fn unload(&mut self) {
        *self = Self::default();
    }

    /// The (seconds, spp, relative MSE) points of the current render.
    #[cfg(test)]
    pub fn points(&self) -> &[(f64, u32, f64)] {
        &self.points
    }

    /// Adds a finished pass's error; starts over for a new render.
    pub fn add(&mut self, frame: &RenderedFrame) {
        let Some((path, reference)) = &self.reference else {
            return;
        };
        if frame.generation != self.generation {
            self.generation = frame.generation;
            self.points.clear();
        }
        let Step::Passes { spp } = frame.step else {
            return;
        };
        if let Err(mismatch) = reference.check_size(path, frame.width, frame.height) {
            self.mismatch = Some(mismatch.to_string());
            return;
        }
        self.mismatch = None;
        let error = rel_mse(&frame.pixels, &reference.pixels);
        if self.points.last().is_none_or(|&(_, last, _)| last != spp) {
            self.points
                .push((frame.since_submit.as_secs_f64(), spp, error));
        }
    }

    /// The plot (or how to get one); true when the user asked to load a reference.
    pub fn show(&mut self, ui: &mut egui::Ui) -> bool {
        let mut load = false;
        ui.heading("Error against a reference");
        ui.horizontal(|ui| {
            load = ui
                .button("Load reference…")
                .on_hover_text("a converged linear EXR of this scene at the render's size")
                .clicked();
            if self.reference.is_some() && ui.button("Clear").clicked() {
                self.unload();
            }
        });
        let Some((path, _)) = &self.reference else {
            ui.weak("Load a reference to plot relative MSE against time as the image refines.");
            return load;
        };
        ui.label(path.file_name().unwrap_or_default().to_string_lossy());
        if let Some(mismatch) = &self.mismatch {
            ui.colored_label(ui.visuals().warn_fg_color, mismatch);
        }
        if let Some(&(seconds, spp, error)) = self.points.last() {
            ui.label(format!(
                "relative MSE {error:.2e} after {seconds:.2} s, {spp} spp"
            ));
        }
        self.plot(ui);
        load
    }

    /// log₁₀ relative MSE against log₁₀ seconds.
    fn plot(&self, ui: &mut egui::Ui) {
        let line: egui_plot::PlotPoints = self
            .points
            .iter()
            .filter(|&&(s, _, e)| s > 0.0 && e > 0.0)
            .map(|&(s, _, e)| [s.log10(), e.log10()])
            .collect();
        // Marks fall between decades too: two significant digits tell them apart.
        let decade = |mark: egui_plot::GridMark, _: &std::ops::RangeInclusive<f64>| {
            format!("{:.1e}", 10f64.powf(mark.value))
        };
        egui_plot::Plot::new("error-against-time")
            .height(180.0)
            .x_axis_label("seconds (log)")
            .y_axis_label("relative MSE (log)")
            .x_axis_formatter(decade)
            .y_axis_formatter(decade)
            .label_formatter(|hover| {
                let (egui_plot::HoverPosition::NearDataPoint { position: p, .. }
                | egui_plot::HoverPosition::Elsewhere { position: p }) = *hover;
                Some(format!(
                    "{:.2} s\nrelative MSE {:.2e}",
                    10f64.powf(p.x),
                    10f64.powf(p.y)
                ))
            })
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.line(egui_plot::Line::new("relative MSE", line));
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use renderer::display::{Display, Legend};
    use std::time::Duration;

    fn frame(generation: u64, spp: u32, value: f32) -> RenderedFrame {
        RenderedFrame {
            generation,
            width: 2,
            height: 1,
            pixels: vec![Vec3::splat(value); 2],
            srgba8: vec![[0; 4]; 2],
            legend: Legend {
                display: Display::Color,
                range: None,
                note: String::new(),
            },
            view: scene::View::default(),
            step: Step::Passes { spp },
            since_submit: Duration::from_millis(u64::from(spp) * 10),
            samples_per_second: 0.0,
            rays_per_second: 0.0,
            discarded: 0,
        }
    }

    fn with_reference(value: f32) -> ErrorPlot {
        let mut plot = ErrorPlot::default();
        plot.set_reference(
            PathBuf::from("ref.exr"),
            LinearImage {
                width: 2,
                height: 1,
                pixels: vec![Vec3::splat(value); 2],
            },
        );
        plot
    }

    #[test]
    fn each_pass_adds_its_relative_mse_and_a_new_render_starts_over() {
        let mut plot = with_reference(1.0);
        plot.add(&frame(1, 1, 2.0));
        plot.add(&frame(1, 2, 1.0));
        // (2 − 1)² / (1² + 0.01) per channel.
        let expected = 1.0 / 1.01;
        assert_eq!(plot.points().len(), 2);
        assert!(
            (plot.points()[0].2 - expected).abs() < 1e-6,
            "{:?}",
            plot.points()
        );
        assert_eq!(plot.points()[1].2, 0.0);
        plot.add(&frame(2, 1, 1.0));
        assert_eq!(plot.points().len(), 1);
    }

    #[test]
    fn a_reference_of_another_size_is_reported_not_compared() {
        let mut plot = with_reference(1.0);
        if let Some((_, image)) = &mut plot.reference {
            image.width = 1;
            image.pixels.truncate(1);
        }
        plot.add(&frame(1, 1, 2.0));
        assert!(plot.points().is_empty());
        assert!(plot.mismatch.as_deref().is_some_and(|m| m.contains("1×1")));
    }
}
