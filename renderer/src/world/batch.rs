//! Many rays at once: [`World::intersect_batch`] hands each mesh instance the
//! whole batch, so that the mesh BVH can trace them as packets or
//! interleaved, with exactly [`World::intersect`]'s hits. Whitted's camera
//! rays in mesh worlds (`integrator/whitted_batch.rs`) and the throughput
//! benchmark (`raylab bench`, its "batched" figures) call it.

use super::{Hit, Item, TriangleRef, World};
use crate::geometry::counters::shape_tests_on_this_thread;
use crate::geometry::ray::Ray;
use crate::shapes::Method;

/// Up to this many mesh instances, [`World::intersect_batch`] sends each
/// instance the whole batch; beyond, it traces ray by ray through the top level.
pub const BATCHED_INSTANCES: usize = 8;

impl World {
    /// [`World::intersect`] of every ray in `rays`, written to `hits` (same
    /// length), for callers holding many rays at once: the same hit bit for
    /// bit (α, object, triangle and barycentrics; a tie between objects goes
    /// to the lower top-level item, as `intersect`'s walk decides it). Each
    /// mesh instance, and the grouped triangles when instances were placed
    /// among them, takes the whole batch in turn
    /// ([`MeshBvh::closest_hits`]: coherent rays in packets, the others
    /// interleaved, which hides memory latency), then each ray meets the
    /// analytic shapes with its interval ending just past its nearest mesh
    /// hit. A top level of more than [`BATCHED_INSTANCES`] mesh instances is
    /// traced ray by ray instead (the top level culls instances there, which
    /// matters more).
    ///
    /// [`MeshBvh::closest_hits`]: crate::accel::MeshBvh::closest_hits
    pub fn intersect_batch(&self, rays: &[Ray], method: Method, hits: &mut [Option<Hit>]) {
        let mut tests = vec![0; rays.len()];
        self.intersect_batch_counted(rays, method, hits, &mut tests);
    }

    /// [`World::intersect_batch`], adding to `tests` (same length) the
    /// shape tests each ray cost: one per mesh instance it was sent
    /// through (every ray meets every instance in a batch, where a lone
    /// ray meets those the top level lets through), plus its own tests of
    /// the analytic shapes and planes; past [`BATCHED_INSTANCES`]
    /// instances, [`World::intersect`]'s own count. A ray's count depends
    /// on it alone, not on the other rays of the batch.
    pub fn intersect_batch_counted(
        &self,
        rays: &[Ray],
        method: Method,
        hits: &mut [Option<Hit>],
        tests: &mut [u32],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        assert_eq!(rays.len(), tests.len(), "one count per ray");
        let top = self.top.for_method(method);
        let mesh_items = top
            .items
            .iter()
            .filter(|item| matches!(item, Item::Mesh(_)))
            .count();
        if mesh_items > BATCHED_INSTANCES {
            for ((ray, hit), tests) in rays.iter().zip(hits.iter_mut()).zip(tests) {
                let before = shape_tests_on_this_thread();
                *hit = self.intersect(ray, method);
                *tests += (shape_tests_on_this_thread() - before) as u32;
            }
            return;
        }
        // Instances placed among the lone triangles take the batch as one.
        let group_batched = top.items.contains(&Item::LoneTriangles)
            && self.top.lone_triangles().has_mesh_triangles();
        // Each ray's closest hit so far and the top-level item it lies on.
        let mut best: Vec<Option<(u32, Hit)>> = vec![None; rays.len()];
        let mut local = Vec::with_capacity(rays.len());
        let mut found = vec![None; rays.len()];
        for (item, kind) in top.items.iter().enumerate() {
            if *kind == Item::LoneTriangles && group_batched {
                local.clear();
                local.extend(rays.iter().zip(&best).map(|(ray, best)| within(ray, best)));
                self.top
                    .lone_triangles()
                    .closest_hits(&local, &mut found, |k, hit| {
                        offer(&mut best[k], item as u32, hit)
                    });
                continue;
            }
            let Item::Mesh(instance) = *kind else {
                continue;
            };
            let placed = &self.meshes[instance as usize];
            local.clear();
            local.extend(
                rays.iter()
                    .zip(&best)
                    .map(|(ray, best)| placed.instance.ray_to_object(&within(ray, best))),
            );
            placed.bvh().closest_hits(&local, &mut found);
            for (best, mesh_hit) in best.iter_mut().zip(&found) {
                if let Some(m) = mesh_hit {
                    let hit = Hit {
                        object: placed.object,
                        alpha: m.alpha,
                        triangle: Some(TriangleRef {
                            instance,
                            triangle: m.triangle,
                            beta: m.beta,
                            gamma: m.gamma,
                        }),
                    };
                    offer(best, item as u32, hit);
                }
            }
        }
        // Items other than instances (shapes, the grouped triangles and
        // spheres) are met ray by ray through the top level.
        let instances = mesh_items + usize::from(group_batched);
        let has_shapes = top.items.len() > instances;
        let mut all_tests = 0usize;
        for (((ray, best), hit), ray_tests) in rays
            .iter()
            .zip(&mut best)
            .zip(hits.iter_mut())
            .zip(tests.iter_mut())
        {
            crate::geometry::counters::count_ray();
            let mut tests = instances;
            if has_shapes {
                let search = within(ray, best);
                // Instances (and the group, when it took the batch) are done.
                let shape = top.closest_with(&search, |item, ray| match top.items[item as usize] {
                    Item::Mesh(_) => None,
                    Item::LoneTriangles if group_batched => None,
                    other => {
                        tests += 1;
                        self.item_hit(other, ray, method)
                    }
                });
                if let Some((item, alpha, (object, triangle))) = shape {
                    let hit = Hit {
                        object,
                        alpha,
                        triangle,
                    };
                    offer(best, item, hit);
                }
            }
            *hit = self.planes_last(ray, best.map(|(_, h)| h), method, &mut tests);
            *ray_tests += tests as u32;
            all_tests += tests;
        }
        crate::geometry::counters::count_shape_tests(all_tests);
    }
}

/// `ray` with its interval ending just past `best`'s α (so that a hit as
/// near still counts, for the tie rule of [`offer`]), or `ray` itself.
#[inline]
fn within(ray: &Ray, best: &Option<(u32, Hit)>) -> Ray {
    best.map_or(*ray, |(_, h)| ray.with_t_max(h.alpha.next_up()))
}

/// Keeps `hit`, on top-level item `item`, when it is nearer than `best` or
/// as near on a lower item: the rule of `SceneBvh::closest_with`'s walk.
#[inline]
fn offer(best: &mut Option<(u32, Hit)>, item: u32, hit: Hit) {
    let better = best.is_none_or(|(best_item, b)| {
        hit.alpha < b.alpha || (hit.alpha == b.alpha && item < best_item)
    });
    if better {
        *best = Some((item, hit));
    }
}
