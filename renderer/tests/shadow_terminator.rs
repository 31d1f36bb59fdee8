//! The shadow terminator of smooth-shaded meshes: a coarse sphere mesh with
//! vertex normals, lit from the side, shades like the sphere it stands for.
//! Without Hanika's offset the shadow rays of its flat triangles near the
//! terminator meet the neighbouring triangles (or the triangle itself) and
//! the lit side shows dark triangular patches along the triangles' edges.

use glam::{Mat4, Vec3};
use renderer::film::aov::{Aov, render_aov};
use renderer::integrator::Integrator;
use renderer::shapes::Method;
use renderer::{Film, RenderOptions, World};
use scene::{
    MeshInstance, MeshSource, ModelFile, ModelMaterial, Object, Scene, Shape, TriangleMesh,
};
use std::f32::consts::PI;
use std::sync::Arc;

/// Pixels nearer the outline than where the sphere's normal makes this
/// cosine with the view are left out: there the mesh's outline (a polygon
/// inside the circle) is hit at other points than the sphere.
const FACING: f32 = 0.3;

/// The matte albedo and the directional light's irradiance E.
const ALBEDO: f32 = 0.8;
const IRRADIANCE: f32 = 3.0;

/// The unit sphere at the origin as `bands` × 2·`bands` quads of two
/// triangles (one at the poles), each vertex with its exact unit normal:
/// 8 bands make triangles 22.5° across, as coarse as a low-polygon model's.
fn uv_sphere(bands: u32) -> TriangleMesh {
    let (nu, nv) = (2 * bands, bands);
    let mut positions = Vec::new();
    for u in 0..=nu {
        for v in 0..=nv {
            let (theta, phi) = (2.0 * PI * u as f32 / nu as f32, PI * v as f32 / nv as f32);
            positions.push(Vec3::new(
                phi.sin() * theta.cos(),
                phi.cos(),
                phi.sin() * theta.sin(),
            ));
        }
    }
    let index = |u: u32, v: u32| u * (nv + 1) + v;
    let mut triangles = Vec::new();
    for u in 0..nu {
        for v in 0..nv {
            let (a, b, c, d) = (
                index(u, v),
                index(u + 1, v),
                index(u + 1, v + 1),
                index(u, v + 1),
            );
            // Wound so that (t1 − t0) × (t2 − t0) points outward.
            if v > 0 {
                triangles.push([a, b, c]);
            }
            if v + 1 < nv {
                triangles.push([a, c, d]);
            }
        }
    }
    TriangleMesh {
        normals: positions.clone(),
        uvs: Vec::new(),
        positions,
        triangles,
    }
}

/// The scene around `shape`: a camera on +z, a directional light from the
/// right and a little behind (the terminator crosses the visible half), no
/// sky, a matte of albedo [`ALBEDO`].
fn lit_from_the_side(shape: Shape) -> World {
    let mut scene: Scene = scene::read_str(
        r#"<scene><camera eye="0 0 4" toward="0 0 -1" up="0 1 0" theta="16" width="96" height="96"/>
           <light type="directional" direction="-1 -0.3 0.5" intensity="3"/></scene>"#,
        "terminator.xml",
    )
    .expect("parses");
    scene.objects.push(Object {
        name: Some("ball".into()),
        shape,
        material: Some("matte".into()),
        params: scene::MaterialParams {
            color: Some(Vec3::splat(ALBEDO)),
            ..Default::default()
        },
    });
    World::from_scene(&scene).expect("valid")
}

fn mesh_sphere(bands: u32) -> World {
    let mut model = ModelFile::default();
    model.meshes = vec![Arc::new(uv_sphere(bands))];
    model.materials = vec![ModelMaterial {
        material: scene::materials::builtin(scene::BaseMaterial::Matte),
        base_color_texture: None,
    }];
    model.instances = vec![MeshInstance {
        mesh: 0,
        material: 0,
        model_from_mesh: Mat4::IDENTITY,
        name: "sphere".into(),
    }];
    lit_from_the_side(Shape::Mesh {
        source: MeshSource {
            src: "generated".into(),
            model: Arc::new(model),
        },
        translate: Some(Vec3::ZERO),
        rotate: Vec3::ZERO,
        scale: Vec3::ONE,
    })
}

