//! Spawning secondary rays without self-intersection and without a fixed epsilon.

use glam::Vec3;

/// Below this magnitude a coordinate is offset by a fixed amount (floats are dense there).
const ORIGIN: f32 = 1.0 / 32.0;
/// The fixed offset near the origin, along the normal.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// The offset elsewhere, in units in the last place, along the normal.
const INT_SCALE: f32 = 256.0;

/// Moves a hit point off its surface to the side `normal` points to, by a
/// few units in the last place of each coordinate (Wächter & Binder, "A Fast
/// and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6).
/// The offset scales with the coordinates, so scenes 1e4 units across get no
/// acne while small scenes get no light leaks; rays spawned here use t_min = 0.
pub fn offset_ray_origin(point: Vec3, normal: Vec3) -> Vec3 {
    let offset_int = (INT_SCALE * normal).as_ivec3();
    let shift = |p: f32, by: i32| -> f32 {
        let by = if p < 0.0 { -by } else { by };
        f32::from_bits((p.to_bits() as i32).wrapping_add(by) as u32)
    };
    let p_int = Vec3::new(
        shift(point.x, offset_int.x),
        shift(point.y, offset_int.y),
        shift(point.z, offset_int.z),
    );
    let near = point + FLOAT_SCALE * normal;
    Vec3::new(
        if point.x.abs() < ORIGIN {
            near.x
        } else {
            p_int.x
        },
        if point.y.abs() < ORIGIN {
            near.y
        } else {
            p_int.y
        },
        if point.z.abs() < ORIGIN {
            near.z
        } else {
            p_int.z
        },
    )
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
                    let q = offset_ray_origin(p, n);
                    assert!((q - p).dot(n) > 0.0, "scale {scale} p {p} n {n} q {q}");
                    assert!(
                        (q - p).length() < 1e-3 * scale.max(1.0),
                        "too far: {}",
                        (q - p).length()
                    );
                }
            }
        }
    }
}
