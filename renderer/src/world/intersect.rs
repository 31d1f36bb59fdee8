//! The ray queries of a [`World`]: the nearest hit through the top-level BVH
//! (infinite planes last) and the any-hit test of shadow rays, counting the
//! rays and shape tests they cost ([`crate::geometry::counters`]).

use super::{Hit, Item, TriangleRef, World};
use crate::geometry::ray::Ray;
use crate::shapes::Method;

impl World {
    /// The nearest hit along the ray. `method` chooses the formulas of
    /// spheres and lone triangles; mesh triangles always use the watertight test.
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<Hit> {
        crate::geometry::counters::count_ray();
        let mut tests = 0usize;
        let top = self.top.for_method(method);
        let found = top.closest_with(ray, |item, ray| {
            tests += 1;
            self.item_hit(top.items[item as usize], ray, method)
        });
        let nearest = found.map(|(_, alpha, (object, triangle))| Hit {
            object,
            alpha,
            triangle,
        });
        let nearest = self.planes_last(ray, nearest, method, &mut tests);
        crate::geometry::counters::count_shape_tests(tests);
        nearest
    }

    /// The nearest hit of `ray` in its interval with the top-level item
    /// `item`: its α, and what `Hit` needs besides (the object, and a mesh
    /// triangle or the object of a lone triangle in the group).
    #[inline(always)]
    pub(super) fn item_hit(
        &self,
        item: Item,
        ray: &Ray,
        method: Method,
    ) -> Option<(f32, (u32, Option<TriangleRef>))> {
        match item {
            Item::Shape(id) => Some((self.analytic(id).intersect(ray, method)?, (id, None))),
            Item::LoneTriangles => {
                let hit = self.top.lone_triangles().closest(ray)?;
                Some((hit.alpha, (hit.object, hit.triangle)))
            }
            Item::LoneSpheres => {
                let hit = self.top.lone_spheres().closest(ray)?;
                Some((hit.alpha, (hit.object, None)))
            }
            Item::Mesh(instance) => {
                let placed = &self.meshes[instance as usize];
                let hit = placed.closest_hit(ray)?;
                let triangle = TriangleRef {
                    instance,
                    triangle: hit.triangle,
                    beta: hit.beta,
                    gamma: hit.gamma,
                };
                Some((hit.alpha, (placed.object, Some(triangle))))
            }
        }
    }

    /// `nearest` (the nearest bounded hit of `ray`, if any) or a nearer hit
    /// with an infinite plane. Planes go last so that a bounded surface lying
    /// exactly in a plane (a cone's base on the floor) wins the tie: a plane
    /// must be strictly nearer. Counts the plane tests in `tests`.
    pub(super) fn planes_last(
        &self,
        ray: &Ray,
        mut nearest: Option<Hit>,
        method: Method,
        tests: &mut usize,
    ) -> Option<Hit> {
        let mut search = nearest.map_or(*ray, |h| ray.with_t_max(h.alpha));
        for &id in &self.unbounded {
            *tests += 1;
            if let Some(alpha) = self.analytic(id).intersect(&search, method) {
                search.t_max = alpha;
                nearest = Some(Hit {
                    object: id,
                    alpha,
                    triangle: None,
                });
            }
        }
        nearest
    }

    /// True when anything lies on the ray inside its interval (shadow rays).
    pub fn occluded(&self, ray: &Ray, method: Method) -> bool {
        crate::geometry::counters::count_ray();
        let mut tests = 0usize;
        let top = self.top.for_method(method);
        let blocked = self.unbounded.iter().any(|&id| {
            tests += 1;
            self.analytic(id).intersect(ray, method).is_some()
        }) || top.any(ray, |item, ray| {
            tests += 1;
            match top.items[item as usize] {
                Item::LoneTriangles => self.top.lone_triangles().any(ray),
                Item::LoneSpheres => self.top.lone_spheres().any(ray),
                Item::Shape(id) => self.analytic(id).intersect(ray, method).is_some(),
                Item::Mesh(instance) => self.meshes[instance as usize].any_hit(ray),
            }
        });
        crate::geometry::counters::count_shape_tests(tests);
        blocked
    }
}
