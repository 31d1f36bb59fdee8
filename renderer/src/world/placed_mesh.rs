//! A mesh placed in the world: one instance of a model file's primitive,
//! sharing its bottom-level BVH with every other instance of the same mesh.

use super::blas_cache::MeshEntry;
use crate::accel::{Aabb, Instance, MeshBvh, MeshHit};
use crate::geometry::ray::Ray;
use crate::geometry::terminator::curved_surface_point;
use crate::shading::bsdf::PreparedBsdf;
use crate::shading::image_texture;
use crate::shapes::Surface;
use glam::{Affine3A, Vec2, Vec3};
use scene::{Material, Texture, TriangleMesh};
use std::sync::Arc;

/// One mesh instance in world space.
#[derive(Clone, Debug)]
pub struct PlacedMesh {
    /// The object (object id) this instance belongs to.
    pub object: u32,
    /// The mesh, in its own space.
    pub mesh: Arc<TriangleMesh>,
    /// Its box and bottom-level BVH (shared by every instance of `mesh`,
    /// kept across worlds; the BVH built when first asked for:
    /// [`PlacedMesh::bvh`]).
    entry: Arc<MeshEntry>,
    /// world_from_mesh (the model file's node transform, then the object's
    /// placement) with its inverse, which takes rays into mesh space.
    pub instance: Instance,
    /// The material the instance is shaded with.
    pub material: Material,
    /// Its BSDF as far as it holds over the whole instance (the texture's
    /// colour added at each hit).
    pub bsdf: PreparedBsdf,
    /// The base-colour texture multiplied with `material.color`, if any.
    pub texture: Option<Arc<Texture>>,
    /// The world-space bounding box.
    pub bounds: Aabb,
}

impl PlacedMesh {
    /// The instance of `mesh` (with its box and BVH, `entry`) placed by
    /// `world_from_mesh`.
    pub fn new(
        object: u32,
        mesh: Arc<TriangleMesh>,
        entry: Arc<MeshEntry>,
        world_from_mesh: Affine3A,
        material: Material,
        texture: Option<Arc<Texture>>,
    ) -> PlacedMesh {
        let instance = Instance::new(world_from_mesh);
        PlacedMesh {
            object,
            mesh,
            bounds: instance.world_bounds(entry.bounds()),
            entry,
            instance,
            bsdf: PreparedBsdf::new(&material),
            material,
            texture,
        }
    }

    /// The mesh's BVH (in mesh space), built now if no world built it yet:
    /// a world that traces this instance among its grouped triangles builds
    /// it only when the lecture's method traces the instance.
    #[inline]
    pub fn bvh(&self) -> &Arc<MeshBvh> {
        self.entry.bvh(&self.mesh)
    }

    /// True once the mesh's BVH is built.
    pub fn bvh_built(&self) -> bool {
        self.entry.is_built()
    }

    /// The mesh's entry in the BVH cache, with the mesh.
    pub(super) fn entry(&self) -> (&Arc<MeshEntry>, &TriangleMesh) {
        (&self.entry, &self.mesh)
    }

    /// The closest triangle hit inside the ray's interval (watertight test);
    /// α is the world ray's.
    #[inline]
    pub fn closest_hit(&self, ray: &Ray) -> Option<MeshHit> {
        self.instance.closest_hit(self.bvh(), ray)
    }

    /// True when any triangle lies on the ray inside its interval.
    #[inline]
    pub fn any_hit(&self, ray: &Ray) -> bool {
        self.instance.any_hit(self.bvh(), ray)
    }

    /// The triangle's corners in mesh space.
    fn corners(&self, triangle: u32) -> [u32; 3] {
        self.mesh.triangles[triangle as usize]
    }

    /// The hit's surface, shading normal, colour and curved-surface point,
    /// the triangle looked up once: the first three what
    /// [`PlacedMesh::surface`], [`PlacedMesh::shading_normal`] and
    /// [`PlacedMesh::base_color`] give, bit for bit.
    #[inline]
    pub fn shading_point(&self, hit: &MeshHit) -> MeshPoint {
        let corners = self.corners(hit.triangle);
        let surface = self.surface_at(corners, hit);
        MeshPoint {
            surface,
            shading_normal: self.shading_normal_at(corners, hit, surface.normal),
            color: self.base_color_at(corners, hit),
            curved_point: self.curved_point_at(corners, hit, surface.point),
        }
    }

