//! Boxes against sixteen rays: [`Cuboid::intersect`]'s slab test in object
//! space and [`Cuboid::surface`]'s snapped point, lane by lane.
//!
//! `Cuboid::intersect` first asks a loose world-space bounding sphere
//! (`shapes/bound.rs`) whether the ray may hit; that test only turns away
//! rays the exact test misses too (its own tests check it), so it is left
//! out here: the slab test alone gives the same answer, and for sixteen
//! incoherent rays it rarely could skip a box anyway.

use super::{FloatLanes, MaskLanes, Nearest, Rays, Vec3s, WIDTH, coordinate, gather3};
use crate::shapes::Cuboid;
use glam::Vec3;
use std::ops::Range;

/// One box's constants.
#[derive(Clone, Copy, Debug)]
struct PackedBox {
    /// The columns of object_from_world (the transposed rotation).
    object_from_world: [Vec3; 3],
    /// The columns of world_from_object.
    world_from_object: [Vec3; 3],
    /// The centre (object space's origin).
    origin: Vec3,
    /// Half the edge lengths.
    half: Vec3,
    /// The object id.
    object: i32,
}

/// The boxes of a world.
#[derive(Clone, Debug, Default)]
pub(super) struct Boxes {
    /// In the order they were pushed.
    items: Vec<PackedBox>,
}

/// `m v` lane by lane for a matrix given by its columns, summed as glam's
/// `Mat3::mul_vec3`: (c0 v.x + c1 v.y) + c2 v.z.
#[inline(always)]
fn transform<F: FloatLanes>(columns: &[Vec3s<F>; 3], v: Vec3s<F>) -> Vec3s<F> {
    columns[0] * v.x + columns[1] * v.y + columns[2] * v.z
}

/// `Placement::ray_to_object` for sixteen rays: origins and directions in
/// object space.
#[inline(always)]
fn to_object<F: FloatLanes>(
    object_from_world: &[Vec3s<F>; 3],
    origin: Vec3s<F>,
    rays: &Rays<F>,
) -> (Vec3s<F>, Vec3s<F>) {
    (
        transform(object_from_world, rays.origin - origin),
        transform(object_from_world, rays.dir),
    )
}

/// `x` with the sign of `s` (f32::copysign: x's magnitude, s's sign bit).
#[inline(always)]
fn copysign<F: FloatLanes>(x: F, s: F) -> F {
    let sign = F::splat(-0.0);
    x.abs() | (s & sign)
}

/// `p` clamped to [−h, h] as glam's `clamp`: p.max(−h).min(h), each
/// `if a > b { a } else { b }`.
#[inline(always)]
fn clamp<F: FloatLanes>(p: F, h: F) -> F {
    let low = -h;
    let p = p.simd_gt(low).select(p, low);
    p.simd_lt(h).select(p, h)
}

/// In the lanes of `on` (the face's axis), the coordinate `p` snapped to
/// ±`h` with its sign; `p` elsewhere.
#[inline(always)]
fn snap<F: FloatLanes>(on: F::Mask, p: F, h: F) -> F {
    on.select(copysign(h, p), p)
}

/// The local normal's coordinate: ±1 with the sign of `p` in the lanes of
/// `on` (the face's axis), +0 elsewhere.
#[inline(always)]
fn face<F: FloatLanes>(on: F::Mask, p: F) -> F {
    on.select(copysign(F::ONE, p), F::ZERO)
}

impl Boxes {
    /// Adds object `object`, the box `b`; returns its index here.
    pub(super) fn push(&mut self, object: i32, b: &Cuboid) -> u32 {
        let placement = b.placement();
        let m = placement.world_from_object;
        let t = m.transpose();
        self.items.push(PackedBox {
            object_from_world: [t.x_axis, t.y_axis, t.z_axis],
            world_from_object: [m.x_axis, m.y_axis, m.z_axis],
            origin: placement.origin,
            half: b.half(),
            object,
        });
        self.items.len() as u32 - 1
    }

