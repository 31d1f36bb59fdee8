//! Scenes generated in code, for benchmarks and tests (no downloads): a
//! torus-knot tube mesh of any triangle count and a field of spheres.

use crate::mesh::TriangleMesh;
use crate::model::model_file::{MeshInstance, ModelFile, ModelMaterial};
use crate::model::{Camera, MeshSource, Object, Scene, Shape};
use glam::{Mat4, Vec3};
use std::f32::consts::TAU;
use std::sync::Arc;

/// Sides of the knot's tube cross-section.
const TUBE_SIDES: u32 = 40;

/// A (p, q) torus knot swept by a circular tube: `segments × TUBE_SIDES × 2`
/// triangles with `segments` chosen so the count is the multiple of
/// 2 · TUBE_SIDES nearest to `triangles` (at least 3 segments). The knot
/// winds p times around the y axis and q times through the hole; it fits in
/// a box about 6 wide and 2 high, centred on the origin. Vertex normals point
/// out of the tube.
pub fn torus_knot(p: u32, q: u32, triangles: usize) -> TriangleMesh {
    let per_segment = 2 * TUBE_SIDES as usize;
    let segments = ((triangles + per_segment / 2) / per_segment).max(3) as u32;
    let (major, minor, tube) = (2.0f32, 0.8f32, 0.35f32);
    let (pf, qf) = (p as f32, q as f32);
    // The knot's centre line at parameter s ∈ [0, 2π).
    let curve = |s: f32| {
        let r = major + minor * (qf * s).cos();
        Vec3::new(
            r * (pf * s).cos(),
            minor * (qf * s).sin(),
            r * (pf * s).sin(),
        )
    };
    let mut positions = Vec::with_capacity((segments * TUBE_SIDES) as usize);
    let mut normals = Vec::with_capacity(positions.capacity());
    for k in 0..segments {
        let s = TAU * k as f32 / segments as f32;
        let centre = curve(s);
        let ds = 1e-3;
        let tangent = (curve(s + ds) - curve(s - ds)).normalize();
        // A frame around the tangent: the normal points away from the y axis.
        let outward = (centre - centre.dot(Vec3::Y) * Vec3::Y).normalize_or(Vec3::X);
        let normal = (outward - outward.dot(tangent) * tangent).normalize();
        let binormal = tangent.cross(normal);
        for side in 0..TUBE_SIDES {
            let a = TAU * side as f32 / TUBE_SIDES as f32;
            let n = a.cos() * normal + a.sin() * binormal;
            positions.push(centre + tube * n);
            normals.push(n);
        }
    }
    let index = |k: u32, side: u32| (k % segments) * TUBE_SIDES + side % TUBE_SIDES;
    let mut tris = Vec::with_capacity((segments * TUBE_SIDES * 2) as usize);
    for k in 0..segments {
        for side in 0..TUBE_SIDES {
            let (a, b) = (index(k, side), index(k + 1, side));
            let (c, d) = (index(k + 1, side + 1), index(k, side + 1));
            // Counter-clockwise seen from outside the tube.
            tris.push([a, d, c]);
            tris.push([a, c, b]);
        }
    }
    TriangleMesh {
        positions,
        triangles: tris,
        normals,
        uvs: Vec::new(),
    }
}

/// A model file made in code holding `mesh` once, untransformed, with a
/// plastic material of colour `color`; `name` stands where a path would.
pub fn model_of(mesh: TriangleMesh, name: &str, color: Vec3) -> ModelFile {
    let mut model = ModelFile {
        path: name.into(),
        ..ModelFile::default()
    };
    let mut material = crate::materials::builtin(crate::BaseMaterial::Plastic);
    material.color = color;
    model.meshes = vec![Arc::new(mesh)];
    model.materials = vec![ModelMaterial {
        material,
        base_color_texture: None,
    }];
    model.instances = vec![MeshInstance {
        mesh: 0,
        material: 0,
        model_from_mesh: Mat4::IDENTITY,
        name: name.to_owned(),
    }];
    model
}

/// A square of half-size `half` in the plane y = 0, facing up: four
/// triangles around its centre.
pub fn floor_square(half: f32) -> TriangleMesh {
    let positions = vec![
        Vec3::new(-half, 0.0, -half),
        Vec3::new(half, 0.0, -half),
        Vec3::new(half, 0.0, half),
        Vec3::new(-half, 0.0, half),
        Vec3::ZERO,
    ];
    TriangleMesh {
        normals: vec![Vec3::Y; positions.len()],
        positions,
        // Counter-clockwise seen from above.
        triangles: vec![[0, 4, 1], [1, 4, 2], [2, 4, 3], [3, 4, 0]],
        uvs: Vec::new(),
    }
}

