//! Lone triangles against sixteen rays: the watertight test of Woop, Benthin
//! and Wald (2013) exactly as [`WatertightRay`] computes it, each lane with
//! its own axis permutation and shear, both set up once per packet
//! ([`ShearedRays`]).
//!
//! [`WatertightRay`]: crate::shapes::WatertightRay

use super::{FloatLanes, MaskLanes, Nearest, Rays, Vec3s, WIDTH, gather3};
use crate::packet::triangle::{Frame, MixedAxes, Permutation, SameAxes, ShearedRays, hit_with};
use crate::shapes::Triangle;
use glam::Vec3;
use std::ops::Range;
use wide::f64x4;

/// How many f64 constants of a triangle its surface's 2×2 solve uses.
const SOLVE: usize = 13;

/// One triangle's constants.
#[derive(Clone, Copy, Debug)]
struct PackedTriangle {
    /// The corners t0, t1, t2, coordinate by coordinate.
    corners: [[f32; 3]; 3],
    /// The object id.
    object: i32,
    /// Its key: the lowest wins a tie ([`Nearest::triangle_limit`]).
    key: i32,
    /// [`Triangle::normal`].
    normal: Vec3,
    /// What [`Triangle::barycentrics`] computes from the corners alone, in
    /// f64: t0, v1 = t1 − t0 and v2 = t2 − t0 (coordinates 0..3, 3..6,
    /// 6..9), v1 · v1, v1 · v2, v2 · v2 and det = v11 v22 − v12² (9..13).
    solve: [f64; SOLVE],
}

/// The lone triangles of a world.
#[derive(Clone, Debug, Default)]
pub(super) struct Triangles {
    /// In the order they were pushed.
    items: Vec<PackedTriangle>,
}

impl Triangles {
    /// Adds the triangle of `corners` (t0, t1, t2) of object `object`, key
    /// `key`; returns its index here.
    pub(super) fn push(&mut self, object: i32, corners: &[Vec3; 3], key: i32) -> u32 {
        let t = Triangle::new(corners[0], corners[1], corners[2]);
        // Exactly `Triangle::barycentrics`' corner-only terms.
        let t0 = t.t0.as_dvec3();
        let v1 = t.t1.as_dvec3() - t0;
        let v2 = t.t2.as_dvec3() - t0;
        let (v11, v12, v22) = (v1.dot(v1), v1.dot(v2), v2.dot(v2));
        self.items.push(PackedTriangle {
            corners: corners.map(|c| c.to_array()),
            object,
            key,
            normal: t.normal(),
            solve: [
                t0.x,
                t0.y,
                t0.z,
                v1.x,
                v1.y,
                v1.z,
                v2.x,
                v2.y,
                v2.z,
                v11,
                v12,
                v22,
                v11 * v22 - v12 * v12,
            ],
        });
        self.items.len() as u32 - 1
    }

    /// True when there are none.
    #[inline(always)]
    pub(super) fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// How many there are.
    #[inline(always)]
    pub(super) fn len(&self) -> usize {
        self.items.len()
    }

    /// The corners t0, t1, t2 of the triangle at `index`.
    pub(super) fn corners(&self, index: u32) -> [Vec3; 3] {
        self.items[index as usize].corners.map(Vec3::from_array)
    }

