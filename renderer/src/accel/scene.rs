//! The top level: a binary BVH (obvhs's PLOC builder, fastest settings, so it
//! can be rebuilt on every edit) over items known only by their bounding
//! boxes — mesh instances and analytic shapes. The caller intersects each item
//! the traversal reaches; boxes are tested with the conservative slab test of
//! [`super::slab`], nearest child first, and children whose entry lies beyond
//! the closest hit so far are skipped.

use super::slab::SlabRay;
use super::stack::Stack;
use crate::geometry::ray::Ray;
pub use ::scene::layout::Aabb;
use glam::Vec3A;
use obvhs::bvh2::node::Bvh2Node;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};

/// A BVH over boxed items (infinite items stay outside it, with the caller).
#[derive(Clone, Debug)]
pub struct SceneBvh {
    /// obvhs's BVH2 nodes; node 0 is the root (none when there are no items).
    nodes: Vec<Bvh2Node>,
    /// Item ids in leaf order: leaves index this list.
    items: Vec<u32>,
    /// The box around every item.
    bounds: Aabb,
}

impl SceneBvh {
    /// Builds the BVH over `bounds`; item i is `bounds[i]`, which must hold
    /// every hit point the caller's test can report for it (pad analytic
    /// shapes' boxes for the rounding of their tests). Items with an
    /// empty box (min > max on some axis) can never be hit and are left out.
    /// Boxes must be finite.
    pub fn build(bounds: &[Aabb]) -> SceneBvh {
        let ids: Vec<u32> = (0..bounds.len() as u32)
            .filter(|&i| {
                let b = bounds[i as usize];
                b.min.cmple(b.max).all()
            })
            .collect();
        let boxes: Vec<obvhs::aabb::Aabb> = ids
            .iter()
            .map(|&i| {
                let b = bounds[i as usize];
                debug_assert!(b.min.is_finite() && b.max.is_finite(), "item {i}: {b:?}");
                obvhs::aabb::Aabb::new(Vec3A::from(b.min), Vec3A::from(b.max))
            })
            .collect();
        let all = ids
            .iter()
            .fold(Aabb::EMPTY, |acc, &i| acc.union(bounds[i as usize]));
        if boxes.is_empty() {
            return SceneBvh {
                nodes: Vec::new(),
                items: Vec::new(),
                bounds: all,
            };
        }
        let bvh2 = PlocBuilder::with_capacity(boxes.len()).build(
            PlocSearchDistance::Minimum,
            &boxes,
            (0..boxes.len() as u32).collect(),
            SortPrecision::U64,
            0,
        );
        SceneBvh {
            items: bvh2
                .primitive_indices
                .iter()
                .map(|&k| ids[k as usize])
                .collect(),
            nodes: bvh2.nodes,
            bounds: all,
        }
    }

