//! Mesh instances: a mesh BVH placed in the world by an affine transform.
//! Rays are mapped into the mesh's space with the direction left
//! unnormalised, so the mesh's α is the world ray's α (P0 + α v maps to
//! M⁻¹P0 + α M⁻¹v) and hits of several instances compare directly.

use super::mesh::{MeshBvh, MeshHit};
use super::scene::Aabb;
use crate::geometry::ray::Ray;
use glam::{Affine3A, Mat3, Vec3};

/// Relative padding of an instance's world box: covers the rounding of the
/// transform of the box's corners and of rays into the mesh's space.
const BOX_PADDING: f32 = 1.0e-5;

/// An affine placement world_from_object of a mesh, with its inverse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instance {
    /// Object space to world space.
    pub world_from_object: Affine3A,
    /// World space to object space.
    pub object_from_world: Affine3A,
    /// Transforms normals to world space: the inverse transpose of the linear part.
    normal_to_world: Mat3,
}

impl Instance {
    /// The instance placed by `world_from_object`, which must be invertible.
    pub fn new(world_from_object: Affine3A) -> Self {
        let object_from_world = world_from_object.inverse();
        Self {
            world_from_object,
            object_from_world,
            normal_to_world: Mat3::from(object_from_world.matrix3).transpose(),
        }
    }

    /// The world ray in the mesh's space: origin and direction mapped by
    /// the inverse, the direction not renormalised, the interval unchanged,
    /// so α means the same point in both spaces.
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self.object_from_world.transform_point3(ray.origin),
            dir: self.object_from_world.transform_vector3(ray.dir),
            t_min: ray.t_min,
            t_max: ray.t_max,
        }
    }

    /// A point of the mesh in world space.
    pub fn point_to_world(&self, p: Vec3) -> Vec3 {
        self.world_from_object.transform_point3(p)
    }

    /// A normal of the mesh in world space (unit length).
    pub fn normal_to_world(&self, n: Vec3) -> Vec3 {
        (self.normal_to_world * n).normalize_or_zero()
    }

    /// The world box of the mesh box `object` (its eight corners mapped and
    /// padded by `BOX_PADDING` of their magnitude), for the top level.
    pub fn world_bounds(&self, object: Aabb) -> Aabb {
        if object.is_empty() {
            return Aabb::EMPTY;
        }
        let b = Aabb::around((0..8).map(|k| {
            let pick = |bit: usize, lo: f32, hi: f32| if k & bit == 0 { lo } else { hi };
            self.point_to_world(Vec3::new(
                pick(1, object.min.x, object.max.x),
                pick(2, object.min.y, object.max.y),
                pick(4, object.min.z, object.max.z),
            ))
        }));
        let pad = BOX_PADDING
            * (b.max - b.min)
                .max(b.min.abs().max(b.max.abs()))
                .max_element();
        Aabb {
            min: b.min - Vec3::splat(pad),
            max: b.max + Vec3::splat(pad),
        }
    }

    /// The closest hit of a world ray with `mesh` placed by this instance;
    /// α is the world ray's, β and γ the mesh triangle's.
    pub fn closest_hit(&self, mesh: &MeshBvh, ray: &Ray) -> Option<MeshHit> {
        mesh.closest_hit(&self.ray_to_object(ray))
    }

    /// True when a world ray hits `mesh` placed by this instance in its interval.
    pub fn any_hit(&self, mesh: &MeshBvh, ray: &Ray) -> bool {
        mesh.any_hit(&self.ray_to_object(ray))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::reference;
    use crate::accel::tests::meshes::grid;
    use crate::integrator::sampler::Sampler;
    use glam::Quat;

    fn placement() -> Affine3A {
        Affine3A::from_scale_rotation_translation(
            Vec3::new(0.5, 2.0, 1.5),
            Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7),
            Vec3::new(4.0, -2.0, 7.0),
        )
    }

    #[test]
    fn transformed_instance_hits_the_same_triangles_as_transformed_triangles_brute_forced() {
        let (p, t) = grid(12, 9, 0.0);
        let mesh = MeshBvh::build(&p, &t);
        let inst = Instance::new(placement());
        let world: Vec<Vec3> = p.iter().map(|&v| inst.point_to_world(v)).collect();
        let mut rng = Sampler::for_sample(5, 0, 0, 0);
        for (k, tri) in t.iter().enumerate() {
            // Aim at a point well inside triangle k, from a random side.
            let (b, g) = (0.2 + 0.3 * rng.next_f32(), 0.1 + 0.3 * rng.next_f32());
            let [a0, a1, a2] = tri.map(|i| world[i as usize]);
            let target = a0 + b * (a1 - a0) + g * (a2 - a0);
            let origin = target + rng.next_direction() * (1.0 + 20.0 * rng.next_f32());
            let ray = Ray::new(origin, target - origin); // unnormalised: α ≈ 1
            let want = reference::closest_hit(&world, &t, &ray).expect("world hit");
            let got = inst.closest_hit(&mesh, &ray).expect("instance hit");
            assert_eq!(got.triangle, want.triangle, "ray {k}");
            assert!((got.alpha - want.alpha).abs() < 1e-4, "{got:?} {want:?}");
            assert!(
                (got.alpha - 1.0).abs() < 1e-4,
                "α is the world ray's: {got:?}"
            );
            assert!((got.beta - want.beta).abs() < 1e-3 && (got.gamma - want.gamma).abs() < 1e-3);
            assert!(inst.any_hit(&mesh, &ray));
            // The world box holds the hit point.
            let hit = ray.at(got.alpha);
            let wb = inst.world_bounds(mesh.bounds());
            assert!(
                hit.cmpge(wb.min).all() && hit.cmple(wb.max).all(),
                "{hit} {wb:?}"
            );
        }
    }

    #[test]
    fn transformed_instance_is_watertight_at_shared_vertices() {
        let (p, t) = grid(6, 6, 0.0);
        let mesh = MeshBvh::build(&p, &t);
        let inst = Instance::new(placement());
        let origin = Vec3::new(-3.0, 11.0, 2.0);
        for j in 1..6 {
            for i in 1..6 {
                let target = inst.point_to_world(Vec3::new(i as f32, j as f32, 0.0));
                let ray = Ray::new(origin, (target - origin).normalize());
                assert!(inst.closest_hit(&mesh, &ray).is_some(), "vertex ({i}, {j})");
            }
        }
    }

    #[test]
    fn normal_maps_with_the_inverse_transpose() {
        let inst = Instance::new(placement());
        let n = inst.normal_to_world(Vec3::Z);
        let (e1, e2) = (
            inst.world_from_object.transform_vector3(Vec3::X),
            inst.world_from_object.transform_vector3(Vec3::Y),
        );
        assert!(
            n.dot(e1).abs() < 1e-5 && n.dot(e2).abs() < 1e-5 && (n.length() - 1.0).abs() < 1e-5
        );
    }
}
