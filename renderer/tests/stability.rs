//! The stability suite (renderer::diagnostics::stability) at test effort: the robust
//! methods meet the bounds, and the lecture's (textbook) methods
//! fail where the suite says they do — if one stopped failing, the case
//! would no longer show anything.

use renderer::diagnostics::stability::{CASES, Effort, Row};
use std::sync::OnceLock;

/// Every row of the suite, run once for all the tests of this file.
fn rows() -> &'static [Row] {
    static ROWS: OnceLock<Vec<Row>> = OnceLock::new();
    ROWS.get_or_init(|| renderer::diagnostics::stability::run_all(Effort::QUICK))
}

/// The rows of one case and method.
fn of(case: &str, method: &str) -> Vec<&'static Row> {
    let found: Vec<_> = rows()
        .iter()
        .filter(|r| r.case == case && r.method == method)
        .collect();
    assert!(!found.is_empty(), "no rows for {case} / {method}");
    found
}

/// The row of one case and method at one condition value.
fn at(case: &str, method: &str, value: f64) -> &'static Row {
    of(case, method)
        .into_iter()
        .find(|r| r.value == value)
        .unwrap_or_else(|| panic!("no row for {case} / {method} at {value}"))
}

fn assert_never_fails(case: &str, method: &str) {
    for row in of(case, method) {
        assert_eq!(
            row.failures, 0,
            "{case} / {method} at {} = {}: {} of {} failed",
            row.condition, row.value, row.failures, row.trials
        );
    }
}

#[test]
fn every_case_has_rows_for_each_of_its_methods_at_every_value() {
    for case in CASES {
        let case_rows: Vec<_> = rows().iter().filter(|r| r.case == case.name).collect();
        assert!(
            case_rows.len() >= 4,
            "{}: {} rows",
            case.name,
            case_rows.len()
        );
        for row in case_rows {
            assert!(row.trials >= 10, "{row:?}");
            assert!(
                row.ns_per_test.is_finite() && row.ns_per_test > 0.0,
                "{row:?}"
            );
        }
    }
}

#[test]
fn robust_sphere_never_misses_up_to_a_million_radii_and_its_alpha_is_accurate() {
    assert_never_fails("sphere far away", "robust");
    for row in of("sphere far away", "robust") {
        let p99 = row.error_p99.expect("hits measured");
        assert!(p99 < 5e-6, "p99 relative error {p99:e} at {}", row.value);
    }
}

#[test]
fn lecture_sphere_loses_hits_from_ten_thousand_radii() {
    let row = at("sphere far away", "lecture", 1e4);
    assert!(row.failure_rate() > 0.05, "{row:?}");
    assert_eq!(at("sphere far away", "lecture", 1e2).failures, 0);
}

#[test]
fn watertight_triangles_never_leak_at_a_shared_edge_while_the_lecture_does() {
    assert_never_fails("triangles: shared edge", "robust");
    assert!(at("triangles: shared edge", "lecture", 1.0).failure_rate() > 0.01);
    assert!(at("triangles: shared edge", "Möller–Trumbore", 1.0).failure_rate() > 0.01);
}

#[test]
fn robust_triangle_hits_slivers_that_the_lecture_misses() {
    assert_never_fails("triangles: slivers", "robust");
    assert!(at("triangles: slivers", "lecture", 1e4).failure_rate() > 0.5);
}

#[test]
fn no_triangle_method_accepts_a_nan_or_off_plane_hit_for_parallel_rays() {
    for method in ["lecture", "Möller–Trumbore", "robust"] {
        assert_never_fails("triangles: parallel rays", method);
    }
}

#[test]
fn robust_torus_misses_at_most_0_3_percent_up_to_ten_thousand_radii_and_never_hits_the_hole() {
    for row in of("torus far away: tube", "robust") {
        assert!(row.failure_rate() <= 0.003, "{row:?}");
    }
    assert_never_fails("torus far away: hole", "robust");
    assert!(at("torus far away: tube", "textbook", 1e2).failure_rate() > 0.1);
}

#[test]
fn offset_origins_give_no_acne_at_any_scale_where_a_fixed_epsilon_does() {
    assert_never_fails("self-intersection: acne", "robust");
    assert!(at("self-intersection: acne", "fixed ε", 1e4).failure_rate() > 0.1);
}

#[test]
fn offset_origins_do_not_leak_through_a_gap_of_1e_minus_5_of_the_scale() {
    assert_never_fails("self-intersection: leak", "robust");
    assert!(at("self-intersection: leak", "fixed ε", 1.0).failure_rate() > 0.5);
}

#[test]
fn stable_cone_finds_a_ray_parallel_to_a_generator_that_the_textbook_misses() {
    assert_never_fails("cone: ray along a generator", "robust");
    assert_eq!(
        at("cone: ray along a generator", "textbook", 0.0).failure_rate(),
        1.0
    );
}

#[test]
fn bvh_loses_no_hit_that_brute_force_finds() {
    assert_never_fails("BVH: lost hits", "bvh");
    assert_never_fails("BVH: lost hits", "brute force");
}

#[test]
fn robust_camera_is_orthonormal_to_1e_minus_6_or_refuses_and_is_never_nan() {
    for case in [
        "camera: u near t",
        "camera: θ near 0° or 90°",
        "camera: length of t",
    ] {
        assert_never_fails(case, "robust");
    }
    // t ∥ u and a pixel too narrow for f32 are refused, not rendered.
    assert_eq!(
        at("camera: u near t", "robust", 0.0).refused,
        at("camera: u near t", "robust", 0.0).trials
    );
    let narrow = at("camera: θ near 0° or 90°", "robust", 1e-4);
    assert_eq!(narrow.refused, narrow.trials);
    // The lecture assumes unit, orthogonal t and u.
    assert_eq!(at("camera: u near t", "lecture", 1.0).failure_rate(), 1.0);
    assert_eq!(
        at("camera: length of t", "lecture", 1e3).failure_rate(),
        1.0
    );
}