    /// How many there are.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.items.len()
    }

    /// The lanes whose ray hits `b` in (0, limit), and α there (anything
    /// elsewhere): `Cuboid::intersect_exact`'s operations lane by lane.
    #[inline(always)]
    fn hit<F: FloatLanes>(b: &PackedBox, rays: &Rays<F>, limit: F) -> (F::Mask, F) {
        let m = &b.object_from_world;
        let columns = [Vec3s::splat(m[0]), Vec3s::splat(m[1]), Vec3s::splat(m[2])];
        let (o, d) = to_object(&columns, Vec3s::splat(b.origin), rays);
        let zero = F::ZERO;
        let (mut t_near, mut t_far) = (F::NEG_INFINITY, F::INFINITY);
        let mut miss = F::Mask::NONE;
        for axis in 0..3 {
            let (o, d) = (coordinate(&o, axis), coordinate(&d, axis));
            let h = b.half[axis];
            // A zero component: the slab does not constrain the ray if the
            // origin lies in it, and the box is missed otherwise.
            let flat = d.simd_eq(zero);
            miss = miss | (flat & o.abs().simd_gt(F::splat(h)));
            // (NaN or ∞ in the flat lanes, which keep t_near and t_far;
            // elsewhere t_lo and t_hi are never NaN, so the fast min and max
            // give f32::min's and f32::max's values.)
            let t_lo = (F::splat(-h) - o) / d;
            let t_hi = (F::splat(h) - o) / d;
            t_near = flat.select(t_near, t_near.fast_max(t_lo.fast_min(t_hi)));
            t_far = flat.select(t_far, t_far.fast_min(t_lo.fast_max(t_hi)));
        }
        let slab = !miss & t_near.simd_le(t_far);
        let near_inside = t_near.simd_gt(zero) & t_near.simd_lt(limit);
        let far_inside = t_far.simd_gt(zero) & t_far.simd_lt(limit);
        (
            slab & (near_inside | far_inside),
            near_inside.select(t_near, t_far),
        )
    }

    /// Takes the hits of the boxes `range` (indices here) that are nearer
    /// than `nearest`'s.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        range: Range<usize>,
        nearest: &mut Nearest<F>,
    ) {
        for b in &self.items[range] {
            let (hit, alpha) = Self::hit(b, rays, nearest.limit);
            nearest.take(hit, alpha, b.object);
        }
    }

    /// Adds the lanes some box of `range` blocks within t_max to
    /// `settled`; true as soon as every lane is settled.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        range: Range<usize>,
        settled: &mut F::Mask,
    ) -> bool {
        for b in &self.items[range] {
            let (hit, _) = Self::hit(b, rays, rays.t_max);
            *settled = *settled | hit;
            if settled.all() {
                return true;
            }
        }
        false
    }

    /// Hit point and normal at α of the boxes `index` (per lane), as
    /// [`Cuboid::surface`] computes them: the object-space point clamped
    /// onto the box, the coordinate of the face it is nearest snapped to
    /// ±half, back to world space with the face's normal.
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
    ) -> (Vec3s<F>, Vec3s<F>) {
        let items = &self.items;
        let world_from_object = [
            gather3(index, |k| items[k].world_from_object[0]),
            gather3(index, |k| items[k].world_from_object[1]),
            gather3(index, |k| items[k].world_from_object[2]),
        ];
        // Its transpose: the columns of object_from_world are its rows.
        let [x, y, z] = world_from_object;
        let object_from_world = [
            Vec3s::new(x.x, y.x, z.x),
            Vec3s::new(x.y, y.y, z.y),
            Vec3s::new(x.z, y.z, z.z),
        ];
        let origin = gather3(index, |k| items[k].origin);
        let half = gather3(index, |k| items[k].half);
        let (o, d) = to_object(&object_from_world, origin, rays);
        let p = o + d * alpha;
        // The face: the axis whose plane the point is nearest (x, then y on ties).
        let excess = p.abs() - half;
        let on_x = excess.x.simd_ge(excess.y) & excess.x.simd_ge(excess.z);
        let on_y = !on_x & excess.y.simd_ge(excess.z);
        let on_z = !(on_x | on_y);
        let p = Vec3s::new(clamp(p.x, half.x), clamp(p.y, half.y), clamp(p.z, half.z));
        // The face's coordinate snapped to ±half, its normal ±1 (with the
        // sign of the clamped coordinate), the other two normal coordinates +0.
        let local_normal = Vec3s::new(face(on_x, p.x), face(on_y, p.y), face(on_z, p.z));
        let p = Vec3s::new(
            snap(on_x, p.x, half.x),
            snap(on_y, p.y, half.y),
            snap(on_z, p.z, half.z),
        );
        // `Placement::surface_to_world`.
        (
            transform(&world_from_object, p) + origin,
            transform(&world_from_object, local_normal),
        )
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

    /// Each lane's α against one box equals `Cuboid::intersect`'s, and its
    /// surface `Cuboid::surface`'s, bit for bit, in lanes `F`.
    fn check_against_one_with<F: FloatLanes>(b: &Cuboid, lanes: &[Ray; WIDTH]) -> usize {
        let mut boxes = Boxes::default();
        boxes.push(3, b);
        let rays = Rays::<F>::from_lanes(lanes);
        let (hit, alpha) = Boxes::hit(&boxes.items[0], &rays, rays.t_max);
        let (point, normal) = boxes.surface(&rays, alpha, &[0; WIDTH]);
        assert_lanes_equal_scalar(
            lanes,
            (hit, alpha),
            (point, normal),
            |ray| b.intersect(ray),
            |ray, alpha| b.surface(ray, alpha),
            b,
        )
    }

    /// [`check_against_one_with`] for every lane type.
    #[derive(Clone)]
    struct AgainstOne<'a>(&'a Cuboid, &'a [Ray; WIDTH]);

    impl WithLanes for AgainstOne<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            check_against_one_with::<F>(self.0, self.1)
        }
    }

    /// [`check_against_one_with`] with every lane type; how many lanes hit.
    fn check_against_one(b: &Cuboid, lanes: &[Ray; WIDTH]) -> usize {
        same_everywhere(on_every_lane_type(AgainstOne(b, lanes)))
    }

    #[test]
    fn every_lane_equals_the_scalar_slab_test_and_surface() {
        let mut rng = Sampler::for_sample(21, 0, 0, 0);
        let mut hits = 0;
        for case in 0..3000 {
            let v = |rng: &mut Sampler, r: f32| {
                Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 * r - Vec3::splat(r)
            };
            let center = v(&mut rng, 2.0);
            let mut size = v(&mut rng, 1.0).abs() * 2.0 + Vec3::splat(0.05);
            if case % 10 == 0 {
                size[case % 3] = 0.0;
            }
            let rotate = if case % 4 == 0 {
                Vec3::ZERO
            } else {
                v(&mut rng, 180.0)
            };
            let b = Cuboid::new(center, size, rotate);
            let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
                let inside = center + b.placement().vector_to_world(v(&mut rng, 0.5) * size);
                let origin = match k % 4 {
                    0 => inside,
                    1 => center + 4.0 * v(&mut rng, 1.0),
                    // On a face plane or an edge line of an unrotated box.
                    2 => {
                        let mut o = center + 3.0 * v(&mut rng, 1.0);
                        o[k % 3] = center[k % 3] + 0.5 * size[k % 3];
                        o
                    }
                    _ => center + 10.0 * v(&mut rng, 1.0),
                };
                let mut dir = match (k + case) % 3 {
                    0 => (inside - origin).normalize_or(Vec3::Y),
                    1 => {
                        // Axis-parallel, with zero and −0 components.
                        let mut d = if case % 2 == 0 {
                            Vec3::splat(-0.0)
                        } else {
                            Vec3::ZERO
                        };
                        d[(k + case / 3) % 3] = if k % 2 == 0 { 1.0 } else { -1.0 };
                        d
                    }
                    _ => v(&mut rng, 1.0).normalize_or(Vec3::X),
                };
                if k == 5 {
                    dir *= 3.0;
                }
                let ray = Ray::new(origin, dir);
                match (k + 2 * case) % 5 {
                    0 => ray.with_t_max(rng.next_f32() * 5.0),
                    1 if case % 7 == 0 => ray.with_t_max(0.0),
                    _ => ray,
                }
            });
            hits += check_against_one(&b, &lanes);
        }
        assert!(hits > 8000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn hand_made_box_cases_equal_the_scalar_test() {
        let unit = Cuboid::new(Vec3::ZERO, Vec3::splat(2.0), Vec3::ZERO);
        let tiny = f32::from_bits(1);
        let cases = [
            // From inside: the exit face.
            Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::Y),
            // From inside with t_max before the exit: no hit.
            Ray::new(Vec3::ZERO, Vec3::X).with_t_max(0.5),
            // Grazing the top face plane, and beside it.
            Ray::new(Vec3::new(-5.0, 1.0, 0.2), Vec3::X),
            Ray::new(Vec3::new(-5.0, 1.0, 1.5), Vec3::X),
            // Along an edge line.
            Ray::new(Vec3::new(1.0, 1.0, -4.0), Vec3::Z),
            // Subnormal components.
            Ray::new(Vec3::new(-3.0, 1.0, -1.0), Vec3::new(1.0, -tiny, tiny)),
            // t_max cutting exactly at the entry.
            Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(4.0),
            Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z).with_t_max(4.0000005),
        ];
        // The cases repeated over the packet's lanes.
        let lanes: [Ray; WIDTH] = std::array::from_fn(|k| cases[k % cases.len()]);
        assert_eq!(check_against_one(&unit, &lanes), 5 * WIDTH / cases.len());
    }

    #[test]
    fn a_world_of_boxes_gives_the_scalar_worlds_hits_bit_for_bit() {
        let world = world_of(
            r#"<scene>
              <box center="0 -1.5 0" size="6 1 6"/>
              <box center="0.335 -0.7 0.38" size="0.6 0.6 0.6" rotate="0 -17 0"/>
              <box center="-0.33 -0.4 -0.28" size="0.6 1.22 0.6" rotate="0 18.25 0"/>
              <box center="0.335 -0.1 0.38" size="0.6 0.6 0.6" rotate="0 -17 0"/>
              <box center="1 1 1" size="1 1 1" rotate="45 45 45"/>
              <box center="-1 1 -1" size="1 0.0001 1"/>
              <box center="0 0 0" size="0.2 0.2 0.2"/>
            </scene>"#,
        );
        let rays = rays_for(&world, 22, 4000);
        let found = check_rays(&world, &rays);
        assert!(found > 2000, "too few hits to mean anything: {found}");
    }
}
