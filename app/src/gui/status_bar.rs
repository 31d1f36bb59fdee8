//! The status bar: refinement step, time since the edit, sampling speed.

use renderer::progressive::{RenderedFrame, Step};
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
            discarded: frame.discarded,
        }
    }
}

/// What the user asked for in the status bar.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Controls {
    /// Refinement stops at this many samples per pixel.
    pub target_spp: u32,
    /// Refinement is paused.
    pub paused: bool,
}

/// Draws the pause button and the target spp; true when either changed.
pub fn controls(ui: &mut egui::Ui, controls: &mut Controls) -> bool {
    let label = if controls.paused { "Resume" } else { "Pause" };
    let mut changed = false;
    if ui.button(label).clicked() {
        controls.paused = !controls.paused;
        changed = true;
    }
    changed |= ui
        .add(
            egui::DragValue::new(&mut controls.target_spp)
                .range(1..=65536)
                .prefix("target spp "),
        )
        .changed();
    ui.separator();
    changed
}

/// Draws the status line.
pub fn show(ui: &mut egui::Ui, shown: Option<&Shown>, error: Option<&str>, target_spp: u32) {
    ui.horizontal(|ui| {
        if let Some(error) = error {
            ui.colored_label(ui.visuals().error_fg_color, error);
            return;
        }
        let Some(s) = shown else {
            ui.label("rendering…");
            return;
        };
        match s.step {
            Step::Preview { stride } => ui.label(format!("preview: every {stride}th pixel")),
            Step::Passes { spp } => ui.label(format!("{spp} / {target_spp} spp")),
        };
        ui.separator();
        ui.label(format!(
            "{:.0} ms since the edit",
            s.since_edit.as_secs_f64() * 1e3
        ));
        if s.samples_per_second > 0.0 {
            ui.separator();
            ui.label(format!("{:.2} M samples/s", s.samples_per_second / 1e6));
        }
        if s.discarded > 0 {
            ui.separator();
            ui.colored_label(
                ui.visuals().warn_fg_color,
                format!("{} NaN/∞ samples left out", s.discarded),
            );
        }
    });
}
