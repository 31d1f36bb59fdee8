//! The top level: an 8-wide BVH (the mesh BVH's nodes, built by the same
//! binned SAH) over items known only by their bounding boxes — mesh
//! instances and analytic shapes. The caller intersects each item the
//! traversal reaches; the eight children of a node are tested at once with
//! the conservative slab test of [`super::wide`], nearest child first, and
//! children whose entry lies beyond the closest hit so far are skipped.

use super::binned_sah::PrimRef;
use super::slab::SlabRay;
use super::stack::Stack;
use super::wide::{ChildRef, WideNode, WideRay, pop_within, push_children_nearest_last};
use super::wide_build::build_wide_refs;
use crate::geometry::ray::Ray;
pub use ::scene::layout::Aabb;
use glam::Vec3A;

/// A BVH over boxed items (infinite items stay outside it, with the caller).
#[derive(Clone, Debug)]
pub struct SceneBvh {
    /// The wide nodes; node 0 is the root (none when there are no items).
    nodes: Vec<WideNode>,
    /// The leaves' runs of `items`: (first, count); a leaf is one or more
    /// consecutive runs.
    runs: Vec<(u32, u32)>,
    /// Item ids in leaf order.
    items: Vec<u32>,
    /// With at most [`FEW_ITEMS`] items, their boxes (by id, with the id),
    /// tested one by one instead of through the nodes.
    few: Vec<(u32, Aabb)>,
    /// The box around every item.
    bounds: Aabb,
}

/// Up to this many items, a ray tests each item's box with the scalar slab
/// test and visits the entered ones nearest first: a wide node's setup and
/// eight-lane test cost more than that for one or two meshes (a glTF model
/// on its floor: Whitted's pass of Duck.gltf took 32% more instructions
/// through the node).
const FEW_ITEMS: usize = 4;

impl SceneBvh {
    /// Builds the BVH over `bounds`; item i is `bounds[i]`, which must hold
    /// every hit point the caller's test can report for it (pad analytic
    /// shapes' boxes for the rounding of their tests). Items with an
    /// empty box (min > max on some axis) can never be hit and are left out.
    /// Boxes must be finite.
    pub fn build(bounds: &[Aabb]) -> SceneBvh {
        Self::build_with(bounds, 1)
    }

    /// [`SceneBvh::build`] with leaves of up to `leaf_max` (1..=8) items, in
    /// runs of at most four ([`SceneBvh::runs`]): for a caller that tests a
    /// run's items together (spheres in a [`SpherePack`]) through
    /// [`SceneBvh::closest_run_with`] and [`SceneBvh::any_run`].
    ///
    /// [`SpherePack`]: super::sphere_pack::SpherePack
    pub fn build_runs(bounds: &[Aabb], leaf_max: usize) -> SceneBvh {
        let mut bvh = Self::build_with(bounds, leaf_max);
        // A run's items are tested together, never box by box.
        bvh.few.clear();
        bvh
    }

    /// The BVH with leaves of up to `leaf_max` items.
    fn build_with(bounds: &[Aabb], leaf_max: usize) -> SceneBvh {
        let ids: Vec<u32> = (0..bounds.len() as u32)
            .filter(|&i| {
                let b = bounds[i as usize];
                b.min.cmple(b.max).all()
            })
            .collect();
        let mut refs: Vec<PrimRef> = ids
            .iter()
            .enumerate()
            .map(|(k, &i)| {
                let b = bounds[i as usize];
                debug_assert!(b.min.is_finite() && b.max.is_finite(), "item {i}: {b:?}");
                PrimRef::new(k as u32, Vec3A::from(b.min), Vec3A::from(b.max))
            })
            .collect();
        let all = ids
            .iter()
            .fold(Aabb::EMPTY, |acc, &i| acc.union(bounds[i as usize]));
        let (nodes, runs, _) = build_wide_refs(&mut refs, leaf_max);
        let few = if ids.len() <= FEW_ITEMS {
            ids.iter().map(|&i| (i, bounds[i as usize])).collect()
        } else {
            Vec::new()
        };
        SceneBvh {
            nodes,
            runs,
            items: refs.iter().map(|r| ids[r.id() as usize]).collect(),
            few,
            bounds: all,
        }
    }

    /// The box around every item in the BVH (empty when there is none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The item ids of each leaf run, in run order (the `run` that
    /// [`SceneBvh::closest_run_with`] hands its test indexes this).
    pub fn runs(&self) -> impl Iterator<Item = &[u32]> {
        self.runs
            .iter()
            .map(|&(first, count)| &self.items[first as usize..(first + count) as usize])
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
            + self.nodes.capacity() * std::mem::size_of::<WideNode>()
            + self.runs.capacity() * std::mem::size_of::<(u32, u32)>()
            + self.items.capacity() * std::mem::size_of::<u32>()
            + self.few.capacity() * std::mem::size_of::<(u32, Aabb)>()
    }

