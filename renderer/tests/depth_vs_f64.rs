//! The depth AOV agrees with an independent float64 ray caster to a relative
//! 1e-4; hit/miss (and which object) may differ only on silhouette pixels.
//!
//! The caster below shares nothing with the renderer but the resolved scene:
//! its own f64 camera from the lecture's formulas, its own rotations, and
//! plain analytic formulas per shape (the torus by fine marching + bisection).

use glam::{DMat3, DVec3, Vec3};
use renderer::film::aov::{Aov, render_aov};
use renderer::{Method, World};
use scene::{Geometry, Object, ResolvedScene, Scene, Shape};

fn rot(deg: Vec3) -> DMat3 {
    let r = deg.as_dvec3().to_array().map(f64::to_radians);
    DMat3::from_rotation_z(r[2]) * DMat3::from_rotation_y(r[1]) * DMat3::from_rotation_x(r[0])
}

/// Smallest root > 1e-9 of a x² + b x + c (plain formula in f64), if any.
fn roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    if a.abs() < 1e-300 {
        return if b != 0.0 { vec![-c / b] } else { vec![] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return vec![];
    }
    let s = disc.sqrt();
    vec![(-b - s) / (2.0 * a), (-b + s) / (2.0 * a)]
}

fn nearest(candidates: impl IntoIterator<Item = f64>) -> Option<f64> {
    candidates
        .into_iter()
        .filter(|&t| t > 1e-9 && t.is_finite())
        .min_by(f64::total_cmp)
}

/// Ray (o, d) against a capped y-axis solid of revolution with radius(y) on [0, h]:
/// cylinder (cone = false) or cone with apex at y = h (cone = true).
fn revolve(o: DVec3, d: DVec3, radius: f64, h: f64, cone: bool) -> Option<f64> {
    let mut hits = Vec::new();
    let k = radius / h;
    let (a, b, c) = if cone {
        // x² + z² = (k (h − y))²
        let (yo, yd) = (h - o.y, -d.y);
        (
            d.x * d.x + d.z * d.z - k * k * yd * yd,
            2.0 * (o.x * d.x + o.z * d.z - k * k * yo * yd),
            o.x * o.x + o.z * o.z - k * k * yo * yo,
        )
    } else {
        (
            d.x * d.x + d.z * d.z,
            2.0 * (o.x * d.x + o.z * d.z),
            o.x * o.x + o.z * o.z - radius * radius,
        )
    };
    for t in roots(a, b, c) {
        let y = o.y + t * d.y;
        if (0.0..=h).contains(&y) {
            hits.push(t);
        }
    }
    let caps: &[f64] = if cone { &[0.0] } else { &[0.0, h] };
    for &y in caps {
        if d.y != 0.0 {
            let t = (y - o.y) / d.y;
            let p = o + t * d;
            if p.x * p.x + p.z * p.z <= radius * radius {
                hits.push(t);
            }
        }
    }
    nearest(hits)
}

