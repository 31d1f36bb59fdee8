//! The comparison builder: obvhs's PLOC (a binary tree, built bottom up in
//! parallel) collapsed to our 8-wide nodes. [`MeshBvh::build_with`] selects
//! it by [`BuildQuality`]; the `bvh` benchmark compares it with our binned
//! SAH, which builds faster and gives faster trees, so nothing renders with it.
//!
//! The collapse: each wide node takes a binary node's two children and, while
//! it has fewer than eight, opens the child with the largest surface area
//! (the one rays enter most often) into its own two; a subtree of at most
//! [`LEAF_TRIANGLES`] triangles becomes a leaf. Child boxes are the binary
//! nodes' boxes, which obvhs computes as exact unions of the triangles'
//! boxes. The nodes are laid out first (one pass, no triangle touched), then
//! the leaves' triangles are copied into packs in parallel.
//!
//! [`MeshBvh::build_with`]: super::MeshBvh::build_with
//! [`BuildQuality`]: super::mesh::BuildQuality
use super::scene::Aabb;
use super::triangle_pack::{PACK, TrianglePack};
use super::wide::{ChildRef, LEAF_TRIANGLES, WIDTH, WideNode};
use glam::{Vec3, Vec3A};
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::ploc::PlocBuilder;
use rayon::prelude::*;

/// The tree of obvhs's PLOC builder with `params`, collapsed to our nodes:
/// (nodes, packs, the box around every triangle).
pub(super) fn build_ploc(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    params: BvhBuildParams,
) -> (Vec<WideNode>, Vec<TrianglePack>, Aabb) {
    let corners = |t: &[u32; 3]| t.map(|i| positions[i as usize]);
    let boxes: Vec<obvhs::aabb::Aabb> = triangles
        .par_iter()
        .map(|t| {
            let [a, b, c] = corners(t);
            obvhs::aabb::Aabb::new(Vec3A::from(a.min(b).min(c)), Vec3A::from(a.max(b).max(c)))
        })
        .collect();
    let bounds = boxes
        .par_iter()
        .map(|b| Aabb {
            min: b.min.into(),
            max: b.max.into(),
        })
        .reduce(|| Aabb::EMPTY, Aabb::union);
    if triangles.is_empty() {
        return (Vec::new(), Vec::new(), bounds);
    }
    let mut bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
        params.ploc_search_distance,
        &boxes,
        (0..triangles.len() as u32).collect(),
        params.sort_precision,
        params.search_depth_threshold,
    );
    drop(boxes);
    ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
    let (nodes, packs) = collapse(&bvh2, |i| corners(&triangles[i as usize]));
    (nodes, packs, bounds)
}

/// The wide nodes (node 0 the root) and leaf packs of `bvh2`, whose
/// primitives are triangles with corners `corners(primitive)`. An empty
/// BVH gives no nodes. Leaves of obvhs's tree must hold at most
/// `ChildRef::MAX_PACKS` packs' worth of triangles (PLOC puts one in each).
pub fn collapse(
    bvh2: &Bvh2,
    corners: impl Fn(u32) -> [Vec3; 3] + Sync,
) -> (Vec<WideNode>, Vec<TrianglePack>) {
    if bvh2.nodes.is_empty() || bvh2.primitive_indices.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let mut nodes = vec![WideNode::EMPTY];
    // The binary node of each leaf, in pack order.
    let mut leaves: Vec<u32> = Vec::with_capacity(bvh2.primitive_indices.len() / 2);
    let mut pack_count = 0usize;
    // The leaf of binary node `c`, which has `triangles` triangles.
    let mut leaf = |c: usize, triangles: usize| {
        let packs = triangles.div_ceil(PACK);
        leaves.push(c as u32);
        let child = ChildRef::leaf(pack_count, packs);
        pack_count += packs;
        child
    };
    let set = |node: &mut WideNode, slot: usize, child: ChildRef, c: usize| {
        let b = bvh2.nodes[c].aabb();
        node.set_child(slot, child, b.min.into(), b.max.into());
    };
    if let Some(triangles) = leaf_triangles(bvh2, 0) {
        // A small mesh: one wide node with the whole tree as its one leaf.
        let child = leaf(0, triangles);
        set(&mut nodes[0], 0, child, 0);
    } else {
        // (binary node whose children fill the wide node, wide node index)
        let mut todo = vec![(0usize, 0usize)];
        while let Some((binary, wide)) = todo.pop() {
            let (slots, len) = open(bvh2, binary);
            let mut slot = 0;
            // Leaves first, then inner nodes, so the inner ones are adjacent.
            for &(c, triangles) in &slots[..len] {
                if let Some(triangles) = triangles {
                    let child = leaf(c, triangles);
                    set(&mut nodes[wide], slot, child, c);
                    slot += 1;
                }
            }
            for &(c, _) in slots[..len].iter().filter(|(_, t)| t.is_none()) {
                let index = nodes.len();
                nodes.push(WideNode::EMPTY);
                todo.push((c, index));
                set(&mut nodes[wide], slot, ChildRef::node(index as u32), c);
                slot += 1;
            }
        }
    }
    let packs: Vec<TrianglePack> = leaves
        .par_iter()
        .flat_map_iter(|&c| leaf_packs(bvh2, c as usize, &corners))
        .collect();
    debug_assert_eq!(packs.len(), pack_count);
    (nodes, packs)
}