    /// The closest item hit: `test(item, ray)` returns the α of the item's
    /// closest hit inside `ray`'s interval, which ends at the closest α found
    /// so far (one float beyond it, for ties). Returns (item, α); of items
    /// hit at the same α, the lowest item id, whatever order the traversal
    /// met them in.
    #[inline(always)]
    pub fn closest(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        self.closest_with(ray, |item, ray| test(item, ray).map(|alpha| (alpha, ())))
            .map(|(item, alpha, ())| (item, alpha))
    }

    /// [`SceneBvh::closest`] where `test` also returns what the caller wants
    /// kept of the hit (a triangle and its barycentrics, say): the closest
    /// hit's is returned with it.
    #[inline(always)]
    pub fn closest_with<T>(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<(f32, T)>,
    ) -> Option<(u32, f32, T)> {
        let mut closest = Closest::new(ray);
        self.traverse(ray, |item, slab| {
            closest.offer(item, test(item, &closest.ray), slab);
            false
        });
        closest.best
    }

    /// [`SceneBvh::closest_with`] over the leaf runs of a BVH built by
    /// [`SceneBvh::build_runs`]: `test(run, ray)` tests every item of run
    /// `run` (an index into [`SceneBvh::runs`]); of runs hit at the same α,
    /// the lowest run wins.
    #[inline(always)]
    pub fn closest_run_with<T>(
        &self,
        ray: &Ray,
        mut test: impl FnMut(u32, &Ray) -> Option<(f32, T)>,
    ) -> Option<(u32, f32, T)> {
        let mut closest = Closest::new(ray);
        self.walk_runs(ray, |run, slab| {
            closest.offer(run, test(run, &closest.ray), slab);
            false
        });
        closest.best
    }

    /// True when `test(run, ray)` is true for some leaf run the ray may
    /// reach (see [`SceneBvh::closest_run_with`]); stops at the first.
    #[inline(always)]
    pub fn any_run(&self, ray: &Ray, mut test: impl FnMut(u32, &Ray) -> bool) -> bool {
        let mut hit = false;
        self.walk_runs(ray, |run, _| {
            hit = test(run, ray);
            hit
        });
        hit
    }

    /// True when `test(item, ray)` is true for some item the ray may reach;
    /// stops at the first.
    #[inline(always)]
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
        if self.nodes.is_empty() {
            return;
        }
        if !self.few.is_empty() {
            // The entered boxes, nearest first.
            let mut slab = SlabRay::new(ray);
            let mut entered = [(0u32, 0.0f32); FEW_ITEMS];
            let mut n = 0;
            for &(item, b) in &self.few {
                if let Some(t) = slab.enter(b.min, b.max) {
                    let mut j = n;
                    while j > 0 && entered[j - 1].1 > t {
                        entered[j] = entered[j - 1];
                        j -= 1;
                    }
                    entered[j] = (item, t);
                    n += 1;
                }
            }
            for &(item, t) in &entered[..n] {
                // A box entered beyond the closest hit so far holds no closer one.
                if t <= slab.t_max_wide && leaf(item, &mut slab) {
                    return;
                }
            }
            return;
        }
        self.walk_runs(ray, |run, slab| {
            let (first, count) = self.runs[run as usize];
            let items = &self.items[first as usize..(first + count) as usize];
            items.iter().any(|&item| leaf(item, slab))
        });
    }

    /// Calls `leaf(run, slab)` for every leaf run (an index into `runs`)
    /// whose box the ray may hit, nearest box first, through the nodes;
    /// `leaf` may lower the slab's t_max, and stops the walk by returning true.
    #[inline(always)]
    fn walk_runs(&self, ray: &Ray, mut leaf: impl FnMut(u32, &mut SlabRay) -> bool) {
        if self.nodes.is_empty() {
            return;
        }
        let mut wide = WideRay::new(ray);
        let mut stack = Stack::<(ChildRef, f32), 64>::new();
        let mut next = Some(ChildRef::node(0));
        while let Some(current) = next {
            if let Some(range) = current.packs() {
                for run in range {
                    if leaf(run as u32, &mut wide.slab) {
                        return;
                    }
                }
            } else {
                let node = &self.nodes[current.0 as usize];
                let (mask, t_near) = wide.child_hits(node);
                if mask != 0 {
                    next = Some(push_children_nearest_last(
                        node,
                        mask,
                        &t_near,
                        &mut stack,
                        |_| {},
                    ));
                    continue;
                }
            }
            next = pop_within(&mut stack, wide.slab.t_max_wide);
        }
    }
}

