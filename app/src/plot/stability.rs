//! The stability chart: one panel per case, failure rate against the value
//! of the condition that breaks a method, one line per method, each method's
//! cost per test in its legend.

use super::style::{COLORS, register_font};
use anyhow::{Result, anyhow};
use plotters::coord::ranged1d::SegmentValue;
use plotters::prelude::*;
use renderer::diagnostics::stability::Row;
use std::path::Path;

/// A condition value as tables and axes show it: 1e4, 0.01, 89.9999.
pub fn format_value(value: f64) -> String {
    if value == 0.0 {
        "0".into()
    } else if (1e-2..1e3).contains(&value.abs()) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// Panels per row of the chart.
const COLUMNS: usize = 4;
/// One panel's size in pixels.
const PANEL: (u32, u32) = (440, 330);

/// Writes the chart of `rows` (grouped by case, in their order) to `path`.
pub fn write_chart(path: &Path, rows: &[Row]) -> Result<()> {
    register_font();
    let mut cases: Vec<&str> = Vec::new();
    for row in rows {
        if !cases.contains(&row.case) {
            cases.push(row.case);
        }
    }
    let panel_rows = cases.len().div_ceil(COLUMNS).max(1);
    let size = (PANEL.0 * COLUMNS as u32, PANEL.1 * panel_rows as u32 + 50);
    let plot_error =
        |e: &dyn std::fmt::Display| anyhow!("{}: cannot draw the chart: {e}", path.display());
    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| plot_error(&e))?;
    let (title, body) = root.split_vertically(50);
    title
        .titled(
            "Where methods fail: failure rate (%) against the condition that breaks them",
            ("sans-serif", 24),
        )
        .map_err(|e| plot_error(&e))?;
    let panels = body.split_evenly((panel_rows, COLUMNS));
    for (case, panel) in cases.iter().zip(&panels) {
        let case_rows: Vec<&Row> = rows.iter().filter(|r| r.case == *case).collect();
        draw_panel(panel, case, &case_rows).map_err(|e| plot_error(&e))?;
    }
    root.present().map_err(|e| plot_error(&e))?;
    Ok(())
}

/// One case's panel: condition values evenly spaced on x (they span decades
/// and may include 0), failure rate in percent on y.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    case: &str,
    rows: &[&Row],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut values: Vec<f64> = Vec::new();
    let mut methods: Vec<&str> = Vec::new();
    for row in rows {
        if !values.contains(&row.value) {
            values.push(row.value);
        }
        if !methods.contains(&row.method) {
            methods.push(row.method);
        }
    }
    let top = rows
        .iter()
        .map(|r| 100.0 * r.failure_rate())
        .fold(1.0f64, f64::max)
        * 1.45; // headroom for the legend above the lines
    let condition = rows.first().map_or("", |r| r.condition);
    let mut chart = ChartBuilder::on(area)
        .caption(case, ("sans-serif", 18))
        .margin(8)
        .x_label_area_size(42)
        .y_label_area_size(44)
        .build_cartesian_2d((0..values.len() as i32 - 1).into_segmented(), 0.0..top)?;
    let label = |v: &SegmentValue<i32>| match v {
        SegmentValue::CenterOf(k) | SegmentValue::Exact(k) => values
            .get(*k as usize)
            .map_or(String::new(), |&x| format_value(x)),
        SegmentValue::Last => String::new(),
    };
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc(condition)
        .x_labels(values.len())
        .x_label_formatter(&label)
        .y_labels(5)
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()?;
    for (k, method) in methods.iter().enumerate() {
        let color = COLORS[k % COLORS.len()];
        let points: Vec<(SegmentValue<i32>, f64)> = rows
            .iter()
            .filter(|r| r.method == *method)
            .filter_map(|r| {
                let x = values.iter().position(|&v| v == r.value)? as i32;
                Some((SegmentValue::CenterOf(x), 100.0 * r.failure_rate()))
            })
            .collect();
        let method_rows = rows.iter().filter(|r| r.method == *method);
        let (ns, n) = method_rows.fold((0.0, 0), |(s, n), r| (s + r.ns_per_test, n + 1));
        let legend = format!("{method} · {:.0} ns/test", ns / f64::from(n.max(1)));
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(legend)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart.draw_series(
            points
                .into_iter()
                .map(|p| Circle::new(p, 3, color.filled())),
        )?;
    }
    chart
        .configure_series_labels()
        .label_font(("sans-serif", 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()?;
    Ok(())
}
