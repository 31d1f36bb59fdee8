//! Meshes from model files, generated in code: placed instances hit where
//! the same triangles as lone `<triangle>`s are hit, shading interpolates
//! vertex normals and texture coordinates, and moving an object keeps its
//! mesh's BVH.

use glam::{Mat4, Vec2, Vec3};
use renderer::World;
use renderer::film::aov::{Aov, render_aov};
use renderer::geometry::ray::Ray;
use renderer::shading::bsdf::PreparedBsdf;
use renderer::shapes::Method;
use scene::{
    MeshInstance, MeshSource, ModelFile, ModelMaterial, Object, Scene, Shape, Texture,
    TriangleMesh, Wrap,
};
use std::sync::Arc;

/// A unit quad in the xy-plane facing +z: corners (0,0), (1,0), (1,1), (0,1),
/// texture coordinates equal to x and 1 − y.
fn quad() -> TriangleMesh {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    TriangleMesh {
        normals: TriangleMesh::face_normals_per_vertex(&positions, &triangles),
        uvs: positions
            .iter()
            .map(|p| Vec2::new(p.x, 1.0 - p.y))
            .collect(),
        positions,
        triangles,
    }
}

/// A model holding `mesh` once per transform, with one matte material.
fn model(mesh: TriangleMesh, transforms: &[Mat4]) -> ModelFile {
    let mut model = ModelFile::default();
    model.meshes = vec![Arc::new(mesh)];
    model.materials = vec![ModelMaterial {
        material: scene::materials::builtin(scene::BaseMaterial::Matte),
        base_color_texture: None,
    }];
    model.instances = transforms
        .iter()
        .enumerate()
        .map(|(k, &t)| MeshInstance {
            mesh: 0,
            material: 0,
            model_from_mesh: t,
            name: format!("instance {k}"),
        })
        .collect();
    model
}

/// A scene with the model placed at `translate`, seen from z = 5.
fn scene_with(model: Arc<ModelFile>, translate: Vec3) -> Scene {
    let mut scene = scene::read_str(
        r#"<scene><camera eye="0.5 0.5 5" toward="0 0 -1" theta="15" width="48" height="48"/></scene>"#,
        "mesh.xml",
    )
    .expect("parses");
    scene.objects.push(Object {
        name: Some("model".into()),
        shape: Shape::Mesh {
            source: MeshSource {
                src: "generated".into(),
                model,
            },
            translate: Some(translate),
            rotate: Vec3::ZERO,
            scale: Vec3::ONE,
        },
        material: None,
        params: Default::default(),
    });
    scene
}

#[test]
fn placed_instances_hit_where_the_same_lone_triangles_do() {
    // Two instances: one as is, one rotated 30° about y and moved back.
    let moved = Mat4::from_translation(Vec3::new(-0.6, -0.4, -1.0)) * Mat4::from_rotation_y(0.5);
    let transforms = [Mat4::IDENTITY, moved];
    let mesh = quad();
    let world = World::from_scene(&scene_with(
        Arc::new(model(mesh.clone(), &transforms)),
        Vec3::ZERO,
    ))
    .expect("valid");
    // The same four triangles written out as <triangle> elements.
    let mut xml = String::from(
        r#"<scene><camera eye="0.5 0.5 5" toward="0 0 -1" theta="15" width="48" height="48"/>"#,
    );
    for t in transforms {
        for [a, b, c] in &mesh.triangles {
            let p = |k: &u32| t.transform_point3(mesh.positions[*k as usize]);
            let v = |q: Vec3| format!("{} {} {}", q.x, q.y, q.z);
            xml += &format!(
                r#"<triangle t0="{}" t1="{}" t2="{}"/>"#,
                v(p(a)),
                v(p(b)),
                v(p(c))
            );
        }
    }
    xml += "</scene>";
    let lone =
        World::from_scene(&scene::read_str(&xml, "lone.xml").expect("parses")).expect("valid");
    let (a, b) = (
        render_aov(&world, Aov::Depth, Method::Robust),
        render_aov(&lone, Aov::Depth, Method::Robust),
    );
    let hits = a.iter().filter(|d| d.is_finite()).count();
    assert!(
        hits > 200,
        "the quads fill part of the image: {hits} pixels"
    );
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert_eq!(x.is_finite(), y.is_finite(), "pixel {k}: {x} vs {y}");
        if x.is_finite() {
            assert!((x - y).abs() <= 1e-5 * y, "pixel {k}: α {x} vs {y}");
        }
    }
}

