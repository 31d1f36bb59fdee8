//! The bottom level: a BVH over one triangle mesh, built with obvhs (PLOC,
//! reinsertion, then collapsed to its compressed 8-wide CWBVH) and traversed
//! by our conservative code ([`super::wide`]). Triangles are copied in leaf
//! order so a leaf's triangles are adjacent in memory, and tested with the
//! same watertight arithmetic as [`crate::shapes::Triangle`]
//! ([`WatertightRay`]), so closest hits equal brute force exactly.

use super::scene::Aabb;
use super::stack::Stack;
use super::wide::{WideNode, WideRay};
use crate::ray::Ray;
use crate::shapes::WatertightRay;
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::cwbvh::bvh2_to_cwbvh::bvh2_to_cwbvh;
use obvhs::ploc::PlocBuilder;

/// The closest hit of a ray with a mesh: P0 + α v = (1 − β − γ) t0 + β t1 + γ t2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshHit {
    /// Index of the triangle in the caller's `triangles`.
    pub triangle: u32,
    /// α, the ray parameter of the hit (the ray's direction is not normalised
    /// by the BVH, so this is the caller's α).
    pub alpha: f32,
    /// β, the weight of t1.
    pub beta: f32,
    /// γ, the weight of t2.
    pub gamma: f32,
}

/// How much effort the builder spends on tree quality (obvhs's presets,
/// always without spatial splits so each triangle is in exactly one leaf).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BuildQuality {
    /// obvhs `fastest_build`: PLOC with the smallest search, no reinsertion.
    Fastest,
    /// obvhs `very_fast_build`.
    VeryFast,
    /// obvhs `fast_build`.
    #[default]
    Fast,
    /// obvhs `medium_build`.
    Medium,
}

impl BuildQuality {
    /// obvhs's parameters for this quality.
    fn params(self) -> BvhBuildParams {
        let mut p = match self {
            BuildQuality::Fastest => BvhBuildParams::fastest_build(),
            BuildQuality::VeryFast => BvhBuildParams::very_fast_build(),
            BuildQuality::Fast => BvhBuildParams::fast_build(),
            BuildQuality::Medium => BvhBuildParams::medium_build(),
        };
        p.pre_split = false;
        p.max_prims_per_leaf = 3;
        p
    }
}

/// One triangle in leaf order: t0, t1, t2.
#[derive(Clone, Copy, Debug)]
struct LeafTriangle {
    /// t0, t1, t2.
    v: [Vec3; 3],
}

/// A BVH over one triangle mesh.
#[derive(Clone, Debug)]
pub struct MeshBvh {
    /// The nodes (obvhs's CWBVH with exact boxes); node 0 is the root
    /// (none for an empty mesh).
    nodes: Vec<WideNode>,
    /// Triangles in the order of the nodes' primitive indices.
    triangles: Vec<LeafTriangle>,
    /// For each of `triangles`, its index in the caller's list.
    indices: Vec<u32>,
    /// The box around every triangle.
    bounds: Aabb,
}

impl MeshBvh {
    /// Builds the BVH of the triangles `triangles` (indices into
    /// `positions`) with the default [`BuildQuality`], in parallel on the
    /// current rayon pool. Positions must be finite; indices in range.
    pub fn build(positions: &[Vec3], triangles: &[[u32; 3]]) -> MeshBvh {
        Self::build_with(positions, triangles, BuildQuality::default())
    }

