//! Roots of a α² + b α + c = 0 without catastrophic cancellation.

/// The real roots of `a α² + b α + c = 0` in increasing order, computed with
/// the stable form q = −(b + sign(b)√disc)/2, roots q/a and c/q (Numerical
/// Recipes §5.6; Ray Tracing Gems ch. 7). A vanishing `a` (a ray parallel to a
/// cone's generator, say) falls back to the linear root −c/b instead of NaN.
pub fn solve_quadratic(a: f32, b: f32, c: f32) -> Option<(f32, f32)> {
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let root = -c / b;
        return Some((root, root));
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 || !disc.is_finite() {
        return None;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (r0, r1) = if q == 0.0 {
        // b = 0 and c = 0: a double root at 0.
        (0.0, 0.0)
    } else {
        (q / a, c / q)
    };
    Some(if r0 <= r1 { (r0, r1) } else { (r1, r0) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_both_roots_in_order() {
        let (r0, r1) = solve_quadratic(1.0, -3.0, 2.0).expect("two roots");
        assert_eq!((r0, r1), (1.0, 2.0));
    }

    #[test]
    fn no_real_roots_is_none() {
        assert!(solve_quadratic(1.0, 0.0, 1.0).is_none());
    }

    #[test]
    fn small_root_keeps_its_precision() {
        // α² − 1e4 α + 1 = 0 has a root near 1e-4; the textbook formula loses it in f32.
        let (r0, _) = solve_quadratic(1.0, -1.0e4, 1.0).expect("roots");
        assert!((r0 - 1.0e-4).abs() / 1.0e-4 < 1e-5, "{r0}");
    }

    #[test]
    fn vanishing_leading_coefficient_gives_the_linear_root() {
        let (r0, r1) = solve_quadratic(0.0, 2.0, -1.0).expect("linear root");
        assert_eq!((r0, r1), (0.5, 0.5));
    }
}
