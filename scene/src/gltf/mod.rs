//! glTF 2.0 import: [`load_model`] reads a `.gltf` (external or `data:` buffers
//! and images) or a `.glb` into a [`ModelFile`].
//!
//! One job per file: `document` (GLB container, JSON, validation),
//! `buffers` (buffer data and URIs), `accessors` (checked typed reads),
//! `primitives` (one primitive → one mesh), `nodes` (hierarchy and
//! transforms), `materials` (the mapping table), `textures` (images and
//! samplers), `cameras`, `lights`, and `warnings` (unsupported features,
//! reported once each). This file ties them together and shares what
//! several nodes use: a mesh, material or texture is built once.
//!
//! Only what the drawn scene uses is loaded: meshes, materials and textures
//! appear in [`ModelFile`] in the order the node walk first meets them.

mod accessors;
mod buffers;
mod cameras;
mod document;
mod lights;
mod materials;
mod nodes;
mod primitives;
mod textures;
mod warnings;

use crate::model::model_file::{MeshInstance, ModelError, ModelFile, ModelMaterial, Wrap};
use ::gltf::{Document, Node};
use buffers::Buffers;
use glam::Mat4;
use primitives::Compression;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;
use warnings::Warnings;

/// Loads a `.gltf` (external or embedded buffers) or `.glb` file.
///
/// What raylab does not support (Draco, skins, morph targets, animations,
/// orthographic cameras…) is listed in [`ModelFile::warnings`], once per
/// feature, and the rest loads. A file that cannot be read, parsed or
/// trusted (an index out of range, a non-finite position, a missing buffer…)
/// is a [`ModelError`] naming the mesh, primitive, accessor or buffer.
/// The material mapping is documented in `scene/src/gltf/materials.rs`.
pub fn load_model(path: &Path) -> Result<ModelFile, ModelError> {
    let fail = |message: String| ModelError {
        path: path.display().to_string(),
        message,
    };
    let bytes = crate::bounded_read::read_limited(path, buffers::MAX_FILE_BYTES).map_err(fail)?;
    load_model_bytes(bytes, path)
}

/// Loads a model from bytes already in memory, as though read from `path`:
/// errors name `path`, and relative buffer and image URIs resolve beside it.
/// The fuzz target and the hostile-file tests use it; [`load_model`] reads
/// the file and calls it.
pub fn load_model_bytes(bytes: Vec<u8>, path: &Path) -> Result<ModelFile, ModelError> {
    let fail = |message: String| ModelError {
        path: path.display().to_string(),
        message,
    };
    let document::Parsed { doc, blob } = document::parse(&bytes).map_err(fail)?;
    drop(bytes);
    warnings::check_required(&doc).map_err(fail)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let buffers = buffers::load(&doc, base, blob).map_err(fail)?;

    let mut warnings = Warnings::default();
    warnings::document_warnings(&doc, &mut warnings);
    let mut builder = Builder {
        doc: &doc,
        buffers: &buffers,
        base,
        compression: Compression::of(&doc),
        model: ModelFile {
            path: path.to_path_buf(),
            ..ModelFile::default()
        },
        meshes: vec![None; doc.meshes().len()],
        materials: HashMap::new(),
        images: HashMap::new(),
        textures: HashMap::new(),
    };
    nodes::walk(&doc, &mut warnings, |node, world, warnings| {
        builder.visit(node, world, warnings)
    })
    .map_err(fail)?;
    let mut model = builder.model;
    model.warnings = warnings.into_vec();
    Ok(model)
}

/// The model being built, with the indices of what it already holds.
struct Builder<'a> {
    doc: &'a Document,
    buffers: &'a Buffers,
    base: &'a Path,
    compression: Compression,
    model: ModelFile,
    /// Per glTF mesh, once loaded: per primitive, its index in `model.meshes`
    /// (`None`: skipped, e.g. lines).
    meshes: Vec<Option<Vec<Option<u32>>>>,
    /// glTF material index (`None`: the default material) → `model.materials`.
    materials: HashMap<Option<usize>, u32>,
    /// glTF image index → the first texture decoded from it (`None`: a
    /// format raylab does not decode).
    images: HashMap<usize, Option<u32>>,
    /// (glTF image, wrap u, wrap v) → `model.textures`.
    textures: HashMap<(usize, Wrap, Wrap), u32>,
}

