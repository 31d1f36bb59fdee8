//! `raylab bench SCENE --export DIR`: writes exactly what the throughput
//! benchmark casts, so that another ray tracer can cast the same rays at the
//! same triangles (`scripts/embree_cast.py` does, with Embree).
//!
//! DIR receives raw little-endian arrays and a manifest:
//! - `vertices.f32`: world-space vertices, x y z as f32;
//! - `triangles.u32`: three vertex indices per triangle, u32, into all vertices;
//! - `primary_rays.f32`, `incoherent_rays.f32`: origin x y z then direction
//!   x y z per ray, f32, in the order raylab casts them;
//! - `manifest.json`: the counts, which triangles and vertices belong to which
//!   object, the rays' interval, and raylab's own figures measured by the
//!   same process (added once the measurement is done).
//!
//! Mesh instances are flattened into world space. A lone triangle is one
//! triangle. An infinite plane (the knot's floor) becomes a square of 2
//! triangles lying exactly in it, centred under the scene and large enough
//! that every exported ray that meets the plane meets the square, so that
//! hit fractions agree; the manifest gives its half-size. Other analytic
//! shapes have no triangle form and are refused.

use super::trace::{self, SceneFigures};
use anyhow::{Context, Result, bail};
use glam::Vec3;
use renderer::World;
use renderer::geometry::ray::Ray;
use renderer::shapes::{Plane, Shape};
use renderer::world::Object;
use scene::Scene;
use serde::Serialize;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Name of the manifest inside the export folder.
pub const MANIFEST: &str = "manifest.json";
const VERTICES: &str = "vertices.f32";
const TRIANGLES: &str = "triangles.u32";
const PRIMARY: &str = "primary_rays.f32";
const INCOHERENT: &str = "incoherent_rays.f32";

/// What `manifest.json` says about an export.
#[derive(Clone, Debug, Serialize)]
pub struct Manifest {
    /// Layout version of the export.
    pub format: &'static str,
    /// The scene, as `raylab bench` labels it.
    pub scene: String,
    /// Image width the primary rays were made for.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// File of the vertices (f32 x y z each).
    pub vertices_file: &'static str,
    /// Vertices in it.
    pub vertices: usize,
    /// File of the triangles (u32 vertex indices, three each).
    pub triangles_file: &'static str,
    /// Triangles in it.
    pub triangles: usize,
    /// The objects, in order: contiguous ranges of vertices and triangles.
    pub geometries: Vec<Geometry>,
    /// Hits at α ≤ t_min are ignored, for every ray.
    pub t_min: f32,
    /// Hits at α ≥ t_max are ignored; raylab's rays run to +∞, written as
    /// the largest f32 (JSON has no infinity).
    pub t_max: f32,
    /// One ray per pixel centre, row by row from the top.
    pub primary: RaySet,
    /// Random rays from the box around the bounded objects; `None` when the
    /// scene has nothing bounded.
    pub incoherent: Option<RaySet>,
    /// raylab's figures on these rays, measured by the process that exported them.
    pub raylab: Option<SceneFigures>,
}

/// One object's triangles in the export.
#[derive(Clone, Debug, Serialize)]
pub struct Geometry {
    /// The object's name (with `#k` for its k-th mesh instance when it has several).
    pub name: String,
    /// `mesh`, `triangle` or `plane`.
    pub kind: &'static str,
    /// Its first vertex.
    pub first_vertex: usize,
    /// Its vertex count.
    pub vertices: usize,
    /// Its first triangle.
    pub first_triangle: usize,
    /// Its triangle count.
    pub triangles: usize,
    /// For a plane: the square that stands for it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub square: Option<Square>,
}

/// The square of 2 triangles that stands for an infinite plane.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Square {
    /// A point of the plane.
    pub point: [f32; 3],
    /// Its unit normal.
    pub normal: [f32; 3],
    /// The square's centre.
    pub centre: [f32; 3],
    /// Half its side.
    pub half_size: f32,
    /// Exported rays that meet the plane inside their interval (all meet the square).
    pub rays_meeting_plane: usize,
}

