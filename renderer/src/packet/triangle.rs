//! The watertight ray–triangle test of Woop, Benthin and Wald (2013) for
//! sixteen rays at once, exactly as [`WatertightRay`] computes it lane by
//! lane: each lane's axis permutation and shear set up once per packet
//! ([`ShearedRays`]), then any triangle given by its corners tested against
//! all sixteen ([`ShearedRays::hit`]). The lone triangles of a packet world
//! (`packet_shapes/triangles.rs`) and the mesh BVH's packets
//! (`accel/mesh/lanes.rs`) both test their triangles with it.
//!
//! [`WatertightRay`]: crate::shapes::WatertightRay

use super::{FloatLanes, MaskLanes, Rays, WIDTH};

/// Which world axis feeds each axis of the sheared frame, for the sixteen
/// lanes together.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Frame<F: FloatLanes> {
    /// Every live lane has the permutation (kx, ky, kz).
    Same([usize; 3]),
    /// Lanes differ: per sheared axis (x', y', z'), the lanes where world x
    /// feeds it, and those where world y does (world z elsewhere).
    Mixed {
        /// Lanes whose x', y', z' is world x.
        from_x: [F::Mask; 3],
        /// Lanes whose x', y', z' is world y.
        from_y: [F::Mask; 3],
    },
}

/// Per lane, `x` where `from_x` is set, else `y` where `from_y` is, else
/// `z`: the coordinate a permuted axis takes from world x, y, z.
#[inline(always)]
fn pick<F: FloatLanes>(from_x: F::Mask, from_y: F::Mask, x: F, y: F, z: F) -> F {
    from_x.select(x, from_y.select(y, z))
}

/// How a [`Frame`] puts a point that is the same in every lane (a corner)
/// into each lane's permuted frame. (A trait with `#[inline(always)]`
/// methods rather than a closure: a closure LLVM declines to inline is
/// compiled without the AVX2 of [`crate::packet::dispatch`], and then every
/// lane operation in it becomes a call.)
pub(crate) trait Permutation<F>: Copy {
    /// The point `p` in each lane's permuted frame.
    fn permute(self, p: &[f32; 3]) -> [F; 3];
}

/// [`Frame::Same`]'s permutation (kx, ky, kz), shared by every lane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SameAxes(pub(crate) [usize; 3]);

impl<F: FloatLanes> Permutation<F> for SameAxes {
    #[inline(always)]
    fn permute(self, p: &[f32; 3]) -> [F; 3] {
        let [kx, ky, kz] = self.0;
        [F::splat(p[kx]), F::splat(p[ky]), F::splat(p[kz])]
    }
}

/// [`Frame::Mixed`]'s permutations: coordinate k is world x in
/// `from_x[k]`'s lanes, world y in `from_y[k]`'s, world z elsewhere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MixedAxes<F: FloatLanes> {
    /// Lanes whose x', y', z' is world x.
    pub(crate) from_x: [F::Mask; 3],
    /// Lanes whose x', y', z' is world y.
    pub(crate) from_y: [F::Mask; 3],
}

impl<F: FloatLanes> Permutation<F> for MixedAxes<F> {
    #[inline(always)]
    fn permute(self, p: &[f32; 3]) -> [F; 3] {
        let (x, y, z) = (F::splat(p[0]), F::splat(p[1]), F::splat(p[2]));
        let (from_x, from_y) = (self.from_x, self.from_y);
        [
            pick(from_x[0], from_y[0], x, y, z),
            pick(from_x[1], from_y[1], x, y, z),
            pick(from_x[2], from_y[2], x, y, z),
        ]
    }
}

/// Corner `p` (already in the lane's permuted frame) relative to P0 and
/// sheared: (x, y) and the unsheared z.
#[inline(always)]
fn shear<F: FloatLanes>(r: &ShearedRays<F>, [px, py, pz]: [F; 3]) -> (F, F, F) {
    let z = pz - r.origin[2];
    (
        (px - r.origin[0]) - r.sx * z,
        (py - r.origin[1]) - r.sy * z,
        z,
    )
}