#[test]
fn the_hit_point_lies_on_the_placed_triangle_with_its_normal() {
    let world = World::from_scene(&scene_with(
        Arc::new(model(quad(), &[Mat4::IDENTITY])),
        Vec3::new(0.0, 0.0, 1.0),
    ))
    .expect("valid");
    let ray = Ray::new(Vec3::new(0.25, 0.5, 5.0), Vec3::NEG_Z);
    let hit = world
        .intersect(&ray, Method::Robust)
        .expect("hits the quad");
    assert_eq!(hit.alpha, 4.0);
    let triangle = hit.triangle.expect("a mesh hit names its triangle");
    assert_eq!(triangle.triangle, 1, "x < y lies in the second triangle");
    let surface = world.surface(&ray, hit);
    assert!((surface.point - Vec3::new(0.25, 0.5, 1.0)).length() < 1e-6);
    assert_eq!(surface.normal, Vec3::Z);
}

#[test]
fn shading_normals_interpolate_the_vertex_normals() {
    // Tilt the vertex normals of the quad's right edge toward +x.
    let mut mesh = quad();
    let tilted = Vec3::new(1.0, 0.0, 1.0).normalize();
    mesh.normals[1] = tilted;
    mesh.normals[2] = tilted;
    let world = World::from_scene(&scene_with(
        Arc::new(model(mesh, &[Mat4::IDENTITY])),
        Vec3::ZERO,
    ))
    .expect("valid");
    for x in [0.0f32, 0.5, 1.0] {
        let ray = Ray::new(Vec3::new(x.clamp(0.01, 0.99), 0.2, 5.0), Vec3::NEG_Z);
        let hit = world.intersect(&ray, Method::Robust).expect("hits");
        let n = world.shading_normal(hit, &world.surface(&ray, hit));
        let expected = (Vec3::Z.lerp(tilted, x.clamp(0.01, 0.99))).normalize();
        assert!((n - expected).length() < 1e-5, "x {x}: {n} vs {expected}");
    }
}

/// A 2×1 texture, its left half red and its right half blue, clamped at
/// the edges.
fn red_blue_texture() -> Arc<Texture> {
    Arc::new(Texture {
        width: 2,
        height: 1,
        texels: vec![[255, 0, 0, 255], [0, 0, 255, 255]].into(),
        wrap_u: Wrap::ClampToEdge,
        wrap_v: Wrap::ClampToEdge,
    })
}

#[test]
fn a_base_colour_texture_multiplies_the_albedo_at_the_interpolated_uv() {
    let mut model = model(quad(), &[Mat4::IDENTITY]);
    model.textures = vec![red_blue_texture()];
    model.materials[0].material.color = Vec3::splat(0.5);
    model.materials[0].base_color_texture = Some(0);
    let world = World::from_scene(&scene_with(Arc::new(model), Vec3::ZERO)).expect("valid");
    let albedo_at = |x: f32| {
        let ray = Ray::new(Vec3::new(x, 0.5, 5.0), Vec3::NEG_Z);
        let hit = world.intersect(&ray, Method::Robust).expect("hits");
        world.material(hit).color
    };
    assert_eq!(albedo_at(0.1), Vec3::new(0.5, 0.0, 0.0));
    assert_eq!(albedo_at(0.9), Vec3::new(0.0, 0.0, 0.5));
}

