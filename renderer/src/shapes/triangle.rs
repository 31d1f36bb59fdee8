//! The triangle: the lecture's ray–plane α and 2×2 barycentric solve, and the
//! watertight test of Woop, Benthin and Wald (JCGT 2013).

use super::{AreaSample, Method, Surface};
use crate::geometry::ray::Ray;
use glam::{DVec3, Vec2, Vec3};
use serde::Serialize;
use wide::f32x4;

/// The triangle T with vertices t0, t1, t2 (edges v1 = t1 − t0, v2 = t2 − t0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// t0.
    pub t0: Vec3,
    /// t1.
    pub t1: Vec3,
    /// t2.
    pub t2: Vec3,
}

/// A hit with the lecture's unknowns: P0 + α v = t0 + β v1 + γ v2.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TriangleHit {
    /// α, the distance along the ray.
    pub alpha: f32,
    /// β, the weight of v1 (of t1).
    pub beta: f32,
    /// γ, the weight of v2 (of t2).
    pub gamma: f32,
}

impl Triangle {
    /// The triangle t0, t1, t2.
    pub fn new(t0: Vec3, t1: Vec3, t2: Vec3) -> Self {
        Self { t0, t1, t2 }
    }

    /// α of the hit inside the ray's interval, if any.
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<f32> {
        self.hit(ray, method).map(|h| h.alpha)
    }

    /// The hit with its barycentric coordinates β, γ as `method` computes
    /// them (what the pixel inspector shows); its α is [`Triangle::intersect`]'s.
    pub fn hit(&self, ray: &Ray, method: Method) -> Option<TriangleHit> {
        match method {
            Method::Lecture => self.lecture_hit(ray),
            Method::Robust => self.watertight_hit(ray),
        }
    }

    /// The lecture, step by step: n = v1 × v2; α = (n · u)/(n · v) with
    /// u = t0 − P0; s = α v − u; then solve
    /// s · v1 = β (v1 · v1) + γ (v1 · v2), s · v2 = β (v1 · v2) + γ (v2 · v2)
    /// and accept β ≥ 0, γ ≥ 0, β + γ ≤ 1.
    fn lecture_hit(&self, ray: &Ray) -> Option<TriangleHit> {
        let v1 = self.t1 - self.t0;
        let v2 = self.t2 - self.t0;
        let n = v1.cross(v2);
        let n_dot_v = n.dot(ray.dir);
        if n_dot_v == 0.0 {
            // Parallel to the plane, or lying in it: no single hit.
            return None;
        }
        let u = self.t0 - ray.origin;
        let alpha = n.dot(u) / n_dot_v;
        if !alpha.is_finite() || !ray.contains(alpha) {
            return None;
        }
        let s = alpha * ray.dir - u;
        let (v11, v12, v22) = (v1.dot(v1), v1.dot(v2), v2.dot(v2));
        let (sv1, sv2) = (s.dot(v1), s.dot(v2));
        let det = v11 * v22 - v12 * v12;
        let beta = (sv1 * v22 - sv2 * v12) / det;
        let gamma = (v11 * sv2 - v12 * sv1) / det;
        // Written so that NaN fails every comparison and is rejected.
        let inside = beta >= 0.0 && gamma >= 0.0 && beta + gamma <= 1.0;
        inside.then_some(TriangleHit { alpha, beta, gamma })
    }

    /// Watertight ray–triangle intersection (Woop, Benthin, Wald 2013): shear
    /// the vertices into the ray's frame so the test is three 2D edge
    /// functions, recomputed in f64 when one is exactly zero. Rays through a
    /// shared edge or vertex of a mesh hit at least one of its triangles.
    fn watertight_hit(&self, ray: &Ray) -> Option<TriangleHit> {
        WatertightRay::new(ray).hit(ray, self.t0, self.t1, self.t2)
    }

