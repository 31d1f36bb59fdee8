//! Running a method over a batch of inputs: its cost per test, and a tally
//! of its answers.

use super::Row;
use std::hint::black_box;
use std::time::Instant;

/// The answers of one method at one condition value, judged one by one.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    trials: u64,
    failures: u64,
    refused: u64,
    errors: Vec<f64>,
}

impl Tally {
    /// A right answer, with its relative error if the case measures one.
    pub fn pass(&mut self, relative_error: Option<f64>) {
        self.trials += 1;
        if let Some(e) = relative_error {
            self.errors.push(e);
        }
    }

    /// A wrong answer given silently.
    pub fn fail(&mut self) {
        self.trials += 1;
        self.failures += 1;
    }

    /// An input refused with a clear error.
    pub fn refuse(&mut self) {
        self.trials += 1;
        self.refused += 1;
    }

    /// A right answer if `ok`, else a failure.
    pub fn judge(&mut self, ok: bool, relative_error: Option<f64>) {
        if ok {
            self.pass(relative_error);
        } else {
            self.fail();
        }
    }

    /// The row of this tally.
    pub fn row(
        mut self,
        case: &'static str,
        condition: &'static str,
        value: f64,
        method: &'static str,
        ns_per_test: f64,
    ) -> Row {
        Row {
            case,
            condition,
            value,
            method,
            trials: self.trials,
            failures: self.failures,
            refused: self.refused,
            error_p99: percentile_99(&mut self.errors),
            ns_per_test,
        }
    }
}

/// The 99th percentile (nearest rank) of `values`; NaN counts as largest.
fn percentile_99(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(|a, b| a.total_cmp(b));
    let rank = ((0.99 * values.len() as f64).ceil() as usize).clamp(1, values.len());
    Some(values[rank - 1])
}

/// Runs `method` on every input: its answers, and the mean cost of one call in ns.
pub fn timed<I, R>(inputs: &[I], method: impl Fn(&I) -> R) -> (Vec<R>, f64) {
    let start = Instant::now();
    let answers: Vec<R> = inputs
        .iter()
        .map(|i| black_box(method(black_box(i))))
        .collect();
    let ns = start.elapsed().as_nanos() as f64 / inputs.len().max(1) as f64;
    (answers, ns)
}

/// Runs `method` on every input ([`timed`]), then tallies each answer with `judge`.
pub fn measure<I, R>(
    inputs: &[I],
    method: impl Fn(&I) -> R,
    judge: impl Fn(&I, &R, &mut Tally),
) -> (Tally, f64) {
    let (answers, ns) = timed(inputs, method);
    let mut tally = Tally::default();
    for (input, answer) in inputs.iter().zip(&answers) {
        judge(input, answer, &mut tally);
    }
    (tally, ns)
}

/// |found − exact| / |exact|, or |found − exact| when exact is 0.
pub fn relative_error(found: f64, exact: f64) -> f64 {
    let diff = (found - exact).abs();
    if exact == 0.0 {
        diff
    } else {
        diff / exact.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentile_99_of_one_to_a_hundred_is_ninety_nine() {
        let mut v: Vec<f64> = (1..=100).map(f64::from).collect();
        v.reverse();
        assert_eq!(percentile_99(&mut v), Some(99.0));
        assert_eq!(percentile_99(&mut []), None);
    }

    #[test]
    fn tally_counts_failures_refusals_and_errors() {
        let mut t = Tally::default();
        t.judge(true, Some(0.5));
        t.judge(false, Some(9.0));
        t.refuse();
        let row = t.row("c", "x", 1.0, "m", 2.0);
        assert_eq!((row.trials, row.failures, row.refused), (3, 1, 1));
        assert_eq!(row.error_p99, Some(0.5));
        assert!((row.failure_rate() - 1.0 / 3.0).abs() < 1e-12);
    }
}
