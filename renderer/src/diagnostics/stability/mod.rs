//! Where numerical methods fail: a suite of hard cases, each run with the
//! lecture's (or the textbook's) method and with raylab's robust one, swept
//! over the condition that breaks the first. Every row records how often a
//! method gave a wrong answer silently, how accurate its right answers were,
//! and what one test cost, so the suite is a speed-against-accuracy chart too.
//! `raylab stability` prints and charts it; `tests/stability.rs` holds the
//! robust methods to their bounds.

mod bvh_lost_hits;
mod camera_basis;
mod cone_generator;
mod measure;
mod self_intersection;
mod sphere_far;
mod torus_far;
mod triangle_edges;
mod triangle_parallel;
mod triangle_slivers;

/// How many tests each (condition value, method) pair gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Effort {
    /// Rays (or cameras) per row.
    pub trials: usize,
}

impl Effort {
    /// Enough to see every failure rate the issue quotes (a few seconds in release).
    pub const FULL: Effort = Effort { trials: 100_000 };
    /// Enough for the tests' bounds, fast in a debug build.
    pub const QUICK: Effort = Effort { trials: 2_000 };
}

/// One method at one value of the condition that breaks it.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The case, e.g. "sphere far away".
    pub case: &'static str,
    /// What the condition is, e.g. "distance / radius".
    pub condition: &'static str,
    /// The condition's value for this row.
    pub value: f64,
    /// The method, e.g. "lecture" or "robust".
    pub method: &'static str,
    /// Tests run.
    pub trials: u64,
    /// Wrong answers given silently: a miss where there is a hit, a hit
    /// where there is none, a NaN, a self-shadow, a leak, a skewed basis.
    pub failures: u64,
    /// Inputs refused with a clear error (not failures).
    pub refused: u64,
    /// The 99th percentile of the relative error of the right answers, if
    /// the case measures one.
    pub error_p99: Option<f64>,
    /// Mean cost of one test in nanoseconds (release builds only are meaningful).
    pub ns_per_test: f64,
}

impl Row {
    /// Failures per test, 0…1.
    pub fn failure_rate(&self) -> f64 {
        if self.trials == 0 {
            0.0
        } else {
            self.failures as f64 / self.trials as f64
        }
    }
}

/// One failure case of the suite.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Its name, as rows and charts show it.
    pub name: &'static str,
    /// What goes wrong and for which method, in a sentence.
    pub about: &'static str,
    /// Runs it: one row per (condition value, method).
    pub run: fn(Effort) -> Vec<Row>,
}

/// Every case, in the order the chart shows them.
pub const CASES: &[Case] = &[
    sphere_far::CASE,
    triangle_edges::CASE,
    triangle_slivers::CASE,
    triangle_parallel::CASE,
    torus_far::TUBE,
    torus_far::HOLE,
    self_intersection::ACNE,
    self_intersection::LEAK,
    cone_generator::CASE,
    bvh_lost_hits::CASE,
    camera_basis::UP_NEAR_TOWARD,
    camera_basis::THETA,
    camera_basis::TOWARD_LENGTH,
];

/// Runs every case with `effort`.
pub fn run_all(effort: Effort) -> Vec<Row> {
    CASES.iter().flat_map(|case| (case.run)(effort)).collect()
}
