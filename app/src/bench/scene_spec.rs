//! Naming a scene on the command line: a file, or a scene generated in code
//! (`knot`, `knot:N`, `spheres`, `spheres:N`, `seed`).

use anyhow::{Context, Result, bail};
use scene::Scene;
use std::path::{Path, PathBuf};

/// Triangles of the generated torus knot unless `knot:N` says otherwise.
pub const KNOT_TRIANGLES: usize = 1_000_000;
/// Spheres of the generated field unless `spheres:N` says otherwise.
pub const SPHERE_COUNT: usize = 10_000;

/// The scene `spec` names and a label for reports: `knot[:TRIANGLES]` (a
/// (2, 3) torus knot on a floor), `spheres[:COUNT]`, `seed` (the lecture's
/// scene), or else a scene or model file's path.
pub fn load(spec: &str, seed_path: &Path) -> Result<(Scene, String)> {
    let (name, count) = match spec.split_once(':') {
        Some((name, n)) => (name, Some(n)),
        None => (spec, None),
    };
    let count = |default: usize| -> Result<usize> {
        match count {
            None => Ok(default),
            Some(n) => {
                let n: usize = n
                    .replace('_', "")
                    .parse()
                    .with_context(|| format!("{spec}: expected a count after ':'"))?;
                if !(1..=50_000_000).contains(&n) {
                    bail!("{spec}: the count must be between 1 and 50000000");
                }
                Ok(n)
            }
        }
    };
    Ok(match name {
        "knot" => {
            let scene = scene::generate::knot_scene(count(KNOT_TRIANGLES)?);
            let label = format!("torus knot + floor ({} triangles)", triangles(&scene));
            (scene, label)
        }
        "spheres" => {
            let n = count(SPHERE_COUNT)?;
            (
                scene::generate::spheres_scene(n),
                format!("{n} spheres + floor"),
            )
        }
        "seed" => (
            scene::read_any(seed_path)?,
            format!("seed ({})", seed_path.display()),
        ),
        _ => {
            let path = PathBuf::from(spec);
            let scene = scene::read_any(&path)?;
            crate::io::output::warn_about_models(&scene);
            (scene, path.display().to_string())
        }
    })
}

/// Triangles the scene's meshes draw.
fn triangles(scene: &Scene) -> usize {
    scene
        .objects
        .iter()
        .map(|o| match &o.shape {
            scene::Shape::Mesh { source, .. } => source.model.drawn_triangles(),
            _ => 0,
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_names_take_an_optional_count() {
        let seed = Path::new("unused.xml");
        let (knot, label) = load("knot:2000", seed).expect("generates");
        // The knot's 2000 and the floor square's 4.
        assert_eq!(triangles(&knot), 2004);
        assert!(label.contains("2004 triangles"), "{label}");
        let (spheres, _) = load("spheres:25", seed).expect("generates");
        assert_eq!(spheres.objects.len(), 26);
        assert!(load("knot:lots", seed).is_err());
        assert!(load("knot:0", seed).is_err());
        assert!(load("no-such-file.xml", seed).is_err());
    }
}
