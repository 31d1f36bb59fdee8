//! Feasibility experiment for issue 26 (not part of raylab; not built by CI):
//! raylab's path-tracing estimator for the reference Cornell box
//! (`assets/reference/cornell.xml`) written as an 8-wide SIMD wavefront.
//! Every stage — random numbers, intersection, shading, light sampling,
//! shadow rays, roulette — runs on 8 paths at once in structure-of-arrays
//! registers (`wide::f32x8`; 16 in `f32x16` with `--features x16`), and a
//! finished lane is refilled with the next sample. The estimator is raylab's `path` integrator's: next-event
//! estimation plus BSDF sampling weighted by the power heuristic, max_depth 8,
//! Russian roulette from depth 5; random numbers are independent (a hash of
//! pixel, sample and draw), not Sobol.
//!
//! What is specialised: the scene is written out (12 triangles, 2 rotated
//! boxes, Lambertian surfaces, one area light of two triangles) and every ray
//! is tested against every primitive (no BVH). Triangles use the Möller–
//! Trumbore test, or with `WT=1` raylab's watertight test (Woop et al.) with
//! each lane's own axis permutation chosen by masks.
//!
//!     cargo run --release -- SPP [SIZE]          # µs per path, relMSE vs the reference
//!     LANES=1 cargo run --release -- 16          # the same code with 1 of 8 lanes used
//!     SCALAR_RAYS=1 cargo run --release -- 16   # rays traced by raylab's World, one at a time
//!     DEPTH=3 cargo run --release -- 64          # another max_depth
//!     RUSTFLAGS="-C target-feature=+avx2,+avx512f,+avx512bw,+avx512dq,+avx512vl" \
//!       cargo run --release --features x16 --target-dir target-x16 -- 16   # 16 lanes, AVX-512
//!     cargo run --release -- 0 0 IMAGE.exr       # relMSE and mean of a raylab render
//!
//! `.cargo/config.toml` builds for AVX2 (what raylab's kernels dispatch to);
//! without it the same code is 4 lanes twice (SSE2). The film digest it
//! prints is the same for every LANES value, 8 or 16 lanes and every
//! instruction set: a lane's arithmetic never depends on its neighbours.

use glam::{Mat3, Vec3};
use renderer::diagnostics::metrics::rel_mse;
use renderer::diagnostics::reference_image::read_exr_rgb;
use std::time::Instant;
#[cfg(not(feature = "x16"))]
use wide::{f32x8 as F, i32x8 as I, u32x8 as U};
#[cfg(feature = "x16")]
use wide::{f32x16 as F, i32x16 as I, u32x16 as U};

/// Paths per register: 8 (AVX2), or 16 with `--features x16` (AVX-512).
#[cfg(not(feature = "x16"))]
const W: usize = 8;
#[cfg(feature = "x16")]
const W: usize = 16;

#[derive(Clone, Copy)]
struct V {
    x: F,
    y: F,
    z: F,
}

