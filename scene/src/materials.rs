//! The built-in materials and how a named material with overrides resolves.

use crate::InvalidScene;
use crate::model::Material;
use crate::model::{BaseMaterial, MaterialDef, MaterialParams};
use glam::Vec3;

/// The parameters of a built-in material before any override.
pub fn builtin(base: BaseMaterial) -> Material {
    let plain = Material {
        base,
        color: Vec3::splat(0.8),
        ior: 1.5,
        shininess: 0.0,
        specular: 0.0,
        reflectivity: 0.0,
        roughness: 0.0,
        emission: Vec3::ZERO,
    };
    match base {
        BaseMaterial::Matte => plain,
        BaseMaterial::Plastic => Material {
            shininess: 64.0,
            specular: 0.5,
            ..plain
        },
        BaseMaterial::Mirror => Material {
            color: Vec3::splat(0.95),
            reflectivity: 1.0,
            ..plain
        },
        BaseMaterial::Metal => Material {
            color: Vec3::splat(0.9),
            reflectivity: 1.0,
            ..plain
        },
        BaseMaterial::Glass => Material {
            color: Vec3::ONE,
            ..plain
        },
        BaseMaterial::Marble => Material {
            color: Vec3::new(0.92, 0.91, 0.88),
            shininess: 80.0,
            specular: 0.3,
            reflectivity: 0.05,
            ..plain
        },
    }
}

/// `material` with every parameter that `params` sets replaced.
pub fn apply(material: Material, params: &MaterialParams) -> Material {
    Material {
        color: params.color.unwrap_or(material.color),
        ior: params.ior.unwrap_or(material.ior),
        shininess: params.shininess.unwrap_or(material.shininess),
        specular: params.specular.unwrap_or(material.specular),
        reflectivity: params.reflectivity.unwrap_or(material.reflectivity),
        roughness: params.roughness.unwrap_or(material.roughness),
        emission: params.emission.unwrap_or(material.emission),
        base: material.base,
    }
}

/// The material called `name` (`None` is matte): a built-in, or a
/// `<material>` definition applied on top of its base, recursively.
pub fn named(defs: &[MaterialDef], name: Option<&str>) -> Result<Material, InvalidScene> {
    let name = name.unwrap_or(BaseMaterial::Matte.name());
    named_at_depth(defs, name, 0)
}

fn named_at_depth(
    defs: &[MaterialDef],
    name: &str,
    depth: usize,
) -> Result<Material, InvalidScene> {
    if let Some(base) = BaseMaterial::from_name(name) {
        return Ok(builtin(base));
    }
    if depth > defs.len() {
        return Err(InvalidScene(format!(
            "material \"{name}\" is defined in terms of itself"
        )));
    }
    let def = defs.iter().find(|d| d.name == name).ok_or_else(|| {
        InvalidScene(format!(
            "unknown material \"{name}\"; expected a built-in ({}) or a <material> of the scene",
            BaseMaterial::ALL.map(BaseMaterial::name).join(", ")
        ))
    })?;
    Ok(apply(
        named_at_depth(defs, &def.base, depth + 1)?,
        &def.params,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn definitions_chain_onto_their_bases() {
        let defs = vec![
            MaterialDef {
                name: "blue-glass".into(),
                base: "glass".into(),
                params: MaterialParams {
                    color: Some(Vec3::new(0.6, 0.8, 1.0)),
                    ..Default::default()
                },
            },
            MaterialDef {
                name: "water".into(),
                base: "blue-glass".into(),
                params: MaterialParams {
                    ior: Some(1.33),
                    ..Default::default()
                },
            },
        ];
        let m = named(&defs, Some("water")).expect("resolves");
        assert_eq!(m.base, BaseMaterial::Glass);
        assert_eq!(m.color, Vec3::new(0.6, 0.8, 1.0));
        assert_eq!(m.ior, 1.33);
    }

    #[test]
    fn unknown_and_cyclic_names_are_errors() {
        assert!(named(&[], Some("unobtainium")).is_err());
        let cyclic = vec![MaterialDef {
            name: "a".into(),
            base: "a".into(),
            params: Default::default(),
        }];
        assert!(named(&cyclic, Some("a")).is_err());
    }

    #[test]
    fn no_name_is_matte() {
        assert_eq!(named(&[], None).expect("matte").base, BaseMaterial::Matte);
    }
}