    /// Takes the hits of the triangles `range` (indices here) that are
    /// nearer than `nearest`'s.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        r: &ShearedRays<F>,
        range: Range<usize>,
        nearest: &mut Nearest<F>,
    ) {
        let items = &self.items[range];
        match r.frame {
            Frame::Same(k) => Self::closest_in(items, r, SameAxes(k), nearest),
            Frame::Mixed { from_x, from_y } => {
                Self::closest_in(items, r, MixedAxes { from_x, from_y }, nearest)
            }
        }
    }

    /// [`Triangles::closest`] with the frame's permutation.
    #[inline(always)]
    fn closest_in<F: FloatLanes>(
        items: &[PackedTriangle],
        r: &ShearedRays<F>,
        permute: impl Permutation<F>,
        nearest: &mut Nearest<F>,
    ) {
        for triangle in items {
            let limit = nearest.triangle_limit(triangle.key);
            let lanes = hit_with(&triangle.corners, r, permute, limit);
            nearest.take_triangle(lanes.hit, lanes.alpha, triangle.object, triangle.key);
        }
    }

    /// Adds the lanes some triangle of `range` blocks within `t_max` to
    /// `settled`; true as soon as every lane is settled.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        r: &ShearedRays<F>,
        range: Range<usize>,
        t_max: F,
        settled: &mut F::Mask,
    ) -> bool {
        let items = &self.items[range];
        match r.frame {
            Frame::Same(k) => Self::occluded_in(items, r, SameAxes(k), t_max, settled),
            Frame::Mixed { from_x, from_y } => {
                Self::occluded_in(items, r, MixedAxes { from_x, from_y }, t_max, settled)
            }
        }
    }

    /// [`Triangles::occluded`] with the frame's permutation.
    #[inline(always)]
    fn occluded_in<F: FloatLanes>(
        items: &[PackedTriangle],
        r: &ShearedRays<F>,
        permute: impl Permutation<F>,
        t_max: F,
        settled: &mut F::Mask,
    ) -> bool {
        for triangle in items {
            let hit = hit_with(&triangle.corners, r, permute, t_max).hit;
            *settled = *settled | hit;
            if settled.all() {
                return true;
            }
        }
        false
    }

    /// Hit point and normal at α of the triangles `index` (per lane), as
    /// [`Triangle::surface`] computes them: β, γ of the point P0 + α v by
    /// the f64 2×2 solve, the point rebuilt as t0 + β v1 + γ v2 in f64.
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
    ) -> (Vec3s<F>, Vec3s<F>) {
        let p = rays.at(alpha);
        let p = [p.x.to_array(), p.y.to_array(), p.z.to_array()];
        let mut point = [[0.0f32; WIDTH]; 3];
        // Four lanes per f64x4, as many of them as the lanes need.
        for quarter in 0..WIDTH / 4 {
            let first = 4 * quarter;
            let solve: [&[f64; SOLVE]; 4] =
                std::array::from_fn(|i| &self.items[index[first + i] as usize].solve);
            let constant = |j: usize| f64x4::from(solve.map(|c| c[j]));
            let (t0, v1, v2) = (
                [0, 1, 2].map(constant),
                [3, 4, 5].map(constant),
                [6, 7, 8].map(constant),
            );
            let (v11, v12, v22, det) = (constant(9), constant(10), constant(11), constant(12));
            let s: [f64x4; 3] = std::array::from_fn(|k| {
                f64x4::from(std::array::from_fn::<f64, 4, _>(|i| p[k][first + i] as f64)) - t0[k]
            });
            // DVec3::dot's order.
            let dot = |a: &[f64x4; 3], b: &[f64x4; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let (sv1, sv2) = (dot(&s, &v1), dot(&s, &v2));
            // β and γ rounded to f32, as `barycentrics` returns them.
            let round = |x: f64x4| f64x4::from(x.to_array().map(|x| x as f32 as f64));
            let beta = round((sv1 * v22 - sv2 * v12) / det);
            let gamma = round((v11 * sv2 - v12 * sv1) / det);
            for k in 0..3 {
                let rebuilt = ((t0[k] + beta * v1[k]) + gamma * v2[k]).to_array();
                for i in 0..4 {
                    point[k][first + i] = rebuilt[i] as f32;
                }
            }
        }
        let point = Vec3s::new(
            F::from_array(point[0]),
            F::from_array(point[1]),
            F::from_array(point[2]),
        );
        let normal = gather3(index, |k| self.items[k].normal);
        (point, normal)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::{
        assert_lanes_equal_scalar, check_rays, rays_for, same_everywhere, world_of,
    };
    use super::super::{PacketShapes, Rays, WIDTH};
    use super::*;
    use crate::geometry::ray::Ray;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::Method;
    use crate::simd::{IntLanes, WithLanes, on_every_lane_type};

    /// Among triangles hit at the same α the lowest key wins, whatever
    /// the order they are tested in (the group's BVH's rule).
    #[test]
    fn at_the_same_alpha_the_lowest_key_wins_in_any_order() {
        #[derive(Clone)]
        struct Check;
        impl WithLanes for Check {
            type Output = ();
            fn run<F: FloatLanes>(self) {
                let corners = [
                    Vec3::new(-1.0, -1.0, 0.0),
                    Vec3::new(1.0, -1.0, 0.0),
                    Vec3::Y,
                ];
                let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
                    let x = k as f32 / WIDTH as f32 - 0.5;
                    Ray::new(Vec3::new(x, 0.0, 3.0), Vec3::NEG_Z)
                });
                let rays = Rays::<F>::from_lanes(&lanes);
                let sheared = ShearedRays::new(&rays, rays.t_max.simd_gt(F::ZERO));
                for keys in [[5, 2, 9], [2, 9, 5], [9, 5, 2]] {
                    let mut triangles = Triangles::default();
                    for (object, key) in keys.into_iter().enumerate() {
                        triangles.push(object as i32, &corners, key);
                    }
                    let mut nearest = Nearest::new(&rays);
                    triangles.closest(&sheared, 0..3, &mut nearest);
                    let hits = nearest.hits();
                    let want = keys.iter().position(|&k| k == 2).expect("key 2") as i32;
                    assert_eq!(hits.triangle.to_array(), [2; WIDTH], "keys {keys:?}");
                    assert_eq!(hits.object.to_array(), [want; WIDTH], "keys {keys:?}");
                    assert!(hits.alpha.to_array().iter().all(|&a| a == 3.0));
                }
            }
        }
        on_every_lane_type(Check);
    }

    /// Each lane's α and hit against one triangle equal `Triangle::hit`'s
    /// with [`Method::Robust`], and its surface `Triangle::surface`'s, in
    /// lanes `F`.
    fn check_against_one_with<F: FloatLanes>(t: &Triangle, lanes: &[Ray; WIDTH]) -> usize {
        let mut triangles = Triangles::default();
        triangles.push(7, &[t.t0, t.t1, t.t2], 0);
        let rays = Rays::<F>::from_lanes(lanes);
        let live = rays.t_max.simd_gt(F::ZERO);
        let sheared = ShearedRays::new(&rays, live);
        let lanes_hit = sheared.hit(&triangles.items[0].corners, rays.t_max);
        let (hit, alpha) = (lanes_hit.hit, lanes_hit.alpha);
        let (point, normal) = triangles.surface(&rays, alpha, &[0; WIDTH]);
        assert_lanes_equal_scalar(
            lanes,
            (hit, alpha),
            (point, normal),
            |ray| t.intersect(ray, Method::Robust),
            |ray, alpha| t.surface(ray, alpha),
            t,
        )
    }

    /// [`check_against_one_with`] for every lane type.
    #[derive(Clone)]
    struct AgainstOne<'a>(&'a Triangle, &'a [Ray; WIDTH]);

    impl WithLanes for AgainstOne<'_> {
        type Output = usize;
        fn run<F: FloatLanes>(self) -> usize {
            check_against_one_with::<F>(self.0, self.1)
        }
    }

    /// [`check_against_one_with`] with every lane type; how many lanes hit.
    fn check_against_one(t: &Triangle, lanes: &[Ray; WIDTH]) -> usize {
        same_everywhere(on_every_lane_type(AgainstOne(t, lanes)))
    }

    /// A small integer lattice point (rays through corners and along edges
    /// make the edge functions exactly zero).
    fn lattice(rng: &mut Sampler, r: f32) -> Vec3 {
        let mut c = || (rng.next_f32() * (2.0 * r + 1.0)).floor() - r;
        Vec3::new(c(), c(), c())
    }

    #[test]
    fn every_lane_equals_the_scalar_watertight_test_on_lattice_triangles() {
        let mut rng = Sampler::for_sample(11, 0, 0, 0);
        let mut hits = 0;
        for case in 0..4000 {
            let t = Triangle::new(
                lattice(&mut rng, 2.0),
                lattice(&mut rng, 2.0),
                lattice(&mut rng, 2.0),
            );
            let lanes: [Ray; WIDTH] = std::array::from_fn(|k| {
                let origin = lattice(&mut rng, 3.0);
                let mut dir = lattice(&mut rng, 2.0) * Vec3::new(1.0, 1.0, 0.5);
                if dir == Vec3::ZERO {
                    dir = Vec3::new(-0.0, 0.0, -1.0);
                }
                if (case + k) % 3 == 0 {
                    // Aimed at a corner or an edge's midpoint exactly.
                    let c = [t.t0, t.t1, t.t2];
                    dir = 0.5 * (c[k % 3] + c[(k + case) % 3]) - origin;
                    if dir == Vec3::ZERO {
                        dir = Vec3::X;
                    }
                }
                let ray = Ray::new(origin, dir);
                match (case + k) % 5 {
                    0 => ray.with_t_max(0.5 + 2.0 * rng.next_f32()),
                    1 if k == 7 => ray.with_t_max(0.0),
                    _ => ray,
                }
            });
            hits += check_against_one(&t, &lanes);
        }
        assert!(hits > 3000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn every_lane_equals_the_scalar_watertight_test_on_random_triangles() {
        let mut rng = Sampler::for_sample(12, 0, 0, 0);
        let mut hits = 0;
        for case in 0..3000 {
            let scale = [1.0, 1e-3, 1e3][case % 3];
            let mut corner = || scale * 2.0 * rng.next_direction() * rng.next_f32();
            let t = Triangle::new(corner(), corner(), corner());
            let lanes: [Ray; WIDTH] = std::array::from_fn(|_| {
                let origin = scale * 5.0 * rng.next_direction();
                let (b, g) = (rng.next_f32(), rng.next_f32());
                let target = t.t0 + b * (t.t1 - t.t0) + g * (t.t2 - t.t0);
                Ray::new(origin, (target - origin).normalize_or(Vec3::Z))
            });
            hits += check_against_one(&t, &lanes);
        }
        assert!(hits > 5000, "too few hits to mean anything: {hits}");
    }

    #[test]
    fn rays_along_shared_edges_and_through_shared_vertices_give_the_scalar_worlds_hits() {
        // A fan of triangles around the origin sharing edges, a quad split
        // on its diagonal, and a triangle standing on that diagonal.
        let world = world_of(
            r#"<scene>
              <triangle t0="0 0 0" t1="1 0 0" t2="1 1 0"/>
              <triangle t0="0 0 0" t1="1 1 0" t2="0 1 0"/>
              <triangle t0="0 0 0" t1="0 1 0" t2="-1 0 0"/>
              <triangle t0="0 0 0" t1="-1 0 0" t2="0 -1 0"/>
              <triangle t0="0 0 0" t1="0 -1 0" t2="1 0 0"/>
              <triangle t0="0 0 0" t1="1 1 0" t2="0.5 0.5 1"/>
            </scene>"#,
        );
        let mut rays = Vec::new();
        let origins = [
            Vec3::new(0.3123, -0.77, 3.1),
            Vec3::new(-2.0, 0.5, 0.0),
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(2.0, 2.0, 0.0),
            Vec3::new(-1.0, -1.0, 0.0),
        ];
        for origin in origins {
            for k in 0..=64 {
                let s = k as f32 / 64.0;
                for target in [
                    Vec3::new(s, s, 0.0),
                    Vec3::new(s, 0.0, 0.0),
                    Vec3::new(0.0, s, 0.0),
                    Vec3::new(-s, 0.0, 0.0),
                    Vec3::new(0.5 * s, 0.5 * s, s),
                ] {
                    rays.push(Ray::new(origin, (target - origin).normalize_or(Vec3::X)));
                    // The same line, unnormalised and cut at the target.
                    rays.push(Ray::new(origin, target - origin).with_t_max(1.0));
                }
            }
        }
        // Rays in the plane z = 0 (parallel to most triangles), along edges.
        for (o, d) in [
            (Vec3::new(-3.0, -3.0, 0.0), Vec3::new(1.0, 1.0, 0.0)),
            (Vec3::new(-3.0, 0.0, 0.0), Vec3::X),
            (Vec3::new(0.0, -3.0, 0.0), Vec3::Y),
            (Vec3::new(0.5, 0.5, 0.0), -Vec3::Z),
            (Vec3::ZERO, Vec3::Z),
        ] {
            rays.push(Ray::new(o, d));
        }
        rays.extend(rays_for(&world, 13, 2000));
        let found = check_rays(&world, &rays);
        assert!(found > 1000, "too few hits to mean anything: {found}");
    }

    /// The permutation every live lane of `lanes` shares, in lanes `F`
    /// (`None`: a mixed frame).
    #[derive(Clone)]
    struct SharedFrame<'a>(&'a [Ray; WIDTH]);

    impl WithLanes for SharedFrame<'_> {
        type Output = Option<[usize; 3]>;
        fn run<F: FloatLanes>(self) -> Option<[usize; 3]> {
            let rays = Rays::<F>::from_lanes(self.0);
            match ShearedRays::new(&rays, rays.t_max.simd_gt(F::ZERO)).frame {
                Frame::Same(k) => Some(k),
                Frame::Mixed { .. } => None,
            }
        }
    }

    /// [`SharedFrame`] with every lane type (they must agree).
    fn shared_frame(lanes: &[Ray; WIDTH]) -> Option<[usize; 3]> {
        same_everywhere(on_every_lane_type(SharedFrame(lanes)))
    }

    #[test]
    fn coherent_and_incoherent_packets_take_both_frames_and_agree() {
        let world = world_of(
            r#"<scene>
              <triangle t0="-1 -1 -1" t1="1 -1 -1" t2="1 1 -1"/>
              <triangle t0="-1 -1 -1" t1="1 1 -1" t2="-1 1 -1"/>
            </scene>"#,
        );
        let shapes = PacketShapes::new(&world).expect("a packet world");
        let coherent: [Ray; WIDTH] = std::array::from_fn(|k| {
            let x = k as f32 / 4.0 - 1.0;
            Ray::new(
                Vec3::new(0.0, 0.0, 3.0),
                Vec3::new(x, 0.5 * x, -3.0).normalize(),
            )
        });
        let frame = shared_frame(&coherent);
        assert!(
            matches!(frame, Some([0, 1, 2]) | Some([1, 0, 2])),
            "{frame:?}"
        );
        super::super::testing::check_packet(&world, &shapes, &coherent);
        // One lane turned sideways makes the packet mixed; the others' answers stay.
        let mut mixed = coherent;
        mixed[3] = Ray::new(Vec3::ZERO, Vec3::new(1.0, 0.1, 0.2));
        assert_eq!(shared_frame(&mixed), None);
        super::super::testing::check_packet(&world, &shapes, &mixed);
        // A dead lane pointing elsewhere does not spoil the shared frame.
        let mut dead = coherent;
        dead[5] = Ray::new(Vec3::ZERO, Vec3::X).with_t_max(0.0);
        assert!(shared_frame(&dead).is_some());
        super::super::testing::check_packet(&world, &shapes, &dead);
    }
}
