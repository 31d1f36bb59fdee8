//! Leaf triangles in packs of four, stored coordinate plane by coordinate
//! plane, so that one ray is tested against four triangles at once with the
//! watertight test ([`WatertightRay::hit_lanes`]).

use crate::shapes::WatertightRay;
use glam::Vec3;
use wide::f32x4;

/// Triangles per pack.
pub const PACK: usize = 4;

/// Up to four triangles of a leaf. A pack of fewer repeats its last
/// triangle in the spare lanes (same α, same index: harmless).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct TrianglePack {
    /// `corners[c][k]`: coordinate k of corner t_c of the four triangles.
    corners: [[f32x4; 3]; 3],
    /// The caller's index of each triangle.
    ids: [u32; PACK],
}

impl TrianglePack {
    /// The pack of `triangles` (1 to 4 of them): (caller's index, t0, t1, t2).
    /// The lanes hold them by increasing index, so that the lowest lane of
    /// a tie is the lowest index.
    pub fn new(triangles: &[(u32, [Vec3; 3])]) -> TrianglePack {
        assert!((1..=PACK).contains(&triangles.len()));
        let mut sorted = [triangles[0]; PACK];
        sorted[..triangles.len()].copy_from_slice(triangles);
        let sorted = &mut sorted[..triangles.len()];
        sorted.sort_unstable_by_key(|&(id, _)| id);
        let triangles = &*sorted;
        // Plain loops: with `array::from_fn` nested three deep, the pack
        // pass of a million-triangle build took 48 ms instead of 39.
        let mut planes = [[[0.0f32; PACK]; 3]; 3];
        let mut ids = [0u32; PACK];
        for i in 0..PACK {
            let (id, corners) = triangles[i.min(triangles.len() - 1)];
            ids[i] = id;
            for (c, corner) in corners.iter().enumerate() {
                for k in 0..3 {
                    planes[c][k][i] = corner[k];
                }
            }
        }
        TrianglePack {
            corners: planes.map(|corner| corner.map(f32x4::new)),
            ids,
        }
    }

    /// The caller's index of the triangle in `lane`.
    #[inline(always)]
    pub fn id(&self, lane: usize) -> u32 {
        self.ids[lane]
    }

    /// t0, t1, t2 of the triangle in `lane` (for tests: traversal reads the
    /// planes directly).
    #[cfg(test)]
    pub fn corners(&self, lane: usize) -> [Vec3; 3] {
        self.corner_arrays(lane).map(Vec3::from_array)
    }

    /// t0, t1, t2 of the triangle in `lane`, coordinate by coordinate (what
    /// a packet of rays tests one triangle at a time).
    #[inline(always)]
    pub fn corner_arrays(&self, lane: usize) -> [[f32; 3]; 3] {
        let at = |c: usize, k: usize| self.corners[c][k].as_array()[lane];
        [
            [at(0, 0), at(0, 1), at(0, 2)],
            [at(1, 0), at(1, 1), at(1, 2)],
            [at(2, 0), at(2, 1), at(2, 2)],
        ]
    }

    /// How many triangles it holds (the lanes past them repeat the last).
    #[inline(always)]
    pub fn triangle_count(&self) -> usize {
        (1..PACK)
            .find(|&i| self.ids[i] == self.ids[i - 1])
            .unwrap_or(PACK)
    }

    /// The nearest hit in (t_min, t_max) among the pack's triangles (the
    /// lowest lane, which is the lowest index, on a tie), with α, β, γ
    /// exactly [`WatertightRay::hit`]'s.
    #[inline(always)]
    pub fn nearest(&self, ray: &WatertightRay, t_min: f32, t_max: f32) -> Option<PackHit> {
        let hits = ray.hit_lanes(&self.corners, t_min, t_max);
        let [a, b, c, d] = hits.alpha.to_array();
        // α is never NaN (a lane without a hit holds +∞), so the plain
        // comparison is the minimum.
        let min = |x: f32, y: f32| if x < y { x } else { y };
        let alpha = min(min(a, b), min(c, d));
        if alpha == f32::INFINITY {
            return None;
        }
        // The lowest lane holding the smallest α.
        let lane = hits.alpha.simd_eq(alpha).to_bitmask().trailing_zeros() as usize;
        Some(PackHit {
            lane,
            alpha,
            v: hits.v.as_array()[lane],
            w: hits.w.as_array()[lane],
            det: hits.det.as_array()[lane],
        })
    }
}

/// A hit in a pack: which lane, α, and what gives β and γ (divided only
/// for the closest hit of all).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PackHit {
    /// The lane of the triangle hit.
    pub lane: usize,
    /// α of the hit.
    pub alpha: f32,
    /// The edge function V (β = V / det).
    v: f32,
    /// The edge function W (γ = W / det).
    w: f32,
    /// The determinant U + V + W.
    det: f32,
}

impl PackHit {
    /// β and γ of the hit.
    #[inline(always)]
    pub fn barycentrics(&self) -> (f32, f32) {
        (self.v / self.det, self.w / self.det)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ray::Ray;

    fn unit_triangle_at(z: f32) -> [Vec3; 3] {
        [
            Vec3::new(-1.0, -1.0, z),
            Vec3::new(1.0, -1.0, z),
            Vec3::new(0.0, 1.0, z),
        ]
    }

    #[test]
    fn nearest_picks_the_closest_triangle_and_reports_its_index() {
        let pack = TrianglePack::new(&[
            (10, unit_triangle_at(-5.0)),
            (11, unit_triangle_at(-2.0)),
            (12, unit_triangle_at(-3.0)),
        ]);
        let ray = Ray::new(Vec3::ZERO, -Vec3::Z);
        let w = WatertightRay::new(&ray);
        let hit = pack.nearest(&w, 0.0, f32::INFINITY).expect("hit");
        assert_eq!((pack.id(hit.lane), hit.alpha), (11, 2.0));
        assert_eq!(pack.corners(hit.lane), unit_triangle_at(-2.0));
        // The ray meets the plane at (0, 0): β = 0.25, γ = 0.5.
        assert_eq!(hit.barycentrics(), (0.25, 0.5));
        // Beyond t_max or before t_min: no hit.
        assert_eq!(pack.nearest(&w, 0.0, 2.0), None);
        assert_eq!(pack.nearest(&w, 5.0, f32::INFINITY), None);
        assert_eq!(
            pack.nearest(&w, 2.5, 4.0).map(|h| pack.id(h.lane)),
            Some(12)
        );
    }

    #[test]
    fn spare_lanes_repeat_the_last_triangle() {
        let pack = TrianglePack::new(&[(7, unit_triangle_at(-1.0))]);
        for lane in 0..PACK {
            assert_eq!(pack.id(lane), 7);
        }
    }
}
