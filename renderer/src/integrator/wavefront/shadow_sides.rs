//! The sixteen lanes' shadow rays: `ShadingContext::lit_side` and
//! `ShadowStart::ray` lane by lane and bit for bit, with rays from below the
//! surface for lights a transmitting lobe sees through it.

use super::lane_math::offset_origins;
use crate::geometry::terminator::TERMINATOR_BAND;
use crate::packet::{FloatLanes, MaskLanes, Rays, Vec3s};

/// The lanes' hit points, normals and curved-surface points, ready to start
/// shadow rays toward any direction.
#[derive(Clone, Copy, Debug)]
pub(super) struct ShadowSides<F: FloatLanes> {
    /// The hit points.
    point: Vec3s<F>,
    /// The unit geometric normals on the side each ray came from.
    geometric: Vec3s<F>,
    /// The unit shading normals on that side.
    shading: Vec3s<F>,
    /// Hanika's points on the curved surfaces, on `curved` lanes.
    curved_point: Vec3s<F>,
    /// The lanes on a mesh hit from the side its normals face.
    curved: F::Mask,
    /// Each lane's object's largest coordinate (the offset's scale).
    magnitude: F,
    /// The points offset above the surfaces: every lane's origin off its
    /// flat surface.
    above: Vec3s<F>,
    /// The points offset below the surfaces.
    below: Vec3s<F>,
}

impl<F: FloatLanes> ShadowSides<F> {
    /// The lanes' sides: hit `point`s, `geometric` and `shading` normals
    /// turned toward the rays, and on `curved` lanes the points of the
    /// surfaces their normals describe.
    #[inline(always)]
    pub(super) fn new(
        point: Vec3s<F>,
        geometric: Vec3s<F>,
        shading: Vec3s<F>,
        curved_point: Vec3s<F>,
        curved: F::Mask,
        magnitude: F,
    ) -> Self {
        Self {
            point,
            geometric,
            shading,
            curved_point,
            curved,
            magnitude,
            above: offset_origins(point, geometric, magnitude),
            below: offset_origins(point, -geometric, magnitude),
        }
    }

    /// The lanes whose ray came from the side light from `dir` reaches
    /// (`ShadingContext::lit_side`), and each lane's shadow ray toward the
    /// light `distance` along `dir` (∞ for light from infinitely far),
    /// ending at `reach` of the way: `ShadowStart::ray` on those lanes, from
    /// below the surface on the rest.
    #[inline(always)]
    pub(super) fn toward(&self, dir: Vec3s<F>, distance: F, reach: f32) -> (F::Mask, Rays<F>) {
        let cos_geometric = dir.dot(self.geometric);
        let lit =
            cos_geometric.simd_gt(F::ZERO) | (self.curved & dir.dot(self.shading).simd_gt(F::ZERO));
        let reach = F::splat(reach);
        let mut rays = Rays {
            origin: Vec3s::select(lit, self.above, self.below),
            dir,
            t_max: distance * reach,
        };
        if !self.curved.any() {
            return (lit, rays);
        }
        let band = F::splat(TERMINATOR_BAND);
        let weight = ((band - cos_geometric) / band).max(F::ZERO).min(F::ONE);
        let lifted = lit & self.curved & weight.simd_gt(F::ZERO);
        if !lifted.any() {
            return (lit, rays);
        }
        let start = self.point + (self.curved_point - self.point) * weight;
        let origin = offset_origins(start, self.geometric, self.magnitude);
        rays.origin = Vec3s::select(lifted, origin, rays.origin);
        // Aimed again from there at the light's point, as `aim` aims it.
        let aimed = lifted & distance.is_finite();
        let d = (self.point + dir * distance) - origin;
        let length = d.dot(d).sqrt();
        rays.dir = Vec3s::select(aimed, d * (F::ONE / length), dir);
        rays.t_max = aimed.select(length * reach, rays.t_max);
        (lit, rays)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::offset::offset_ray_origin;
    use crate::geometry::ray::Ray;
    use crate::geometry::terminator::ShadowStart;
    use crate::packet::{WIDTH, mask_from};
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec3;

    #[derive(Clone)]
    struct Sides;

    impl WithLanes for Sides {
        type Output = ();
        fn run<F: FloatLanes>(self) {
            // Lanes with and without a curved point, lights above, grazing
            // and below the flat surface and in the terminator band, near
            // and infinitely far.
            let lane = |k: usize, a: f32| Vec3::new(a.cos(), 0.3 + 0.1 * k as f32, a.sin());
            let point: [Vec3; WIDTH] = std::array::from_fn(|k| lane(k, k as f32 * 0.7) * 3.0);
            let geometric: [Vec3; WIDTH] =
                std::array::from_fn(|k| lane(k, 1.1 * k as f32).normalize());
            let shading: [Vec3; WIDTH] =
                std::array::from_fn(|k| (geometric[k] + lane(k, 0.4 * k as f32) * 0.6).normalize());
            let curved_point: [Vec3; WIDTH] =
                std::array::from_fn(|k| point[k] + geometric[k] * (0.01 * k as f32));
            let curved_lanes = |k: usize| !k.is_multiple_of(3);
            let distance: [f32; WIDTH] = std::array::from_fn(|k| match k % 4 {
                0 => f32::INFINITY,
                k => 0.5 * k as f32,
            });
            for reach in [1.0, 1.0 - 1e-4] {
                for cos in [-0.6f32, -0.02, 0.0, 0.03, 0.07, 0.1, 0.5] {
                    let dir: [Vec3; WIDTH] = std::array::from_fn(|k| {
                        let n = geometric[k];
                        let t = n.any_orthonormal_vector();
                        (n * cos + t * (1.0 - cos * cos).sqrt()).normalize()
                    });
                    let sides = ShadowSides::<F>::new(
                        Vec3s::from_lanes(&point),
                        Vec3s::from_lanes(&geometric),
                        Vec3s::from_lanes(&shading),
                        Vec3s::from_lanes(&curved_point),
                        mask_from::<F>(curved_lanes),
                        F::splat(3.0),
                    );
                    let (lit, rays) =
                        sides.toward(Vec3s::from_lanes(&dir), F::from_array(distance), reach);
                    for k in 0..WIDTH {
                        let d = dir[k];
                        let curved = curved_lanes(k);
                        let expected_lit =
                            d.dot(geometric[k]) > 0.0 || (curved && d.dot(shading[k]) > 0.0);
                        let expected = if expected_lit {
                            ShadowStart {
                                point: point[k],
                                geometric: geometric[k],
                                magnitude: 3.0,
                                curved: curved.then_some(curved_point[k]),
                            }
                            .ray(d, distance[k], reach)
                        } else {
                            Ray::new(offset_ray_origin(point[k], -geometric[k], 3.0), d)
                                .with_t_max(distance[k] * reach)
                        };
                        let at = format!("cos {cos}, reach {reach}, lane {k}");
                        assert_eq!(lit.to_bitmask() >> k & 1 == 1, expected_lit, "{at}");
                        assert_eq!(rays.origin.lane(k), expected.origin, "{at}");
                        assert_eq!(rays.dir.lane(k), expected.dir, "{at}");
                        assert_eq!(rays.t_max.as_array()[k], expected.t_max, "{at}");
                    }
                }
            }
        }
    }

    #[test]
    fn shadow_rays_equal_the_scalar_ones_bit_for_bit() {
        on_every_lane_type(Sides);
    }
}