fn torus(o: DVec3, d: DVec3, big: f64, small: f64) -> Option<f64> {
    let f = |t: f64| {
        let p = o + t * d;
        let q = p.length_squared() + big * big - small * small;
        q * q - 4.0 * big * big * (p.x * p.x + p.z * p.z)
    };
    // March over the bounding sphere's chord and bisect the first sign change.
    let chord = roots(
        d.length_squared(),
        2.0 * o.dot(d),
        o.length_squared() - (big + small).powi(2),
    );
    let (&t0, &t1) = (chord.first()?, chord.last()?);
    let (start, end) = (t0.max(0.0), t1);
    let steps = 20_000;
    let dt = (end - start) / steps as f64;
    let mut prev = f(start);
    for s in 1..=steps {
        let t = start + s as f64 * dt;
        let cur = f(t);
        if prev.signum() != cur.signum() {
            let (mut lo, mut hi) = (t - dt, t);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if f(mid).signum() == f(lo).signum() {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            return Some(0.5 * (lo + hi));
        }
        prev = cur;
    }
    None
}

fn hit(g: &Geometry, o: DVec3, d: DVec3) -> Option<f64> {
    match *g {
        Geometry::Sphere { center, radius } => {
            let oc = o - center.as_dvec3();
            nearest(roots(
                d.dot(d),
                2.0 * oc.dot(d),
                oc.dot(oc) - (radius as f64).powi(2),
            ))
        }
        Geometry::Plane { point, normal } => {
            let n = normal.as_dvec3();
            nearest([n.dot(point.as_dvec3() - o) / n.dot(d)])
        }
        Geometry::Triangle { t0, t1, t2 } => {
            let (a, b, c) = (t0.as_dvec3(), t1.as_dvec3(), t2.as_dvec3());
            let n = (b - a).cross(c - a);
            let t = n.dot(a - o) / n.dot(d);
            let p = o + t * d;
            let inside = [(a, b), (b, c), (c, a)]
                .iter()
                .all(|&(u, v)| (v - u).cross(p - u).dot(n) >= 0.0);
            if inside { nearest([t]) } else { None }
        }
        Geometry::Box {
            center,
            size,
            rotate,
        } => {
            let r = rot(rotate).transpose();
            let (lo_, d_) = (r * (o - center.as_dvec3()), r * d);
            let half = 0.5 * size.as_dvec3();
            let (mut near, mut far) = (f64::NEG_INFINITY, f64::INFINITY);
            for k in 0..3 {
                let (a, b) = ((-half[k] - lo_[k]) / d_[k], (half[k] - lo_[k]) / d_[k]);
                near = near.max(a.min(b));
                far = far.min(a.max(b));
            }
            if near <= far {
                nearest([near, far])
            } else {
                None
            }
        }
        Geometry::Cylinder {
            base,
            radius,
            height,
            rotate,
        }
        | Geometry::Cone {
            base,
            radius,
            height,
            rotate,
        } => {
            let r = rot(rotate).transpose();
            let cone = matches!(g, Geometry::Cone { .. });
            revolve(
                r * (o - base.as_dvec3()),
                r * d,
                radius as f64,
                height as f64,
                cone,
            )
        }
        Geometry::Torus {
            center,
            major,
            minor,
            rotate,
        } => {
            let r = rot(rotate).transpose();
            torus(
                r * (o - center.as_dvec3()),
                r * d,
                major as f64,
                minor as f64,
            )
        }
        Geometry::Mesh { .. } => unimplemented!("the shipped scenes compared here have no meshes"),
    }
}

/// (depth, object) per pixel from the f64 caster, with its own lecture camera.
fn cast_f64(scene: &ResolvedScene) -> Vec<(f64, i64)> {
    let cam = &scene.camera;
    let (w, h) = (cam.width as f64, cam.height as f64);
    let t = cam.toward.as_dvec3().normalize();
    let up = cam.up.as_dvec3();
    let u = (up - up.dot(t) * t).normalize();
    let r = t.cross(u);
    let theta = (cam.theta_deg as f64).to_radians();
    let d = h / (2.0 * theta.tan());
    let (h_d, w_d) = (2.0 * d * theta.tan(), 2.0 * d * theta.tan() * w / h);
    let c00 = d * t + (h_d / 2.0) * u - (w_d / 2.0) * r; // relative to P0
    let p0 = cam.eye.as_dvec3();
    let mut out = Vec::new();
    for j in 0..cam.height {
        for i in 0..cam.width {
            let p = c00 + (i as f64 + 0.5) * (w_d / w) * r - (j as f64 + 0.5) * (h_d / h) * u;
            let v = p.normalize();
            let best = scene
                .objects
                .iter()
                .enumerate()
                .filter_map(|(k, o)| hit(&o.geometry, p0, v).map(|a| (a, k as i64)))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            out.push(best.unwrap_or((f64::INFINITY, -1)));
        }
    }
    out
}

fn object(shape: Shape) -> Object {
    Object {
        name: None,
        shape,
        material: None,
        params: Default::default(),
    }
}

#[test]
fn depth_agrees_with_an_independent_f64_caster() {
    let v = Vec3::new;
    let scene = Scene {
        camera: scene::Camera {
            eye: Some(v(0.5, 3.0, 9.0)),
            toward: Some(v(0.0, -0.3, -1.0)),
            width: 160,
            height: 100,
            ..Default::default()
        },
        objects: vec![
            object(Shape::Sphere {
                center: Some(v(-3.5, 1.0, 0.0)),
                radius: 1.0,
            }),
            object(Shape::Box {
                center: Some(v(-1.2, 0.8, 0.5)),
                size: v(1.4, 1.6, 1.2),
                rotate: v(10.0, 35.0, -5.0),
            }),
            object(Shape::Cylinder {
                base: Some(v(0.8, 0.0, -0.5)),
                radius: 0.6,
                height: 1.8,
                rotate: v(0.0, 0.0, 12.0),
            }),
            object(Shape::Cone {
                base: Some(v(2.6, 0.0, 0.5)),
                radius: 0.8,
                height: 2.0,
                rotate: v(-10.0, 0.0, 0.0),
            }),
            object(Shape::Torus {
                center: Some(v(4.4, 0.8, 0.0)),
                major: 0.8,
                minor: 0.3,
                rotate: v(60.0, 20.0, 0.0),
            }),
            object(Shape::Triangle {
                t0: v(-2.0, 0.0, -3.0),
                t1: v(2.0, 0.0, -3.0),
                t2: v(0.0, 3.0, -3.5),
            }),
            object(Shape::Floor { y: 0.0 }),
        ],
        ..Default::default()
    };
    let resolved = scene::resolve(&scene).expect("resolves");
    let world = World::new(&resolved).expect("valid");
    let (w, h) = (
        resolved.camera.width as usize,
        resolved.camera.height as usize,
    );
    let reference = cast_f64(&resolved);

    for method in [Method::Robust, Method::Lecture] {
        let depth = render_aov(&world, Aov::Depth, method);
        let ids = render_aov(&world, Aov::Object, method);
        // A pixel is on a silhouette when its 3×3 neighbourhood in either image sees more than one object.
        let silhouette = |i: usize, j: usize| {
            let mut seen = std::collections::BTreeSet::new();
            for jj in j.saturating_sub(1)..=(j + 1).min(h - 1) {
                for ii in i.saturating_sub(1)..=(i + 1).min(w - 1) {
                    seen.insert(reference[jj * w + ii].1);
                    seen.insert(ids[jj * w + ii] as i64);
                }
            }
            seen.len() > 1
        };
        let (mut compared, mut silhouettes, mut worst) = (0, 0, 0.0f64);
        for j in 0..h {
            for i in 0..w {
                let k = j * w + i;
                let (ref_depth, ref_id) = reference[k];
                if silhouette(i, j) {
                    silhouettes += 1;
                    continue;
                }
                assert_eq!(
                    ids[k] as i64, ref_id,
                    "{method:?}: object differs at interior pixel ({i}, {j})"
                );
                if ref_id >= 0 {
                    let rel = (depth[k] as f64 - ref_depth).abs() / ref_depth;
                    worst = worst.max(rel);
                    assert!(
                        rel <= 1e-4,
                        "{method:?}: pixel ({i}, {j}) depth {} vs {ref_depth} (rel {rel:e})",
                        depth[k]
                    );
                    compared += 1;
                } else {
                    assert!(depth[k].is_infinite(), "{method:?}: a miss has depth +inf");
                }
            }
        }
        assert!(
            compared > w * h / 2,
            "{method:?}: most pixels are interior hits ({compared})"
        );
        assert!(
            silhouettes < w * h / 5,
            "{method:?}: silhouettes stay a minority ({silhouettes})"
        );
        println!(
            "{method:?}: {compared} hits compared, worst relative depth error {worst:e}, {silhouettes} silhouette pixels"
        );
    }
}