#[test]
fn a_hits_surface_looked_up_at_once_is_what_the_separate_look_ups_give() {
    // A textured, tilted-normal mesh and, in the knot scene, mesh instances,
    // spheres and an infinite plane.
    let mut textured = model(quad(), &[Mat4::IDENTITY]);
    textured.textures = vec![red_blue_texture()];
    textured.materials[0].base_color_texture = Some(0);
    let mut knot = scene::generate::knot_scene(3000);
    knot.objects
        .extend(scene::generate::spheres_scene(40).objects);
    (knot.camera.width, knot.camera.height) = (64, 36);
    for scene in [scene_with(Arc::new(textured), Vec3::ZERO), knot] {
        let world = World::from_scene(&scene).expect("world");
        let mut hits = 0;
        for ray in renderer::diagnostics::throughput::primary_rays(&world) {
            let Some(hit) = world.intersect(&ray, Method::Robust) else {
                continue;
            };
            hits += 1;
            let at = world.hit_surface(&ray, &hit);
            let surface = world.surface(&ray, hit);
            let material = world.material(hit);
            assert_eq!(at.surface, surface);
            assert_eq!(at.shading_normal, world.shading_normal(hit, &surface));
            assert_eq!(
                scene::Material {
                    color: at.color,
                    ..*at.material
                },
                material
            );
            assert_eq!(*at.bsdf, PreparedBsdf::new(&material));
        }
        assert!(hits > 100, "{hits} hits");
    }
}

#[test]
fn moving_a_mesh_object_keeps_its_bottom_level_bvh() {
    let model = Arc::new(model(quad(), &[Mat4::IDENTITY]));
    let before = World::from_scene(&scene_with(model.clone(), Vec3::ZERO)).expect("valid");
    let after = World::from_scene(&scene_with(model, Vec3::new(0.0, 1.0, 0.0))).expect("valid");
    assert!(Arc::ptr_eq(before.meshes[0].bvh(), after.meshes[0].bvh()));
    assert_ne!(before.meshes[0].bounds, after.meshes[0].bounds);
}

#[test]
fn a_material_on_the_mesh_element_replaces_the_files_materials() {
    let model = Arc::new(model(quad(), &[Mat4::IDENTITY]));
    let mut scene = scene_with(model, Vec3::ZERO);
    scene.objects[0].params.color = Some(Vec3::new(0.1, 0.2, 0.3));
    let world = World::from_scene(&scene).expect("valid");
    let ray = Ray::new(Vec3::new(0.5, 0.5, 5.0), Vec3::NEG_Z);
    let hit = world.intersect(&ray, Method::Robust).expect("hits");
    assert_eq!(world.material(hit).color, Vec3::new(0.1, 0.2, 0.3));
}

#[test]
fn a_model_is_drawn_in_its_files_material_colour_unless_overridden() {
    let mut model = model(quad(), &[Mat4::IDENTITY]);
    model.materials[0].material.color = Vec3::new(0.9, 0.8, 0.1);
    let model = Arc::new(model);
    let world = World::from_scene(&scene_with(model.clone(), Vec3::ZERO)).expect("valid");
    assert_eq!(world.object_color(0), Vec3::new(0.9, 0.8, 0.1));
    let mut painted = scene_with(model, Vec3::ZERO);
    painted.objects[0].params.color = Some(Vec3::new(0.1, 0.2, 0.3));
    let world = World::from_scene(&painted).expect("valid");
    assert_eq!(world.object_color(0), Vec3::new(0.1, 0.2, 0.3));
}

#[test]
fn a_batch_of_rays_finds_the_same_hits_as_ray_by_ray() {
    // Two mesh instances (knot, floor square), 40 spheres and an infinite
    // floor plane lying exactly in the floor square (a tie the square wins).
    let mut scene = scene::generate::knot_scene(3000);
    scene
        .objects
        .extend(scene::generate::spheres_scene(40).objects);
    (scene.camera.width, scene.camera.height) = (64, 36);
    let world = World::from_scene(&scene).expect("world");
    let mut rays = renderer::diagnostics::throughput::primary_rays(&world);
    rays.extend(renderer::diagnostics::throughput::incoherent_rays(
        Vec3::splat(-4.0),
        Vec3::splat(4.0),
        3000,
        7,
    ));
    let mut hits = vec![None; rays.len()];
    world.intersect_batch(&rays, Method::Robust, &mut hits);
    let objects: std::collections::HashSet<u32> = hits.iter().flatten().map(|h| h.object).collect();
    assert!(
        objects.len() > 20,
        "the rays should meet many objects: {objects:?}"
    );
    for (ray, hit) in rays.iter().zip(&hits) {
        assert_eq!(*hit, world.intersect(ray, Method::Robust), "{ray:?}");
    }
}

