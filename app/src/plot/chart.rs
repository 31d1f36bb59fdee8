//! The PNG chart of `raylab chart`: speed-against-accuracy curves, relative
//! MSE and FLIP against render time, log–log (plotters).

use super::style::{COLORS, register_font};
use anyhow::{Result, anyhow};
use plotters::prelude::*;
use renderer::diagnostics::convergence::ConvergencePoint;
use std::path::Path;

/// One method's curve.
pub struct Curve {
    /// The method's name as the command line spells it.
    pub name: &'static str,
    /// Its passes.
    pub points: Vec<ConvergencePoint>,
}

/// Chart size in pixels.
const SIZE: (u32, u32) = (1600, 680);

/// The smallest and largest positive values, widened to whole decades.
fn decades(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    (hi > 0.0).then(|| {
        (
            10f64.powf(lo.log10().floor()),
            10f64.powf(hi.log10().ceil()),
        )
    })
}

/// Writes two panels to `path`, relative MSE and FLIP against seconds,
/// one line per curve in each.
pub fn write_chart(path: &Path, title: &str, curves: &[Curve]) -> Result<()> {
    register_font();
    let plot_error =
        |e: &dyn std::fmt::Display| anyhow!("{}: cannot draw the chart: {e}", path.display());
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(&e))?;
    let root = root
        .titled(title, ("sans-serif", 24))
        .map_err(|e| plot_error(&e))?;
    let panels = root.split_evenly((1, 2));
    let rel_mse = |p: &ConvergencePoint| Some(p.rel_mse);
    let flip = |p: &ConvergencePoint| p.perceptual;
    draw_panel(
        &panels[0],
        curves,
        "relative MSE against the reference",
        &rel_mse,
    )
    .map_err(|e| plot_error(&e))?;
    draw_panel(
        &panels[1],
        curves,
        "FLIP (mean, LDR) against the reference",
        &flip,
    )
    .map_err(|e| plot_error(&e))?;
    root.present().map_err(|e| plot_error(&e))?;
    Ok(())
}

/// One log–log panel: `metric` against seconds, one line per curve (points
/// without the metric are left out).
fn draw_panel(
    area: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    curves: &[Curve],
    y_desc: &str,
    metric: &dyn Fn(&ConvergencePoint) -> Option<f64>,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let points = || curves.iter().flat_map(|c| c.points.iter());
    let (x0, x1) = decades(points().map(|p| p.seconds)).unwrap_or((1e-2, 1.0));
    let (y0, y1) = decades(points().filter_map(metric)).unwrap_or((1e-4, 1.0));
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("render time (s)")
        .y_desc(y_desc)
        .label_style(("sans-serif", 16))
        .x_label_formatter(&|x| format!("{x}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    for (k, curve) in curves.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let line: Vec<(f64, f64)> = curve
            .points
            .iter()
            .filter_map(|p| metric(p).map(|y| (p.seconds, y)))
            .filter(|&(_, y)| y > 0.0 && y.is_finite())
            .collect();
        chart
            .draw_series(LineSeries::new(line.iter().copied(), color.stroke_width(2)))?
            .label(curve.name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
            });
        chart.draw_series(line.iter().map(|&p| Circle::new(p, 2, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 18))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    Ok(())
}