    /// The box around every item in the BVH (empty when there is none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of items in the BVH.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True when no item is in the BVH.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Bytes held by the structure.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.nodes.capacity() * std::mem::size_of::<Bvh2Node>()
            + self.items.capacity() * std::mem::size_of::<u32>()
    }

    /// The closest item hit: `test(item, ray)` returns the α of the item's
    /// closest hit inside `ray`'s interval, whose t_max is lowered to the
    /// closest α found so far. Returns (item, α).
    pub fn closest(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let mut current = *ray;
        let mut best = None;
        self.traverse(ray, |item, slab| {
            if let Some(alpha) = test(item, &current)
                && alpha > current.t_min
                && alpha < current.t_max
            {
                current.t_max = alpha;
                slab.set_t_max(alpha);
                best = Some((item, alpha));
            }
            false
        });
        best
    }

    /// True when `test(item, ray)` is true for some item the ray may reach;
    /// stops at the first.
    pub fn any(&self, ray: &Ray, mut test: impl FnMut(u32, &Ray) -> bool) -> bool {
        let mut hit = false;
        self.traverse(ray, |item, _| {
            hit = test(item, ray);
            hit
        });
        hit
    }

    /// Calls `leaf(item, slab)` for every item whose box the ray may hit,
    /// nearest box first; `leaf` may lower the slab's t_max, and stops the
    /// traversal by returning true.
    #[inline(always)]
    fn traverse(&self, ray: &Ray, mut leaf: impl FnMut(u32, &mut SlabRay) -> bool) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let mut slab = SlabRay::new(ray);
        let enter = |slab: &SlabRay, n: &Bvh2Node| slab.enter(n.aabb.min.into(), n.aabb.max.into());
        let Some(mut t_enter) = enter(&slab, root) else {
            return;
        };
        let mut current = 0usize;
        let mut stack = Stack::<(u32, f32), 64>::new();
        loop {
            // A node popped from the stack may now lie beyond the closest hit.
            if t_enter <= slab.t_max_wide {
                let node = &self.nodes[current];
                if node.is_leaf() {
                    let first = node.first_index as usize;
                    for &item in &self.items[first..first + node.prim_count as usize] {
                        if leaf(item, &mut slab) {
                            return;
                        }
                    }
                } else {
                    let l = node.first_index as usize;
                    let (tl, tr) = (
                        enter(&slab, &self.nodes[l]),
                        enter(&slab, &self.nodes[l + 1]),
                    );
                    match (tl, tr) {
                        (Some(a), Some(b)) => {
                            let (near, far) = if a <= b {
                                ((l, a), (l + 1, b))
                            } else {
                                ((l + 1, b), (l, a))
                            };
                            stack.push((far.0 as u32, far.1));
                            (current, t_enter) = near;
                            continue;
                        }
                        (Some(a), None) => {
                            (current, t_enter) = (l, a);
                            continue;
                        }
                        (None, Some(b)) => {
                            (current, t_enter) = (l + 1, b);
                            continue;
                        }
                        (None, None) => {}
                    }
                }
            }
            match stack.pop() {
                Some((n, t)) => (current, t_enter) = (n as usize, t),
                None => return,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;
    use crate::shapes::{Method, Sphere};
    use glam::Vec3;

    /// `n` spheres of radius 0.05–0.5 scattered in a 20-unit cube.
    fn spheres(n: usize, seed: u64) -> Vec<Sphere> {
        let mut rng = Sampler::for_sample(seed, 0, 0, 0);
        (0..n)
            .map(|_| {
                let c = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 20.0 - 10.0;
                Sphere::new(c, 0.05 + 0.45 * rng.next_f32())
            })
            .collect()
    }

    /// The sphere's box, padded for the rounding of its intersection test
    /// (a box must hold every hit point its item can report).
    fn sphere_box(s: &Sphere) -> Aabb {
        let r = Vec3::splat(s.radius * 1.001);
        Aabb {
            min: s.center - r,
            max: s.center + r,
        }
    }

    #[test]
    fn closest_and_any_equal_brute_force_over_spheres() {
        let items = spheres(2000, 3);
        let boxes: Vec<Aabb> = items.iter().map(sphere_box).collect();
        let bvh = SceneBvh::build(&boxes);
        assert_eq!(bvh.len(), items.len());
        let mut rng = Sampler::for_sample(9, 0, 0, 0);
        let mut hits = 0;
        for k in 0..2000 {
            let origin = rng.next_direction() * 15.0 * rng.next_f32();
            let mut ray = Ray::new(origin, rng.next_direction());
            if k % 3 == 0 {
                ray.t_max = 5.0 * rng.next_f32();
            }
            let test = |i: u32, r: &Ray| items[i as usize].intersect(r, Method::Robust);
            let want = items
                .iter()
                .enumerate()
                .filter_map(|(i, s)| s.intersect(&ray, Method::Robust).map(|a| (i as u32, a)))
                .min_by(|a, b| a.1.total_cmp(&b.1));
            let got = bvh.closest(&ray, test);
            assert_eq!(got.map(|g| g.1), want.map(|w| w.1), "ray {k}: {ray:?}");
            assert_eq!(bvh.any(&ray, |i, r| test(i, r).is_some()), want.is_some());
            hits += want.is_some() as u32;
        }
        assert!(hits > 200, "too few hits ({hits}) to mean anything");
    }

    #[test]
    fn empty_boxes_are_left_out_and_no_items_means_no_hits() {
        let empty = SceneBvh::build(&[]);
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        assert_eq!(empty.closest(&ray, |_, _| Some(1.0)), None);
        let bvh = SceneBvh::build(&[
            Aabb::EMPTY,
            Aabb {
                min: Vec3::splat(1.0),
                max: Vec3::splat(2.0),
            },
        ]);
        assert_eq!(bvh.len(), 1);
        let toward = Ray::new(Vec3::ZERO, Vec3::ONE);
        assert_eq!(
            bvh.closest(&toward, |i, _| Some(1.5 + i as f32)),
            Some((1, 2.5))
        );
    }

    #[test]
    fn rays_in_the_faces_of_flat_boxes_reach_their_items() {
        // Unit squares in the plane z = 0 (flat boxes), and a ray along that
        // plane with ±0 components: it lies in every box's faces.
        let boxes: Vec<Aabb> = (0..50)
            .map(|i| Aabb {
                min: Vec3::new(i as f32, 0.0, 0.0),
                max: Vec3::new(i as f32 + 1.0, 1.0, 0.0),
            })
            .collect();
        let bvh = SceneBvh::build(&boxes);
        for dir in [Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, -0.0, -0.0)] {
            for y in [0.0, 0.5, 1.0] {
                let ray = Ray::new(Vec3::new(-1.0, y, 0.0), dir);
                let mut seen = vec![false; boxes.len()];
                bvh.any(&ray, |i, _| {
                    seen[i as usize] = true;
                    false
                });
                assert!(seen.iter().all(|&s| s), "y = {y} dir = {dir}: {seen:?}");
            }
        }
    }
}