/// What the watertight test of one triangle gives sixteen rays.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleLanes<F: FloatLanes> {
    /// The lanes that hit it in (0, limit).
    pub(crate) hit: F::Mask,
    /// α (anything in the other lanes).
    pub(crate) alpha: F,
    /// The edge function V (β = V / det).
    pub(crate) v: F,
    /// The edge function W (γ = W / det).
    pub(crate) w: F,
    /// The determinant U + V + W.
    pub(crate) det: F,
}

/// The per-ray half of the watertight test for sixteen rays: what
/// [`WatertightRay::new`](crate::shapes::WatertightRay::new) computes, lane by lane.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShearedRays<F: FloatLanes> {
    /// The permutation (kx, ky, kz) of every lane.
    pub(crate) frame: Frame<F>,
    /// The origins P0 in the permuted frame: (P0[kx], P0[ky], P0[kz]).
    origin: [F; 3],
    /// v[kx] / v[kz].
    sx: F,
    /// v[ky] / v[kz].
    sy: F,
    /// 1 / v[kz].
    sz: F,
    /// The live lanes (the rare exact-zero fallback runs only for them).
    live: F::Mask,
}

impl<F: FloatLanes> ShearedRays<F> {
    /// The permutation and shear of each lane's ray: kz the axis of the
    /// direction's largest magnitude (glam's `max_position`: the first on a
    /// tie), kx and ky the next two, swapped when v[kz] < 0.
    #[inline(always)]
    pub(crate) fn new(rays: &Rays<F>, live: F::Mask) -> Self {
        let d = rays.dir;
        let (ax, ay, az) = (d.x.abs(), d.y.abs(), d.z.abs());
        let y_beats_x = ay.simd_gt(ax);
        let kz_z = az.simd_gt(y_beats_x.select(ay, ax));
        let kz_y = y_beats_x & !kz_z;
        let kz_x = !(y_beats_x | kz_z);
        // kx = kz + 1 and ky = kz + 2 (mod 3) ...
        let (kx_x, kx_y) = (kz_z, kz_x);
        let (ky_x, ky_y) = (kz_y, kz_z);
        let dz = pick(kz_x, kz_y, d.x, d.y, d.z);
        // ... swapped when v[kz] < 0, to keep the winding.
        let swap = dz.simd_lt(F::ZERO);
        let (kx_x, kx_y, ky_x, ky_y) = (
            swap.select_mask(ky_x, kx_x),
            swap.select_mask(ky_y, kx_y),
            swap.select_mask(kx_x, ky_x),
            swap.select_mask(kx_y, ky_y),
        );
        let (from_x, from_y) = ([kx_x, ky_x, kz_x], [kx_y, ky_y, kz_y]);
        let o = rays.origin;
        Self {
            frame: Self::frame(from_x, from_y, live),
            origin: [
                pick(from_x[0], from_y[0], o.x, o.y, o.z),
                pick(from_x[1], from_y[1], o.x, o.y, o.z),
                pick(from_x[2], from_y[2], o.x, o.y, o.z),
            ],
            sx: pick(kx_x, kx_y, d.x, d.y, d.z) / dz,
            sy: pick(ky_x, ky_y, d.x, d.y, d.z) / dz,
            sz: F::ONE / dz,
            live,
        }
    }

