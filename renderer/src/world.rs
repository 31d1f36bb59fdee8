//! The prepared, immutable render copy of a scene: camera, objects,
//! materials, lights, and the two-level BVH over them.

use crate::accel::{Aabb, SceneBvh};
use crate::blas_cache;
use crate::camera::{Camera, CameraError};
use crate::emitters::Emitters;
use crate::light::Light;
use crate::placed_mesh::PlacedMesh;
use crate::ray::Ray;
use crate::shapes::{Method, Shape, Surface};
use glam::{Affine3A, Vec3};
use scene::{Geometry, InvalidScene, Material, ResolvedObject, ResolvedScene, Scene};
use std::ops::Range;
use std::sync::Arc;

/// Why a scene cannot be rendered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// The scene itself is inconsistent.
    #[error(transparent)]
    Scene(#[from] InvalidScene),
    /// The camera is degenerate.
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
    /// The image would not fit in memory ([`crate::image_memory`]).
    #[error("image size: {0}")]
    Memory(String),
}

/// What the ray hit: which object, how far along the ray, and for meshes
/// which triangle where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The object's index (its object id).
    pub object: u32,
    /// α, the distance along the ray.
    pub alpha: f32,
    /// The triangle hit, when the object is a mesh.
    pub triangle: Option<TriangleRef>,
}

/// Up to this many mesh instances, [`World::intersect_batch`] sends each
/// instance the whole batch; beyond, it traces ray by ray through the top level.
pub const BATCHED_INSTANCES: usize = 8;

/// A triangle of a placed mesh, and where on it a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleRef {
    /// Index into [`World::meshes`].
    pub instance: u32,
    /// The triangle's index in its mesh.
    pub triangle: u32,
    /// β, the weight of t1.
    pub beta: f32,
    /// γ, the weight of t2.
    pub gamma: f32,
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

/// What the top-level BVH holds: an analytic shape or a mesh instance.
#[derive(Clone, Copy, Debug)]
enum Item {
    /// The object with this id, an analytic shape.
    Shape(u32),
    /// This entry of `meshes`.
    Mesh(u32),
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
    /// One name per object.
    pub names: Vec<String>,
    /// Every mesh instance, grouped by object.
    pub meshes: Vec<PlacedMesh>,
    /// Point and directional lights (ambient ones are folded into `ambient`).
    pub lights: Vec<Light>,
    /// Total ambient radiance: lights every surface unshadowed, and is what
    /// rays escaping the scene see (Whitted only; the path tracer has no ambient term).
    pub ambient: Vec3,
    /// Radiance of the constant environment (`<sky>`), zero without one.
    pub sky: Vec3,
    /// Every emissive surface, as area lights.
    pub emitters: Emitters,
    /// The top level's items, in BVH item order.
    items: Vec<Item>,
    /// The top level over every bounded item.
    top: SceneBvh,
    /// Objects no box holds (infinite planes), tested by every ray.
    unbounded: Vec<u32>,
    /// Per object, the largest coordinate magnitude of its geometry (see [`World::magnitude`]).
    magnitudes: Vec<f32>,
}

/// Relative padding of an analytic shape's box in the top level, so that a
/// grazing hit that the shape's own test rounds to just outside its exact
/// box is still found.
const BOX_PADDING: f32 = 1.0e-3;

impl World {
    /// Resolves `scene`'s defaults and prepares it.
    pub fn from_scene(scene: &Scene) -> Result<World, RenderError> {
        World::new(&scene::resolve(scene)?)
    }