/// One file of rays.
#[derive(Clone, Debug, Serialize)]
pub struct RaySet {
    /// The file (origin x y z, direction x y z, f32 each).
    pub file: &'static str,
    /// Rays in it.
    pub count: usize,
    /// Incoherent rays: the box their origins are uniform in.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub box_min: Option<[f32; 3]>,
    /// The box's largest corner.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub box_max: Option<[f32; 3]>,
    /// Incoherent rays: the seed they were drawn with.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
}

/// Triangles gathered in world space.
#[derive(Default)]
struct Soup {
    vertices: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    geometries: Vec<Geometry>,
}

impl Soup {
    /// Appends one object's vertices and its triangles (indices local to them).
    fn add(
        &mut self,
        name: String,
        kind: &'static str,
        vertices: impl IntoIterator<Item = Vec3>,
        triangles: &[[u32; 3]],
    ) -> Result<()> {
        let first_vertex = self.vertices.len();
        self.vertices.extend(vertices);
        let base = u32::try_from(first_vertex).context("more than 2³² vertices")?;
        let first_triangle = self.triangles.len();
        self.triangles
            .extend(triangles.iter().map(|t| t.map(|i| base + i)));
        self.geometries.push(Geometry {
            name,
            kind,
            first_vertex,
            vertices: self.vertices.len() - first_vertex,
            first_triangle,
            triangles: triangles.len(),
            square: None,
        });
        Ok(())
    }
}

/// Writes `scene` (already at the benchmark's image size) and the rays the
/// benchmark casts in it to `dir` (created if needed), with a manifest
/// without raylab's figures; returns that manifest.
pub fn export(scene: &Scene, label: &str, dir: &Path) -> Result<Manifest> {
    let world = World::from_scene(scene)?;
    renderer::film::image_memory::check_world_fits(&world)?;
    let primary = renderer::diagnostics::throughput::primary_rays(&world);
    let incoherent = trace::incoherent_rays(&world);
    let all_rays = || {
        primary
            .iter()
            .chain(incoherent.iter().flat_map(|(_, rays)| rays.iter()))
    };
    let (t_min, t_max) = interval(all_rays())?;
    let around = incoherent.as_ref().map(|((lo, hi), _)| (*lo + *hi) / 2.0);

    let mut soup = Soup::default();
    for (id, object) in world.objects.iter().enumerate() {
        let name = world.names.get(id).cloned().unwrap_or_default();
        match object {
            Object::Model { instances } => {
                let several = instances.len() > 1;
                for (k, instance) in instances.clone().enumerate() {
                    let placed = &world.meshes[instance as usize];
                    let name = if several {
                        format!("{name}#{k}")
                    } else {
                        name.clone()
                    };
                    let vertices = placed
                        .mesh
                        .positions
                        .iter()
                        .map(|&p| placed.instance.point_to_world(p));
                    soup.add(name, "mesh", vertices, &placed.mesh.triangles)?;
                }
            }
            Object::Shape(Shape::Triangle(t)) => {
                soup.add(name, "triangle", [t.t0, t.t1, t.t2], &[[0, 1, 2]])?;
            }
            Object::Shape(Shape::Plane(plane)) => {
                let (corners, square) =
                    plane_square(plane, around.unwrap_or(plane.point), all_rays());
                soup.add(name, "plane", corners, &[[0, 1, 2], [0, 2, 3]])?;
                if let Some(g) = soup.geometries.last_mut() {
                    g.square = Some(square);
                }
            }
            Object::Shape(other) => bail!(
                "{name}: a {} has no triangle form; an export holds meshes, triangles and planes only",
                other.kind_name()
            ),
        }
    }

    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    write_f32s(
        &dir.join(VERTICES),
        soup.vertices.iter().flat_map(|v| v.to_array()),
    )?;
    write_u32s(
        &dir.join(TRIANGLES),
        soup.triangles.iter().flatten().copied(),
    )?;
    write_rays(&dir.join(PRIMARY), &primary)?;
    let incoherent = match &incoherent {
        Some(((lo, hi), rays)) => {
            write_rays(&dir.join(INCOHERENT), rays)?;
            Some(RaySet {
                file: INCOHERENT,
                count: rays.len(),
                box_min: Some(lo.to_array()),
                box_max: Some(hi.to_array()),
                seed: Some(trace::INCOHERENT_SEED),
            })
        }
        None => None,
    };
    let manifest = Manifest {
        format: "raylab-bench-export 1",
        scene: label.to_owned(),
        width: world.camera.w,
        height: world.camera.h,
        vertices_file: VERTICES,
        vertices: soup.vertices.len(),
        triangles_file: TRIANGLES,
        triangles: soup.triangles.len(),
        geometries: soup.geometries,
        t_min,
        t_max,
        primary: RaySet {
            file: PRIMARY,
            count: primary.len(),
            box_min: None,
            box_max: None,
            seed: None,
        },
        incoherent,
        raylab: None,
    };
    write_manifest(dir, &manifest)?;
    Ok(manifest)
}