    /// [`Frame::Same`] when every live lane has the same permutation.
    #[inline(always)]
    fn frame(from_x: [F::Mask; 3], from_y: [F::Mask; 3], live: F::Mask) -> Frame<F> {
        // The masks as bits first: what follows is scalar code (closures
        // and iterators over lane values might not be inlined).
        let live_bits = live.to_bitmask();
        let x_bits = [
            from_x[0].to_bitmask(),
            from_x[1].to_bitmask(),
            from_x[2].to_bitmask(),
        ];
        let y_bits = [
            from_y[0].to_bitmask(),
            from_y[1].to_bitmask(),
            from_y[2].to_bitmask(),
        ];
        let uniform = |bits: u32| {
            let bits = bits & live_bits;
            bits == 0 || bits == live_bits
        };
        if live_bits != 0 && x_bits.iter().chain(&y_bits).all(|&m| uniform(m)) {
            let first = 1 << live_bits.trailing_zeros();
            let axis = |k: usize| {
                if x_bits[k] & first != 0 {
                    0
                } else if y_bits[k] & first != 0 {
                    1
                } else {
                    2
                }
            };
            Frame::Same([axis(0), axis(1), axis(2)])
        } else {
            Frame::Mixed { from_x, from_y }
        }
    }
    /// The lanes whose ray hits the triangle of `corners` (t0, t1, t2) in
    /// (0, limit), with α, β and γ's terms: [`WatertightRay::hit`]'s
    /// operations lane by lane, for a caller holding its own triangles (the
    /// mesh BVH's packets).
    ///
    /// [`WatertightRay::hit`]: crate::shapes::WatertightRay::hit
    #[inline(always)]
    pub(crate) fn hit(&self, corners: &[[f32; 3]; 3], limit: F) -> TriangleLanes<F> {
        match self.frame {
            Frame::Same(k) => hit_with(corners, self, SameAxes(k), limit),
            Frame::Mixed { from_x, from_y } => {
                hit_with(corners, self, MixedAxes { from_x, from_y }, limit)
            }
        }
    }
}

/// The lanes whose ray hits the triangle of `corners` in (0, limit),
/// with α (anything elsewhere) and what gives β and γ:
/// `WatertightRay::hit`'s operations lane by lane,
/// `permute` giving a corner in each lane's frame ([`SameAxes`] or
/// [`MixedAxes`], as `r.frame` says).
#[inline(always)]
pub(crate) fn hit_with<F: FloatLanes>(
    corners: &[[f32; 3]; 3],
    r: &ShearedRays<F>,
    permute: impl Permutation<F>,
    limit: F,
) -> TriangleLanes<F> {
    let (ax, ay, az) = shear(r, permute.permute(&corners[0]));
    let (bx, by, bz) = shear(r, permute.permute(&corners[1]));
    let (cx, cy, cz) = shear(r, permute.permute(&corners[2]));
    let mut eu = cx * by - cy * bx;
    let mut ev = ax * cy - ay * cx;
    let mut ew = bx * ay - by * ax;
    let zero = F::ZERO;
    let exact_zero = (eu.simd_eq(zero) | ev.simd_eq(zero) | ew.simd_eq(zero)) & r.live;
    if exact_zero.any() {
        // Rare (the ray through an edge or vertex): recomputed in f64.
        let f = |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
        let (ax, ay, bx, by) = (ax.to_array(), ay.to_array(), bx.to_array(), by.to_array());
        let (cx, cy) = (cx.to_array(), cy.to_array());
        let (mut u, mut v, mut w) = (eu.to_array(), ev.to_array(), ew.to_array());
        let lanes = exact_zero.to_bitmask();
        for i in (0..WIDTH).filter(|i| lanes & (1 << i) != 0) {
            u[i] = f(cx[i], by[i], cy[i], bx[i]);
            v[i] = f(ax[i], cy[i], ay[i], cx[i]);
            w[i] = f(bx[i], ay[i], by[i], ax[i]);
        }
        (eu, ev, ew) = (F::from_array(u), F::from_array(v), F::from_array(w));
    }
    let negative = eu.simd_lt(zero) | ev.simd_lt(zero) | ew.simd_lt(zero);
    let positive = eu.simd_gt(zero) | ev.simd_gt(zero) | ew.simd_gt(zero);
    let det = eu + ev + ew;
    let inside = !(negative & positive);
    if !inside.any() {
        // Every ray passes outside the triangle (most tests of a walk):
        // α, and its division, would be masked out on every lane.
        return TriangleLanes {
            hit: inside,
            alpha: zero,
            v: ev,
            w: ew,
            det,
        };
    }
    let t_scaled = eu * (r.sz * az) + ev * (r.sz * bz) + ew * (r.sz * cz);
    let alpha = t_scaled / det;
    // A zero det gives α = ±∞ or NaN, and a non-finite α is never in
    // (0, limit): the scalar code's `det == 0` and `is_finite` tests.
    let hit = inside & alpha.simd_gt(zero) & alpha.simd_lt(limit);
    TriangleLanes {
        hit,
        alpha,
        v: ev,
        w: ew,
        det,
    }
}
