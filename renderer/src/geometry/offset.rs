//! Spawning secondary rays without self-intersection and without a fixed epsilon.

use glam::Vec3;

/// The offset along the normal, in units of f32's ε times the magnitude of
/// the coordinates the hit point was computed from. Hit points are placed on
/// their surface to within a few ε of that magnitude, so 64 ε keeps a wide
/// margin against acne, while 64 ε ≈ 7.6 × 10⁻⁶ of the largest coordinate
/// stays below a gap of 10⁻⁵ of it, so such a gap lets no light through
/// (`raylab stability` measures both).
pub(crate) const OFFSET_EPSILONS: f32 = 64.0;

/// Moves a hit point off its surface to the side `normal` points to, by
/// 64 ε · m along the normal, where m is the largest of `magnitude` (the
/// largest coordinate of the object the point lies on: its error bound scales
/// with it, as in pbrt-v4's offset by the intersection's error bound) and the
/// point's own coordinates. The offset scales with the coordinates, so a
/// scene 10⁵ units across gets no acne and one 10⁻² across leaks no light
/// through gaps of 10⁻⁵ of its size; near the world origin it shrinks with the object,
/// unlike a fixed ε or Wächter & Binder's fixed offset there (Ray Tracing Gems
/// ch. 6). Rays spawned here use t_min = 0.
pub fn offset_ray_origin(point: Vec3, normal: Vec3, magnitude: f32) -> Vec3 {
    let m = magnitude
        .max(point.abs().max_element())
        .max(f32::MIN_POSITIVE);
    point + (OFFSET_EPSILONS * f32::EPSILON * m) * normal
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_to_the_normal_side_at_every_scale() {
        for scale in [1e-2f32, 1.0, 1e2, 1e4, 1e5] {
            for p in [
                Vec3::new(scale, -scale, 0.5 * scale),
                Vec3::new(-scale, 0.0, scale),
            ] {
                for n in [Vec3::X, -Vec3::Y, Vec3::new(0.6, 0.0, -0.8)] {
                    let q = offset_ray_origin(p, n, scale);
                    assert!((q - p).dot(n) > 0.0, "scale {scale} p {p} n {n} q {q}");
                    assert!(
                        (q - p).length() < 1e-5 * scale,
                        "too far: {}",
                        (q - p).length()
                    );
                }
            }
        }
    }
}