    /// β and γ of a point in the triangle's plane, by the lecture's 2×2 solve
    /// (in f64, so the reconstructed point is accurate).
    pub fn barycentrics(&self, p: Vec3) -> (f32, f32) {
        let t0 = self.t0.as_dvec3();
        let v1 = self.t1.as_dvec3() - t0;
        let v2 = self.t2.as_dvec3() - t0;
        let s: DVec3 = p.as_dvec3() - t0;
        let (v11, v12, v22) = (v1.dot(v1), v1.dot(v2), v2.dot(v2));
        let (sv1, sv2) = (s.dot(v1), s.dot(v2));
        let det = v11 * v22 - v12 * v12;
        let beta = (sv1 * v22 - sv2 * v12) / det;
        let gamma = (v11 * sv2 - v12 * sv1) / det;
        (beta as f32, gamma as f32)
    }

    /// The unit normal along (t1 − t0) × (t2 − t0).
    pub fn normal(&self) -> Vec3 {
        (self.t1 - self.t0)
            .cross(self.t2 - self.t0)
            .try_normalize()
            .unwrap_or(Vec3::Y)
    }

    /// The hit point rebuilt as t0 + β v1 + γ v2 (on the plane), and the normal.
    pub fn surface(&self, ray: &Ray, alpha: f32) -> Surface {
        let (beta, gamma) = self.barycentrics(ray.at(alpha));
        let t0 = self.t0.as_dvec3();
        let point =
            t0 + beta as f64 * (self.t1.as_dvec3() - t0) + gamma as f64 * (self.t2.as_dvec3() - t0);
        Surface {
            point: point.as_vec3(),
            normal: self.normal(),
        }
    }
}

/// What [`WatertightRay::hit_lanes`] finds for four triangles: per lane, α
/// (+∞ for no hit), and the edge functions V, W and the determinant that
/// give β = V / det and γ = W / det.
#[derive(Clone, Copy, Debug)]
pub struct LaneHits {
    /// α per lane, +∞ where the ray misses the triangle in its interval.
    pub alpha: f32x4,
    /// V per lane.
    pub v: f32x4,
    /// W per lane.
    pub w: f32x4,
    /// det = U + V + W per lane.
    pub det: f32x4,
}

impl LaneHits {
    /// β and γ of the hit in `lane`, as [`WatertightRay::hit`] computes them.
    #[inline(always)]
    pub fn barycentrics(&self, lane: usize) -> (f32, f32) {
        let (v, w, det) = (
            self.v.as_array()[lane],
            self.w.as_array()[lane],
            self.det.as_array()[lane],
        );
        (v / det, w / det)
    }
}

/// The per-ray half of the watertight test (Woop, Benthin, Wald 2013): the
/// axis permutation and shear, computed once per ray. [`WatertightRay::hit`]
/// is the per-triangle half; [`Triangle::hit`] with [`Method::Robust`] is
/// exactly `WatertightRay::new(ray).hit(ray, t0, t1, t2)`, so an acceleration
/// structure calling it gets bit-identical α, β, γ.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    /// The ray's origin P0.
    origin: Vec3,
    /// The axis of the direction's largest magnitude (the shear's z)...
    kz: usize,
    /// ...and the other two, swapped when `v[kz] < 0` to keep the winding.
    kx: usize,
    /// See `kx`.
    ky: usize,
    /// Shear factors `v[kx]/v[kz]`, `v[ky]/v[kz]` and `1/v[kz]`.
    sx: f32,
    /// See `sx`.
    sy: f32,
    /// See `sx`.
    sz: f32,
}

