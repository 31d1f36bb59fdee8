//! A model file (glTF 2.0) loaded into raylab's terms: meshes, materials,
//! textures, the node instances that place them, cameras and lights.
//!
//! Loading never renders anything; the renderer places the instances with
//! the transform of the `<mesh>` object that refers to the file.

use crate::mesh::TriangleMesh;
use crate::model::Light;
use crate::model::Material;
use glam::{Mat4, Vec3};
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

/// Everything raylab takes from one model file. Shared through an `Arc` by
/// every `<mesh>` that names the same file.
#[derive(Clone, Debug, Default)]
pub struct ModelFile {
    /// The file as it was opened.
    pub path: PathBuf,
    /// One mesh per glTF primitive (mesh space), shared by all its instances;
    /// only primitives the loaded scene draws, in the order first drawn.
    pub meshes: Vec<Arc<TriangleMesh>>,
    /// The file's materials mapped to raylab materials, with their textures
    /// (those the drawn primitives use, plus the default when one has none).
    pub materials: Vec<ModelMaterial>,
    /// Decoded images used as base-colour textures, one per (image, wrap modes).
    pub textures: Vec<Arc<Texture>>,
    /// Every drawn (node, primitive) pair: which mesh, which material, where.
    pub instances: Vec<MeshInstance>,
    /// Perspective cameras found in the node tree, in model space.
    pub cameras: Vec<ModelCamera>,
    /// Punctual lights found in the node tree, in model space.
    pub lights: Vec<Light>,
    /// What the file uses that raylab does not support, one line per feature
    /// (reported once; the rest of the file still loads).
    pub warnings: Vec<String>,
    /// [`ModelFile::bounds`], computed on first use (resolving a scene asks
    /// for it after every edit; a million-vertex walk each time is too slow).
    pub(crate) bounds_cache: OnceLock<Option<(Vec3, Vec3)>>,
}

/// One placed primitive: `model_from_mesh` takes the mesh into the model's space.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshInstance {
    /// Index into [`ModelFile::meshes`].
    pub mesh: u32,
    /// Index into [`ModelFile::materials`].
    pub material: u32,
    /// The node's world transform in the file (parents' transforms applied).
    pub model_from_mesh: Mat4,
    /// The node's name, or `node <index>`.
    pub name: String,
}

/// A raylab material plus the base-colour texture that modulates its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelMaterial {
    /// The mapped material (base colour factor in `color`).
    pub material: Material,
    /// Index into [`ModelFile::textures`], multiplied with `material.color`.
    pub base_color_texture: Option<u32>,
}

/// How texture coordinates outside [0, 1] are mapped (glTF sampler wrap modes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Wrap {
    /// Repeat the image (the glTF default).
    #[default]
    Repeat,
    /// Repeat, mirroring every other copy.
    MirroredRepeat,
    /// Clamp to the edge texel.
    ClampToEdge,
}

/// A decoded RGBA8 image with its sampler's wrap modes; texels are sRGB
/// encoded, row 0 at the top (texture coordinate v = 0), as glTF stores them.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width × height` texels, row by row from the top; shared by the
    /// textures that use one image under different wrap modes.
    pub texels: Arc<[[u8; 4]]>,
    /// Wrap mode along u (glTF wrapS).
    pub wrap_u: Wrap,
    /// Wrap mode along v (glTF wrapT).
    pub wrap_v: Wrap,
}

/// A perspective camera from the file, in the lecture's terms.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCamera {
    /// The camera's or its node's name.
    pub name: String,
    /// P0, the viewpoint.
    pub eye: Vec3,
    /// t, the viewing direction (the node's −z).
    pub toward: Vec3,
    /// u, the up vector (the node's +y).
    pub up: Vec3,
    /// θ = yfov / 2, in degrees.
    pub theta_deg: f32,
    /// The file's aspect ratio (width / height), if it gives one.
    pub aspect: Option<f32>,
}

/// Why a model file cannot be loaded at all, shown as `FILE: what is wrong`
/// on one line (control characters in the path or message escaped, as for
/// [`crate::SceneError`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}: {}", crate::error::OneLine(.path), crate::error::elide(.message))]
pub struct ModelError {
    /// The file.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

impl ModelFile {
    /// The model-space box around every instance, as (min, max); `None` when
    /// nothing is drawn.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        *self.bounds_cache.get_or_init(|| self.compute_bounds())
    }

    fn compute_bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut bounds: Option<(Vec3, Vec3)> = None;
        for instance in &self.instances {
            let mesh = &self.meshes[instance.mesh as usize];
            for &[a, b, c] in &mesh.triangles {
                for v in [a, b, c] {
                    let p = instance
                        .model_from_mesh
                        .transform_point3(mesh.positions[v as usize]);
                    bounds = Some(match bounds {
                        None => (p, p),
                        Some((lo, hi)) => (lo.min(p), hi.max(p)),
                    });
                }
            }
        }
        bounds
    }

    /// Triangles drawn: each instance counts its mesh's triangles.
    pub fn drawn_triangles(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh as usize].triangles.len())
            .sum()
    }
}