/// Writes `manifest` as `DIR/manifest.json`.
pub fn write_manifest(dir: &Path, manifest: &Manifest) -> Result<()> {
    let path = dir.join(MANIFEST);
    std::fs::write(&path, serde_json::to_string_pretty(manifest)? + "\n")
        .with_context(|| format!("writing {}", path.display()))
}

/// The interval every ray shares (+∞ written as the largest f32).
fn interval<'a>(mut rays: impl Iterator<Item = &'a Ray>) -> Result<(f32, f32)> {
    let Some(first) = rays.next() else {
        return Ok((0.0, f32::MAX));
    };
    if rays.any(|r| r.t_min != first.t_min || r.t_max != first.t_max) {
        bail!("the rays do not share one interval; the export format assumes they do");
    }
    Ok((first.t_min, first.t_max.min(f32::MAX)))
}

/// Two unit axes spanning the plane of unit normal `n`: the coordinate
/// axes when `n` is one, so that a square on a floor has exactly the
/// floor's height at every corner.
fn plane_axes(n: Vec3) -> (Vec3, Vec3) {
    if n.x == 0.0 && n.y == 0.0 {
        (Vec3::X, Vec3::Y)
    } else if n.x == 0.0 && n.z == 0.0 {
        (Vec3::Z, Vec3::X)
    } else if n.y == 0.0 && n.z == 0.0 {
        (Vec3::Y, Vec3::Z)
    } else {
        n.any_orthonormal_pair()
    }
}

/// The square of `plane` centred where `around` projects onto it, 1% (plus
/// one unit) larger than needed for every ray of `rays` that meets the plane
/// inside its interval to meet it inside the square; its corners in order
/// around it.
fn plane_square<'a>(
    plane: &Plane,
    around: Vec3,
    rays: impl Iterator<Item = &'a Ray>,
) -> ([Vec3; 4], Square) {
    let (u, v) = plane_axes(plane.normal);
    let s = plane.point;
    let (cu, cv) = ((around - s).dot(u), (around - s).dot(v));
    let (mut reach, mut meeting) = (0.0f32, 0usize);
    for ray in rays {
        let Some(alpha) = plane.intersect(ray) else {
            continue;
        };
        let d = ray.at(alpha) - s;
        let e = (d.dot(u) - cu).abs().max((d.dot(v) - cv).abs());
        if e.is_finite() {
            reach = reach.max(e);
            meeting += 1;
        }
    }
    let half = (reach * 1.01 + 1.0).min(1e15);
    let corner = |a: f32, b: f32| s + (cu + a * half) * u + (cv + b * half) * v;
    let corners = [
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
    ];
    let square = Square {
        point: s.to_array(),
        normal: plane.normal.to_array(),
        centre: (s + cu * u + cv * v).to_array(),
        half_size: half,
        rays_meeting_plane: meeting,
    };
    (corners, square)
}

