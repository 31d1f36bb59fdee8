//! The prepared, immutable render copy of a scene: camera, shapes, materials, lights.

use crate::camera::{Camera, CameraError};
use crate::light::Light;
use crate::ray::Ray;
use crate::shapes::{Method, Shape, Surface};
use glam::Vec3;
use scene::{InvalidScene, Material, ResolvedScene, Scene};

/// Why a scene cannot be rendered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// The scene itself is inconsistent.
    #[error(transparent)]
    Scene(#[from] InvalidScene),
    /// The camera is degenerate.
    #[error("camera: {0}")]
    Camera(#[from] CameraError),
}

/// What the ray hit: which object, and how far along the ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The object's index (its object id).
    pub object: u32,
    /// α, the distance along the ray.
    pub alpha: f32,
}

/// A scene prepared for rendering: built once per render, never edited.
#[derive(Clone, Debug)]
pub struct World {
    /// The lecture's camera.
    pub camera: Camera,
    /// One shape per object, in object-id order.
    pub shapes: Vec<Shape>,
    /// One material per object.
    pub materials: Vec<Material>,
    /// One name per object.
    pub names: Vec<String>,
    /// Point and directional lights (ambient ones are folded into `ambient`).
    pub lights: Vec<Light>,
    /// Total ambient radiance: lights every surface unshadowed, and is what
    /// rays escaping the scene see.
    pub ambient: Vec3,
}

impl World {
    /// Resolves `scene`'s defaults and prepares it.
    pub fn from_scene(scene: &Scene) -> Result<World, RenderError> {
        World::new(&scene::resolve(scene)?)
    }

    /// Prepares a resolved scene.
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
        Ok(World {
            camera,
            shapes: resolved
                .objects
                .iter()
                .map(|o| Shape::from_geometry(&o.geometry))
                .collect(),
            materials: resolved.objects.iter().map(|o| o.material).collect(),
            names: resolved.objects.iter().map(|o| o.name.clone()).collect(),
            lights,
            ambient,
        })
    }

    /// The nearest hit along the ray (every shape is tested; a BVH comes later).
    pub fn intersect(&self, ray: &Ray, method: Method) -> Option<Hit> {
        crate::ray_count::count_ray();
        crate::shape_tests::count_shape_tests(self.shapes.len());
        let mut nearest: Option<Hit> = None;
        let mut search = *ray;
        for (index, shape) in self.shapes.iter().enumerate() {
            if let Some(alpha) = shape.intersect(&search, method) {
                search.t_max = alpha;
                nearest = Some(Hit {
                    object: index as u32,
                    alpha,
                });
            }
        }
        nearest
    }

    /// True when anything lies on the ray inside its interval (shadow rays).
    /// Shapes are tested in object order up to the first occluder.
    pub fn occluded(&self, ray: &Ray, method: Method) -> bool {
        crate::ray_count::count_ray();
        let first = self
            .shapes
            .iter()
            .position(|shape| shape.intersect(ray, method).is_some());
        crate::shape_tests::count_shape_tests(first.map_or(self.shapes.len(), |k| k + 1));
        first.is_some()
    }

    /// Hit point and normal of a hit.
    pub fn surface(&self, ray: &Ray, hit: Hit) -> Surface {
        self.shapes[hit.object as usize].surface(ray, hit.alpha)
    }
}