#[test]
fn a_batch_of_rays_breaks_ties_between_objects_as_ray_by_ray() {
    // Two instances of one quad at the same place, a second model of it
    // placed there too, a lone quad of two triangles in the same plane and
    // a box whose face lies in it: every hit is a tie, which the lower
    // top-level item wins one ray at a time; the batch must agree, its
    // camera rays going as packets.
    let mut scene = scene_with(
        Arc::new(model(quad(), &[Mat4::IDENTITY, Mat4::IDENTITY])),
        Vec3::ZERO,
    );
    let again = scene.objects[0].clone();
    let extra = scene::read_str(
        r#"<scene>
             <triangle t0="0 0 0" t1="1 0 0" t2="1 1 0"/>
             <triangle t0="0 0 0" t1="1 1 0" t2="0 1 0"/>
             <box center="0.5 0.5 -0.25" size="1 1 0.5"/>
           </scene>"#,
        "extra.xml",
    )
    .expect("parses");
    // The lone shapes first: their items are the lower ones.
    let first = std::mem::take(&mut scene.objects);
    scene.objects.extend(extra.objects);
    scene.objects.extend(first);
    scene.objects.push(again);
    let world = World::from_scene(&scene).expect("world");
    let rays = renderer::diagnostics::throughput::primary_rays(&world);
    let mut hits = vec![None; rays.len()];
    world.intersect_batch(&rays, Method::Robust, &mut hits);
    let objects: std::collections::HashSet<u32> = hits.iter().flatten().map(|h| h.object).collect();
    assert!(
        objects.contains(&0),
        "the lone triangles win the ties: {objects:?}"
    );
    for (ray, hit) in rays.iter().zip(&hits) {
        assert_eq!(*hit, world.intersect(ray, Method::Robust), "{ray:?}");
    }
}

#[test]
fn meshes_in_the_films_passes_are_the_samples_traced_alone_for_both_integrators() {
    use renderer::RenderOptions;
    use renderer::integrator::sampler::Sampling;
    use renderer::integrator::{Integrator, SampleRef, SampleResult, sample_pixel, trace_samples};
    // The film's batches against each sample traced alone, on meshes with
    // interpolated normals: two instances, a lone sphere, a light, the sky.
    let moved = Mat4::from_translation(Vec3::new(-0.6, -0.4, -1.0)) * Mat4::from_rotation_y(0.5);
    let mut scene = scene_with(
        Arc::new(model(quad(), &[Mat4::IDENTITY, moved])),
        Vec3::ZERO,
    );
    let extra = scene::read_str(
        r#"<scene><sky color="0.3 0.4 0.5"/><light position="1 2 3" intensity="6"/>
           <sphere center="1.2 0.2 -0.5" radius="0.3" material="matte" color="0.8 0.3 0.3"/></scene>"#,
        "extra.xml",
    )
    .expect("parses");
    scene.objects.extend(extra.objects);
    scene.lights.extend(extra.lights);
    scene.sky = extra.sky;
    let (width, height) = (16, 16);
    scene.camera.width = width;
    scene.camera.height = height;
    let world = World::from_scene(&scene).expect("valid");
    for (integrator, sampling) in [
        (Integrator::Path, Sampling::Independent),
        (Integrator::Path, Sampling::Sobol),
        (Integrator::Whitted, Sampling::Independent),
    ] {
        let options = RenderOptions {
            integrator,
            sampling,
            seed: 3,
            ..RenderOptions::default()
        };
        let samples: Vec<SampleRef> = (0..2)
            .flat_map(|sample| {
                (0..height).flat_map(move |j| (0..width).map(move |i| SampleRef { i, j, sample }))
            })
            .collect();
        let mut results = vec![SampleResult::default(); samples.len()];
        trace_samples(&world, &options, &samples, &mut results);
        let mut lit = 0;
        for (s, result) in samples.iter().zip(&results) {
            let alone = sample_pixel(&world, &options, s.i, s.j, s.sample);
            assert_eq!(
                result.radiance.to_array().map(f32::to_bits),
                alone.to_array().map(f32::to_bits),
                "sample {s:?}"
            );
            lit += usize::from(alone != Vec3::ZERO);
        }
        assert!(
            lit > samples.len() / 2,
            "{lit} of {} samples lit",
            samples.len()
        );
    }
}