impl WatertightRay {
    /// The permutation and shear of `ray`.
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self {
            origin: ray.origin,
            kz,
            kx,
            ky,
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            sz: 1.0 / d[kz],
        }
    }

    /// The edge functions U, V, W and the scaled distance of the triangle
    /// t0, t1, t2, or `None` when the ray passes outside it or the
    /// determinant U + V + W is zero. α = t_scaled / det, β = V / det,
    /// γ = W / det.
    #[inline(always)]
    fn edges(&self, t0: Vec3, t1: Vec3, t2: Vec3) -> Option<[f32; 5]> {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let (sx, sy, sz) = (self.sx, self.sy, self.sz);
        let a = (t0 - self.origin).to_array();
        let b = (t1 - self.origin).to_array();
        let c = (t2 - self.origin).to_array();
        let (ax, ay) = (a[kx] - sx * a[kz], a[ky] - sy * a[kz]);
        let (bx, by) = (b[kx] - sx * b[kz], b[ky] - sy * b[kz]);
        let (cx, cy) = (c[kx] - sx * c[kz], c[ky] - sy * c[kz]);

        let mut eu = cx * by - cy * bx;
        let mut ev = ax * cy - ay * cx;
        let mut ew = bx * ay - by * ax;
        if eu == 0.0 || ev == 0.0 || ew == 0.0 {
            let f =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            eu = f(cx, by, cy, bx);
            ev = f(ax, cy, ay, cx);
            ew = f(bx, ay, by, ax);
        }
        if (eu < 0.0 || ev < 0.0 || ew < 0.0) && (eu > 0.0 || ev > 0.0 || ew > 0.0) {
            return None;
        }
        let det = eu + ev + ew;
        if det == 0.0 {
            return None;
        }
        let t_scaled = eu * (sz * a[kz]) + ev * (sz * b[kz]) + ew * (sz * c[kz]);
        Some([eu, ev, ew, det, t_scaled])
    }

    /// α of the hit with triangle t0, t1, t2 inside the ray's interval
    /// (t_min, t_max), if any; the same α as [`WatertightRay::hit`].
    #[inline(always)]
    pub fn alpha(&self, t0: Vec3, t1: Vec3, t2: Vec3, t_min: f32, t_max: f32) -> Option<f32> {
        let [_, _, _, det, t_scaled] = self.edges(t0, t1, t2)?;
        let alpha = t_scaled / det;
        (alpha.is_finite() && alpha > t_min && alpha < t_max).then_some(alpha)
    }

    /// [`WatertightRay::hit`] for four triangles at once, stored plane by
    /// plane: `corners[c][k]` holds coordinate k of corner t_c of the four
    /// triangles. The same operations as `edges`, lane by lane in SIMD
    /// vectors, so the same α, β, γ bit for bit; α is +∞ for a lane without
    /// a hit in (t_min, t_max).
    #[inline(always)]
    pub fn hit_lanes(&self, corners: &[[f32x4; 3]; 3], t_min: f32, t_max: f32) -> LaneHits {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let o = self.origin.to_array();
        let (ox, oy, oz) = (
            f32x4::splat(o[kx]),
            f32x4::splat(o[ky]),
            f32x4::splat(o[kz]),
        );
        let (sx, sy) = (f32x4::splat(self.sx), f32x4::splat(self.sy));
        // Corner c relative to P0, sheared: (x, y) and the unsheared z.
        let shear = |c: usize| {
            let p = &corners[c];
            let z = p[kz] - oz;
            ((p[kx] - ox) - sx * z, (p[ky] - oy) - sy * z, z)
        };
        let ((ax, ay, az), (bx, by, bz), (cx, cy, cz)) = (shear(0), shear(1), shear(2));
        let mut eu = cx * by - cy * bx;
        let mut ev = ax * cy - ay * cx;
        let mut ew = bx * ay - by * ax;
        let zero = f32x4::ZERO;
        let exact_zero = eu.simd_eq(zero) | ev.simd_eq(zero) | ew.simd_eq(zero);
        if exact_zero.any() {
            // Rare (the ray through an edge or vertex): exactly as `edges`.
            let f =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            let [ax, ay, bx, by, cx, cy] = [ax, ay, bx, by, cx, cy].map(f32x4::to_array);
            let (mut u, mut v, mut w) = (eu.to_array(), ev.to_array(), ew.to_array());
            let lanes = exact_zero.to_bitmask();
            for i in (0..4).filter(|i| lanes & (1 << i) != 0) {
                u[i] = f(cx[i], by[i], cy[i], bx[i]);
                v[i] = f(ax[i], cy[i], ay[i], cx[i]);
                w[i] = f(bx[i], ay[i], by[i], ax[i]);
            }
            (eu, ev, ew) = (u.into(), v.into(), w.into());
        }
        // `edges`'s tests on all lanes at once (the same truth values).
        let negative = eu.simd_lt(zero) | ev.simd_lt(zero) | ew.simd_lt(zero);
        let positive = eu.simd_gt(zero) | ev.simd_gt(zero) | ew.simd_gt(zero);
        let det = eu + ev + ew;
        let inside = !(negative & positive) & det.simd_ne(zero);
        if !inside.any() {
            // The ray passes outside all four (most packs a walk tests):
            // α, and its division, would be masked out on every lane.
            return LaneHits {
                alpha: f32x4::INFINITY,
                v: ev,
                w: ew,
                det,
            };
        }
        let sz = f32x4::splat(self.sz);
        let t_scaled = eu * (sz * az) + ev * (sz * bz) + ew * (sz * cz);
        let alpha = t_scaled / det;
        let finite = alpha.abs().simd_lt(f32x4::INFINITY);
        let hit = inside
            & finite
            & alpha.simd_gt(f32x4::splat(t_min))
            & alpha.simd_lt(f32x4::splat(t_max));
        LaneHits {
            alpha: hit.select(alpha, f32x4::INFINITY),
            v: ev,
            w: ew,
            det,
        }
    }

    /// The hit with triangle t0, t1, t2 inside `ray`'s interval, with its
    /// barycentric coordinates. `ray` must be the ray this was made from
    /// (only its interval is read here).
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t0: Vec3, t1: Vec3, t2: Vec3) -> Option<TriangleHit> {
        let [_, ev, ew, det, t_scaled] = self.edges(t0, t1, t2)?;
        let alpha = t_scaled / det;
        if !alpha.is_finite() || !ray.contains(alpha) {
            return None;
        }
        Some(TriangleHit {
            alpha,
            beta: ev / det,
            gamma: ew / det,
        })
    }
}

