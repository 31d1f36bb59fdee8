//! The status bar: pause, refinement step, time since the edit, sampling
//! speed and the UI's own frame time.

use renderer::progressive::{RenderedFrame, Step};
use std::collections::VecDeque;
use std::time::Duration;

/// What the status bar reports about the frame on screen.
#[derive(Clone, Copy, Debug)]
pub struct Shown {
    /// Preview stride or samples per pixel.
    pub step: Step,
    /// Time from the edit to this frame.
    pub since_edit: Duration,
    /// Camera samples per second of the full passes.
    pub samples_per_second: f64,
    /// Rays (every kind) per second of the full passes.
    pub rays_per_second: f64,
    /// NaN/∞ samples left out.
    pub discarded: u64,
}

impl Shown {
    /// The summary of `frame`.
    pub fn of(frame: &RenderedFrame) -> Self {
        Self {
            step: frame.step,
            since_edit: frame.since_submit,
            samples_per_second: frame.samples_per_second,
            rays_per_second: frame.rays_per_second,
            discarded: frame.discarded,
        }
    }
}

/// The UI thread's recent frame times.
#[derive(Clone, Debug, Default)]
pub struct FrameTimes {
    recent: VecDeque<Duration>,
}

impl FrameTimes {
    /// Frames remembered.
    const WINDOW: usize = 120;

    /// Records one frame's time.
    pub fn record(&mut self, time: Duration) {
        if self.recent.len() == Self::WINDOW {
            self.recent.pop_front();
        }
        self.recent.push_back(time);
    }

    /// The newest frame time and the largest of the remembered ones.
    pub fn latest_and_max(&self) -> Option<(Duration, Duration)> {
        let latest = *self.recent.back()?;
        Some((latest, self.recent.iter().copied().max().unwrap_or(latest)))
    }
}

/// Draws the status line; true when the pause button was pressed.
pub fn show(
    ui: &mut egui::Ui,
    shown: Option<&Shown>,
    note: Option<&str>,
    error: Option<&str>,
    target_spp: Option<u32>,
    paused: bool,
    frame_times: &FrameTimes,
) -> bool {
    let mut toggled = false;
    ui.horizontal(|ui| {
        if ui.button(if paused { "Resume" } else { "Pause" }).clicked() {
            toggled = true;
        }
        ui.separator();
        if let Some(note) = note {
            ui.strong(note);
            ui.separator();
        }
        if let Some(error) = error {
            ui.colored_label(ui.visuals().error_fg_color, error);
            ui.separator();
        }
        match shown {
            None => {
                ui.label("rendering…");
            }
            Some(s) => {
                match (s.step, target_spp) {
                    (Step::Preview { stride }, _) => {
                        ui.label(format!("preview: 1 pixel in {stride}×{stride}"))
                    }
                    // One sample per pixel per pass: passes and spp move together.
                    (Step::Passes { spp }, Some(target)) => {
                        ui.label(format!("{spp} / {target} spp"));
                        ui.weak(format!("{spp} passes"))
                    }
                    (Step::Passes { spp }, None) => {
                        ui.label(format!("{spp} spp"));
                        ui.weak(format!("{spp} passes"))
                    }
                };
                ui.separator();
                ui.label(format!(
                    "{:.0} ms since the edit",
                    s.since_edit.as_secs_f64() * 1e3
                ));
                if s.samples_per_second > 0.0 {
                    ui.separator();
                    ui.label(format!(
                        "{:.2} M rays/s ({:.2} M samples/s)",
                        s.rays_per_second / 1e6,
                        s.samples_per_second / 1e6
                    ));
                }
                if s.discarded > 0 {
                    ui.separator();
                    ui.colored_label(
                        ui.visuals().warn_fg_color,
                        format!("{} NaN/∞ samples left out", s.discarded),
                    );
                }
            }
        }
        if let Some((latest, max)) = frame_times.latest_and_max() {
            ui.separator();
            ui.weak(format!(
                "UI {:.1} ms (max {:.1})",
                latest.as_secs_f64() * 1e3,
                max.as_secs_f64() * 1e3
            ));
        }
    });
    toggled
}