    /// [`MeshBvh::build`] with a chosen build effort.
    pub fn build_with(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        quality: BuildQuality,
    ) -> MeshBvh {
        let corners = |t: &[u32; 3]| t.map(|i| positions[i as usize]);
        let boxes: Vec<obvhs::aabb::Aabb> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = corners(t);
                obvhs::aabb::Aabb::new(Vec3A::from(a.min(b).min(c)), Vec3A::from(a.max(b).max(c)))
            })
            .collect();
        let bounds = boxes.iter().fold(Aabb::EMPTY, |acc, b| {
            acc.union(Aabb {
                min: b.min.into(),
                max: b.max.into(),
            })
        });
        if triangles.is_empty() {
            return MeshBvh {
                nodes: Vec::new(),
                triangles: Vec::new(),
                indices: Vec::new(),
                bounds,
            };
        }
        let params = quality.params();
        let mut bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
            params.ploc_search_distance,
            &boxes,
            (0..triangles.len() as u32).collect(),
            params.sort_precision,
            params.search_depth_threshold,
        );
        drop(boxes);
        ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
        let cw = bvh2_to_cwbvh(&bvh2, params.max_prims_per_leaf, true, true);
        drop(bvh2);
        let nodes = WideNode::from_cwbvh(&cw, |slot| {
            let [a, b, c] = corners(&triangles[cw.primitive_indices[slot] as usize]);
            (a.min(b).min(c).to_array(), a.max(b).max(c).to_array())
        });
        let triangles = cw
            .primitive_indices
            .iter()
            .map(|&i| LeafTriangle {
                v: corners(&triangles[i as usize]),
            })
            .collect();
        MeshBvh {
            nodes,
            triangles,
            indices: cw.primitive_indices,
            bounds,
        }
    }

    /// The box around every triangle (empty for an empty mesh).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True for a mesh without triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Bytes held by the structure: nodes plus the leaf-order triangle copies.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.nodes.capacity() * std::mem::size_of::<WideNode>()
            + self.triangles.capacity() * std::mem::size_of::<LeafTriangle>()
            + self.indices.capacity() * std::mem::size_of::<u32>()
    }

    /// The hit with the smallest α in (t_min, t_max), with the same α as
    /// testing every triangle with the watertight test (ties: any triangle at
    /// that α).
    pub fn closest_hit(&self, ray: &Ray) -> Option<MeshHit> {
        let tri = WatertightRay::new(ray);
        let mut wide = WideRay::new(ray);
        let mut best = None;
        self.traverse(&mut wide, |slot, wide| {
            let t = &self.triangles[slot];
            let s = &mut wide.slab;
            if let Some(alpha) = tri.alpha(t.v[0], t.v[1], t.v[2], s.t_min, s.t_max) {
                s.set_t_max(alpha);
                best = Some(slot);
            }
            false
        });
        let best = best?;
        let t = &self.triangles[best];
        // The same arithmetic again, now with β and γ; α is unchanged.
        let hit = tri.hit(ray, t.v[0], t.v[1], t.v[2])?;
        Some(MeshHit {
            triangle: self.indices[best],
            alpha: hit.alpha,
            beta: hit.beta,
            gamma: hit.gamma,
        })
    }

    /// True when any triangle is hit in (t_min, t_max) (for shadow rays:
    /// stops at the first hit found).
    pub fn any_hit(&self, ray: &Ray) -> bool {
        let tri = WatertightRay::new(ray);
        let mut wide = WideRay::new(ray);
        let mut hit = false;
        self.traverse(&mut wide, |slot, wide| {
            let t = &self.triangles[slot];
            hit = tri
                .alpha(t.v[0], t.v[1], t.v[2], wide.slab.t_min, wide.slab.t_max)
                .is_some();
            hit
        });
        hit
    }

    /// Visits, nearest children first, every leaf triangle whose boxes the
    /// ray may hit, calling `leaf(slot, ray)` (which may lower `ray.t_max`);
    /// stops early when `leaf` returns true.
    #[inline(always)]
    fn traverse(&self, ray: &mut WideRay, mut leaf: impl FnMut(usize, &mut WideRay) -> bool) {
        const NODE_BITS: u32 = 0xff00_0000;
        let Some(root) = self.nodes.first() else {
            return;
        };
        let hits = ray.intersect(root);
        // (first child node, bits 24..32: children to visit, 0..8: imask)
        let mut nodes = (root.child_base, (hits & NODE_BITS) | root.imask as u32);
        // (first triangle slot, bits: triangles to test)
        let mut tris = (root.prim_base, hits & !NODE_BITS);
        let mut stack = Stack::<(u32, u32), 32>::new();
        loop {
            while tris.1 != 0 {
                let k = tris.1.trailing_zeros();
                tris.1 &= tris.1 - 1;
                if leaf((tris.0 + k) as usize, ray) {
                    return;
                }
            }
            if nodes.1 & NODE_BITS != 0 {
                let bit = 31 - nodes.1.leading_zeros();
                nodes.1 &= !(1 << bit);
                let group = nodes;
                if group.1 & NODE_BITS != 0 {
                    stack.push(group);
                }
                let slot = (bit - 24) ^ ray.oct;
                let before = (group.1 & 0xff & ((1 << slot) - 1)).count_ones();
                let node = &self.nodes[(group.0 + before) as usize];
                let hits = ray.intersect(node);
                nodes = (node.child_base, (hits & NODE_BITS) | node.imask as u32);
                tris = (node.prim_base, hits & !NODE_BITS);
            } else if let Some(group) = stack.pop() {
                nodes = group;
            } else {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::reference;
    use crate::accel::test_meshes::grid;

    #[test]
    fn empty_mesh_has_no_hits_and_empty_bounds() {
        let bvh = MeshBvh::build(&[], &[]);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(bvh.closest_hit(&ray), None);
        assert!(!bvh.any_hit(&ray));
        assert!(bvh.bounds().is_empty());
    }

    #[test]
    fn single_triangle_hit_reports_caller_index_and_barycentrics() {
        let p = [
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let bvh = MeshBvh::build(&p, &[[0, 1, 2]]);
        let h = bvh
            .closest_hit(&Ray::new(Vec3::new(0.0, 0.5, 2.0), -Vec3::Z))
            .expect("hit");
        assert_eq!(h.triangle, 0);
        assert!((h.alpha - 2.0).abs() < 1e-6);
        assert!(
            (h.beta - 0.25).abs() < 1e-6 && (h.gamma - 0.5).abs() < 1e-6,
            "{h:?}"
        );
    }

    #[test]
    fn closest_hit_and_bounds_match_brute_force_on_a_small_grid() {
        let (p, t) = grid(8, 8, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        assert_eq!(bvh.len(), t.len());
        assert_eq!(bvh.bounds().min, Vec3::new(0.0, 0.0, 0.0));
        assert_eq!(bvh.bounds().max, Vec3::new(8.0, 8.0, 0.0));
        let ray = Ray::new(Vec3::new(3.3, 2.7, 5.0), Vec3::new(0.01, 0.02, -1.0));
        let want = reference::closest_hit(&p, &t, &ray).expect("brute-force hit");
        let got = bvh.closest_hit(&ray).expect("bvh hit");
        assert_eq!(got, want);
    }

    #[test]
    fn bytes_counts_nodes_and_triangle_copies() {
        let (p, t) = grid(20, 20, 0.0);
        let bvh = MeshBvh::build(&p, &t);
        assert!(bvh.bytes() >= t.len() * std::mem::size_of::<LeafTriangle>());
        assert!(bvh.bytes() < t.len() * 200, "{}", bvh.bytes());
    }
}