    /// Hanika's point over the hit on the surface the vertex normals
    /// describe ([`curved_surface_point`], found in mesh space and placed),
    /// where shadow rays near the terminator start, for the triangle with
    /// these corners and the placed hit point `point` (itself on a mesh
    /// without normals).
    #[inline]
    fn curved_point_at(&self, corners: [u32; 3], hit: &MeshHit, point: Vec3) -> Vec3 {
        let Some([n0, n1, n2]) = self.vertex_normals(corners) else {
            return point;
        };
        let [a, b, c] = corners;
        let p = &self.mesh.positions;
        let (p0, p1, p2) = (p[a as usize], p[b as usize], p[c as usize]);
        let local = p0 + hit.beta * (p1 - p0) + hit.gamma * (p2 - p0);
        let weights = [1.0 - hit.beta - hit.gamma, hit.beta, hit.gamma];
        let curved = curved_surface_point(local, [p0, p1, p2], [n0, n1, n2], weights);
        if curved == local {
            point
        } else {
            self.instance.point_to_world(curved)
        }
    }

    /// The hit point (interpolated in mesh space, then placed) and the
    /// geometric normal: (t1 − t0) × (t2 − t0) taken to world space by the
    /// inverse transpose, so that a mirroring transform keeps it outward.
    pub fn surface(&self, hit: &MeshHit) -> Surface {
        self.surface_at(self.corners(hit.triangle), hit)
    }

    /// [`PlacedMesh::surface`] of the triangle with these corners.
    #[inline]
    fn surface_at(&self, [a, b, c]: [u32; 3], hit: &MeshHit) -> Surface {
        let p = &self.mesh.positions;
        let (p0, p1, p2) = (p[a as usize], p[b as usize], p[c as usize]);
        let local = p0 + hit.beta * (p1 - p0) + hit.gamma * (p2 - p0);
        let normal = self.instance.normal_to_world((p1 - p0).cross(p2 - p0));
        Surface {
            point: self.instance.point_to_world(local),
            normal: if normal == Vec3::ZERO {
                Vec3::Y
            } else {
                normal
            },
        }
    }

    /// The interpolated vertex normal in world space (smooth shading), or
    /// `geometric` when the mesh has none or it degenerates.
    pub fn shading_normal(&self, hit: &MeshHit, geometric: Vec3) -> Vec3 {
        self.shading_normal_at(self.corners(hit.triangle), hit, geometric)
    }

    /// [`PlacedMesh::shading_normal`] of the triangle with these corners.
    #[inline]
    fn shading_normal_at(&self, corners: [u32; 3], hit: &MeshHit, geometric: Vec3) -> Vec3 {
        let Some([n0, n1, n2]) = self.vertex_normals(corners) else {
            return geometric;
        };
        let alpha = 1.0 - hit.beta - hit.gamma;
        let local = alpha * n0 + hit.beta * n1 + hit.gamma * n2;
        let n = self.instance.normal_to_world(local);
        if n == Vec3::ZERO { geometric } else { n }
    }

    /// The unit normals of the triangle's corners, if the mesh has them.
    #[inline]
    fn vertex_normals(&self, [a, b, c]: [u32; 3]) -> Option<[Vec3; 3]> {
        let n = &self.mesh.normals;
        Some([
            *n.get(a as usize)?,
            *n.get(b as usize)?,
            *n.get(c as usize)?,
        ])
    }

    /// The interpolated texture coordinate, if the mesh has them.
    pub fn uv(&self, hit: &MeshHit) -> Option<Vec2> {
        self.uv_at(self.corners(hit.triangle), hit)
    }

    /// [`PlacedMesh::uv`] of the triangle with these corners.
    fn uv_at(&self, [a, b, c]: [u32; 3], hit: &MeshHit) -> Option<Vec2> {
        let uv = &self.mesh.uvs;
        let (u0, u1, u2) = (
            uv.get(a as usize)?,
            uv.get(b as usize)?,
            uv.get(c as usize)?,
        );
        Some((1.0 - hit.beta - hit.gamma) * *u0 + hit.beta * *u1 + hit.gamma * *u2)
    }

    /// The albedo at the hit: the material's colour times the texture, if any.
    pub fn base_color(&self, hit: &MeshHit) -> Vec3 {
        self.base_color_at(self.corners(hit.triangle), hit)
    }

    /// [`PlacedMesh::base_color`] of the triangle with these corners; the
    /// texture coordinate is only interpolated for a textured instance.
    #[inline]
    fn base_color_at(&self, corners: [u32; 3], hit: &MeshHit) -> Vec3 {
        let Some(texture) = &self.texture else {
            return self.material.color;
        };
        match self.uv_at(corners, hit) {
            Some(uv) => self.material.color * image_texture::sample(texture, uv),
            None => self.material.color,
        }
    }
}

/// What [`PlacedMesh::shading_point`] finds at a hit.
#[derive(Clone, Copy, Debug)]
pub struct MeshPoint {
    /// The hit point and the geometric normal.
    pub surface: Surface,
    /// The interpolated vertex normal (or the geometric one).
    pub shading_normal: Vec3,
    /// The material's colour times the texture there.
    pub color: Vec3,
    /// Hanika's point on the surface the vertex normals describe, where
    /// shadow rays near the terminator start.
    pub curved_point: Vec3,
}