impl V {
    #[inline(always)]
    fn splat(v: Vec3) -> V {
        V {
            x: F::splat(v.x),
            y: F::splat(v.y),
            z: F::splat(v.z),
        }
    }
    #[inline(always)]
    fn add(self, o: V) -> V {
        V {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
    #[inline(always)]
    fn sub(self, o: V) -> V {
        V {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    #[inline(always)]
    fn mul(self, s: F) -> V {
        V {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    #[inline(always)]
    fn mulv(self, o: V) -> V {
        V {
            x: self.x * o.x,
            y: self.y * o.y,
            z: self.z * o.z,
        }
    }
    #[inline(always)]
    fn dot(self, o: V) -> F {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    fn cross(self, o: V) -> V {
        V {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    fn sel(m: F, a: V, b: V) -> V {
        V {
            x: m.select(a.x, b.x),
            y: m.select(a.y, b.y),
            z: m.select(a.z, b.z),
        }
    }
    #[inline(always)]
    fn mat(m: &Mat3, v: V) -> V {
        let (c0, c1, c2) = (m.x_axis, m.y_axis, m.z_axis);
        V {
            x: v.x * F::splat(c0.x) + v.y * F::splat(c1.x) + v.z * F::splat(c2.x),
            y: v.x * F::splat(c0.y) + v.y * F::splat(c1.y) + v.z * F::splat(c2.y),
            z: v.x * F::splat(c0.z) + v.y * F::splat(c1.z) + v.z * F::splat(c2.z),
        }
    }
}

struct Tri {
    corners: [Vec3; 3],
    v0: Vec3,
    e1: Vec3,
    e2: Vec3,
    n: Vec3,
}

struct Cuboid {
    center: Vec3,
    to_world: Mat3,
    to_local: Mat3,
    half: Vec3,
}

struct Scene {
    tris: Vec<Tri>,
    boxes: Vec<Cuboid>,
    /// Per primitive (triangles, then boxes): albedo and unit normal (boxes: unused).
    albedo: Vec<Vec3>,
    normal: Vec<Vec3>,
    /// The two light triangles' ids and their radiance.
    lights: [usize; 2],
    le: Vec3,
    light_area: f32,
}

fn v(x: f32, y: f32, z: f32) -> Vec3 {
    Vec3::new(x, y, z)
}

fn cornell() -> Scene {
    let white = v(0.885809, 0.698859, 0.666422);
    let green = v(0.105421, 0.37798, 0.076425);
    let red = v(0.570068, 0.0430135, 0.0443706);
    let t = |a: Vec3, b: Vec3, c: Vec3, col: Vec3| (a, b, c, col);
    let list = [
        t(v(-1., -1., 1.), v(1., -1., 1.), v(1., -1., -1.), white),
        t(v(-1., -1., 1.), v(1., -1., -1.), v(-1., -1., -1.), white),
        t(v(-1., 1., -1.), v(1., 1., -1.), v(1., 1., 1.), white),
        t(v(-1., 1., -1.), v(1., 1., 1.), v(-1., 1., 1.), white),
        t(v(-1., -1., -1.), v(1., -1., -1.), v(1., 1., -1.), white),
        t(v(-1., -1., -1.), v(1., 1., -1.), v(-1., 1., -1.), white),
        t(v(1., -1., -1.), v(1., -1., 1.), v(1., 1., 1.), green),
        t(v(1., -1., -1.), v(1., 1., 1.), v(1., 1., -1.), green),
        t(v(-1., -1., 1.), v(-1., -1., -1.), v(-1., 1., -1.), red),
        t(v(-1., -1., 1.), v(-1., 1., -1.), v(-1., 1., 1.), red),
        t(
            v(-0.23, 0.99, -0.18),
            v(0.23, 0.99, -0.18),
            v(0.23, 0.99, 0.2),
            white,
        ),
        t(
            v(-0.23, 0.99, -0.18),
            v(0.23, 0.99, 0.2),
            v(-0.23, 0.99, 0.2),
            white,
        ),
    ];
    let mut tris = Vec::new();
    let mut albedo = Vec::new();
    let mut normal = Vec::new();
    for (a, b, c, col) in list {
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2).normalize();
        tris.push(Tri {
            corners: [a, b, c],
            v0: a,
            e1,
            e2,
            n,
        });
        albedo.push(col);
        normal.push(n);
    }
    let cuboid = |c: Vec3, size: Vec3, ry: f32| {
        let to_world = Mat3::from_rotation_y(ry.to_radians());
        Cuboid {
            center: c,
            to_world,
            to_local: to_world.transpose(),
            half: size * 0.5,
        }
    };
    let boxes = vec![
        cuboid(v(0.335, -0.7, 0.38), v(0.6, 0.6, 0.6), -17.0),
        cuboid(v(-0.33, -0.4, -0.28), v(0.6, 1.22, 0.6), 18.25),
    ];
    for _ in &boxes {
        albedo.push(white);
        normal.push(Vec3::ZERO);
    }
    let light_area = 0.5 * tris[10].e1.cross(tris[10].e2).length();
    Scene {
        tris,
        boxes,
        albedo,
        normal,
        lights: [10, 11],
        le: v(18.387, 13.9873, 6.75357),
        light_area,
    }
}

/// The watertight test's per-ray set-up (Woop et al.), lane by lane: each
/// lane's own axis permutation as masks, its shear and permuted origin.
struct Sheared {
    /// Per target axis (x', y', z'), masks saying which world axis feeds it.
    from_x: [F; 3],
    from_y: [F; 3],
    o: [F; 3],
    sx: F,
    sy: F,
    sz: F,
}

#[inline(always)]
fn pick(from_x: F, from_y: F, v: [F; 3]) -> F {
    from_x.select(v[0], from_y.select(v[1], v[2]))
}

#[inline(always)]
fn shear_rays(o: V, d: V) -> Sheared {
    let (ax, ay, az) = (d.x.abs(), d.y.abs(), d.z.abs());
    // kz: the axis of the largest |d| (x on ties with y, as max_position).
    let kz_x = ax.simd_ge(ay) & ax.simd_ge(az);
    let kz_y = !kz_x & ay.simd_ge(az);
    let kz_z = !(kz_x | kz_y);
    // kx = kz + 1, ky = kz + 2 (mod 3), swapped when d[kz] < 0.
    let dz = kz_x.select(d.x, kz_y.select(d.y, d.z));
    let swap = dz.simd_lt(F::ZERO);
    let (kx_x, kx_y) = (kz_z, kz_x);
    let (ky_x, ky_y) = (kz_y, kz_z);
    let (kx_x, kx_y, ky_x, ky_y) = (
        swap.select(ky_x, kx_x),
        swap.select(ky_y, kx_y),
        swap.select(kx_x, ky_x),
        swap.select(kx_y, ky_y),
    );
    let dv = [d.x, d.y, d.z];
    let ov = [o.x, o.y, o.z];
    let dx = pick(kx_x, kx_y, dv);
    let dy = pick(ky_x, ky_y, dv);
    Sheared {
        from_x: [kx_x, ky_x, kz_x],
        from_y: [kx_y, ky_y, kz_y],
        o: [
            pick(kx_x, kx_y, ov),
            pick(ky_x, ky_y, ov),
            pick(kz_x, kz_y, ov),
        ],
        sx: dx / dz,
        sy: dy / dz,
        sz: F::ONE / dz,
    }
}

/// α of the watertight test of each lane's ray with triangle `c` (+∞: no hit).
#[inline(always)]
fn watertight(r: &Sheared, c: &[Vec3; 3]) -> F {
    let corner = |p: Vec3| {
        let pv = [F::splat(p.x), F::splat(p.y), F::splat(p.z)];
        let z = pick(r.from_x[2], r.from_y[2], pv) - r.o[2];
        (
            (pick(r.from_x[0], r.from_y[0], pv) - r.o[0]) - r.sx * z,
            (pick(r.from_x[1], r.from_y[1], pv) - r.o[1]) - r.sy * z,
            z,
        )
    };
    let ((ax, ay, az), (bx, by, bz), (cx, cy, cz)) = (corner(c[0]), corner(c[1]), corner(c[2]));
    let eu = cx * by - cy * bx;
    let ev = ax * cy - ay * cx;
    let ew = bx * ay - by * ax;
    // (The exact-zero case falls back to f64 lane by lane in raylab; rare,
    // and only checked here.)
    let zero = F::ZERO;
    let negative = eu.simd_lt(zero) | ev.simd_lt(zero) | ew.simd_lt(zero);
    let positive = eu.simd_gt(zero) | ev.simd_gt(zero) | ew.simd_gt(zero);
    let det = eu + ev + ew;
    let t_scaled = eu * (r.sz * az) + ev * (r.sz * bz) + ew * (r.sz * cz);
    let alpha = t_scaled / det;
    let hit =
        !(negative & positive) & det.simd_ne(zero) & alpha.abs().simd_lt(F::splat(f32::INFINITY));
    hit.select(alpha, F::splat(f32::INFINITY))
}

static WATERTIGHT: std::sync::LazyLock<bool> =
    std::sync::LazyLock::new(|| std::env::var("WT").is_ok());

/// Closest hit of W rays: (t, primitive id as float; +∞ / -1 for a miss).
#[inline(always)]
fn closest(s: &Scene, o: V, d: V) -> (F, F) {
    let eps = F::splat(1e-6);
    let mut best = F::splat(f32::INFINITY);
    let mut id = F::splat(-1.0);
    if *WATERTIGHT {
        let r = shear_rays(o, d);
        for (k, t) in s.tris.iter().enumerate() {
            let a = watertight(&r, &t.corners);
            let hit = a.simd_gt(eps) & a.simd_lt(best);
            best = hit.select(a, best);
            id = hit.select(F::splat(k as f32), id);
        }
    } else {
        for (k, t) in s.tris.iter().enumerate() {
            let (e1, e2) = (V::splat(t.e1), V::splat(t.e2));
            let p = d.cross(e2);
            let det = e1.dot(p);
            let inv = F::ONE / det;
            let sv = o.sub(V::splat(t.v0));
            let u = sv.dot(p) * inv;
            let q = sv.cross(e1);
            let w = d.dot(q) * inv;
            let tt = e2.dot(q) * inv;
            let hit = u.simd_ge(F::ZERO)
                & w.simd_ge(F::ZERO)
                & (u + w).simd_le(F::ONE)
                & tt.simd_gt(eps)
                & tt.simd_lt(best);
            best = hit.select(tt, best);
            id = hit.select(F::splat(k as f32), id);
        }
    }
    for (k, b) in s.boxes.iter().enumerate() {
        let lo = V::mat(&b.to_local, o.sub(V::splat(b.center)));
        let ld = V::mat(&b.to_local, d);
        let h = V::splat(b.half);
        let (tn, tf) = slab(lo, ld, h);
        let t = tn.simd_gt(eps).select(tn, tf);
        let hit = tn.simd_le(tf) & tf.simd_gt(eps) & t.simd_lt(best);
        best = hit.select(t, best);
        id = hit.select(F::splat((s.tris.len() + k) as f32), id);
    }
    (best, id)
}

#[inline(always)]
fn slab(lo: V, ld: V, h: V) -> (F, F) {
    let ax = |o: F, d: F, h: F| {
        let inv = F::ONE / d;
        let a = (-h - o) * inv;
        let b = (h - o) * inv;
        (a.min(b), a.max(b))
    };
    let (nx, fx) = ax(lo.x, ld.x, h.x);
    let (ny, fy) = ax(lo.y, ld.y, h.y);
    let (nz, fz) = ax(lo.z, ld.z, h.z);
    (nx.max(ny).max(nz), fx.min(fy).min(fz))
}

/// Lanes whose ray is blocked before t_max (any hit).
#[inline(always)]
fn occluded(s: &Scene, o: V, d: V, t_max: F, active: F) -> F {
    let eps = F::splat(1e-6);
    let mut blocked = F::ZERO;
    if *WATERTIGHT {
        let r = shear_rays(o, d);
        for t in &s.tris {
            let a = watertight(&r, &t.corners);
            blocked |= a.simd_gt(eps) & a.simd_lt(t_max);
            if (blocked | !active).all() {
                return blocked;
            }
        }
    } else {
        for t in &s.tris {
            let (e1, e2) = (V::splat(t.e1), V::splat(t.e2));
            let p = d.cross(e2);
            let inv = F::ONE / e1.dot(p);
            let sv = o.sub(V::splat(t.v0));
            let u = sv.dot(p) * inv;
            let q = sv.cross(e1);
            let w = d.dot(q) * inv;
            let tt = e2.dot(q) * inv;
            blocked |= u.simd_ge(F::ZERO)
                & w.simd_ge(F::ZERO)
                & (u + w).simd_le(F::ONE)
                & tt.simd_gt(eps)
                & tt.simd_lt(t_max);
            if (blocked | !active).all() {
                return blocked;
            }
        }
    }
    for b in &s.boxes {
        let lo = V::mat(&b.to_local, o.sub(V::splat(b.center)));
        let ld = V::mat(&b.to_local, d);
        let (tn, tf) = slab(lo, ld, V::splat(b.half));
        let t = tn.simd_gt(eps).select(tn, tf);
        blocked |= tn.simd_le(tf) & tf.simd_gt(eps) & t.simd_lt(t_max);
    }
    blocked
}

/// The outward normal of box `b` at world point `p` (lanes of any box).
#[inline(always)]
fn box_normal(b: &Cuboid, p: V) -> V {
    let l = V::mat(&b.to_local, p.sub(V::splat(b.center)));
    let (ex, ey, ez) = (
        l.x.abs() / F::splat(b.half.x),
        l.y.abs() / F::splat(b.half.y),
        l.z.abs() / F::splat(b.half.z),
    );
    let one = F::ONE;
    let sign = |c: F| c.simd_lt(F::ZERO).select(-one, one);
    let xm = ex.simd_ge(ey) & ex.simd_ge(ez);
    let ym = !xm & ey.simd_ge(ez);
    let zm = !(xm | ym);
    let n = V {
        x: xm.select(sign(l.x), F::ZERO),
        y: ym.select(sign(l.y), F::ZERO),
        z: zm.select(sign(l.z), F::ZERO),
    };
    V::mat(&b.to_world, n)
}

/// Counter-based random numbers: lowbias32 of (lane key + draw).
#[inline(always)]
fn hash(mut x: U) -> U {
    x ^= x >> 16;
    x *= U::splat(0x7feb_352d);
    x ^= x >> 15;
    x *= U::splat(0x846c_a68b);
    x ^= x >> 16;
    x
}

#[inline(always)]
fn uniform(key: &mut U) -> F {
    *key += U::splat(0x9e37_79b9);
    let bits: I = bytemuck::cast(hash(*key) >> 8);
    bits.round_float() * F::splat(1.0 / 16_777_216.0)
}

#[inline(always)]
fn sin_cos_quarter(x: F) -> (F, F) {
    // |x| ≤ π/4: Taylor to x⁹ / x⁸ (error < 4e-8).
    let x2 = x * x;
    let s = x
        * (F::ONE
            + x2 * (F::splat(-1.0 / 6.0)
                + x2 * (F::splat(1.0 / 120.0)
                    + x2 * (F::splat(-1.0 / 5040.0) + x2 * F::splat(1.0 / 362_880.0)))));
    let c = F::ONE
        + x2 * (F::splat(-0.5)
            + x2 * (F::splat(1.0 / 24.0)
                + x2 * (F::splat(-1.0 / 720.0) + x2 * F::splat(1.0 / 40_320.0))));
    (s, c)
}

/// Cosine-weighted hemisphere about z (concentric disk, Malley).
#[inline(always)]
fn cosine_hemisphere(u1: F, u2: F) -> V {
    let a = u1 * F::splat(2.0) - F::ONE;
    let b = u2 * F::splat(2.0) - F::ONE;
    let c1 = a.abs().simd_gt(b.abs());
    let r = c1.select(a, b);
    let safe = r.simd_eq(F::ZERO);
    let ratio = c1.select(b, a) / safe.select(F::ONE, r);
    let (s, c) = sin_cos_quarter(ratio * F::splat(std::f32::consts::FRAC_PI_4));
    let x = safe.select(F::ZERO, r * c1.select(c, s));
    let y = safe.select(F::ZERO, r * c1.select(s, c));
    let z = (F::ONE - x * x - y * y)
        .max(F::ZERO)
        .sqrt()
        .max(F::splat(1e-6));
    V { x, y, z }
}

/// Duff et al.'s branchless frame around n: local (x, y, z) to world.
#[inline(always)]
fn to_world(n: V, l: V) -> V {
    let sign = n.z.simd_lt(F::ZERO).select(-F::ONE, F::ONE);
    let a = -F::ONE / (sign + n.z);
    let b = n.x * n.y * a;
    let s = V {
        x: F::ONE + sign * n.x * n.x * a,
        y: sign * b,
        z: -sign * n.x,
    };
    let t = V {
        x: b,
        y: sign + n.y * n.y * a,
        z: -n.y,
    };
    s.mul(l.x).add(t.mul(l.y)).add(n.mul(l.z))
}

#[inline(always)]
fn gather(table: &[Vec3], id: F) -> V {
    let ids = id.to_array();
    let mut x = [0.0; W];
    let mut y = [0.0; W];
    let mut z = [0.0; W];
    for i in 0..W {
        let k = ids[i].max(0.0) as usize;
        let p = table[k];
        (x[i], y[i], z[i]) = (p.x, p.y, p.z);
    }
    V {
        x: F::from(x),
        y: F::from(y),
        z: F::from(z),
    }
}

struct Camera {
    eye: Vec3,
    tan: f32,
    w: u32,
    h: u32,
}

impl Camera {
    fn dir(&self, i: u32, j: u32, ux: f32, uy: f32) -> Vec3 {
        let aspect = self.w as f32 / self.h as f32;
        let x = (2.0 * (i as f32 + ux) / self.w as f32 - 1.0) * self.tan * aspect;
        let y = (1.0 - 2.0 * (j as f32 + uy) / self.h as f32) * self.tan;
        Vec3::new(x, y, -1.0).normalize()
    }
}

/// With `SCALAR_RAYS=1`: each lane's rays are traced by raylab itself
/// (`World::intersect` / `World::occluded`, one ray at a time, its BVHs and
/// exact shapes), the rest stays 8-wide: what SIMD shading alone gains.
static SCALAR_RAYS: std::sync::LazyLock<bool> =
    std::sync::LazyLock::new(|| std::env::var("SCALAR_RAYS").is_ok());

/// raylab's world of the reference Cornell box.
fn world() -> renderer::world::World {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/reference/cornell.xml"
    );
    let text = std::fs::read_to_string(path).expect("cornell.xml");
    let scene = scene::read_str(&text, path).expect("parses");
    renderer::world::World::from_scene(&scene).expect("valid")
}

/// Each lane's ray as raylab's `Ray` (`None` for lanes off in `on`).
fn lane_rays(o: V, d: V, on: F) -> [Option<renderer::geometry::ray::Ray>; W] {
    let (ox, oy, oz) = (o.x.to_array(), o.y.to_array(), o.z.to_array());
    let (dx, dy, dz) = (d.x.to_array(), d.y.to_array(), d.z.to_array());
    let on = on.to_array();
    std::array::from_fn(|l| {
        (on[l].to_bits() != 0).then(|| {
            renderer::geometry::ray::Ray::new(
                Vec3::new(ox[l], oy[l], oz[l]),
                Vec3::new(dx[l], dy[l], dz[l]),
            )
        })
    })
}

/// Closest hits through raylab, lane by lane: t (+∞ on a miss), the
/// geometric normal, the albedo and whether the light was hit.
fn closest_world(w: &renderer::world::World, o: V, d: V, live: F) -> (F, V, V, F) {
    let mut t = [f32::INFINITY; W];
    let mut n = [[0.0f32; W]; 3];
    let mut a = [[0.0f32; W]; 3];
    let mut light = [0.0f32; W];
    for (l, ray) in lane_rays(o, d, live).into_iter().enumerate() {
        let Some(ray) = ray else { continue };
        let Some(hit) = w.intersect(&ray, renderer::shapes::Method::Robust) else {
            continue;
        };
        let at = w.hit_surface(&ray, &hit);
        t[l] = hit.alpha;
        for k in 0..3 {
            n[k][l] = at.surface.normal[k];
            a[k][l] = at.color[k];
        }
        if hit.object == 10 || hit.object == 11 {
            light[l] = f32::from_bits(u32::MAX);
        }
    }
    let v3 = |c: [[f32; W]; 3]| V {
        x: F::from(c[0]),
        y: F::from(c[1]),
        z: F::from(c[2]),
    };
    (F::from(t), v3(n), v3(a), F::from(light))
}

/// Shadow rays through raylab, lane by lane.
fn occluded_world(w: &renderer::world::World, o: V, d: V, t_max: F, active: F) -> F {
    let t_max = t_max.to_array();
    let mut blocked = [0.0f32; W];
    for (l, ray) in lane_rays(o, d, active).into_iter().enumerate() {
        let Some(ray) = ray else { continue };
        if w.occluded(&ray.with_t_max(t_max[l]), renderer::shapes::Method::Robust) {
            blocked[l] = f32::from_bits(u32::MAX);
        }
    }
    F::from(blocked)
}

static MAX_DEPTH: std::sync::LazyLock<i32> = std::sync::LazyLock::new(|| {
    std::env::var("DEPTH")
        .ok()
        .and_then(|d| d.parse().ok())
        .unwrap_or(8)
});
const RR_DEPTH: i32 = 5;

fn render(
    s: &Scene,
    world: Option<&renderer::world::World>,
    cam: &Camera,
    spp: u32,
    film: &mut [Vec3],
) -> u64 {
    let pixels = cam.w * cam.h;
    let total = (pixels as u64) * spp as u64;
    let mut next: u64 = 0;
    // Lane state.
    let mut o = V::splat(Vec3::ZERO);
    let mut d = V::splat(Vec3::Z);
    let mut beta = V::splat(Vec3::ONE);
    let mut rad = V::splat(Vec3::ZERO);
    let mut depth = [0i32; W];
    let mut prev_pdf = F::ZERO; // 0: camera ray (no MIS)
    let mut key = U::ZERO;
    let mut pixel = [u32::MAX; W];
    let mut alive = [false; W];
    let le = V::splat(s.le);
    let inv_pi = F::splat(std::f32::consts::FRAC_1_PI);
    let pmf_over_area = F::splat(0.5 / s.light_area);
    let mut paths = 0u64;
    loop {
        // Refill finished lanes.
        {
            let mut ox = o.x.to_array();
            let mut oy = o.y.to_array();
            let mut oz = o.z.to_array();
            let mut dx = d.x.to_array();
            let mut dy = d.y.to_array();
            let mut dz = d.z.to_array();
            let mut bx = beta.x.to_array();
            let mut by = beta.y.to_array();
            let mut bz = beta.z.to_array();
            let mut rx = rad.x.to_array();
            let mut ry = rad.y.to_array();
            let mut rz = rad.z.to_array();
            let mut pp = prev_pdf.to_array();
            let mut keys = key.to_array();
            let mut any = false;
            let lanes_used: usize = std::env::var("LANES")
                .ok()
                .and_then(|l| l.parse().ok())
                .unwrap_or(W);
            for l in 0..lanes_used {
                if alive[l] {
                    any = true;
                    continue;
                }
                if pixel[l] != u32::MAX {
                    film[pixel[l] as usize] += Vec3::new(rx[l], ry[l], rz[l]);
                    pixel[l] = u32::MAX;
                }
                if next >= total {
                    continue;
                }
                let p = (next % pixels as u64) as u32;
                let sample = (next / pixels as u64) as u32;
                next += 1;
                paths += 1;
                let mut k =
                    U::splat(p.wrapping_mul(0x2545_f491) ^ sample.wrapping_mul(0x9e37_79b9));
                k = hash(k);
                let kk = k.to_array()[0];
                let ux = (hash(U::splat(kk ^ 1)).to_array()[0] >> 8) as f32 / 16_777_216.0;
                let uy = (hash(U::splat(kk ^ 2)).to_array()[0] >> 8) as f32 / 16_777_216.0;
                let dir = cam.dir(p % cam.w, p / cam.w, ux, uy);
                (ox[l], oy[l], oz[l]) = (cam.eye.x, cam.eye.y, cam.eye.z);
                (dx[l], dy[l], dz[l]) = (dir.x, dir.y, dir.z);
                (bx[l], by[l], bz[l]) = (1.0, 1.0, 1.0);
                (rx[l], ry[l], rz[l]) = (0.0, 0.0, 0.0);
                pp[l] = 0.0;
                keys[l] = kk.wrapping_mul(0x85eb_ca6b);
                depth[l] = 0;
                pixel[l] = p;
                alive[l] = true;
                any = true;
            }
            if !any {
                return paths;
            }
            o = V {
                x: F::from(ox),
                y: F::from(oy),
                z: F::from(oz),
            };
            d = V {
                x: F::from(dx),
                y: F::from(dy),
                z: F::from(dz),
            };
            beta = V {
                x: F::from(bx),
                y: F::from(by),
                z: F::from(bz),
            };
            rad = V {
                x: F::from(rx),
                y: F::from(ry),
                z: F::from(rz),
            };
            prev_pdf = F::from(pp);
            key = U::from(keys);
        }
        let live = F::from(alive.map(|a| if a { f32::from_bits(u32::MAX) } else { 0.0 }));
        // Closest hits.
        let (t, mut n, albedo, on_light) = match world {
            Some(w) => closest_world(w, o, d, live),
            None => {
                let (t, id) = closest(s, o, d);
                let p = o.add(d.mul(t));
                // Normals: triangles from the table, boxes from the face.
                let mut n = gather(&s.normal, id);
                for (k, b) in s.boxes.iter().enumerate() {
                    let on = id.simd_eq(F::splat((s.tris.len() + k) as f32));
                    if on.any() {
                        n = V::sel(on, box_normal(b, p), n);
                    }
                }
                let on_light = id.simd_eq(F::splat(s.lights[0] as f32))
                    | id.simd_eq(F::splat(s.lights[1] as f32));
                (t, n, gather(&s.albedo, id), on_light)
            }
        };
        let hit = live & t.simd_lt(F::splat(f32::INFINITY));
        let p = o.add(d.mul(t));
        let cos_o = n.dot(d);
        let front = cos_o.simd_lt(F::ZERO);
        n = V::sel(front, n, n.mul(-F::ONE));
        // Emission (front of the light), MIS against light sampling.
        let emit = hit & on_light & front;
        if emit.any() {
            let light_pdf = pmf_over_area * t * t / (-cos_o);
            let bsdf = prev_pdf;
            let w = prev_pdf.simd_eq(F::ZERO).select(
                F::ONE,
                (bsdf * bsdf) / (bsdf * bsdf + light_pdf * light_pdf),
            );
            let add = beta.mulv(le).mul(emit.select(w, F::ZERO));
            rad = rad.add(add);
        }
        let depth_v = I::from(depth);
        let going =
            hit & bytemuck::cast::<I, F>((depth_v + I::splat(1)).simd_lt(I::splat(*MAX_DEPTH)));
        if going.any() {
            let eps = F::splat(8e-6);
            let origin = p.add(n.mul(eps));
            // Light sample: a triangle of the light, a point on it.
            let u_sel = uniform(&mut key);
            let u1 = uniform(&mut key);
            let u2 = uniform(&mut key);
            let pick = u_sel.simd_lt(F::splat(0.5));
            let (la, lb) = (&s.tris[s.lights[0]], &s.tris[s.lights[1]]);
            let v0 = V::sel(pick, V::splat(la.v0), V::splat(lb.v0));
            let e1 = V::sel(pick, V::splat(la.e1), V::splat(lb.e1));
            let e2 = V::sel(pick, V::splat(la.e2), V::splat(lb.e2));
            let fold = (u1 + u2).simd_gt(F::ONE);
            let (bu, bv) = (fold.select(F::ONE - u1, u1), fold.select(F::ONE - u2, u2));
            let q = v0.add(e1.mul(bu)).add(e2.mul(bv));
            let to = q.sub(p);
            let dist2 = to.dot(to);
            let dist = dist2.sqrt();
            let wi = to.mul(F::ONE / dist);
            let ln = V::splat(la.n);
            let cos_l = -wi.dot(ln);
            let cos_s = wi.dot(n);
            let valid = going & cos_l.simd_gt(F::ZERO) & cos_s.simd_gt(F::ZERO);
            if valid.any() {
                let light_pdf = pmf_over_area * dist2 / cos_l;
                let bsdf_pdf = cos_s * inv_pi;
                let mis = (light_pdf * light_pdf) / (light_pdf * light_pdf + bsdf_pdf * bsdf_pdf);
                let t_max = dist * F::splat(1.0 - 1e-4);
                let blocked = match world {
                    Some(w) => occluded_world(w, origin, wi, t_max, valid),
                    None => occluded(s, origin, wi, t_max, valid),
                };
                let lit = valid & !blocked;
                let scale = lit.select(cos_s * inv_pi * mis / light_pdf, F::ZERO);
                rad = rad.add(beta.mulv(albedo).mulv(le).mul(scale));
            }
            // BSDF sample.
            let u3 = uniform(&mut key);
            let u4 = uniform(&mut key);
            let local = cosine_hemisphere(u3, u4);
            let wo = to_world(n, local);
            beta = V::sel(going, beta.mulv(albedo), beta);
            prev_pdf = going.select(local.z * inv_pi, prev_pdf);
            o = V::sel(going, origin, o);
            d = V::sel(going, wo, d);
        }
        // Depth, roulette, and who goes on.
        let u_rr = uniform(&mut key);
        let g = going.to_array();
        let b_max = beta.x.max(beta.y).max(beta.z);
        let keep = b_max.min(F::splat(0.95));
        let survive = u_rr.simd_lt(keep);
        let mut scale = [1.0f32; W];
        let (keep_a, surv_a) = (keep.to_array(), survive.to_array());
        for l in 0..W {
            if !alive[l] {
                continue;
            }
            if g[l].to_bits() == 0 {
                alive[l] = false;
                continue;
            }
            depth[l] += 1;
            if depth[l] >= RR_DEPTH {
                if surv_a[l].to_bits() == 0 {
                    alive[l] = false;
                    continue;
                }
                scale[l] = 1.0 / keep_a[l];
            }
        }
        beta = beta.mul(F::from(scale));
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let spp: u32 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(16);
    let size: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(384);
    if let Some(path) = args.get(3) {
        let img = read_exr_rgb(std::path::Path::new(path)).expect("image");
        let reference = read_exr_rgb(std::path::Path::new(
            "/work/main/assets/reference/cornell.exr",
        ))
        .expect("reference");
        let mean: Vec3 = img.pixels.iter().copied().sum::<Vec3>() / img.pixels.len() as f32;
        println!(
            "{path}: relMSE {:.5} mean {mean}",
            rel_mse(&img.pixels, &reference.pixels)
        );
        return;
    }
    let s = cornell();
    let cam = Camera {
        eye: v(0.0, 0.0, 3.9),
        tan: 19.65385f32.to_radians().tan(),
        w: size,
        h: size,
    };
    let mut film = vec![Vec3::ZERO; (size * size) as usize];
    let start = Instant::now();
    let w = SCALAR_RAYS.then(world);
    let paths = render(&s, w.as_ref(), &cam, spp, &mut film);
    let secs = start.elapsed().as_secs_f64();
    for p in &mut film {
        *p /= spp as f32;
    }
    let digest = film.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, p| {
        [p.x, p.y, p.z].iter().fold(h, |h, c| {
            (h ^ u64::from(c.to_bits())).wrapping_mul(0x100_0000_01b3)
        })
    });
    println!("film digest {digest:016x}");
    println!(
        "{paths} paths in {secs:.3} s: {:.3} µs per path (1 thread)",
        secs * 1e6 / paths as f64
    );
    if size == 384 {
        let reference = read_exr_rgb(std::path::Path::new(
            "/work/main/assets/reference/cornell.exr",
        ))
        .expect("reference");
        println!(
            "relMSE at {spp} spp: {:.5}",
            rel_mse(&film, &reference.pixels)
        );
        let mean: Vec3 = film.iter().copied().sum::<Vec3>() / film.len() as f32;
        let rmean: Vec3 = reference.pixels.iter().copied().sum::<Vec3>() / film.len() as f32;
        println!("mean {mean} reference {rmean}");
    }
}