    /// Prepares a resolved scene: bottom-level BVHs for meshes not seen
    /// before (built in parallel), then the top level over everything.
    pub fn new(resolved: &ResolvedScene) -> Result<World, RenderError> {
        let camera = Camera::new(&resolved.camera)?;
        crate::image_memory::check_fits(camera.w, camera.h).map_err(RenderError::Memory)?;
        let mut lights = Vec::new();
        let mut ambient = Vec3::ZERO;
        for light in resolved.lights.iter().map(Light::from_scene) {
            match light {
                Light::Ambient { radiance } => ambient += radiance,
                other => lights.push(other),
            }
        }
        let meshes = place_meshes(&resolved.objects);
        let mut objects = Vec::with_capacity(resolved.objects.len());
        let (mut items, mut bounds, mut unbounded) = (Vec::new(), Vec::new(), Vec::new());
        let mut next_instance = 0u32;
        let mut magnitudes = Vec::with_capacity(resolved.objects.len());
        let largest = |min: Vec3, max: Vec3| min.abs().max(max.abs()).max_element();
        for (id, object) in resolved.objects.iter().enumerate() {
            let id = id as u32;
            let Some(shape) = Shape::from_geometry(&object.geometry) else {
                let start = next_instance;
                while meshes
                    .get(next_instance as usize)
                    .is_some_and(|m| m.object == id)
                {
                    items.push(Item::Mesh(next_instance));
                    bounds.push(meshes[next_instance as usize].bounds);
                    next_instance += 1;
                }
                objects.push(Object::Model {
                    instances: start..next_instance,
                });
                magnitudes.push(
                    meshes[start as usize..next_instance as usize]
                        .iter()
                        .map(|m| largest(m.bounds.min, m.bounds.max))
                        .fold(0.0, f32::max),
                );
                continue;
            };
            objects.push(Object::Shape(shape));
            match scene::layout::bounds(&object.geometry) {
                Some(b) => {
                    let magnitude = largest(b.min, b.max);
                    magnitudes.push(magnitude);
                    let pad =
                        BOX_PADDING * (b.max - b.min).max_element() + f32::EPSILON * magnitude;
                    items.push(Item::Shape(id));
                    bounds.push(Aabb {
                        min: b.min - Vec3::splat(pad),
                        max: b.max + Vec3::splat(pad),
                    });
                }
                None => {
                    // An infinite plane: its hit points are placed from its point.
                    magnitudes.push(match &object.geometry {
                        scene::Geometry::Plane { point, .. } => point.abs().max_element(),
                        _ => 0.0,
                    });
                    unbounded.push(id);
                }
            }
        }
        let emissive_shapes: Vec<_> = objects
            .iter()
            .zip(&resolved.objects)
            .map(|(object, resolved)| match object {
                Object::Shape(shape) => (Some(*shape), resolved.material.emission),
                Object::Model { .. } => (None, Vec3::ZERO),
            })
            .collect();
        let emitters = Emitters::new(&emissive_shapes, &meshes);
        Ok(World {
            camera,
            emitters,
            sky: resolved.sky,
            objects,
            materials: resolved.objects.iter().map(|o| o.material).collect(),
            names: resolved.objects.iter().map(|o| o.name.clone()).collect(),
            meshes,
            lights,
            ambient,
            top: SceneBvh::build(&bounds),
            items,
            unbounded,
            magnitudes,
        })
    }

    /// The largest coordinate magnitude of an object's geometry (its world
    /// bounds; for a plane, its point). Hit points on it are placed to within
    /// a few ε of this, so secondary rays leave it by an offset that scales
    /// with it ([`crate::offset::offset_ray_origin`]).
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

