//! The watertight test of one ray against N triangles at once, written lane
//! by lane over plain arrays: inside a function compiled for AVX2
//! ([`crate::accel`]'s `with_widest_simd`) the compiler turns each loop into
//! eight-lane instructions. Every lane performs [`WatertightRay::hit`]'s
//! operations in the same order (Rust never fuses a multiply and an add), so
//! α, β and γ are the scalar test's bit for bit.

use super::WatertightRay;

/// The hits of one ray with N triangles: α per lane (+∞ for no hit in the
/// interval), and the edge functions V, W and the determinant that give
/// β = V / det and γ = W / det.
#[derive(Clone, Copy, Debug)]
pub struct BlockHits<const N: usize> {
    /// α per lane, +∞ where the ray misses the triangle in its interval.
    pub alpha: [f32; N],
    /// V per lane.
    pub v: [f32; N],
    /// W per lane.
    pub w: [f32; N],
    /// det = U + V + W per lane.
    pub det: [f32; N],
}

impl WatertightRay {
    /// [`WatertightRay::hit`] for N triangles at once, stored plane by
    /// plane: `corners[c][k][i]` is coordinate k of corner t_c of triangle
    /// i. α is +∞ for a lane without a hit in (t_min, t_max).
    #[inline(always)]
    pub fn hit_block<const N: usize>(
        &self,
        corners: &[[[f32; N]; 3]; 3],
        t_min: f32,
        t_max: f32,
    ) -> BlockHits<N> {
        let (kx, ky, kz) = (self.kx, self.ky, self.kz);
        let o = self.origin.to_array();
        let (ox, oy, oz) = (o[kx], o[ky], o[kz]);
        let (sx, sy, sz) = (self.sx, self.sy, self.sz);
        // Corner c relative to P0, sheared: x, y and the unsheared z.
        let mut sheared = [[[0.0f32; N]; 3]; 3];
        for (p, s) in corners.iter().zip(&mut sheared) {
            for i in 0..N {
                let z = p[kz][i] - oz;
                s[0][i] = (p[kx][i] - ox) - sx * z;
                s[1][i] = (p[ky][i] - oy) - sy * z;
                s[2][i] = z;
            }
        }
        let [[ax, ay, az], [bx, by, bz], [cx, cy, cz]] = sheared;
        let (mut eu, mut ev, mut ew) = ([0.0f32; N], [0.0f32; N], [0.0f32; N]);
        let mut exact_zero = [false; N];
        for i in 0..N {
            eu[i] = cx[i] * by[i] - cy[i] * bx[i];
            ev[i] = ax[i] * cy[i] - ay[i] * cx[i];
            ew[i] = bx[i] * ay[i] - by[i] * ax[i];
            exact_zero[i] = (eu[i] == 0.0) | (ev[i] == 0.0) | (ew[i] == 0.0);
        }
        if exact_zero.iter().any(|&z| z) {
            // Rare (the ray through an edge or vertex): exactly as `edges`.
            let f =
                |p: f32, q: f32, r: f32, s: f32| (p as f64 * q as f64 - r as f64 * s as f64) as f32;
            for i in (0..N).filter(|&i| exact_zero[i]) {
                eu[i] = f(cx[i], by[i], cy[i], bx[i]);
                ev[i] = f(ax[i], cy[i], ay[i], cx[i]);
                ew[i] = f(bx[i], ay[i], by[i], ax[i]);
            }
        }
        let mut hits = BlockHits {
            alpha: [f32::INFINITY; N],
            v: ev,
            w: ew,
            det: [0.0; N],
        };
        for i in 0..N {
            let (u, v, w) = (eu[i], ev[i], ew[i]);
            // `edges`'s tests without its branches (the same truth values).
            let negative = (u < 0.0) | (v < 0.0) | (w < 0.0);
            let positive = (u > 0.0) | (v > 0.0) | (w > 0.0);
            let det = u + v + w;
            let t_scaled = u * (sz * az[i]) + v * (sz * bz[i]) + w * (sz * cz[i]);
            let alpha = t_scaled / det;
            let hit = !(negative & positive)
                & (det != 0.0)
                & (alpha.abs() < f32::INFINITY)
                & (alpha > t_min)
                & (alpha < t_max);
            hits.alpha[i] = if hit { alpha } else { f32::INFINITY };
            hits.det[i] = det;
        }
        hits
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::ray::Ray;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::WatertightRay;
    use glam::Vec3;

    /// Random triangles (some sharing edges and vertices with the ray
    /// aimed at them, so the exact-zero fallback runs) against random rays:
    /// every lane equals the scalar watertight test bit for bit.
    #[test]
    fn every_lane_matches_the_scalar_watertight_test_bit_for_bit() {
        const N: usize = 8;
        let mut rng = Sampler::for_sample(11, 0, 0, 0);
        let point = |rng: &mut Sampler| rng.next_direction() * 3.0 * rng.next_f32();
        let (mut hits, mut edge_cases) = (0, 0);
        for k in 0..5000 {
            let shared = point(&mut rng);
            let triangles: Vec<[Vec3; 3]> = (0..N)
                .map(|_| [shared, point(&mut rng), point(&mut rng)])
                .collect();
            let origin = point(&mut rng) * 2.0;
            // Through the shared vertex now and then (exact zeros).
            let target = if k % 4 == 0 { shared } else { point(&mut rng) };
            let mut ray = Ray::new(origin, target - origin);
            if k % 3 == 0 {
                ray.t_max = 2.0 * rng.next_f32();
            }
            let w = WatertightRay::new(&ray);
            let mut corners = [[[0.0f32; N]; 3]; 3];
            for (i, t) in triangles.iter().enumerate() {
                for c in 0..3 {
                    for axis in 0..3 {
                        corners[c][axis][i] = t[c][axis];
                    }
                }
            }
            let block = w.hit_block(&corners, ray.t_min, ray.t_max);
            for (i, t) in triangles.iter().enumerate() {
                let want = w.hit(&ray, t[0], t[1], t[2]);
                let got = (block.alpha[i] != f32::INFINITY).then(|| {
                    let (v, w, det) = (block.v[i], block.w[i], block.det[i]);
                    (block.alpha[i], v / det, w / det)
                });
                assert_eq!(
                    got.map(|(a, b, c)| [a, b, c].map(f32::to_bits)),
                    want.map(|h| [h.alpha, h.beta, h.gamma].map(f32::to_bits)),
                    "case {k}, lane {i}: {ray:?} {t:?}"
                );
                hits += usize::from(want.is_some());
                edge_cases += usize::from(k % 4 == 0 && want.is_some());
            }
        }
        assert!(
            hits > 2000 && edge_cases > 100,
            "{hits} hits, {edge_cases} through a vertex"
        );
    }
}
