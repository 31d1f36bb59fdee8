//! `<material>` definitions and the shape elements.

use super::element::Element;
use super::values::{self, Range, degenerate_triangle};
use crate::SceneError;
use crate::model::model_file::ModelFile;
use crate::model::{BaseMaterial, MaterialDef, MeshSource, Object, Shape};
use crate::suggest::did_you_mean;
use glam::Vec3;
use std::sync::Arc;

/// The attributes every shape takes after its own, in writing order.
pub(crate) const COMMON: [&str; 9] = [
    "name",
    "material",
    "color",
    "ior",
    "shininess",
    "specular",
    "reflectivity",
    "roughness",
    "emission",
];

/// The attributes `<material>` takes, in writing order.
pub(crate) const MATERIAL_ATTRS: [&str; 9] = [
    "name",
    "base",
    "color",
    "ior",
    "shininess",
    "specular",
    "reflectivity",
    "roughness",
    "emission",
];

/// A shape's own attributes, in writing order; `None` for a non-shape tag.
pub(crate) fn shape_attrs(tag: &str) -> Option<&'static [&'static str]> {
    Some(match tag {
        "sphere" => &["center", "radius"],
        "box" => &["center", "size", "rotate"],
        "cylinder" | "cone" => &["base", "radius", "height", "rotate"],
        "torus" => &["center", "major", "minor", "rotate"],
        "triangle" => &["t0", "t1", "t2"],
        "plane" => &["point", "normal"],
        "floor" => &["y"],
        "mesh" => &["src", "translate", "rotate", "scale"],
        _ => return None,
    })
}

/// Every attribute a shape element takes: its own, then [`COMMON`].
pub(crate) fn allowed_on_shape(tag: &str) -> Vec<&'static str> {
    let own = shape_attrs(tag).unwrap_or(&[]);
    own.iter().chain(COMMON.iter()).copied().collect()
}

/// A shape element as an object; parameters not given keep the shape's
/// defaults. The `material` name is checked later, once every `<material>`
/// is known.
pub(crate) fn object(el: &Element<'_>) -> Result<Object, SceneError> {
    let Some(default) = Shape::default_for_tag(&el.tag) else {
        return Err(el.error(format!("<{}> is not a shape", el.tag)));
    };
    let positive = |name: &str, dflt: f32| -> Result<f32, SceneError> {
        Ok(el.number(name, Range::Positive)?.unwrap_or(dflt))
    };
    let rotate = || -> Result<Vec3, SceneError> { Ok(el.vector("rotate")?.unwrap_or(Vec3::ZERO)) };
    let shape = match default {
        Shape::Sphere { radius, .. } => Shape::Sphere {
            center: el.vector("center")?,
            radius: positive("radius", radius)?,
        },
        Shape::Box { size, .. } => Shape::Box {
            center: el.vector("center")?,
            size: el.parsed("size", values::positive_vector)?.unwrap_or(size),
            rotate: rotate()?,
        },
        Shape::Cylinder { radius, height, .. } => Shape::Cylinder {
            base: el.vector("base")?,
            radius: positive("radius", radius)?,
            height: positive("height", height)?,
            rotate: rotate()?,
        },
        Shape::Cone { radius, height, .. } => Shape::Cone {
            base: el.vector("base")?,
            radius: positive("radius", radius)?,
            height: positive("height", height)?,
            rotate: rotate()?,
        },
        Shape::Torus { major, minor, .. } => Shape::Torus {
            center: el.vector("center")?,
            major: positive("major", major)?,
            minor: positive("minor", minor)?,
            rotate: rotate()?,
        },
        Shape::Triangle { t0, t1, t2 } => {
            let t0 = el.vector("t0")?.unwrap_or(t0);
            let t1 = el.vector("t1")?.unwrap_or(t1);
            let t2 = el.vector("t2")?.unwrap_or(t2);
            if degenerate_triangle(t0, t1, t2) {
                return Err(el.error(
                    "degenerate triangle: t0, t1 and t2 lie on one line (or coincide); \
                     expected three corners spanning a non-zero area",
                ));
            }
            Shape::Triangle { t0, t1, t2 }
        }
        Shape::Plane { point, normal } => Shape::Plane {
            point: el.vector("point")?.unwrap_or(point),
            normal: el
                .parsed("normal", values::nonzero_vector)?
                .unwrap_or(normal),
        },
        Shape::Floor { y } => Shape::Floor {
            y: el.number("y", Range::Any)?.unwrap_or(y),
        },
        Shape::Mesh { .. } => return Err(el.error("<mesh> is read by objects::mesh")),
    };
    Ok(Object {
        name: el.string("name"),
        shape,
        material: el.string("material"),
        params: el.params()?,
    })
}

/// A `<mesh src=… translate=… rotate=… scale=…/>`; `load` opens the model
/// file named by `src` (relative to the scene file's folder).
pub(crate) fn mesh(
    el: &Element<'_>,
    load: impl FnOnce(&str) -> Result<Arc<ModelFile>, String>,
) -> Result<Object, SceneError> {
    let Some(src) = el.string("src") else {
        return Err(el.error(
            "<mesh> needs a src attribute naming a glTF file (.gltf or .glb), \
             relative to the scene file",
        ));
    };
    let model = load(&src).map_err(|message| el.error_at("src", message))?;
    let shape = Shape::Mesh {
        source: MeshSource { src, model },
        translate: el.vector("translate")?,
        rotate: el.vector("rotate")?.unwrap_or(Vec3::ZERO),
        scale: el
            .parsed("scale", values::positive_vector)?
            .unwrap_or(Vec3::ONE),
    };
    Ok(Object {
        name: el.string("name"),
        shape,
        material: el.string("material"),
        params: el.params()?,
    })
}

/// The built-in materials' names, for messages.
pub(crate) fn builtin_names() -> String {
    BaseMaterial::ALL.map(BaseMaterial::name).join(", ")
}

/// A `<material>`. `earlier` holds the names (and name offsets) of the
/// materials defined before it: `base` may name one of those or a built-in.
pub(crate) fn material(
    el: &Element<'_>,
    earlier: &[(String, usize)],
) -> Result<MaterialDef, SceneError> {
    let Some(name) = el.string("name") else {
        return Err(
            el.error("<material> needs a name attribute (the name shapes use in material=\"…\")")
        );
    };
    if name.trim().is_empty() {
        return Err(el.error_at("name", "a material name must not be empty"));
    }
    if BaseMaterial::from_name(&name).is_some() {
        return Err(el.error_at(
            "name",
            format!(
                "{name:?} is a built-in material; choose another name (the built-ins are {})",
                builtin_names()
            ),
        ));
    }
    if let Some((_, first)) = earlier.iter().find(|(n, _)| *n == name) {
        let (line, column) = el.line_column(*first);
        return Err(el.error_at(
            "name",
            format!("material {name:?} is already defined at line {line}, column {column}"),
        ));
    }
    let base = el.string("base").unwrap_or_else(|| "matte".into());
    if BaseMaterial::from_name(&base).is_none() && !earlier.iter().any(|(n, _)| *n == base) {
        let names = BaseMaterial::ALL
            .map(BaseMaterial::name)
            .into_iter()
            .chain(earlier.iter().map(|(n, _)| n.as_str()));
        return Err(el.error_at(
            "base",
            format!(
                "unknown base material {base:?}{} (expected a built-in material ({}) or a \
                 <material> defined earlier in the file)",
                did_you_mean(&base, names),
                builtin_names()
            ),
        ));
    }
    Ok(MaterialDef {
        name,
        base,
        params: el.params()?,
    })
}
