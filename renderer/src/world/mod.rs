//! The prepared, immutable render copy of a scene: camera, objects,
//! materials, lights, and the two-level BVH over them.
//!
//! [`World::new`] (in `build.rs`) prepares it; `intersect.rs` answers the
//! integrators' ray queries; `batch.rs` traces many rays at once.

mod batch;
pub mod blas_cache;
mod build;
pub mod emitters;
pub mod environment;
mod group_cache;
mod hit;
mod hit_surface;
mod intersect;
pub mod light;
mod lone_spheres;
pub mod placed_mesh;
mod top_level;

pub use batch::BATCHED_INSTANCES;
pub use environment::{Environment, EnvironmentSample, MapOrientation};
pub use hit::{Hit, TriangleRef};
pub use hit_surface::HitSurface;
pub(crate) use top_level::GroupedTriangle;

use crate::accel::Aabb;
use crate::camera::{Camera, CameraError};
use crate::geometry::ray::Ray;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::{Shape, Surface};
use emitters::Emitters;
use glam::Vec3;
use light::Light;
use placed_mesh::PlacedMesh;
use scene::{InvalidScene, Material};
use std::ops::Range;

/// Why a scene cannot be rendered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// The scene itself is inconsistent.
    #[error(transparent)]
    Scene(#[from] InvalidScene),
    /// The camera is degenerate.
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    /// The image would not fit in memory ([`crate::film::image_memory`]).
    #[error("image size: {0}")]
    Memory(String),
}

/// What one object is made of.
#[derive(Clone, Debug)]
pub enum Object {
    /// One analytic shape (or a lone `<triangle>`).
    Shape(Shape),
    /// A model file's mesh instances: `World::meshes[instances]`.
    Model {
        /// Which entries of [`World::meshes`] belong to the object.
        instances: Range<u32>,
    },
}

/// What the top-level BVH holds: an analytic shape, a mesh instance, or
/// (robust method) the lone triangles grouped in one BVH.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Item {
    /// The object with this id, an analytic shape.
    Shape(u32),
    /// This entry of `meshes`.
    Mesh(u32),
    /// The world's [`top_level::LoneTriangles`].
    LoneTriangles,
    /// The world's [`lone_spheres::LoneSpheres`].
    LoneSpheres,
}

/// A scene prepared for rendering: built once per render, never edited.
#[derive(Clone, Debug)]
pub struct World {
    /// The lecture's camera.
    pub camera: Camera,
    /// One entry per object, in object-id order.
    pub objects: Vec<Object>,
    /// One material per object (for a model shown with its file's
    /// materials, what the object's own settings say; instances carry theirs).
    pub materials: Vec<Material>,
    /// One prepared BSDF per object, of its material (a model's instances
    /// carry theirs).
    bsdfs: Vec<PreparedBsdf>,
    /// One name per object.
    pub names: Vec<String>,
    /// Every mesh instance, grouped by object.
    pub meshes: Vec<PlacedMesh>,
    /// Point and directional lights (ambient ones are folded into `ambient`).
    pub lights: Vec<Light>,
    /// Total ambient radiance: lights every surface unshadowed, and is what
    /// rays escaping the scene see (Whitted only; the path tracer has no ambient term).
    pub ambient: Vec3,
    /// What escaping rays see (`<sky>`: a colour or a map; black without one).
    pub environment: Environment,
    /// Every emissive surface, as area lights.
    pub emitters: Emitters,
    /// The top level over every bounded item, as each method traces it.
    top: top_level::TopLevels,
    /// Objects no box holds (infinite planes), tested by every ray.
    unbounded: Vec<u32>,
    /// Per object, the largest coordinate magnitude of its geometry (see [`World::magnitude`]).
    magnitudes: Vec<f32>,
    /// Per analytic object, the box the top level holds it in (padded for
    /// the rounding of its test); `None` for planes and models.
    shape_bounds: Vec<Option<Aabb>>,
    /// Its own number (see [`World::id`]).
    id: WorldId,
}

/// A number no other world in this process has: drawn when a world is
/// built, and drawn afresh for a clone (which may then be changed through
/// its public fields without being taken for the original).
#[derive(Debug)]
struct WorldId(u64);

impl WorldId {
    /// A number not handed out before.
    fn fresh() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        WorldId(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }
}

impl Clone for WorldId {
    fn clone(&self) -> Self {
        WorldId::fresh()
    }
}

impl World {
    /// The ambient light Whitted's shading adds: the ambient lights' and
    /// the sky's mean radiance.
    #[inline]
    pub fn shading_ambient(&self) -> Vec3 {
        self.ambient + self.environment.mean()
    }

