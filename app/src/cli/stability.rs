//! `raylab stability`: runs the suite of cases where numerical methods fail
//! (renderer::diagnostics::stability), prints a table and writes it as CSV and a PNG chart.

use super::args::StabilityArgs;
use crate::cli::progress::Progress;
use crate::io::stdout::say;
use crate::plot::stability::{format_value, write_chart};
use anyhow::{Context, Result};
use renderer::diagnostics::stability::{CASES, Effort, Row};
use std::io::Write;
use std::path::PathBuf;

/// Runs the suite; returns the files written.
pub fn run(args: &StabilityArgs) -> Result<Vec<PathBuf>> {
    let effort = if args.quick {
        Effort::QUICK
    } else {
        Effort::FULL
    };
    if cfg!(debug_assertions) {
        eprintln!("note: a debug build; the ns per test are not what a release build costs");
    }
    let mut rows = Vec::new();
    let progress = Progress::new(CASES.len() as u64, "cases");
    for case in CASES {
        progress.say(case.name);
        let case_rows = (case.run)(effort);
        progress.suspend(|| {
            say!("\n{}: {}", case.name, case.about);
            if let Some(first) = case_rows.first() {
                say!(
                    "  {:>12}  {:<16} {:>9} {:>8} {:>10} {:>9}",
                    "value",
                    "method",
                    "failures",
                    "refused",
                    "p99 error",
                    "ns/test"
                );
                say!("  ({})", first.condition);
            }
            for row in &case_rows {
                say!("  {}", table_line(row));
            }
        });
        progress.step();
        rows.extend(case_rows);
    }
    progress.finish();
    let (csv, png) = crate::io::output_path::csv_and_png(args.output.as_deref(), "stability");
    write_csv(&csv, &rows)?;
    write_chart(&png, &rows)?;
    Ok(vec![csv, png])
}

/// One row of the printed table.
fn table_line(row: &Row) -> String {
    format!(
        "{:>12}  {:<16} {:>8.3}% {:>8} {:>10} {:>9.1}",
        format_value(row.value),
        row.method,
        100.0 * row.failure_rate(),
        row.refused,
        row.error_p99.map_or("-".into(), |e| format!("{e:.1e}")),
        row.ns_per_test
    )
}

/// Quotes a CSV field that holds a comma or a quote.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// One line per row: case, condition, value, method, trials, failures,
/// failure_rate, refused, error_p99, ns_per_test.
fn write_csv(path: &std::path::Path, rows: &[Row]) -> Result<()> {
    let mut out = String::from(
        "case,condition,value,method,trials,failures,failure_rate,refused,error_p99,ns_per_test\n",
    );
    for row in rows {
        out.push_str(&format!(
            "{},{},{:e},{},{},{},{:.6e},{},{},{:.2}\n",
            csv_field(row.case),
            csv_field(row.condition),
            row.value,
            csv_field(row.method),
            row.trials,
            row.failures,
            row.failure_rate(),
            row.refused,
            row.error_p99.map_or(String::new(), |e| format!("{e:.3e}")),
            row.ns_per_test
        ));
    }
    let mut file =
        std::fs::File::create(path).with_context(|| format!("cannot write {}", path.display()))?;
    file.write_all(out.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))
}