impl Builder<'_> {
    /// Adds what `node` carries: one instance per drawable primitive of its
    /// mesh, its camera and its light.
    fn visit(&mut self, node: &Node, world: &Mat4, warnings: &mut Warnings) -> Result<(), String> {
        let name = nodes::node_name(node);
        if let Some(mesh) = node.mesh() {
            let meshes = self.mesh(&mesh, warnings)?;
            for (primitive, index) in mesh.primitives().zip(meshes) {
                let Some(mesh) = index else { continue };
                let material = self.material(&primitive.material(), warnings)?;
                self.model.instances.push(MeshInstance {
                    mesh,
                    material,
                    model_from_mesh: *world,
                    name: name.clone(),
                });
            }
        }
        if let Some(camera) = node.camera()
            && let Some(json) = self.doc.as_json().cameras.get(camera.index())
            && let Some(camera) = cameras::camera(camera.index(), json, &name, world, warnings)?
        {
            self.model.cameras.push(camera);
        }
        if let Some(light) = node.light()
            && let Some(light) = lights::light(&light, &name, world, warnings)
        {
            self.model.lights.push(light);
        }
        Ok(())
    }

    /// The model's mesh index of every primitive of `mesh`, loading them on
    /// first use.
    fn mesh(
        &mut self,
        mesh: &::gltf::Mesh,
        warnings: &mut Warnings,
    ) -> Result<Vec<Option<u32>>, String> {
        if let Some(Some(done)) = self.meshes.get(mesh.index()) {
            return Ok(done.clone());
        }
        let mesh_name = match mesh.name() {
            Some(name) => format!("mesh {} \"{name}\"", mesh.index()),
            None => format!("mesh {}", mesh.index()),
        };
        let mut indices = Vec::with_capacity(mesh.primitives().len());
        for primitive in mesh.primitives() {
            let place = format!("{mesh_name}, primitive {}", primitive.index());
            let loaded =
                primitives::load(&primitive, &place, self.buffers, self.compression, warnings)?;
            indices.push(loaded.map(|triangles| {
                self.model.meshes.push(Arc::new(triangles));
                (self.model.meshes.len() - 1) as u32
            }));
        }
        if let Some(slot) = self.meshes.get_mut(mesh.index()) {
            *slot = Some(indices.clone());
        }
        Ok(indices)
    }

    /// The model's material index for `material`, mapping it on first use.
    fn material(
        &mut self,
        material: &::gltf::Material,
        warnings: &mut Warnings,
    ) -> Result<u32, String> {
        let key = material.index();
        if let Some(&index) = self.materials.get(&key) {
            return Ok(index);
        }
        let mapped = match key {
            None => ModelMaterial {
                material: materials::default_material(),
                base_color_texture: None,
            },
            Some(_) => {
                materials::warn_ignored(material, warnings);
                let texture = match material.pbr_metallic_roughness().base_color_texture() {
                    Some(info) if info.tex_coord() == 0 => {
                        self.texture(&info.texture(), warnings)?
                    }
                    _ => None,
                };
                ModelMaterial {
                    material: materials::map(&materials::Pbr::of(material)),
                    base_color_texture: texture,
                }
            }
        };
        self.model.materials.push(mapped);
        let index = (self.model.materials.len() - 1) as u32;
        self.materials.insert(key, index);
        Ok(index)
    }

    /// The model's texture index for `texture`, decoding its image on first
    /// use; `None` when raylab cannot decode it (reported).
    fn texture(
        &mut self,
        texture: &::gltf::Texture,
        warnings: &mut Warnings,
    ) -> Result<Option<u32>, String> {
        let Some(image) = texture.source() else {
            warnings.once("texture without image", || {
                format!("texture {} has no PNG or JPEG image (only one in an extension's format), so it is ignored", texture.index())
            });
            return Ok(None);
        };
        let (wrap_u, wrap_v) = textures::wraps(texture);
        let key = (image.index(), wrap_u, wrap_v);
        if let Some(&index) = self.textures.get(&key) {
            return Ok(Some(index));
        }
        let texels = match self.images.get(&image.index()) {
            Some(None) => return Ok(None),
            // The same image under other wrap modes: share its texels.
            Some(Some(first)) => {
                let t = &self.model.textures[*first as usize];
                Some((t.width, t.height, t.texels.clone()))
            }
            None => textures::decode(self.doc, &image, self.buffers, self.base, warnings)?,
        };
        let Some(texels) = texels else {
            self.images.insert(image.index(), None);
            return Ok(None);
        };
        self.model
            .textures
            .push(Arc::new(textures::texture(texels, (wrap_u, wrap_v))));
        let index = (self.model.textures.len() - 1) as u32;
        self.images.entry(image.index()).or_insert(Some(index));
        self.textures.insert(key, index);
        Ok(Some(index))
    }
}