    /// A number no other world in this process has, a clone included:
    /// what the renderer keys what it derives from a world by, so that it
    /// is derived once per world.
    pub fn id(&self) -> u64 {
        self.id.0
    }

    /// The box around every hit point the analytic object `object`'s test
    /// can report (its bounds padded for rounding, as the top-level BVH
    /// holds it); `None` for an infinite plane or a model.
    pub(crate) fn shape_bounds(&self, object: u32) -> Option<Aabb> {
        self.shape_bounds.get(object as usize).copied().flatten()
    }

    /// The triangles [`Method::Robust`] tests in one group, by their index
    /// there (the lowest wins a tie): the `<triangle>` objects and, when
    /// [`World::instances_grouped`], every mesh triangle placed in world
    /// space; `None` when there is no group (fewer than four triangles).
    ///
    /// [`Method::Robust`]: crate::shapes::Method::Robust
    pub(crate) fn grouped_triangles(&self) -> Option<&[GroupedTriangle]> {
        self.top.lone_triangles.as_ref().and_then(|g| g.triangles())
    }

    /// True when [`Method::Robust`] meets every mesh instance's triangles
    /// among [`World::grouped_triangles`] (true without instances).
    ///
    /// [`Method::Robust`]: crate::shapes::Method::Robust
    pub(crate) fn instances_grouped(&self) -> bool {
        self.top.instances_grouped
    }

    /// The largest coordinate magnitude of an object's geometry (its world
    /// bounds; for a plane, its point). Hit points on it are placed to within
    /// a few ε of this, so secondary rays leave it by an offset that scales
    /// with it ([`crate::geometry::offset::offset_ray_origin`]).
    pub fn magnitude(&self, object: u32) -> f32 {
        self.magnitudes.get(object as usize).copied().unwrap_or(0.0)
    }

    /// The analytic shape of an object, `None` for a model.
    pub fn shape(&self, object: u32) -> Option<&Shape> {
        match &self.objects[object as usize] {
            Object::Shape(shape) => Some(shape),
            Object::Model { .. } => None,
        }
    }

    /// The BSDF of an object's material as prepared with the world.
    pub(crate) fn prepared_bsdf(&self, object: u32) -> &PreparedBsdf {
        &self.bsdfs[object as usize]
    }

    /// The analytic shape of an object known to be one.
    fn analytic(&self, object: u32) -> &Shape {
        match &self.objects[object as usize] {
            Object::Shape(shape) => shape,
            Object::Model { .. } => unreachable!("object {object} is a model, not a shape"),
        }
    }

    /// Hit point and geometric normal of a hit.
    pub fn surface(&self, ray: &Ray, hit: Hit) -> Surface {
        match hit.triangle {
            Some(t) => self.meshes[t.instance as usize].surface(&t.mesh_hit(hit.alpha)),
            None => self.analytic(hit.object).surface(ray, hit.alpha),
        }
    }

    /// The normal to shade with: the interpolated vertex normal on meshes,
    /// the geometric normal elsewhere.
    pub fn shading_normal(&self, hit: Hit, surface: &Surface) -> Vec3 {
        match hit.triangle {
            Some(t) => self.meshes[t.instance as usize]
                .shading_normal(&t.mesh_hit(hit.alpha), surface.normal),
            None => surface.normal,
        }
    }

    /// The material at a hit, its colour multiplied by the mesh's texture there.
    pub fn material(&self, hit: Hit) -> Material {
        match hit.triangle {
            Some(t) => {
                let mesh = &self.meshes[t.instance as usize];
                Material {
                    color: mesh.base_color(&t.mesh_hit(hit.alpha)),
                    ..mesh.material
                }
            }
            None => self.materials[hit.object as usize],
        }
    }

    /// The colour that stands for an object in drawings: its material's, or
    /// for a model its first instance's (textures aside); grey for an
    /// object id out of range.
    pub fn object_color(&self, object: u32) -> Vec3 {
        let first_instance = match self.objects.get(object as usize) {
            Some(Object::Model { instances }) => self.meshes.get(instances.start as usize),
            _ => None,
        };
        match (first_instance, self.materials.get(object as usize)) {
            (Some(mesh), _) => mesh.material.color,
            (None, Some(material)) => material.color,
            (None, None) => Vec3::splat(0.7),
        }
    }

    /// The box around every bounded object (the top level's root box).
    pub fn bounded_box(&self) -> Aabb {
        self.top.all.bvh.bounds()
    }

    /// Triangles drawn (every mesh instance counts its mesh's triangles).
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.mesh.triangles.len()).sum()
    }
}