fn write_f32s(path: &Path, values: impl Iterator<Item = f32>) -> Result<()> {
    write_bytes(path, values.map(f32::to_le_bytes))
}

fn write_u32s(path: &Path, values: impl Iterator<Item = u32>) -> Result<()> {
    write_bytes(path, values.map(u32::to_le_bytes))
}

fn write_rays(path: &Path, rays: &[Ray]) -> Result<()> {
    write_f32s(
        path,
        rays.iter()
            .flat_map(|r| r.origin.to_array().into_iter().chain(r.dir.to_array())),
    )
}

fn write_bytes(path: &Path, chunks: impl Iterator<Item = [u8; 4]>) -> Result<()> {
    let context = || format!("writing {}", path.display());
    let mut out = BufWriter::new(File::create(path).with_context(context)?);
    for chunk in chunks {
        out.write_all(&chunk).with_context(context)?;
    }
    out.flush().with_context(context)
}

#[cfg(test)]
mod tests {
    use super::*;
    use renderer::integrator::sampler::Sampler;

    /// True when `p` (in the plane y = 0) lies inside the square `c`.
    fn inside_floor_square(c: &[Vec3; 4], p: Vec3) -> bool {
        let (lo, hi) = (c[0].min(c[2]), c[0].max(c[2]));
        p.x >= lo.x && p.x <= hi.x && p.z >= lo.z && p.z <= hi.z
    }

    #[test]
    fn every_ray_that_meets_the_floor_meets_its_square_whose_corners_lie_exactly_on_it() {
        let floor = Plane::new(Vec3::new(0.0, 0.25, 0.0), Vec3::Y);
        // Origins above and below, directions down to grazing ones.
        let mut rays: Vec<Ray> = (0..20_000u32)
            .map(|k| {
                let mut s = Sampler::for_sample(3, k, 0, 0);
                let o = Vec3::new(s.next_f32() * 4.0 - 2.0, s.next_f32() * 2.0, 1.0);
                Ray::new(o, s.next_direction())
            })
            .collect();
        rays.push(Ray::new(Vec3::Y, Vec3::new(1.0, -1e-6, 0.0)));
        let (corners, square) = plane_square(&floor, Vec3::new(0.0, 1.0, 0.0), rays.iter());
        assert!(corners.iter().all(|c| c.y == 0.25), "{corners:?}");
        assert!(square.half_size > 7e5, "the grazing ray lands far away");
        let meeting: Vec<Vec3> = rays
            .iter()
            .filter_map(|r| floor.intersect(r).map(|a| r.at(a)))
            .collect();
        assert_eq!(meeting.len(), square.rays_meeting_plane);
        assert!(meeting.len() > 9_000);
        for p in meeting {
            assert!(inside_floor_square(&corners, p), "{p}");
        }
    }

    #[test]
    fn a_plane_of_any_orientation_gets_a_square_in_it_around_the_scene() {
        let plane = Plane::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 1.0, -0.5));
        let rays = [Ray::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0).normalize())];
        let (corners, square) = plane_square(&plane, Vec3::splat(10.0), rays.iter());
        for c in corners {
            let off = plane.normal.dot(c - plane.point);
            assert!(off.abs() < 1e-4 * square.half_size, "{c} is {off} off");
        }
        let centre = Vec3::from_array(square.centre);
        assert!((centre - Vec3::splat(10.0)).cross(plane.normal).length() < 1e-4);
        assert_eq!(square.rays_meeting_plane, 1);
    }

    #[test]
    fn a_sphere_cannot_be_exported_and_says_so() {
        let (scene, label) = crate::bench::scene_spec::load("spheres:3", Path::new("unused.xml"))
            .expect("generates");
        let dir = std::env::temp_dir().join(format!("raylab-export-{}", std::process::id()));
        let err = export(&scene, &label, &dir).expect_err("spheres have no triangles");
        assert!(err.to_string().contains("sphere"), "{err}");
    }
}