/// The closest hit so far of a walk whose hits are offered one by one, and
/// the ray each next test is given: its t_max one float beyond the closest
/// α, so that a tie still reaches the caller (the lowest id wins it).
struct Closest<T> {
    /// The ray the next test gets.
    ray: Ray,
    /// The interval a hit must lie in (the caller's ray's).
    t_min: f32,
    t_max: f32,
    /// (id, α, what the caller keeps) of the closest hit so far.
    best: Option<(u32, f32, T)>,
}

impl<T> Closest<T> {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        Self {
            ray: *ray,
            t_min: ray.t_min,
            t_max: ray.t_max,
            best: None,
        }
    }

    /// Keeps `found`, the hit of item or run `id`, when it is inside the
    /// interval and closer than the best so far (or as close, with a lower
    /// id); then the walk's boxes beyond it are skipped.
    #[inline(always)]
    fn offer(&mut self, id: u32, found: Option<(f32, T)>, slab: &mut SlabRay) {
        let Some((alpha, kept)) = found else { return };
        if !(alpha > self.t_min && alpha < self.t_max) {
            return;
        }
        let better = match &self.best {
            None => true,
            Some((best_id, best_alpha, _)) => {
                alpha < *best_alpha || (alpha == *best_alpha && id < *best_id)
            }
        };
        if better {
            self.ray.t_max = alpha.next_up();
            slab.set_t_max(alpha);
            self.best = Some((id, alpha, kept));
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
        // Few items are tested box by box, more through the nodes.
        for n in [1, 2, 4, 5, 2000] {
            closest_and_any_equal_brute_force(n);
        }
    }

    fn closest_and_any_equal_brute_force(n: usize) {
        let items = spheres(n, 3);
        let boxes: Vec<Aabb> = items.iter().map(sphere_box).collect();
        let bvh = SceneBvh::build(&boxes);
        assert_eq!(bvh.len(), items.len());
        let mut rng = Sampler::for_sample(9, 0, 0, 0);
        let mut hits = 0;
        for k in 0..2000 {
            let origin = rng.next_direction() * 15.0 * rng.next_f32();
            // With few spheres, aim near one of them, or most rays miss them all.
            let dir = if n < 100 {
                let s = &items[k % n];
                let target = s.center + rng.next_direction() * s.radius * 1.5;
                (target - origin).normalize()
            } else {
                rng.next_direction()
            };
            let mut ray = Ray::new(origin, dir);
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
        assert!(
            hits > 200,
            "{n} spheres: too few hits ({hits}) to mean anything"
        );
    }

    #[test]
    fn a_tie_goes_to_the_lowest_item_whatever_the_traversal_order() {
        // Nested boxes, each holding every point the rays reach before
        // α = 9, shifted along x so that rays going either way meet them in
        // opposite orders; several items report the same α. Three boxes are
        // tested one by one, forty through the nodes.
        for count in [3u32, 40] {
            let boxes: Vec<Aabb> = (0..count)
                .map(|i| {
                    let shift = Vec3::new(i as f32 * 0.25 - 5.0, 0.0, 0.0);
                    Aabb {
                        min: Vec3::splat(-20.0) + shift,
                        max: Vec3::splat(20.0) + shift,
                    }
                })
                .collect();
            let bvh = SceneBvh::build(&boxes);
            for dir in [Vec3::X, Vec3::NEG_X, Vec3::Y] {
                let ray = Ray::new(Vec3::ZERO, dir);
                // Items in `tied` report α = 5, the others α = 6 + (i mod 3).
                let hits = |tied: fn(u32) -> bool| {
                    move |i: u32, r: &Ray| {
                        let alpha = if tied(i) { 5.0 } else { 6.0 + (i % 3) as f32 };
                        (alpha > r.t_min && alpha < r.t_max).then_some(alpha)
                    }
                };
                let all_but_0 = |i: u32| i > 0 && i % 2 == 1;
                assert_eq!(
                    bvh.closest(&ray, hits(|_| true)),
                    Some((0, 5.0)),
                    "{count} {dir}"
                );
                assert_eq!(
                    bvh.closest(&ray, hits(all_but_0)),
                    Some((1, 5.0)),
                    "{count} {dir}"
                );
                let last_two = |i: u32| i >= 1;
                assert_eq!(
                    bvh.closest(&ray, hits(last_two)),
                    Some((1, 5.0)),
                    "{count} {dir}"
                );
            }
        }
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
