//! The scene with every default filled in: what a renderer consumes.

use crate::model::model_file::ModelFile;
use crate::model::{Light, Material, Sky};
use glam::{Mat4, Vec3};
use std::sync::Arc;

/// A scene with concrete positions, camera, lights and materials.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedScene {
    /// The camera with P0 and t decided.
    pub camera: ResolvedCamera,
    /// The lights to shade with (the scene's own, or the default key + ambient).
    pub lights: Vec<Light>,
    /// What rays that escape see: a colour or an environment map; black
    /// when the scene has no sky.
    pub sky: Sky,
    /// The objects in document order; an object's index is its object id.
    pub objects: Vec<ResolvedObject>,
}

/// The lecture's camera inputs, all decided; t and u are as given (not normalised).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResolvedCamera {
    /// P0, the viewpoint.
    pub eye: Vec3,
    /// t, the toward vector (any non-zero length).
    pub toward: Vec3,
    /// u, the up vector (any non-zero length, not parallel to t).
    pub up: Vec3,
    /// θ, the half-height angle in degrees.
    pub theta_deg: f32,
    /// d, the view-window distance; `None` means h / (2 tan θ).
    pub d: Option<f32>,
    /// w, image width in pixels.
    pub width: u32,
    /// h, image height in pixels.
    pub height: u32,
}

/// An object with concrete geometry and material.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedObject {
    /// The object's name, or `<tag> <index>` when it has none.
    pub name: String,
    /// Concrete geometry.
    pub geometry: Geometry,
    /// Concrete material.
    pub material: Material,
}

/// Concrete geometry in world space (the floor has become a plane).
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// Sphere with centre C and radius r.
    Sphere {
        /// C.
        center: Vec3,
        /// r.
        radius: f32,
    },
    /// Box centred at `center`, edge lengths `size`, rotated by `rotate` degrees (x, then y, then z).
    Box {
        /// Centre.
        center: Vec3,
        /// Edge lengths.
        size: Vec3,
        /// Degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// Capped cylinder on the disk at `base`, axis along the rotated +y.
    Cylinder {
        /// Centre of the bottom disk.
        base: Vec3,
        /// Radius.
        radius: f32,
        /// Height.
        height: f32,
        /// Degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// Capped cone on the disk at `base`, apex at base + height·(rotated y).
    Cone {
        /// Centre of the base disk.
        base: Vec3,
        /// Base radius.
        radius: f32,
        /// Height.
        height: f32,
        /// Degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// Torus in the rotated xz-plane around `center`.
    Torus {
        /// Centre.
        center: Vec3,
        /// R.
        major: f32,
        /// r.
        minor: f32,
        /// Degrees about x, then y, then z.
        rotate: Vec3,
    },
    /// Triangle t0, t1, t2.
    Triangle {
        /// t0.
        t0: Vec3,
        /// t1.
        t1: Vec3,
        /// t2.
        t2: Vec3,
    },
    /// Infinite plane through `point` with normal `normal` (not normalised).
    Plane {
        /// A point on the plane.
        point: Vec3,
        /// The normal.
        normal: Vec3,
    },
    /// A model file's instances, all placed by one transform.
    Mesh {
        /// The loaded model.
        model: ModelRef,
        /// world_from_model = translate · rotate (x, then y, then z) · scale.
        world_from_model: Mat4,
        /// True: each primitive keeps the file's material; false: the
        /// object's own material (named or overridden) replaces them all.
        file_materials: bool,
    },
}

/// A shared, loaded model inside a resolved scene; equal when it is the same
/// load (the same `Arc`), so comparing scenes never walks vertex arrays.
#[derive(Clone)]
pub struct ModelRef(pub Arc<ModelFile>);

impl PartialEq for ModelRef {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl std::fmt::Debug for ModelRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "ModelRef({}, {} triangles)",
            self.0.path.display(),
            self.0.drawn_triangles()
        )
    }
}

impl std::ops::Deref for ModelRef {
    type Target = ModelFile;
    fn deref(&self) -> &ModelFile {
        &self.0
    }
}
