//! Many rays at once: [`World::intersect_batch`] hands each mesh instance the
//! whole batch, so that the mesh BVH can trace them as packets or
//! interleaved. Today only the throughput benchmark (`raylab bench`, its
//! "batched" figures) calls it; the integrators trace one ray at a time.

use super::{Hit, Item, TriangleRef, World};
use crate::geometry::ray::Ray;
use crate::shapes::Method;

/// Up to this many mesh instances, [`World::intersect_batch`] sends each
/// instance the whole batch; beyond, it traces ray by ray through the top level.
pub const BATCHED_INSTANCES: usize = 8;

impl World {
    /// [`World::intersect`] of every ray in `rays`, written to `hits` (same
    /// length), for callers holding many rays at once. Each mesh instance
    /// takes the whole batch in turn ([`MeshBvh::closest_hits`]: several
    /// rays interleaved, which hides memory latency on incoherent rays),
    /// then each ray meets the analytic shapes with its interval ending at
    /// its nearest mesh hit. The same nearest α as `intersect`; on an exact
    /// tie between two objects either may be reported. A world of more than
    /// [`BATCHED_INSTANCES`] mesh instances is traced ray by ray instead (the
    /// top level culls instances there, which matters more).
    ///
    /// [`MeshBvh::closest_hits`]: crate::accel::MeshBvh::closest_hits
    pub fn intersect_batch(&self, rays: &[Ray], method: Method, hits: &mut [Option<Hit>]) {
        assert_eq!(rays.len(), hits.len(), "one hit slot per ray");
        if self.meshes.len() > BATCHED_INSTANCES {
            for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
                *hit = self.intersect(ray, method);
            }
            return;
        }
        hits.fill(None);
        let mut local = Vec::with_capacity(rays.len());
        let mut found = vec![None; rays.len()];
        for (instance, placed) in self.meshes.iter().enumerate() {
            local.clear();
            local.extend(rays.iter().zip(hits.iter()).map(|(ray, hit)| {
                let ray = hit.map_or(*ray, |h: Hit| ray.with_t_max(h.alpha));
                placed.instance.ray_to_object(&ray)
            }));
            placed.bvh.closest_hits(&local, &mut found);
            for (hit, mesh_hit) in hits.iter_mut().zip(&found) {
                if let Some(m) = mesh_hit {
                    *hit = Some(Hit {
                        object: placed.object,
                        alpha: m.alpha,
                        triangle: Some(TriangleRef {
                            instance: instance as u32,
                            triangle: m.triangle,
                            beta: m.beta,
                            gamma: m.gamma,
                        }),
                    });
                }
            }
        }
        let top = self.top.for_method(method);
        let has_shapes = top.items.len() > self.meshes.len();
        let mut tests = 0usize;
        for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
            crate::geometry::counters::count_ray();
            tests += self.meshes.len();
            if has_shapes {
                let search = hit.map_or(*ray, |h| ray.with_t_max(h.alpha));
                let shape =
                    top.bvh
                        .closest_with(&search, |item, ray| match top.items[item as usize] {
                            Item::Shape(id) => {
                                tests += 1;
                                Some((self.analytic(id).intersect(ray, method)?, id))
                            }
                            Item::LoneTriangles => {
                                tests += 1;
                                let hit = self.top.lone_triangles().closest(ray)?;
                                Some((hit.alpha, hit.object))
                            }
                            Item::LoneSpheres => {
                                tests += 1;
                                let hit = self.top.lone_spheres().closest(ray)?;
                                Some((hit.alpha, hit.object))
                            }
                            Item::Mesh(_) => None,
                        });
                if let Some((_, alpha, object)) = shape {
                    *hit = Some(Hit {
                        object,
                        alpha,
                        triangle: None,
                    });
                }
            }
            *hit = self.planes_last(ray, *hit, method, &mut tests);
        }
        crate::geometry::counters::count_shape_tests(tests);
    }
}