impl Triangle {
    /// The area ½ ‖(t1 − t0) × (t2 − t0)‖.
    pub fn area(&self) -> f32 {
        0.5 * (self.t1 - self.t0).cross(self.t2 - self.t0).length()
    }

    /// A point drawn uniformly over the triangle (barycentrics from the unit
    /// square folded along its diagonal), with the normal (t1 − t0) × (t2 − t0).
    pub fn sample_area(&self, u: Vec2) -> Option<AreaSample> {
        Some(self.area_sampler()?.sample(u))
    }

    /// What [`Triangle::sample_area`] computes before it draws, made once
    /// (an emitter draws from it at every path vertex); `None` for a
    /// triangle of no area.
    pub fn area_sampler(&self) -> Option<TriangleSampler> {
        let (v1, v2) = (self.t1 - self.t0, self.t2 - self.t0);
        let n = v1.cross(v2);
        let area = 0.5 * n.length();
        if !(area > 0.0) {
            return None;
        }
        Some(TriangleSampler {
            t0: self.t0,
            v1,
            v2,
            normal: n / (2.0 * area),
            pdf_area: 1.0 / area,
        })
    }
}

/// A triangle prepared for drawing points uniformly over it
/// ([`Triangle::area_sampler`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleSampler {
    /// t0.
    t0: Vec3,
    /// t1 − t0.
    v1: Vec3,
    /// t2 − t0.
    v2: Vec3,
    /// The unit normal (t1 − t0) × (t2 − t0) / ‖…‖.
    normal: Vec3,
    /// 1 / area: the density of every point.
    pub pdf_area: f32,
}

