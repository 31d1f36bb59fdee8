//! A mesh placed in the world: one instance of a model file's primitive,
//! sharing its bottom-level BVH with every other instance of the same mesh.

use crate::accel_stub::{Aabb, MeshBvh, MeshHit};
use crate::image_texture;
use crate::ray::Ray;
use crate::shapes::Surface;
use glam::{Affine3A, Mat3, Vec2, Vec3};
use scene::{Material, Texture, TriangleMesh};
use std::sync::Arc;

/// One mesh instance in world space.
#[derive(Clone, Debug)]
pub struct PlacedMesh {
    /// The object (object id) this instance belongs to.
    pub object: u32,
    /// The mesh, in its own space.
    pub mesh: Arc<TriangleMesh>,
    /// Its bottom-level BVH (shared by every instance of `mesh`).
    pub bvh: Arc<MeshBvh>,
    /// world_from_mesh: the model file's node transform, then the object's placement.
    pub world_from_mesh: Affine3A,
    /// The inverse, which takes rays into mesh space.
    pub mesh_from_world: Affine3A,
    /// Normals go to world space by the inverse transpose of the linear part.
    pub normal_to_world: Mat3,
    /// The material the instance is shaded with.
    pub material: Material,
    /// The base-colour texture multiplied with `material.color`, if any.
    pub texture: Option<Arc<Texture>>,
    /// The world-space bounding box.
    pub bounds: Aabb,
}

impl PlacedMesh {
    /// The instance of `mesh` (with its BVH) placed by `world_from_mesh`.
    pub fn new(
        object: u32,
        mesh: Arc<TriangleMesh>,
        bvh: Arc<MeshBvh>,
        world_from_mesh: Affine3A,
        material: Material,
        texture: Option<Arc<Texture>>,
    ) -> PlacedMesh {
        let local = bvh.bounds();
        let corners = (0..8).map(|k| {
            Vec3::new(
                if k & 1 == 0 { local.min.x } else { local.max.x },
                if k & 2 == 0 { local.min.y } else { local.max.y },
                if k & 4 == 0 { local.min.z } else { local.max.z },
            )
        });
        let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for c in corners {
            let p = world_from_mesh.transform_point3(c);
            min = min.min(p);
            max = max.max(p);
        }
        let linear = Mat3::from(world_from_mesh.matrix3);
        PlacedMesh {
            object,
            mesh,
            bvh,
            world_from_mesh,
            mesh_from_world: world_from_mesh.inverse(),
            normal_to_world: linear.inverse().transpose(),
            material,
            texture,
            bounds: Aabb { min, max },
        }
    }

    /// The ray in mesh space: the direction is transformed but not
    /// normalised, so α means the same point in both spaces.
    #[inline]
    pub fn ray_to_mesh(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self.mesh_from_world.transform_point3(ray.origin),
            dir: self.mesh_from_world.transform_vector3(ray.dir),
            ..*ray
        }
    }

    /// The closest triangle hit inside the ray's interval (watertight test).
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<MeshHit> {
        self.bvh.closest_hit(&self.ray_to_mesh(ray))
    }

    /// True when any triangle lies on the ray inside its interval.
    #[inline]
    pub fn any_hit(&self, ray: &Ray) -> bool {
        self.bvh.any_hit(&self.ray_to_mesh(ray))
    }

    /// The triangle's corners in mesh space.
    fn corners(&self, triangle: u32) -> [u32; 3] {
        self.mesh.triangles[triangle as usize]
    }

    /// The hit point (interpolated in mesh space, then placed) and the
    /// geometric normal: (t1 − t0) × (t2 − t0) taken to world space by the
    /// inverse transpose, so that a mirroring transform keeps it outward.
    pub fn surface(&self, hit: &MeshHit) -> Surface {
        let [a, b, c] = self.corners(hit.triangle);
        let p = &self.mesh.positions;
        let (p0, p1, p2) = (p[a as usize], p[b as usize], p[c as usize]);
        let local = p0 + hit.beta * (p1 - p0) + hit.gamma * (p2 - p0);
        let normal = (self.normal_to_world * (p1 - p0).cross(p2 - p0)).normalize_or(Vec3::Y);
        Surface {
            point: self.world_from_mesh.transform_point3(local),
            normal,
        }
    }

    /// The interpolated vertex normal in world space (smooth shading), or
    /// `geometric` when the mesh has none or it degenerates.
    pub fn shading_normal(&self, hit: &MeshHit, geometric: Vec3) -> Vec3 {
        let n = &self.mesh.normals;
        let [a, b, c] = self.corners(hit.triangle);
        let (Some(n0), Some(n1), Some(n2)) =
            (n.get(a as usize), n.get(b as usize), n.get(c as usize))
        else {
            return geometric;
        };
        let alpha = 1.0 - hit.beta - hit.gamma;
        let local = alpha * *n0 + hit.beta * *n1 + hit.gamma * *n2;
        (self.normal_to_world * local)
            .try_normalize()
            .unwrap_or(geometric)
    }

    /// The interpolated texture coordinate, if the mesh has them.
    pub fn uv(&self, hit: &MeshHit) -> Option<Vec2> {
        let uv = &self.mesh.uvs;
        let [a, b, c] = self.corners(hit.triangle);
        let (u0, u1, u2) = (
            uv.get(a as usize)?,
            uv.get(b as usize)?,
            uv.get(c as usize)?,
        );
        Some((1.0 - hit.beta - hit.gamma) * *u0 + hit.beta * *u1 + hit.gamma * *u2)
    }

    /// The albedo at the hit: the material's colour times the texture, if any.
    pub fn base_color(&self, hit: &MeshHit) -> Vec3 {
        match (&self.texture, self.uv(hit)) {
            (Some(texture), Some(uv)) => self.material.color * image_texture::sample(texture, uv),
            _ => self.material.color,
        }
    }
}