/// The number of triangles under binary node `n` when it is a leaf of
/// obvhs's tree or has at most `limit` triangles below it, else `None`
/// (found without walking more than a few nodes).
fn small_subtree(bvh2: &Bvh2, n: usize, limit: usize) -> Option<usize> {
    let node = &bvh2.nodes[n];
    if node.is_leaf() {
        return Some(node.prim_count as usize);
    }
    let mut stack = [0usize; 2 * LEAF_TRIANGLES];
    stack[0] = n;
    let mut len = 1;
    let mut total = 0usize;
    while len > 0 {
        len -= 1;
        let node = &bvh2.nodes[stack[len]];
        if node.is_leaf() {
            total += node.prim_count as usize;
        } else if len + 2 <= stack.len() {
            let first = node.first_index as usize;
            stack[len] = first;
            stack[len + 1] = first + 1;
            len += 2;
        } else {
            return None;
        }
        if total > limit {
            return None;
        }
    }
    Some(total)
}

/// The triangle count of binary node `n` when it becomes a leaf of the
/// wide BVH, `None` when it becomes an inner node.
fn leaf_triangles(bvh2: &Bvh2, n: usize) -> Option<usize> {
    small_subtree(bvh2, n, LEAF_TRIANGLES)
}

/// The up to eight binary nodes that become the children of the wide node
/// made from binary node `n`: its two children, then repeatedly the
/// largest-area inner one replaced by its own two; each with its
/// [`leaf_triangles`].
fn open(bvh2: &Bvh2, n: usize) -> ([(usize, Option<usize>); WIDTH], usize) {
    let child = |c: usize| (c, leaf_triangles(bvh2, c));
    let first = bvh2.nodes[n].first_index as usize;
    let mut slots = [(0usize, None); WIDTH];
    (slots[0], slots[1]) = (child(first), child(first + 1));
    let mut len = 2;
    while len < WIDTH {
        let mut widest: Option<(usize, f32)> = None;
        for (i, &(c, _)) in slots[..len]
            .iter()
            .enumerate()
            .filter(|(_, s)| s.1.is_none())
        {
            let area = bvh2.nodes[c].aabb().half_area();
            if widest.is_none_or(|(_, a)| area > a) {
                widest = Some((i, area));
            }
        }
        let Some((i, _)) = widest else { break };
        let c = bvh2.nodes[slots[i].0].first_index as usize;
        (slots[i], slots[len]) = (child(c), child(c + 1));
        len += 1;
    }
    (slots, len)
}

/// The packs of the leaf made from binary node `n`: its triangles, four
/// to a pack (no allocation: a leaf has at most 32 triangles).
fn leaf_packs(
    bvh2: &Bvh2,
    n: usize,
    corners: &impl Fn(u32) -> [Vec3; 3],
) -> impl Iterator<Item = TrianglePack> {
    const MAX: usize = ChildRef::MAX_PACKS * PACK;
    let mut prims = [0u32; MAX];
    let mut len = 0;
    let mut stack = [0usize; 2 * MAX];
    stack[0] = n;
    let mut depth = 1;
    while depth > 0 {
        depth -= 1;
        let node = &bvh2.nodes[stack[depth]];
        if node.is_leaf() {
            let first = node.first_index as usize;
            for &p in &bvh2.primitive_indices[first..first + node.prim_count as usize] {
                prims[len] = p;
                len += 1;
            }
        } else {
            let first = node.first_index as usize;
            stack[depth] = first + 1;
            stack[depth + 1] = first;
            depth += 2;
        }
    }
    (0..len.div_ceil(PACK)).map(move |k| {
        let chunk = &prims[k * PACK..len.min(k * PACK + PACK)];
        let mut triangles = [(0u32, [Vec3::ZERO; 3]); PACK];
        for (t, &p) in triangles.iter_mut().zip(chunk) {
            *t = (p, corners(p));
        }
        TrianglePack::new(&triangles[..chunk.len()])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tests::meshes::grid;
    use glam::Vec3A;
    use obvhs::ploc::PlocBuilder;

    fn binary(p: &[Vec3], t: &[[u32; 3]]) -> Bvh2 {
        let boxes: Vec<obvhs::aabb::Aabb> = t
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vec3A::from(p[i as usize]));
                obvhs::aabb::Aabb::new(a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        let params = obvhs::BvhBuildParams::fast_build();
        PlocBuilder::with_capacity(boxes.len()).build(
            params.ploc_search_distance,
            &boxes,
            (0..t.len() as u32).collect(),
            params.sort_precision,
            params.search_depth_threshold,
        )
    }

    /// Every triangle of every leaf reachable from the root, and checks
    /// that each child's box holds everything under it.
    fn leaf_triangles(nodes: &[WideNode], packs: &[TrianglePack]) -> Vec<u32> {
        let mut out = Vec::new();
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            for child in nodes[n].children {
                if child == ChildRef::EMPTY {
                    continue;
                }
                match child.packs() {
                    Some(range) => {
                        for pack in &packs[range] {
                            let mut ids: Vec<u32> = (0..PACK).map(|l| pack.id(l)).collect();
                            ids.dedup();
                            out.extend(ids);
                        }
                    }
                    None => stack.push(child.0 as usize),
                }
            }
        }
        out
    }

    #[test]
    fn every_triangle_is_in_exactly_one_leaf() {
        for (w, h) in [(1, 1), (2, 1), (7, 5), (40, 30)] {
            let (p, t) = grid(w, h, 0.0);
            let bvh2 = binary(&p, &t);
            let (nodes, packs) = collapse(&bvh2, |i| t[i as usize].map(|v| p[v as usize]));
            let mut ids = leaf_triangles(&nodes, &packs);
            ids.sort_unstable();
            assert_eq!(ids, (0..t.len() as u32).collect::<Vec<_>>(), "{w}×{h}");
        }
    }

    #[test]
    fn empty_bvh_collapses_to_nothing() {
        let (nodes, packs) = collapse(&Bvh2::default(), |_| [Vec3::ZERO; 3]);
        assert!(nodes.is_empty() && packs.is_empty());
    }
}
