//! The scalar path tracer's small formulas, lane by lane and bit for bit:
//! the shading frame, the ray origin's offset off a surface and the power
//! heuristic.

use crate::packet::{FloatLanes, MaskLanes, Vec3s};

/// Sixteen shading frames around unit normals (local +z), as
/// `ShadingFrame::new` builds each (Duff et al. 2017, glam's
/// `any_orthonormal_pair`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Frame<F: FloatLanes> {
    /// First tangents.
    pub(super) s: Vec3s<F>,
    /// Second tangents.
    pub(super) t: Vec3s<F>,
    /// The normals.
    pub(super) n: Vec3s<F>,
}

impl<F: FloatLanes> Frame<F> {
    /// The frames around the unit normals `n`.
    #[inline(always)]
    pub(super) fn new(n: Vec3s<F>) -> Self {
        // f32::signum: −1 for a negative z (−0 included), else 1.
        let sign = n.z.is_sign_negative().select(F::splat(-1.0), F::ONE);
        let a = F::splat(-1.0) / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3s::new(F::ONE + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3s::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// World directions → local coordinates (`ShadingFrame::to_local`).
    #[inline(always)]
    pub(super) fn to_local(self, v: Vec3s<F>) -> Vec3s<F> {
        Vec3s::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local coordinates → world directions (`ShadingFrame::to_world`).
    #[inline(always)]
    pub(super) fn to_world(self, v: Vec3s<F>) -> Vec3s<F> {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// `offset_ray_origin` lane by lane: each point moved off its surface to
/// the side of its `normal` by 64 ε times the largest of its object's
/// `magnitude` and its own coordinates.
#[inline(always)]
pub(super) fn offset_origins<F: FloatLanes>(
    point: Vec3s<F>,
    normal: Vec3s<F>,
    magnitude: F,
) -> Vec3s<F> {
    let m = magnitude
        .max(point.abs().max_element())
        .max(F::splat(f32::MIN_POSITIVE));
    point + normal * (F::splat(crate::geometry::offset::OFFSET_EPSILONS * f32::EPSILON) * m)
}

/// `power_heuristic(own, other)` lane by lane.
#[inline(always)]
pub(super) fn power_heuristics<F: FloatLanes>(own: F, other: F) -> F {
    let (a, b) = (own * own, other * other);
    let usable = (a + b).simd_gt(F::ZERO) & a.is_finite();
    let otherwise = own.simd_gt(F::ZERO).select(F::ONE, F::ZERO);
    usable.select(a / (a + b), otherwise)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::offset::offset_ray_origin;
    use crate::integrator::path::power_heuristic;
    use crate::packet::WIDTH;
    use crate::shading::bsdf::ShadingFrame;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec3;

    /// Unit vectors in every octant, at the poles and near them.
    fn normals(seed: u32) -> [Vec3; WIDTH] {
        std::array::from_fn(|k| {
            let a = (k as f32 + 0.3 * seed as f32) * 0.77;
            let v = match (k + seed as usize) % 4 {
                0 => Vec3::new(a.cos(), a.sin(), 0.1 * a),
                1 => Vec3::new(0.0, 0.0, if k % 2 == 0 { 1.0 } else { -1.0 }),
                2 => Vec3::new(1e-4 * a, -2e-4, -1.0),
                _ => Vec3::new(-a.sin(), 0.5, -a.cos()),
            };
            v.normalize()
        })
    }

    #[derive(Clone)]
    struct Frames;

    impl WithLanes for Frames {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            for seed in 0..16 {
                let n = normals(seed);
                let frames = Frame::new(Vec3s::<F>::from_lanes(&n));
                let v = Vec3s::<F>::from_lanes(&normals(seed + 7));
                let world = frames.to_world(v);
                for (k, &normal) in n.iter().enumerate() {
                    let scalar = ShadingFrame::new(normal);
                    assert_eq!(frames.s.lane(k), scalar.s, "s, n = {normal}");
                    assert_eq!(frames.t.lane(k), scalar.t, "t, n = {normal}");
                    assert_eq!(world.lane(k), scalar.to_world(v.lane(k)));
                }
            }
        }
    }

    #[test]
    fn frames_equal_the_scalar_shading_frames_bit_for_bit() {
        on_every_lane_type(Frames);
    }

    #[derive(Clone)]
    struct Offsets;

    impl WithLanes for Offsets {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            for scale in [1e-3f32, 0.5, 1.0, 37.0, 1e5] {
                let p: [Vec3; WIDTH] = normals(3).map(|v| v * scale * 1.3);
                let n = normals(5);
                let m: [f32; WIDTH] = std::array::from_fn(|k| scale * (k as f32) * 0.25);
                let lanes = offset_origins(
                    Vec3s::<F>::from_lanes(&p),
                    Vec3s::from_lanes(&n),
                    F::from_array(m),
                );
                for k in 0..WIDTH {
                    assert_eq!(
                        lanes.lane(k),
                        offset_ray_origin(p[k], n[k], m[k]),
                        "scale {scale} lane {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn offsets_equal_the_scalar_offsets_bit_for_bit() {
        on_every_lane_type(Offsets);
    }

    #[derive(Clone)]
    struct Heuristics;

    impl WithLanes for Heuristics {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            let values = [0.0f32, 1e-30, 0.3, 1.0, 7.5, 1e30, f32::INFINITY, f32::MAX];
            let others: [f32; WIDTH] = std::array::from_fn(|k| values[k % values.len()]);
            for &own in &values {
                let lanes = power_heuristics(F::splat(own), F::from_array(others)).to_array();
                for (k, &o) in others.iter().enumerate() {
                    assert_eq!(
                        lanes[k].to_bits(),
                        power_heuristic(own, o).to_bits(),
                        "{own} vs {o}"
                    );
                }
            }
        }
    }

    #[test]
    fn power_heuristics_equal_the_scalar_one_bit_for_bit() {
        on_every_lane_type(Heuristics);
    }
}