#[test]
fn whitted_traces_camera_rays_in_batches_as_each_sample_alone_with_its_own_cost() {
    use renderer::RenderOptions;
    use renderer::integrator::{Integrator, SampleRef, SampleResult, sample_pixel, trace_samples};
    // The knot (a mesh instance), its floor square, 40 spheres and the
    // infinite plane in the floor: camera rays go through the mesh as a
    // batch (coherent ones as packets). The 40 spheres alone: camera rays
    // go as packets through the packet tree (more than 20 primitives).
    let mut knot = scene::generate::knot_scene(3000);
    knot.objects
        .extend(scene::generate::spheres_scene(40).objects);
    let mut spheres = scene::generate::spheres_scene(40);
    // Without its infinite floor, which packets do not test.
    spheres
        .objects
        .retain(|o| !matches!(o.shape, scene::Shape::Floor { .. }));
    let (width, height) = (48, 28);
    let options = RenderOptions {
        integrator: Integrator::Whitted,
        ..RenderOptions::default()
    };
    for (name, mut scene) in [("knot", knot), ("spheres", spheres)] {
        (scene.camera.width, scene.camera.height) = (width, height);
        let world = World::from_scene(&scene).expect("world");
        let mut on_mesh = 0;
        let mut hits = 0;
        // Band by band (four rows), each in strips of 20 columns, every
        // row of a strip in turn, as a pass gathers them (so in 4 × 4
        // tiles); then the same list shifted by five samples, which puts
        // each sample in a batch with other neighbours.
        for band in 0..height / 4 {
            let samples: Vec<SampleRef> = (0..width)
                .step_by(20)
                .flat_map(|start| {
                    (4 * band..4 * band + 4).flat_map(move |j| {
                        (start..(start + 20).min(width)).map(move |i| SampleRef { i, j, sample: 1 })
                    })
                })
                .collect();
            let mut shifted = samples.clone();
            shifted.rotate_left(5);
            let mut results = vec![SampleResult::default(); samples.len()];
            let mut results_shifted = results.clone();
            trace_samples(&world, &options, &samples, &mut results);
            trace_samples(&world, &options, &shifted, &mut results_shifted);
            results_shifted.rotate_right(5);
            for ((s, result), other) in samples.iter().zip(&results).zip(&results_shifted) {
                let alone = sample_pixel(&world, &options, s.i, s.j, s.sample);
                assert_eq!(
                    result.radiance.to_array().map(f32::to_bits),
                    alone.to_array().map(f32::to_bits),
                    "{name}: sample {s:?}"
                );
                assert_eq!(result, other, "{name}: sample {s:?}: its cost is its own");
                let ray = world.camera.ray(s.i, s.j, glam::Vec2::splat(0.5));
                let hit = world.intersect(&ray, Method::Robust);
                hits += usize::from(hit.is_some());
                on_mesh += usize::from(hit.is_some_and(|h| h.triangle.is_some()));
            }
        }
        let all = (width * height) as usize;
        assert!(hits > all / 10, "{name}: {hits} of {all} camera rays hit");
        if name == "knot" {
            assert!(
                on_mesh > all / 4,
                "{on_mesh} of {all} camera rays meet a mesh"
            );
        }
    }
}