impl TriangleSampler {
    /// t0, t1 − t0 and t2 − t0: a drawn point is t0 + b (t1 − t0) + c (t2 − t0).
    pub fn corner_and_edges(&self) -> [Vec3; 3] {
        [self.t0, self.v1, self.v2]
    }

    /// The unit normal (t1 − t0) × (t2 − t0) / ‖…‖.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    /// The point drawn from `u` ∈ [0, 1)² (barycentrics from the unit square
    /// folded along its diagonal), with the normal and density.
    #[inline]
    pub fn sample(&self, u: Vec2) -> AreaSample {
        let (b, c) = if u.x + u.y > 1.0 {
            (1.0 - u.x, 1.0 - u.y)
        } else {
            (u.x, u.y)
        };
        AreaSample {
            point: self.t0 + b * self.v1 + c * self.v2,
            normal: self.normal,
            pdf_area: self.pdf_area,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const METHODS: [Method; 2] = [Method::Lecture, Method::Robust];

    fn lecture_triangle() -> Triangle {
        Triangle::new(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        )
    }

    #[test]
    fn hit_has_the_expected_alpha_beta_gamma() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, 2.0), -Vec3::Z);
        for m in METHODS {
            let h = lecture_triangle().hit(&ray, m).expect("hit");
            assert!((h.alpha - 2.0).abs() < 1e-6, "{m:?} {h:?}");
            // (0, 0.5) = t0 + β (2, 0) + γ (1, 1) → γ = 0.5, β = 0.25.
            assert!(
                (h.beta - 0.25).abs() < 1e-6 && (h.gamma - 0.5).abs() < 1e-6,
                "{m:?} {h:?}"
            );
        }
    }

    #[test]
    fn ray_outside_the_edges_misses() {
        let ray = Ray::new(Vec3::new(0.9, 0.9, 2.0), -Vec3::Z);
        for m in METHODS {
            assert_eq!(lecture_triangle().intersect(&ray, m), None, "{m:?}");
        }
    }

    #[test]
    fn triangle_behind_the_ray_misses() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, 2.0), Vec3::Z);
        for m in METHODS {
            assert_eq!(lecture_triangle().intersect(&ray, m), None, "{m:?}");
        }
    }

    #[test]
    fn parallel_ray_never_hits_and_never_yields_nan() {
        for origin in [Vec3::new(0.0, 0.5, 1.0), Vec3::new(-2.0, 0.5, 0.0)] {
            let ray = Ray::new(origin, Vec3::X);
            for m in METHODS {
                assert_eq!(
                    lecture_triangle().intersect(&ray, m),
                    None,
                    "{m:?} {origin}"
                );
            }
        }
    }

    #[test]
    fn back_side_is_hit_too() {
        let ray = Ray::new(Vec3::new(0.0, 0.5, -2.0), Vec3::Z);
        for m in METHODS {
            assert_eq!(lecture_triangle().intersect(&ray, m), Some(2.0), "{m:?}");
        }
    }

    #[test]
    fn watertight_test_never_leaks_through_a_shared_edge() {
        // The quad [0,1]² at z = 0 split along its diagonal; rays aimed exactly
        // at diagonal points must hit one of the two triangles.
        let a = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0));
        let b = Triangle::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::Y);
        let origin = Vec3::new(0.3123, -0.77, 3.1);
        for k in 1..1000 {
            let s = k as f32 / 1000.0;
            let ray = Ray::new(origin, (Vec3::new(s, s, 0.0) - origin).normalize());
            let hit = a
                .intersect(&ray, Method::Robust)
                .or(b.intersect(&ray, Method::Robust));
            assert!(hit.is_some(), "leak at s = {s}");
        }
    }

    proptest! {
        #[test]
        fn surface_point_is_on_the_triangle_plane(
            b in 0.0f32..0.5, g in 0.0f32..0.5, oz in 0.5f32..100.0, ox in -5.0f32..5.0,
        ) {
            let t = Triangle::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 2.5, 3.5), Vec3::new(2.0, 6.0, 2.0));
            let target = t.t0 + b * (t.t1 - t.t0) + g * (t.t2 - t.t0);
            let origin = target + Vec3::new(ox, 0.3, oz);
            let ray = Ray::new(origin, (target - origin).normalize());
            for m in METHODS {
                let alpha = t.intersect(&ray, m);
                prop_assert!(alpha.is_some(), "{:?}", m);
                let surf = t.surface(&ray, alpha.unwrap_or_default());
                let off_plane = (surf.point - t.t0).dot(t.normal()).abs();
                prop_assert!(off_plane < 1e-5, "{off_plane}");
            }
        }
    }
    proptest! {
        /// The density an emitter reports for a point a BSDF ray found
        /// (`Shape::pdf_area`, for MIS) is bit for bit the one its prepared
        /// sampler draws with, on any triangle.
        #[test]
        fn the_prepared_sampler_draws_with_the_shapes_own_density(
            c in proptest::array::uniform9(-50.0f32..50.0), ux in 0.0f32..1.0, uy in 0.0f32..1.0,
        ) {
            let t = Triangle::new(
                Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]), Vec3::new(c[6], c[7], c[8]),
            );
            let shape = super::super::Shape::Triangle(t);
            match t.area_sampler() {
                Some(sampler) => {
                    let drawn = sampler.sample(Vec2::new(ux, uy));
                    prop_assert_eq!(drawn.pdf_area.to_bits(), shape.pdf_area(drawn.point).to_bits());
                    prop_assert_eq!(Some(drawn), t.sample_area(Vec2::new(ux, uy)));
                }
                None => prop_assert!(t.sample_area(Vec2::new(ux, uy)).is_none()),
            }
        }
    }

    /// Four triangles with small integer corners, so rays through their
    /// edges and vertices (exact zero edge functions) come up often.
    fn lattice_triangle() -> impl Strategy<Value = [Vec3; 3]> {
        let corner = (-2i8..=2, -2i8..=2, -2i8..=2)
            .prop_map(|(x, y, z)| Vec3::new(x as f32, y as f32, z as f32));
        [corner.clone(), corner.clone(), corner]
    }

    proptest! {
        #[test]
        fn hit_lanes_equals_hit_bit_for_bit(
            tris in proptest::array::uniform4(lattice_triangle()),
            o in (-3i8..=3, -3i8..=3, -3i8..=3),
            d in (-2i8..=2, -2i8..=2, -2i8..=2),
            t_min in prop_oneof![Just(0.0f32), 0.0f32..0.5],
            t_max in prop_oneof![Just(f32::INFINITY), 0.5f32..3.0],
        ) {
            let dir = Vec3::new(d.0 as f32, d.1 as f32, d.2 as f32 * 0.5);
            prop_assume!(dir != Vec3::ZERO);
            let ray = Ray { origin: Vec3::new(o.0 as f32, o.1 as f32, o.2 as f32), dir, t_min, t_max };
            let w = WatertightRay::new(&ray);
            let corners: [[f32x4; 3]; 3] = std::array::from_fn(|c| {
                std::array::from_fn(|k| f32x4::new(std::array::from_fn(|i| tris[i][c][k])))
            });
            let lanes = w.hit_lanes(&corners, t_min, t_max);
            for (i, [t0, t1, t2]) in tris.iter().enumerate() {
                let one = w.alpha(*t0, *t1, *t2, t_min, t_max).unwrap_or(f32::INFINITY);
                prop_assert_eq!(lanes.alpha.as_array()[i].to_bits(), one.to_bits(), "lane {}", i);
                if let Some(hit) = w.hit(&ray, *t0, *t1, *t2) {
                    let (beta, gamma) = lanes.barycentrics(i);
                    prop_assert_eq!((beta.to_bits(), gamma.to_bits()), (hit.beta.to_bits(), hit.gamma.to_bits()));
                }
            }
        }
    }
}
