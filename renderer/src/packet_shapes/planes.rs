//! Infinite planes against sixteen rays: [`Plane::intersect`] and
//! [`Plane::surface`], lane by lane. No box holds a plane, so planes stand
//! outside the tree: a nearest-hit search meets them after every bounded
//! primitive, in world order, and takes a plane only where it is strictly
//! nearer (as `World::intersect` does: a cone's base lying in the floor
//! wins the tie); a shadow ray meets them first, as `World::occluded` does.

use super::{FloatLanes, MaskLanes, Nearest, Rays, Vec3s, WIDTH, gather3};
use crate::shapes::Plane;

/// One plane's constants.
#[derive(Clone, Copy, Debug)]
struct PackedPlane {
    /// s, a point on the plane.
    point: glam::Vec3,
    /// n, the unit normal.
    normal: glam::Vec3,
    /// The object id.
    object: i32,
}

/// The planes of a world.
#[derive(Clone, Debug, Default)]
pub(super) struct Planes {
    /// In world order.
    items: Vec<PackedPlane>,
}

impl Planes {
    /// Adds object `object`, the plane `p`; returns its index here.
    pub(super) fn push(&mut self, object: i32, p: &Plane) -> u32 {
        self.items.push(PackedPlane {
            point: p.point,
            normal: p.normal,
            object,
        });
        self.items.len() as u32 - 1
    }

    /// True when there are none (the packet checker's test counts).
    #[cfg(test)]
    pub(super) fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The lanes whose ray meets `p` in (0, limit), and α there (anything
    /// elsewhere): α = n · (s − P0) / (n · v), none where n · v = 0, the
    /// scalar operations in the scalar order.
    #[inline(always)]
    fn hit<F: FloatLanes>(p: &PackedPlane, rays: &Rays<F>, limit: F) -> (F::Mask, F) {
        let n = Vec3s::<F>::splat(p.normal);
        let denom = n.dot(rays.dir);
        let alpha = n.dot(Vec3s::splat(p.point) - rays.origin) / denom;
        let hit = denom.simd_ne(F::ZERO) & alpha.simd_gt(F::ZERO) & alpha.simd_lt(limit);
        (hit, alpha)
    }

    /// Takes the hits of every plane that are strictly nearer than
    /// `nearest`'s, one plane after the other, adding to `tests` one test
    /// per plane for each lane of `live`.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        live: F::Mask,
        nearest: &mut Nearest<F>,
        tests: &mut F::Ints,
    ) {
        for p in &self.items {
            *tests = *tests + super::count::<F>(live, 1);
            let (hit, alpha) = Self::hit(p, rays, nearest.limit);
            nearest.take(hit, alpha, p.object);
        }
    }

