//! `raylab export-meshes`: a scene's mesh instances as placed in its world,
//! one Wavefront OBJ each (world-space positions and shading normals), and
//! `meshes.json` saying which object each belongs to and its material, so
//! that another renderer (the Mitsuba comparison,
//! `scripts/mitsuba_reference.py`) sees exactly raylab's triangles.

use super::args::ExportMeshesArgs;
use super::prepare::{UserError, prepare};
use anyhow::{Context, Result};
use renderer::World;
use renderer::world::Object;
use renderer::world::placed_mesh::PlacedMesh;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One model object of the scene (a `<mesh>` element) and its instances.
#[derive(Debug, Serialize)]
pub struct ExportedModel {
    /// The object id (its place among the scene's objects).
    pub object: u32,
    /// Its instances, in the world's order.
    pub instances: Vec<ExportedInstance>,
}

/// One mesh instance: its file and what it is made of.
#[derive(Debug, Serialize)]
pub struct ExportedInstance {
    /// The OBJ file, beside `meshes.json`.
    pub obj: String,
    /// How many triangles it holds.
    pub triangles: usize,
    /// Its material as a scene element's attributes (`material`, `color`,
    /// `ior`, `shininess`, `specular`, `reflectivity`, `roughness`,
    /// `emission`), the colour without the texture.
    pub material: std::collections::BTreeMap<&'static str, String>,
    /// Whether a base-colour texture multiplies `color`.
    pub textured: bool,
}

/// Writes the OBJ files and `meshes.json` into `args.dir` (created if
/// needed); returns the path of `meshes.json`.
pub fn run(args: &ExportMeshesArgs) -> Result<PathBuf> {
    let (world, ..) = prepare(&args.scene)?;
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("creating {}", args.dir.display()))?;
    let models = export(&world, &args.dir)?;
    let index = args.dir.join("meshes.json");
    std::fs::write(&index, serde_json::to_string_pretty(&models)?)
        .map_err(|e| UserError(format!("{}: {e}", index.display())))?;
    Ok(index)
}

/// Writes one OBJ per mesh instance of `world` into `dir` and lists the
/// models (every model object, in object order, even one without instances).
pub fn export(world: &World, dir: &Path) -> Result<Vec<ExportedModel>> {
    let mut models = Vec::new();
    for (id, object) in world.objects.iter().enumerate() {
        let Object::Model { instances } = object else {
            continue;
        };
        let mut exported = Vec::new();
        for k in instances.clone() {
            let placed = &world.meshes[k as usize];
            let name = format!("mesh{k}.obj");
            let path = dir.join(&name);
            std::fs::write(&path, obj_text(placed))
                .map_err(|e| UserError(format!("{}: {e}", path.display())))?;
            exported.push(ExportedInstance {
                obj: name,
                triangles: placed.mesh.triangles.len(),
                material: attributes(&placed.material),
                textured: placed.texture.is_some(),
            });
        }
        models.push(ExportedModel {
            object: id as u32,
            instances: exported,
        });
    }
    Ok(models)
}

/// The instance as OBJ text: world-space vertices (as the renderer places
/// them) with their shading normals, and its triangles in their order.
fn obj_text(placed: &PlacedMesh) -> String {
    let mesh = &placed.mesh;
    let mut text = String::with_capacity(64 * mesh.positions.len());
    for &p in &mesh.positions {
        let p = placed.instance.point_to_world(p);
        let _ = writeln!(text, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    let with_normals = mesh.normals.len() == mesh.positions.len();
    if with_normals {
        for &n in &mesh.normals {
            let n = placed.instance.normal_to_world(n).normalize_or_zero();
            let _ = writeln!(text, "vn {:?} {:?} {:?}", n.x, n.y, n.z);
        }
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| i + 1);
        if with_normals {
            let _ = writeln!(text, "f {a}//{a} {b}//{b} {c}//{c}");
        } else {
            let _ = writeln!(text, "f {a} {b} {c}");
        }
    }
    text
}

/// A material as the attributes of a scene element.
fn attributes(m: &scene::Material) -> std::collections::BTreeMap<&'static str, String> {
    let rgb = |c: glam::Vec3| format!("{:?} {:?} {:?}", c.x, c.y, c.z);
    [
        ("material", m.base.name().to_string()),
        ("color", rgb(m.color)),
        ("ior", format!("{:?}", m.ior)),
        ("shininess", format!("{:?}", m.shininess)),
        ("specular", format!("{:?}", m.specular)),
        ("reflectivity", format!("{:?}", m.reflectivity)),
        ("roughness", format!("{:?}", m.roughness)),
        ("emission", rgb(m.emission)),
    ]
    .into_iter()
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn each_instance_is_written_with_the_worlds_placed_vertices_and_its_material() {
        // The knot scene: two models (the knot, its floor square), one
        // instance each, placed by translation.
        let world = World::from_scene(&scene::generate::knot_scene(300)).expect("valid");
        let dir = tempfile::tempdir().expect("a temporary directory");
        let models = export(&world, dir.path()).expect("written");
        assert_eq!(models.len(), 2);
        for model in &models {
            let Object::Model { instances } = &world.objects[model.object as usize] else {
                panic!("object {} is not a model", model.object);
            };
            assert_eq!(model.instances.len(), instances.len());
            for (exported, k) in model.instances.iter().zip(instances.clone()) {
                let placed = &world.meshes[k as usize];
                let text = std::fs::read_to_string(dir.path().join(&exported.obj)).expect("obj");
                let vertices: Vec<Vec3> = text
                    .lines()
                    .filter_map(|l| l.strip_prefix("v "))
                    .map(|l| {
                        let c: Vec<f32> =
                            l.split(' ').map(|x| x.parse().expect("a number")).collect();
                        Vec3::new(c[0], c[1], c[2])
                    })
                    .collect();
                // Exactly the world's vertices (Debug formatting round-trips f32).
                let want: Vec<Vec3> = placed
                    .mesh
                    .positions
                    .iter()
                    .map(|&p| placed.instance.point_to_world(p))
                    .collect();
                assert_eq!(vertices, want);
                let faces = text.lines().filter(|l| l.starts_with("f ")).count();
                assert_eq!(faces, placed.mesh.triangles.len());
                assert_eq!(exported.triangles, faces);
                assert_eq!(exported.material["material"], placed.material.base.name());
                assert!(!exported.textured);
            }
        }
    }
}
