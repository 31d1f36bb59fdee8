//! What a file uses that raylab does not support: each feature is reported
//! once, as one sentence naming it and saying what raylab does instead.

use ::gltf::Document;
use std::collections::HashSet;

/// Extensions raylab reads (the material ones as `materials.rs` documents;
/// KHR_mesh_quantization because every attribute is read as any component type).
pub(super) const SUPPORTED_EXTENSIONS: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_emissive_strength",
    "KHR_mesh_quantization",
];

/// The draco extension, whose compressed primitives are skipped.
pub(super) const DRACO: &str = "KHR_draco_mesh_compression";
/// The meshopt extension, whose compressed buffer views are not decoded.
pub(super) const MESHOPT: &str = "EXT_meshopt_compression";

/// Warnings in the order they were first met, one per feature.
#[derive(Debug, Default)]
pub(super) struct Warnings {
    seen: HashSet<String>,
    list: Vec<String>,
}

impl Warnings {
    /// Reports `feature` with `message()` unless it was reported already.
    pub(super) fn once(&mut self, feature: &str, message: impl FnOnce() -> String) {
        if !self.seen.contains(feature) {
            self.seen.insert(feature.to_owned());
            self.list.push(message());
        }
    }

    /// The messages, in order.
    pub(super) fn into_vec(self) -> Vec<String> {
        self.list
    }
}

/// Reports the file-wide features raylab ignores: unsupported extensions,
/// animations and extra scenes.
pub(super) fn document_warnings(doc: &Document, warnings: &mut Warnings) {
    let required: HashSet<&str> = doc.extensions_required().collect();
    for name in doc.extensions_used().chain(doc.extensions_required()) {
        if SUPPORTED_EXTENSIONS.contains(&name) {
            continue;
        }
        let kind = if required.contains(name) {
            "required extension"
        } else {
            "extension"
        };
        warnings.once(name, || {
            format!("{kind} {name} is not supported: {}", instead(name))
        });
    }
    let animations = doc.animations().len();
    if animations > 0 {
        warnings.once("animations", || {
            format!(
                "animations are not supported: the file's {animations} animation(s) are ignored and every node keeps its static transform"
            )
        });
    }
}

/// A required extension that raylab neither reads nor has a documented
/// fallback for (see [`fallback`]) is an error naming it: glTF says a loader
/// must not load a file whose required extensions it does not support.
pub(super) fn check_required(doc: &Document) -> Result<(), String> {
    for (index, name) in doc.extensions_required().enumerate() {
        if !SUPPORTED_EXTENSIONS.contains(&name) && fallback(name).is_none() {
            return Err(format!(
                "extensionsRequired[{index}]: the file requires extension {name}, which raylab \
                 does not know, so it cannot be shown faithfully"
            ));
        }
    }
    Ok(())
}

/// What raylab does instead of an unsupported extension.
fn instead(name: &str) -> &'static str {
    fallback(name).unwrap_or("its data is ignored and the rest of the file loads without it")
}

/// What raylab does instead of an extension it knows but does not read;
/// `None` for an extension it does not know.
fn fallback(name: &str) -> Option<&'static str> {
    Some(match name {
        DRACO => {
            "its Draco-compressed primitives are skipped (primitives with uncompressed data still load)"
        }
        MESHOPT => "primitives whose data is meshopt-compressed are skipped",
        "KHR_texture_transform" => {
            "textures are mapped with the untransformed TEXCOORD_0 (offset, rotation and scale are ignored)"
        }
        "KHR_texture_basisu" | "EXT_texture_webp" | "EXT_texture_avif" | "MSFT_texture_dds" => {
            "images in that format are not decoded; a texture uses its PNG or JPEG fallback when it has one, otherwise the base colour factor alone"
        }
        "KHR_materials_pbrSpecularGlossiness" => {
            "materials are mapped from their metallic-roughness parameters (the defaults where absent)"
        }
        "KHR_materials_unlit" => "unlit materials are shaded like lit ones",
        "KHR_materials_variants" => "every primitive uses its default material",
        "EXT_mesh_gpu_instancing" => "each node's mesh is drawn once, at the node's own transform",
        "KHR_animation_pointer" => "animations are ignored",
        _ if name.starts_with("KHR_materials_") || name.starts_with("EXT_materials_") => {
            "that part of the material is ignored; the metallic-roughness mapping is used"
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_feature_is_reported_once_in_first_seen_order() {
        let mut w = Warnings::default();
        w.once("b", || "B".into());
        w.once("a", || "A".into());
        w.once("b", || "B again".into());
        assert_eq!(w.into_vec(), vec!["B".to_string(), "A".to_string()]);
    }

    #[test]
    fn known_extensions_say_what_raylab_does_instead() {
        assert!(instead(DRACO).contains("skipped"));
        assert!(instead("KHR_texture_transform").contains("TEXCOORD_0"));
        assert!(instead("KHR_materials_clearcoat").contains("ignored"));
        assert!(instead("VENDOR_whatever").contains("ignored"));
    }
}