    /// The nearest hit along the ray. `method` chooses the formulas of
    /// spheres and lone triangles; mesh triangles always use the watertight test.
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<Hit> {
        crate::ray_count::count_ray();
        let mut tests = 0usize;
        // The triangle of the last hit the top level accepted: each accepted
        // hit lies inside the interval shrunk by the one before, so the last
        // is the nearest.
        let mut last_triangle = None;
        let found = self
            .top
            .closest(ray, |item, ray| match self.items[item as usize] {
                Item::Shape(id) => {
                    tests += 1;
                    let alpha = self.analytic(id).intersect(ray, method)?;
                    last_triangle = None;
                    Some(alpha)
                }
                Item::Mesh(instance) => {
                    tests += 1;
                    let hit = self.meshes[instance as usize].closest_hit(ray)?;
                    last_triangle = Some(TriangleRef {
                        instance,
                        triangle: hit.triangle,
                        beta: hit.beta,
                        gamma: hit.gamma,
                    });
                    Some(hit.alpha)
                }
            });
        let nearest = found.map(|(item, alpha)| Hit {
            object: match self.items[item as usize] {
                Item::Shape(id) => id,
                Item::Mesh(instance) => self.meshes[instance as usize].object,
            },
            alpha,
            triangle: last_triangle,
        });
        let nearest = self.planes_last(ray, nearest, method, &mut tests);
        crate::shape_tests::count_shape_tests(tests);
        nearest
    }

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
        let has_shapes = self.items.len() > self.meshes.len();
        let mut tests = 0usize;
        for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
            crate::ray_count::count_ray();
            tests += self.meshes.len();
            if has_shapes {
                let search = hit.map_or(*ray, |h| ray.with_t_max(h.alpha));
                let shape =
                    self.top
                        .closest(&search, |item, ray| match self.items[item as usize] {
                            Item::Shape(id) => {
                                tests += 1;
                                self.analytic(id).intersect(ray, method)
                            }
                            Item::Mesh(_) => None,
                        });
                if let Some((item, alpha)) = shape {
                    let Item::Shape(object) = self.items[item as usize] else {
                        unreachable!("only shapes are accepted above")
                    };
                    *hit = Some(Hit {
                        object,
                        alpha,
                        triangle: None,
                    });
                }
            }
            *hit = self.planes_last(ray, *hit, method, &mut tests);
        }
        crate::shape_tests::count_shape_tests(tests);
    }

    /// `nearest` (the nearest bounded hit of `ray`, if any) or a nearer hit
    /// with an infinite plane. Planes go last so that a bounded surface lying
    /// exactly in a plane (a cone's base on the floor) wins the tie: a plane
    /// must be strictly nearer. Counts the plane tests in `tests`.
    fn planes_last(
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
        crate::ray_count::count_ray();
        let mut tests = 0usize;
        let blocked = self.unbounded.iter().any(|&id| {
            tests += 1;
            self.analytic(id).intersect(ray, method).is_some()
        }) || self.top.any(ray, |item, ray| {
            tests += 1;
            match self.items[item as usize] {
                Item::Shape(id) => self.analytic(id).intersect(ray, method).is_some(),
                Item::Mesh(instance) => self.meshes[instance as usize].any_hit(ray),
            }
        });
        crate::shape_tests::count_shape_tests(tests);
        blocked
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
            Some(t) => self.meshes[t.instance as usize].surface(&mesh_hit(hit, t)),
            None => self.analytic(hit.object).surface(ray, hit.alpha),
        }
    }

    /// The normal to shade with: the interpolated vertex normal on meshes,
    /// the geometric normal elsewhere.
    pub fn shading_normal(&self, hit: Hit, surface: &Surface) -> Vec3 {
        match hit.triangle {
            Some(t) => {
                self.meshes[t.instance as usize].shading_normal(&mesh_hit(hit, t), surface.normal)
            }
            None => surface.normal,
        }
    }

    /// The material at a hit, its colour multiplied by the mesh's texture there.
    pub fn material(&self, hit: Hit) -> Material {
        match hit.triangle {
            Some(t) => {
                let mesh = &self.meshes[t.instance as usize];
                Material {
                    color: mesh.base_color(&mesh_hit(hit, t)),
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
        self.top.bounds()
    }

    /// Triangles drawn (every mesh instance counts its mesh's triangles).
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.mesh.triangles.len()).sum()
    }
}

/// The accelerator's view of a world hit on a mesh.
fn mesh_hit(hit: Hit, t: TriangleRef) -> crate::accel::MeshHit {
    crate::accel::MeshHit {
        triangle: t.triangle,
        alpha: hit.alpha,
        beta: t.beta,
        gamma: t.gamma,
    }
}

/// Every instance of every model object, in object order, with its BVH
/// (shared per mesh, reused from earlier worlds) and its material.
fn place_meshes(objects: &[ResolvedObject]) -> Vec<PlacedMesh> {
    let mut wanted = Vec::new();
    for (id, object) in objects.iter().enumerate() {
        if let Geometry::Mesh {
            model,
            world_from_model,
            file_materials,
        } = &object.geometry
        {
            for instance in &model.instances {
                let mesh = model.meshes[instance.mesh as usize].clone();
                let file_material = model.materials.get(instance.material as usize);
                let (material, texture) = match file_material {
                    Some(m) if *file_materials => (
                        m.material,
                        m.base_color_texture
                            .and_then(|k| model.textures.get(k as usize).cloned()),
                    ),
                    _ => (object.material, None),
                };
                let transform = *world_from_model * instance.model_from_mesh;
                wanted.push((id as u32, mesh, transform, material, texture));
            }
        }
    }
    let meshes: Vec<Arc<scene::TriangleMesh>> = wanted.iter().map(|w| w.1.clone()).collect();
    let bvhs = blas_cache::bvhs_for(&meshes);
    wanted
        .into_iter()
        .zip(bvhs)
        .map(|((object, mesh, transform, material, texture), bvh)| {
            PlacedMesh::new(
                object,
                mesh,
                bvh,
                Affine3A::from_mat4(transform),
                material,
                texture,
            )
        })
        .collect()
}