/// An object showing `model` with its origin at `translate`.
fn mesh_object(name: &str, model: ModelFile, translate: Vec3) -> Object {
    Object {
        name: Some(name.into()),
        shape: Shape::Mesh {
            source: MeshSource {
                src: model.path.display().to_string(),
                model: Arc::new(model),
            },
            translate: Some(translate),
            rotate: Vec3::ZERO,
            scale: Vec3::ONE,
        },
        material: None,
        params: Default::default(),
    }
}

/// The torus-knot benchmark scene, as the Embree and Mitsuba
/// figures were measured: a (2, 3) knot of about `triangles` triangles
/// resting on a 12 × 12 floor square of 4 more triangles, seen from the
/// front and above so that about two thirds of the primary rays hit
/// (the rest see the sky beyond the floor's edge).
pub fn knot_scene(triangles: usize) -> Scene {
    let mesh = torus_knot(2, 3, triangles);
    let knot = model_of(
        mesh,
        &format!("torus-knot-{}", triangles),
        Vec3::new(0.85, 0.55, 0.2),
    );
    let floor = model_of(floor_square(6.0), "floor-square", Vec3::splat(0.7));
    Scene {
        camera: Camera {
            eye: Some(Vec3::new(0.0, 5.65, 8.5)),
            toward: Some(Vec3::new(0.0, -5.1, -8.5)),
            theta_deg: 20.6,
            width: 1920,
            height: 1080,
            ..Camera::default()
        },
        objects: vec![
            mesh_object("torus knot", knot, Vec3::new(0.0, 1.15, 0.0)),
            mesh_object("floor", floor, Vec3::ZERO),
        ],
        ..Scene::default()
    }
}

/// `count` spheres of radius 0.2 to 0.5 scattered (reproducibly) over a
/// square on the floor, in a few colours, with a camera that frames them.
pub fn spheres_scene(count: usize) -> Scene {
    // A square grid big enough for `count` cells of 1.2 × 1.2, jittered.
    let side = (count as f32).sqrt().ceil().max(1.0) as usize;
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut next = move || {
        // xorshift64*: reproducible and dependency-free; quality is not at stake.
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32
    };
    let palette = [
        Vec3::new(0.8, 0.2, 0.2),
        Vec3::new(0.2, 0.6, 0.8),
        Vec3::new(0.9, 0.8, 0.3),
        Vec3::new(0.3, 0.7, 0.3),
    ];
    let half = 0.6 * side as f32;
    let mut objects: Vec<Object> = (0..count)
        .map(|k| {
            let radius = 0.2 + 0.3 * next();
            let (gx, gz) = ((k % side) as f32, (k / side) as f32);
            let x = 1.2 * gx - half + 0.6 + 0.2 * (next() - 0.5);
            let z = 1.2 * gz - half + 0.6 + 0.2 * (next() - 0.5);
            Object {
                name: None,
                shape: Shape::Sphere {
                    center: Some(Vec3::new(x, radius, z)),
                    radius,
                },
                material: Some("plastic".into()),
                params: crate::MaterialParams {
                    color: Some(palette[k % palette.len()]),
                    ..Default::default()
                },
            }
        })
        .collect();
    objects.push(Object {
        name: Some("floor".into()),
        shape: Shape::Floor { y: 0.0 },
        material: None,
        params: Default::default(),
    });
    Scene {
        camera: Camera {
            toward: Some(Vec3::new(0.0, -0.8, -1.0)),
            width: 1280,
            height: 720,
            ..Camera::default()
        },
        objects,
        ..Scene::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_knot_has_the_requested_triangle_count_and_a_closed_tube() {
        let mesh = torus_knot(2, 3, 10_000);
        assert_eq!(mesh.triangles.len(), 10_000);
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        // Closed: every edge is shared by exactly two triangles.
        let mut edges = std::collections::HashMap::new();
        for &[a, b, c] in &mesh.triangles {
            for (u, v) in [(a, b), (b, c), (c, a)] {
                *edges.entry((u.min(v), u.max(v))).or_insert(0) += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
        // Winding agrees with the outward vertex normals.
        for &[a, b, c] in &mesh.triangles {
            let p = |k: u32| mesh.positions[k as usize];
            let face = (p(b) - p(a)).cross(p(c) - p(a));
            assert!(face.dot(mesh.normals[a as usize]) > 0.0);
        }
    }

    #[test]
    fn a_million_triangle_knot_is_what_the_benchmark_asks_for() {
        assert_eq!(torus_knot(2, 3, 1_000_000).triangles.len(), 1_000_000);
    }

    #[test]
    fn the_sphere_field_has_the_requested_count_plus_a_floor() {
        let scene = spheres_scene(10_000);
        assert_eq!(scene.objects.len(), 10_001);
        let resolved = crate::resolve(&scene).expect("resolves");
        assert_eq!(resolved.objects.len(), 10_001);
    }
}
