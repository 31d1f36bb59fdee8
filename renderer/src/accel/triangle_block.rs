//! The triangles of a small mesh in blocks of eight, stored coordinate plane
//! by coordinate plane, tested without a tree: one ray against eight
//! triangles per AVX2 instruction ([`WatertightRay::hit_block`]), the
//! scalar watertight test's α, β, γ bit for bit.

use super::mesh_hit::MeshHit;
use crate::shapes::WatertightRay;
use glam::Vec3;

/// Triangles per block: one AVX2 register of f32.
pub const BLOCK: usize = 8;

/// Up to eight triangles. A block of fewer repeats its last triangle in the
/// spare lanes (same α, same index: harmless).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct TriangleBlock {
    /// `corners[c][k][i]`: coordinate k of corner t_c of triangle i.
    corners: [[[f32; BLOCK]; 3]; 3],
    /// The caller's index of each triangle.
    ids: [u32; BLOCK],
}

impl TriangleBlock {
    /// The blocks of `triangles` (corner positions by index into
    /// `positions`), in index order: triangle k is lane k % 8 of block k / 8.
    pub fn blocks(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<TriangleBlock> {
        (0..triangles.len())
            .step_by(BLOCK)
            .map(|first| {
                let last = triangles.len().min(first + BLOCK) - 1;
                let mut block = TriangleBlock {
                    corners: [[[0.0; BLOCK]; 3]; 3],
                    ids: [0; BLOCK],
                };
                for i in 0..BLOCK {
                    let k = (first + i).min(last);
                    block.ids[i] = k as u32;
                    for (c, &vertex) in triangles[k].iter().enumerate() {
                        let p = positions[vertex as usize];
                        for axis in 0..3 {
                            block.corners[c][axis][i] = p[axis];
                        }
                    }
                }
                block
            })
            .collect()
    }

    /// The nearest hit in (t_min, t_max) among the block's triangles (the
    /// lowest index on a tie), as [`WatertightRay::hit`] gives it.
    #[inline(always)]
    pub fn nearest(&self, ray: &WatertightRay, t_min: f32, t_max: f32) -> Option<MeshHit> {
        let hits = ray.hit_block(&self.corners, t_min, t_max);
        // α is never NaN (a lane without a hit holds +∞), so the plain
        // comparison is the minimum; the first lane holding it is the
        // lowest index.
        let mut lane = 0;
        for i in 1..BLOCK {
            if hits.alpha[i] < hits.alpha[lane] {
                lane = i;
            }
        }
        let alpha = hits.alpha[lane];
        (alpha != f32::INFINITY).then(|| MeshHit {
            triangle: self.ids[lane],
            alpha,
            beta: hits.v[lane] / hits.det[lane],
            gamma: hits.w[lane] / hits.det[lane],
        })
    }

    /// True when some triangle of the block is hit in (t_min, t_max).
    #[inline(always)]
    pub fn any(&self, ray: &WatertightRay, t_min: f32, t_max: f32) -> bool {
        let hits = ray.hit_block(&self.corners, t_min, t_max);
        hits.alpha.iter().any(|&a| a != f32::INFINITY)
    }
}

#[cfg(test)]
mod tests {
    use crate::accel::MeshBvh;
    use crate::geometry::ray::Ray;
    use glam::Vec3;

    /// A small mesh's closest hit on a tie is its lowest triangle index,
    /// whichever block or lane holds it: the same triangle twice (indices
    /// 2 and 9), and a quad's diagonal met exactly (indices 0 and 1).
    #[test]
    fn a_tie_goes_to_the_lowest_triangle_index() {
        let positions = vec![
            Vec3::new(-1.0, -1.0, -2.0),
            Vec3::new(1.0, -1.0, -2.0),
            Vec3::new(1.0, 1.0, -2.0),
            Vec3::new(-1.0, 1.0, -2.0),
            Vec3::new(-1.0, -1.0, -5.0),
            Vec3::new(1.0, -1.0, -5.0),
            Vec3::new(0.0, 1.0, -5.0),
        ];
        let far = [4, 5, 6];
        let mut triangles = vec![[0, 1, 2], [0, 2, 3], far];
        triangles.extend([[5, 6, 4]; 6]);
        triangles.push(far);
        assert_eq!(triangles.len(), 10);
        let bvh = MeshBvh::build(&positions, &triangles);
        // Through the quad's diagonal (x = y): both halves at α = 2.
        let diagonal = bvh
            .closest_hit(&Ray::new(Vec3::ZERO, Vec3::new(0.25, 0.25, -1.0)))
            .expect("hit");
        assert_eq!((diagonal.triangle, diagonal.alpha), (0, 2.0));
        // Past the quad: the far triangle, listed as 2, 3..8 (turned) and 9.
        let mut ray = Ray::new(Vec3::new(0.0, 0.0, -3.0), -Vec3::Z);
        ray.t_min = 0.0;
        let far_hit = bvh.closest_hit(&ray).expect("hit");
        assert_eq!((far_hit.triangle, far_hit.alpha), (2, 2.0));
    }
}