    /// Adds the lanes a plane blocks within their t_max to
    /// `settled`, and to `tests` one test per plane for each lane that
    /// was still open when it was tested (a lane stops at the first
    /// plane that blocks it, as `World::occluded`'s do); true as soon as
    /// every lane is settled.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        settled: &mut F::Mask,
        tests: &mut F::Ints,
    ) -> bool {
        for p in &self.items {
            *tests = *tests + super::count::<F>(!*settled, 1);
            let (hit, _) = Self::hit(p, rays, rays.t_max);
            *settled = *settled | hit;
            if settled.all() {
                return true;
            }
        }
        false
    }

    /// Hit point and normal at α of the planes `index` (per lane), as
    /// [`Plane::surface`] computes them: P0 + α v projected onto the plane
    /// (p − n (n · (p − s))), and n.
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
    ) -> (Vec3s<F>, Vec3s<F>) {
        let point = gather3(index, |k| self.items[k].point);
        let normal = gather3(index, |k| self.items[k].normal);
        let p = rays.at(alpha);
        (p - normal * normal.dot(p - point), normal)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::{
        assert_lanes_equal_scalar, check_rays, rays_for, same_everywhere, world_of,
    };
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::integrator::sampler::Sampler;
    use crate::simd::{WithLanes, on_every_lane_type};
    use glam::Vec3;

    /// Each lane's α against one plane equals `Plane::intersect`'s, and its
    /// surface `Plane::surface`'s, bit for bit, in lanes `F`.
    fn check_against_one_with<F: FloatLanes>(p: &Plane, lanes: &[Ray; WIDTH]) -> usize {
        let mut planes = Planes::default();
        planes.push(3, p);
        let rays = Rays::<F>::from_lanes(lanes);
        let (hit, alpha) = Planes::hit(&planes.items[0], &rays, rays.t_max);
        let (point, normal) = planes.surface(&rays, alpha, &[0; WIDTH]);
        assert_lanes_equal_scalar(
            lanes,
            (hit, alpha),
            (point, normal),
            |ray| p.intersect(ray),
            |ray, alpha| p.surface(ray, alpha),
            p,
        )
    }

    /// [`check_against_one_with`] for every lane type.
    #[derive(Clone)]
    struct AgainstOne<'a>(&'a Plane, &'a [Ray; WIDTH]);

    impl WithLanes for AgainstOne<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            check_against_one_with::<F>(self.0, self.1)
        }
    }

    #[test]
    fn every_lane_equals_the_scalar_plane_test_and_surface() {
        let mut rng = Sampler::for_sample(41, 0, 0, 0);
        let mut hits = 0;
        for case in 0..3000 {
            let scale = [1.0, 1e-3, 1e3][case % 3];
            let point = rng.next_direction() * 5.0 * rng.next_f32() * scale;
            // Axis-aligned normals half the time (floors, walls).
            let normal = match case % 4 {
                0 => Vec3::Y,
                1 => Vec3::new(0.0, 0.0, -1.0),
                _ => rng.next_direction(),
            };
            let p = Plane::new(point, normal);
            let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
                let origin = match k % 3 {
                    // On the plane (a bounce's origin, α ≈ 0).
                    0 => point + (rng.next_direction() * scale).reject_from(p.normal),
                    _ => point + rng.next_direction() * scale * (1.0 + 50.0 * rng.next_f32()),
                };
                let dir = match (k + case) % 4 {
                    // Parallel to the plane.
                    0 => rng
                        .next_direction()
                        .reject_from(p.normal)
                        .normalize_or(Vec3::X),
                    _ => rng.next_direction(),
                };
                let ray = Ray::new(origin, dir);
                match (k + case) % 5 {
                    0 => ray.with_t_max(10.0 * scale * rng.next_f32()),
                    1 if k == 4 => ray.with_t_max(0.0),
                    _ => ray,
                }
            });
            hits += same_everywhere(on_every_lane_type(AgainstOne(&p, &lanes)));
        }
        assert!(hits > 10_000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn a_box_standing_on_the_floor_wins_the_tie_and_a_world_of_planes_alone_matches() {
        // Rays from under the floor straight up meet the box's bottom face
        // and the floor at the same α = 1: the box must win, as the scalar
        // test decides (a plane only when strictly nearer).
        let world = world_of(
            r#"<scene><floor y="0"/><box center="0 0.5 0" size="1 1 1"/><sphere center="5 1 0" radius="1"/></scene>"#,
        );
        let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
            let (x, z) = ((k % 4) as f32 * 0.2 - 0.3, (k / 4) as f32 * 0.1 - 0.15);
            Ray::new(Vec3::new(x, -1.0, z), Vec3::Y)
        });
        for ray in &lanes {
            let want = world
                .intersect(ray, crate::shapes::Method::Robust)
                .expect("a hit");
            assert_eq!(
                (want.object, want.alpha),
                (1, 1.0),
                "the box, at the floor's α"
            );
        }
        assert_eq!(check_rays(&world, &lanes), WIDTH);
        // Planes and nothing else: no tree, every lane's plane hit.
        let planes = world_of(
            r#"<scene><floor y="0"/><plane point="0 0 -4" normal="0 0.3 1"/><plane point="3 0 0" normal="-1 0 0"/></scene>"#,
        );
        let rays = rays_for(&planes, 44, 500);
        assert!(check_rays(&planes, &rays) > 100);
    }

    #[test]
    fn worlds_with_floors_and_walls_give_the_scalar_worlds_hits_bit_for_bit() {
        // A floor, a tilted wall and a wall through the shapes, with boxes
        // standing on the floor (a box's face and the floor tie there, and
        // the box must win), with few primitives (every one tested) and
        // with many (through the tree).
        let mut rng = Sampler::for_sample(42, 0, 0, 0);
        let planes = r#"<floor y="0"/><plane point="0 0 -4" normal="0 0.3 1"/><plane point="0 0 0" normal="1 0 0"/>"#;
        for count in [3, 40] {
            let shapes: String = (0..count)
                .map(|k| {
                    let c = rng.next_direction() * 3.0 * rng.next_f32();
                    match k % 3 {
                        0 => format!(r#"<sphere center="{} {} {}" radius="0.4"/>"#, c.x, c.y, c.z),
                        1 => format!(r#"<box center="{} 0.5 {}" size="1 1 1"/>"#, c.x, c.z),
                        _ => format!(
                            r#"<triangle t0="{} 0 {}" t1="{} 1 {}" t2="{} 0 {}"/>"#,
                            c.x,
                            c.z,
                            c.x + 0.5,
                            c.z,
                            c.x + 1.0,
                            c.z + 0.5
                        ),
                    }
                })
                .collect();
            let world = world_of(&format!("<scene>{planes}{shapes}</scene>"));
            let rays = rays_for(&world, 43 + count as u64, 4000);
            let found = check_rays(&world, &rays);
            assert!(found > 2000, "{count} shapes: too few hits ({found})");
        }
    }
}
