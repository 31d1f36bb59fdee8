//! Building a [`World`] from a resolved scene: the camera, the lights, every
//! mesh instance with its shared bottom-level BVH, the emitters, and the top
//! level over every bounded object.

use super::blas_cache;
use super::emitters::Emitters;
use super::environment::Environment;
use super::group_cache;
use super::light::Light;
use super::placed_mesh::PlacedMesh;
use super::top_level::{BAKED_TRIANGLES, GroupInput, Lone, LoneTriangles, TopLevels};
use super::{Item, Object, RenderError, World};
use crate::accel::Aabb;
use crate::camera::Camera;
use crate::shading::bsdf::PreparedBsdf;
use crate::shapes::Shape;
use glam::{Affine3A, Vec3};
use scene::{Geometry, ResolvedObject, ResolvedScene, Scene};
use std::sync::Arc;

/// Relative padding of an analytic shape's box in the top level, so that a
/// grazing hit that the shape's own test rounds to just outside its exact
/// box is still found.
const BOX_PADDING: f32 = 1.0e-3;

/// `b` padded as the top level holds an analytic shape: by [`BOX_PADDING`]
/// of its largest extent and an ε of its largest coordinate magnitude.
fn padded_bounds(b: Aabb) -> Aabb {
    let magnitude = b.min.abs().max(b.max.abs()).max_element();
    let pad = BOX_PADDING * (b.max - b.min).max_element() + f32::EPSILON * magnitude;
    Aabb {
        min: b.min - Vec3::splat(pad),
        max: b.max + Vec3::splat(pad),
    }
}

impl World {
    /// Resolves `scene`'s defaults and prepares it.
    pub fn from_scene(scene: &Scene) -> Result<World, RenderError> {
        World::new(&scene::resolve(scene)?)
    }

    /// Prepares a resolved scene: bottom-level BVHs for meshes not seen
    /// before (built in parallel), then the top level over everything.
    pub fn new(resolved: &ResolvedScene) -> Result<World, RenderError> {
        let camera = Camera::new(&resolved.camera)?;
        let mut lights = Vec::new();
        let mut ambient = Vec3::ZERO;
        for light in resolved.lights.iter().map(Light::from_scene) {
            match light {
                Light::Ambient { radiance } => ambient += radiance,
                other => lights.push(other),
            }
        }
        let (wanted, entries) = wanted_meshes(&resolved.objects);
        let mesh_triangles: usize = wanted.iter().map(|w| w.1.triangles.len()).sum();
        // Instances are placed in world space among the lone triangles when
        // they are small, or when no mesh is shared (each triangle is then
        // held once more at most); a large group is kept across worlds.
        let mut shared: Vec<*const scene::TriangleMesh> =
            wanted.iter().map(|w| Arc::as_ptr(&w.1)).collect();
        shared.sort();
        let shared = shared.windows(2).any(|w| w[0] == w[1]);
        let bake = mesh_triangles <= BAKED_TRIANGLES || !shared;
        let meshes = place_meshes(wanted, entries);
        let key = (bake && mesh_triangles > BAKED_TRIANGLES)
            .then(|| group_cache::Key::of(&resolved.objects, &meshes));
        if key.is_none() {
            // Traced as instances (or small): every mesh's BVH now.
            blas_cache::build_bvhs(meshes.iter().map(PlacedMesh::entry));
        }
        let kept = key.as_ref().and_then(group_cache::kept);
        let mut group = GroupInput::new(mesh_triangles <= BAKED_TRIANGLES);
        let mut objects = Vec::with_capacity(resolved.objects.len());
        let (mut items, mut bounds, mut unbounded) = (Vec::new(), Vec::new(), Vec::new());
        let mut lone = Lone::default();
        let mut next_instance = 0u32;
        let mut magnitudes = Vec::with_capacity(resolved.objects.len());
        let mut shape_bounds = vec![None; resolved.objects.len()];
        let largest = |min: Vec3, max: Vec3| min.abs().max(max.abs()).max_element();
        for (id, object) in resolved.objects.iter().enumerate() {
            let id = id as u32;
            let Some(shape) = Shape::from_geometry(&object.geometry) else {
                let start = next_instance;
                while meshes
                    .get(next_instance as usize)
                    .is_some_and(|m| m.object == id)
                {
                    let placed = &meshes[next_instance as usize];
                    items.push(Item::Mesh(next_instance));
                    bounds.push(placed.bounds);
                    if bake && kept.is_none() {
                        group.instance(
                            id,
                            next_instance,
                            &placed.mesh,
                            |p| placed.instance.point_to_world(p),
                            padded_bounds,
                        );
                    }
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
                    magnitudes.push(largest(b.min, b.max));
                    let padded = padded_bounds(b);
                    items.push(Item::Shape(id));
                    bounds.push(padded);
                    shape_bounds[id as usize] = Some(padded);
                    match shape {
                        Shape::Triangle(t) => {
                            lone.triangle_objects.push(id);
                            if kept.is_none() {
                                group.triangle(id, [t.t0, t.t1, t.t2], padded);
                            }
                        }
                        Shape::Sphere(s) => lone.spheres.push((id, s, bounds[bounds.len() - 1])),
                        _ => {}
                    }
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
        lone.triangles = kept.or_else(|| {
            let built = LoneTriangles::new(group).map(Arc::new);
            if let (Some(key), Some(built)) = (key, &built) {
                group_cache::keep(key, built.clone());
            }
            built
        });
        let emissive_shapes: Vec<_> = objects
            .iter()
            .zip(&resolved.objects)
            .map(|(object, resolved)| match object {
                Object::Shape(shape) => (Some(*shape), resolved.material.emission),
                Object::Model { .. } => (None, Vec3::ZERO),
            })
            .collect();
        let emitters = Emitters::new(&emissive_shapes, &meshes);
        let environment = Environment::new(&resolved.sky);
        Ok(World {
            camera,
            emitters,
            environment,
            objects,
            materials: resolved.objects.iter().map(|o| o.material).collect(),
            bsdfs: resolved
                .objects
                .iter()
                .map(|o| PreparedBsdf::new(&o.material))
                .collect(),
            names: resolved.objects.iter().map(|o| o.name.clone()).collect(),
            meshes,
            lights,
            ambient,
            top: TopLevels::new(items, &bounds, lone),
            unbounded,
            magnitudes,
            shape_bounds,
            id: super::WorldId::fresh(),
        })
    }
}

/// An instance to place: its object, mesh, world_from_mesh, material and
/// texture.
type Wanted = (
    u32,
    Arc<scene::TriangleMesh>,
    glam::Mat4,
    scene::Material,
    Option<Arc<scene::Texture>>,
);

/// Every instance of every model object, in object order, with its mesh's
/// entry (box and BVH, shared per mesh, reused from earlier worlds; the
/// BVH not built here).
fn wanted_meshes(objects: &[ResolvedObject]) -> (Vec<Wanted>, Vec<Arc<blas_cache::MeshEntry>>) {
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
    let entries = blas_cache::entries_for(&meshes);
    (wanted, entries)
}

/// The `wanted` instances placed, each with its mesh's entry.
fn place_meshes(wanted: Vec<Wanted>, entries: Vec<Arc<blas_cache::MeshEntry>>) -> Vec<PlacedMesh> {
    wanted
        .into_iter()
        .zip(entries)
        .map(|((object, mesh, transform, material, texture), entry)| {
            PlacedMesh::new(
                object,
                mesh,
                entry,
                Affine3A::from_mat4(transform),
                material,
                texture,
            )
        })
        .collect()
}