fn analytic_sphere() -> World {
    lit_from_the_side(Shape::Sphere {
        center: Some(Vec3::ZERO),
        radius: 1.0,
    })
}

/// How much darker than the analytic sphere the mesh's darkest pixel on the
/// sphere's lit side is, in units of the fully lit radiance ρ/π · E (so 0.2
/// means "as dark as a cosine of 0.2 less"), over the pixels where both are
/// hit; and how many such pixels there are.
fn darkest_shortfall(integrator: Integrator, spp: u32, bands: u32) -> (f32, usize) {
    let options = RenderOptions {
        integrator,
        // Direct light only: nothing else in the scene lights the ball.
        max_depth: if integrator == Integrator::Path { 2 } else { 0 },
        ..Default::default()
    };
    let (mesh, sphere) = (mesh_sphere(bands), analytic_sphere());
    let covered = |world: &World| render_aov(world, Aov::Depth, Method::Robust);
    let (mesh_hits, sphere_hits) = (covered(&mesh), covered(&sphere));
    let sphere_normals = render_aov(&sphere, Aov::Normal, Method::Robust);
    // A pixel whose centre and neighbours' centres hit both, so that its
    // samples (anywhere in the pixel) do too.
    let (w, h) = (mesh.camera.w as i64, mesh.camera.h as i64);
    let inside = |k: usize| {
        let (i, j) = (k as i64 % w, k as i64 / w);
        (-1..=1).all(|dj| {
            (-1..=1).all(|di| {
                let (x, y) = (i + di, j + dj);
                let n = (y * w + x) as usize;
                (0..w).contains(&x)
                    && (0..h).contains(&y)
                    && mesh_hits[n].is_finite()
                    && sphere_hits[n].is_finite()
            })
        })
    };
    let (mesh_film, sphere_film) = (
        Film::render(&mesh, &options, spp),
        Film::render(&sphere, &options, spp),
    );
    let full = ALBEDO / PI * IRRADIANCE;
    let mut worst = 0.0f32;
    let mut lit = 0;
    for (k, (m, s)) in mesh_film
        .linear()
        .iter()
        .zip(sphere_film.linear())
        .enumerate()
    {
        if !inside(k) || s.x <= 0.0 || sphere_normals[3 * k + 2] < FACING {
            continue;
        }
        lit += 1;
        worst = worst.max((s.x - m.x) / full);
    }
    (worst, lit)
}

/// The bound: on the lit side no pixel of the 22.5° mesh is darker than
/// the analytic sphere's by more than 0.02 ρ/π · E. Without the offset
/// (shadow rays from the flat triangles) its darkest shortfall is 0.16 with
/// either integrator; with it, 0.
const BOUND: f32 = 0.02;

/// The lit side of the 22.5° mesh rendered by `integrator` at `spp`
/// stays within [`BOUND`] of the analytic sphere.
fn assert_lit_up_to_the_smooth_terminator(integrator: Integrator, spp: u32) {
    let (worst, lit) = darkest_shortfall(integrator, spp, 8);
    assert!(
        lit > 1000,
        "the lit side fills part of the image: {lit} pixels"
    );
    assert!(
        worst <= BOUND,
        "{integrator:?}: a lit pixel is {worst} of ρ/π·E darker than on the analytic sphere (bound {BOUND})"
    );
}

#[test]
fn whitted_a_coarse_sphere_mesh_is_lit_up_to_its_smooth_terminator() {
    assert_lit_up_to_the_smooth_terminator(Integrator::Whitted, 1);
}

#[test]
fn path_a_coarse_sphere_mesh_is_lit_up_to_its_smooth_terminator() {
    assert_lit_up_to_the_smooth_terminator(Integrator::Path, 4);
}
