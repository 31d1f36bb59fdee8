//! The wavefront path tracer computes exactly the scalar path tracer's
//! samples: every sample's radiance equal bit for bit to `sample_pixel`'s
//! (a `PathLane` traced alone, as the inspector traces it), whatever the
//! order and grouping of the samples.

use super::*;
use crate::integrator::sampler::Sampling;
use crate::integrator::{Integrator, sample_pixel};
use crate::shapes::Method;

/// A world read from a scene file's text, at `width` × `height`.
fn world_from(xml: &str, width: u32, height: u32) -> World {
    let mut scene = ::scene::read_str(xml, "test.xml").expect("scene parses");
    scene.camera.width = width;
    scene.camera.height = height;
    World::from_scene(&scene).expect("scene is valid")
}

/// The reference scenes' environment map (`assets/reference/sky_map.exr`:
/// a sky, a ground and a small bright sun) turned by `rotate` degrees.
fn sky_map(rotate: glam::Vec3) -> ::scene::Sky {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/reference/sky_map.exr"
    );
    let image = ::scene::load_sky_map(std::path::Path::new(path)).expect("the reference map");
    ::scene::Sky {
        color: glam::Vec3::new(0.9, 1.0, 0.8),
        map: Some(::scene::SkyMap {
            src: path.into(),
            image: std::sync::Arc::new(image),
        }),
        rotate,
        strength: 1.0,
    }
}

fn cornell(width: u32, height: u32) -> World {
    world_from(
        include_str!("../../../../assets/reference/cornell.xml"),
        width,
        height,
    )
}

fn path_options(sampling: Sampling, max_depth: u32, seed: u64) -> RenderOptions {
    RenderOptions {
        integrator: Integrator::Path,
        method: Method::Robust,
        max_depth,
        seed,
        sampling,
        ..RenderOptions::default()
    }
}

/// Every (pixel, sample) of a `width` × `height` image with `spp` samples.
fn all_samples(width: u32, height: u32, spp: u32) -> Vec<SampleRef> {
    let mut samples = Vec::new();
    for sample in 0..spp {
        for j in 0..height {
            for i in 0..width {
                samples.push(SampleRef { i, j, sample });
            }
        }
    }
    samples
}

/// Traces `samples` with the wavefront and checks each against the scalar path tracer.
fn assert_wavefront_equals_scalar(world: &World, options: &RenderOptions, samples: &[SampleRef]) {
    let scene = WavefrontScene::new(world, options.method);
    assert_scene_equals_scalar(world, scene, options, samples);
}

/// `world`'s wavefront view with every ray through its BVH, lane by lane,
/// even where packets would take them.
fn through_bvh(world: &World, method: Method) -> WavefrontScene {
    WavefrontScene {
        shapes: None,
        ..WavefrontScene::new(world, method)
    }
}

/// [`assert_wavefront_equals_scalar`] with the view `scene` of `world`.
fn assert_scene_equals_scalar(
    world: &World,
    scene: WavefrontScene,
    options: &RenderOptions,
    samples: &[SampleRef],
) {
    let mut results = vec![SampleResult::default(); samples.len()];
    // The widest lanes this CPU has, as a render runs them, then every
    // narrower lane type, each refilling lanes at once and by cohorts: all
    // give the same samples.
    trace_wavefront(world, &scene, options, samples, &mut results);
    for lanes in crate::simd::LaneType::available() {
        for cohort in COHORTS {
            let mut narrower = vec![SampleResult::default(); samples.len()];
            lanes.run(Trace {
                world,
                scene: &scene,
                options,
                samples,
                results: &mut narrower,
                cohort,
            });
            assert_eq!(
                narrower, results,
                "{lanes:?} lanes refilled by {cohort} and the widest agree"
            );
        }
    }
    let mut nonzero = 0;
    for (s, result) in samples.iter().zip(&results) {
        let scalar = sample_pixel(world, options, s.i, s.j, s.sample);
        assert_eq!(
            result.radiance.to_array().map(f32::to_bits),
            scalar.to_array().map(f32::to_bits),
            "sample {s:?}: wavefront {} vs scalar {scalar}",
            result.radiance
        );
        nonzero += usize::from(scalar != glam::Vec3::ZERO);
    }
    assert!(
        results.iter().any(|r| r.shape_tests > 0),
        "shape tests are counted"
    );
    if scene.shapes.is_none() {
        // Traced through the world, a sample costs the scalar lanes' tests.
        let mut lanes = vec![SampleResult::default(); samples.len()];
        crate::integrator::lanes::trace_lanes::<crate::integrator::path::PathLane<()>>(
            world, options, samples, 16, &mut lanes,
        );
        for ((s, wavefront), scalar) in samples.iter().zip(&results).zip(&lanes) {
            assert_eq!(
                wavefront.shape_tests, scalar.shape_tests,
                "shape tests of {s:?}"
            );
        }
    }
    // With direct light (depth 2 on), most samples carry light; with
    // emitters alone, some do.
    let expected = if options.max_depth >= 2 {
        samples.len() / 2
    } else {
        0
    };
    assert!(
        nonzero > expected,
        "{nonzero} of {} samples carry light",
        samples.len()
    );
}

/// [`assert_wavefront_equals_scalar`] over every pixel of `world`'s image,
/// `spp` samples each, with both samplers and each (max depth, seed).
fn assert_every_pixel_matches(world: &World, depths_and_seeds: &[(u32, u64)], spp: u32) {
    assert_every_pixel_matches_in(world, depths_and_seeds, spp, false);
}

/// [`assert_every_pixel_matches`], every ray through the world's BVH when
/// `bvh`.
fn assert_every_pixel_matches_in(
    world: &World,
    depths_and_seeds: &[(u32, u64)],
    spp: u32,
    bvh: bool,
) {
    let samples = all_samples(world.camera.w, world.camera.h, spp);
    for sampling in [Sampling::Independent, Sampling::Sobol] {
        for &(max_depth, seed) in depths_and_seeds {
            let options = path_options(sampling, max_depth, seed);
            let scene = if bvh {
                through_bvh(world, options.method)
            } else {
                WavefrontScene::new(world, options.method)
            };
            assert_scene_equals_scalar(world, scene, &options, &samples);
        }
    }
}

#[test]
fn every_cornell_sample_is_the_scalar_path_tracers_bit_for_bit() {
    let world = cornell(24, 24);
    assert_every_pixel_matches(&world, &[(8, 0), (2, 5), (1, 1), (30, 9)], 2);
}

#[test]
fn samples_do_not_depend_on_their_order_or_neighbours() {
    let world = cornell(12, 12);
    let options = path_options(Sampling::Sobol, 8, 3);
    let mut samples = all_samples(12, 12, 3);
    // Reverse, then interleave: every sample gets other lane neighbours.
    samples.reverse();
    let (a, b) = samples.split_at(samples.len() / 2);
    let shuffled: Vec<SampleRef> = a.iter().zip(b).flat_map(|(x, y)| [*y, *x]).collect();
    assert_wavefront_equals_scalar(&world, &options, &shuffled);
    // A lone sample (seven dead lanes) too.
    assert_wavefront_equals_scalar(&world, &options, &shuffled[..1]);
}

#[test]
fn a_world_with_spheres_boxes_a_sky_and_no_emitters_matches_too() {
    let world = world_from(
        r#"<scene>
  <camera eye="0 1 6" toward="0 -0.2 -1" up="0 1 0" theta="30" width="16" height="12"/>
  <sky color="0.4 0.5 0.7"/>
  <sphere center="0 0 0" radius="1" material="matte" color="0.8 0.3 0.2"/>
  <sphere center="1.5 0.5 -1" radius="0.5" material="matte" color="0.2 0.8 0.3" emission="2 2 2"/>
  <box center="-1.5 -0.5 0" size="1 1 1" rotate="10 30 0" material="matte" color="0.5 0.5 0.5"/>
  <triangle t0="-5 -1 5" t1="5 -1 5" t2="5 -1 -5" material="matte" color="0.7 0.7 0.7"/>
  <triangle t0="-5 -1 5" t1="5 -1 -5" t2="-5 -1 -5" material="matte" color="0.7 0.7 0.7"/>
</scene>"#,
        16,
        12,
    );
    assert_every_pixel_matches(&world, &[(8, 11)], 4);
}

#[test]
fn rough_conductors_and_rough_glass_on_lanes_match_too() {
    let world = world_from(
        include_str!("../../../../assets/reference/rough.xml"),
        20,
        20,
    );
    assert_every_pixel_matches(&world, &[(8, 2)], 3);
}

#[test]
fn every_material_matches_lanes_and_handed_over_alike() {
    let world = world_from(
        r#"<scene>
  <camera eye="0 1.5 7" toward="0 -0.3 -1" up="0 1 0" theta="28" width="20" height="14"/>
  <sky color="0.3 0.35 0.4"/>
  <sphere center="-2.4 0 0" radius="0.7" material="mirror" color="0.9 0.8 0.7"/>
  <sphere center="-0.8 0 0" radius="0.7" material="glass" ior="1.5"/>
  <sphere center="0.8 0 0" radius="0.7" material="plastic" color="0.2 0.4 0.8"/>
  <sphere center="2.4 0 0" radius="0.7" material="marble"/>
  <box center="0 1.6 -1" size="1 0.5 0.5" material="metal" color="0.9 0.6 0.3" roughness="0.2"/>
  <box center="1.5 1.6 -1" size="0.6 0.6 0.6" rotate="0 45 0" material="matte" color="0.7 0.7 0.7" reflectivity="0.3"/>
  <triangle t0="-1 3 -2" t1="1 3 -2" t2="0 3 0" material="matte" emission="6 6 5"/>
  <triangle t0="-6 -0.7 6" t1="6 -0.7 6" t2="6 -0.7 -6" material="matte" color="0.6 0.6 0.6"/>
  <triangle t0="-6 -0.7 6" t1="6 -0.7 -6" t2="-6 -0.7 -6" material="matte" color="0.6 0.6 0.6"/>
</scene>"#,
        20,
        14,
    );
    assert_every_pixel_matches(&world, &[(12, 4), (3, 8)], 3);
}

#[test]
fn emitters_seen_through_mirrors_metal_and_glass_match_too() {
    // A mirror wall, a metal box, glass spheres (one inside another's
    // view) and a partly reflective floor, all facing a wide emitter
    // behind the camera: most paths reach it through a delta lobe, where
    // no light sample competes (MIS weight 1), and some refract twice.
    let world = world_from(
        r#"<scene>
  <camera eye="0 0.5 5" toward="0 -0.1 -1" up="0 1 0" theta="30" width="18" height="14"/>
  <triangle t0="-4 -1 -2" t1="4 -1 -2" t2="4 4 -2" material="mirror" color="0.9 0.9 0.8"/>
  <triangle t0="-4 -1 -2" t1="4 4 -2" t2="-4 4 -2" material="mirror" color="0.9 0.9 0.8"/>
  <box center="-1.6 0 0" size="0.8 0.8 0.8" rotate="0 30 0" material="metal" color="0.95 0.64 0.54"/>
  <sphere center="0.2 0.1 0" radius="0.7" material="glass" ior="1.5" color="0.95 0.9 0.8"/>
  <sphere center="1.7 -0.3 0.8" radius="0.5" material="glass" ior="1.33"/>
  <triangle t0="-6 -1 6" t1="6 -1 6" t2="6 -1 -6" material="matte" color="0.6 0.6 0.6" reflectivity="0.5"/>
  <triangle t0="-6 -1 6" t1="6 -1 -6" t2="-6 -1 -6" material="matte" color="0.6 0.6 0.6" reflectivity="0.5"/>
  <triangle t0="-5 -1 7" t1="5 5 7" t2="5 -1 7" material="matte" emission="3 3 3"/>
  <triangle t0="-5 -1 7" t1="-5 5 7" t2="5 5 7" material="matte" emission="3 3 3"/>
</scene>"#,
        18,
        14,
    );
    assert_every_pixel_matches(&world, &[(12, 4), (3, 8)], 3);
}

#[test]
fn other_shapes_through_the_bvh_and_big_worlds_through_the_tree_match_too() {
    // Nine cylinders, cones and tori are more than the packets test lane
    // by lane (eight): their rays go through the world's BVH, lane by lane;
    // so does every shape under the lecture's formulas. Three of them go in
    // packets. The 104 primitives of spheres.xml are walked in packets
    // through a tree.
    let rows = |depths: &[f32]| {
        let rows: String = depths
            .iter()
            .map(|z| {
                format!(
                    r#"
  <cylinder base="-2 -0.75 {z}" radius="0.6" height="1.5" material="matte" color="0.8 0.4 0.3"/>
  <cone base="0 -0.75 {z}" radius="0.7" height="1.5" material="glass"/>
  <torus center="2 0.2 {z}" major="0.7" minor="0.25" material="matte" color="0.3 0.7 0.4"/>"#
                )
            })
            .collect();
        world_from(
            &format!(
                r#"<scene>
  <camera eye="0 2 9" toward="0 -0.3 -1" up="0 1 0" theta="30" width="16" height="12"/>
  <sky color="0.5 0.5 0.6"/>{rows}
  <sphere center="0 3 -1" radius="0.5" material="matte" emission="8 8 8"/>
  <plane point="0 -0.75 0" normal="0 1 0" material="matte" color="0.6 0.6 0.6"/>
</scene>"#
            ),
            16,
            12,
        )
    };
    let shapes = rows(&[0.0, -2.0, -4.0]);
    let one_row = rows(&[0.0]);
    let spheres = world_from(
        include_str!("../../../../assets/reference/spheres.xml"),
        16,
        12,
    );
    let cornell = cornell(12, 12);
    for world in [&shapes, &one_row, &spheres, &cornell] {
        for method in [Method::Robust, Method::Lecture] {
            let options = RenderOptions {
                method,
                ..path_options(Sampling::Sobol, 8, 6)
            };
            let scene = WavefrontScene::new(world, method);
            let packets = method == Method::Robust && !std::ptr::eq(world, &shapes);
            assert_eq!(
                scene.shapes.is_some(),
                packets,
                "packet tests only for small robust worlds"
            );
            assert_wavefront_equals_scalar(world, &options, &all_samples(12, 12, 2));
        }
    }
}

#[test]
fn point_and_directional_lights_match_too() {
    let lit = world_from(
        r#"<scene>
  <camera eye="0 2 8" toward="0 -0.25 -1" up="0 1 0" theta="30" width="16" height="12"/>
  <light position="2 4 3" color="1 0.9 0.8" intensity="30"/>
  <light position="-3 3 1" intensity="12"/>
  <light type="directional" direction="-0.3 -1 -0.2" intensity="0.7"/>
  <light type="ambient" intensity="0.1"/>
  <sphere center="-1.2 0 0" radius="0.8" material="matte" color="0.8 0.5 0.3"/>
  <sphere center="1.2 0 0" radius="0.8" material="plastic" color="0.3 0.5 0.8"/>
  <box center="0 -0.5 -1.5" size="1 1 1" rotate="0 30 0" material="matte" color="0.6 0.6 0.6"/>
  <triangle t0="-1 1.5 -0.5" t1="1 1.5 -0.5" t2="0 1.5 0.5" material="matte" emission="4 4 4"/>
  <plane point="0 -0.8 0" normal="0 1 0" material="matte" color="0.5 0.5 0.5"/>
</scene>"#,
        16,
        12,
    );
    let seed = world_from(include_str!("../../../../assets/scenes/seed.xml"), 16, 12);
    for world in [&lit, &seed] {
        assert_every_pixel_matches(world, &[(8, 13)], 2);
    }
}

#[test]
fn floors_and_walls_go_in_packets_with_the_tree_and_match_too() {
    // Infinite planes are packet primitives outside the tree: a floor, a
    // tilted wall, and 36 spheres and boxes (every smooth and rough
    // material the lanes shade), under a sky, two point lights and the sun;
    // a box stands on the floor, so its face and the floor tie there.
    let materials = [
        r#"material="matte" color="0.7 0.3 0.2""#,
        r#"material="mirror" color="0.9 0.8 0.7" roughness="0.4""#,
        r#"material="glass" ior="1.5""#,
        r#"material="glass" roughness="0.3""#,
        r#"material="metal" color="0.8 0.6 0.3""#,
    ];
    let mut xml = String::from(
        r#"<scene>
  <camera eye="0 4 9" toward="0 -3 -9" up="0 1 0" theta="28" width="12" height="9"/>
  <sky color="0.2 0.25 0.3"/>
  <light position="-3 5 2" intensity="40"/>
  <light position="3 2 4" color="0.6 0.7 1" intensity="15"/>
  <light type="directional" direction="0.4 -1 -0.6" intensity="1"/>
  <floor y="0" color="0.55 0.55 0.5"/>
  <plane point="0 0 -5" normal="0 0.2 1" color="0.4 0.45 0.5"/>
  <sphere center="0 4 -2" radius="0.5" material="matte" color="0 0 0" emission="10 10 10"/>
"#,
    );
    for k in 0..36 {
        let (x, z) = ((k % 6) as f32 - 2.5, (k / 6) as f32 * 0.8 - 3.0);
        let paint = materials[k % materials.len()];
        xml += &if k % 3 == 0 {
            format!(
                "  <box center=\"{x} 0.25 {z}\" size=\"0.5 0.5 0.5\" rotate=\"0 {k}0 0\" {paint}/>\n"
            )
        } else {
            format!("  <sphere center=\"{x} 0.3 {z}\" radius=\"0.3\" {paint}/>\n")
        };
    }
    xml += "</scene>";
    let world = world_from(&xml, 12, 9);
    assert!(
        WavefrontScene::new(&world, Method::Robust).shapes.is_some(),
        "packets through the tree, planes after it"
    );
    assert_every_pixel_matches(&world, &[(8, 21), (3, 22)], 3);
}

#[test]
fn mesh_hits_on_lanes_and_handed_over_match_too() {
    use super::scene::{Column, LaneBsdf};
    use ::scene::materials::builtin;
    use ::scene::{
        BaseMaterial, MeshInstance, MeshSource, ModelFile, ModelMaterial, Object, Shape, Texture,
        TriangleMesh, Wrap,
    };
    use glam::{Mat4, Vec2, Vec3};
    use std::sync::Arc;
    // A bent quad whose vertex normals lean far from its faces' (so that
    // some rays meet the shading frame from below), placed once per
    // material of the model file beside lone shapes: on lanes a textured
    // matte, a matte with a mirror lobe, smooth and rough metal, smooth and
    // rough glass, a plastic (highlight), a textured marble; handed over an
    // emitting matte.
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.3),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.2),
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    let leaning = [(0.7, 0.0), (-0.6, 0.3), (0.2, -0.8), (-0.4, -0.5)];
    let normals = TriangleMesh::face_normals_per_vertex(&positions, &triangles)
        .iter()
        .zip(leaning)
        .map(|(n, (x, y))| (*n + Vec3::new(x, y, 0.0)).normalize())
        .collect();
    let mesh = TriangleMesh {
        normals,
        uvs: positions.iter().map(|p| Vec2::new(p.x, p.y)).collect(),
        positions,
        triangles,
    };
    let with = |base, f: &dyn Fn(&mut ::scene::Material)| {
        let mut m = builtin(base);
        f(&mut m);
        m
    };
    let materials = [
        builtin(BaseMaterial::Matte),
        with(BaseMaterial::Matte, &|m| m.reflectivity = 0.3),
        builtin(BaseMaterial::Metal),
        with(BaseMaterial::Metal, &|m| m.roughness = 0.3),
        builtin(BaseMaterial::Glass),
        with(BaseMaterial::Glass, &|m| m.roughness = 0.2),
        builtin(BaseMaterial::Plastic),
        builtin(BaseMaterial::Marble),
        with(BaseMaterial::Matte, &|m| m.emission = Vec3::splat(2.0)),
    ];
    let mut model = ModelFile::default();
    model.meshes = vec![Arc::new(mesh)];
    model.textures = vec![Arc::new(Texture {
        width: 2,
        height: 2,
        texels: Arc::from(vec![
            [255, 40, 40, 255],
            [40, 255, 40, 255],
            [40, 40, 255, 255],
            [250, 250, 60, 255],
        ]),
        wrap_u: Wrap::Repeat,
        wrap_v: Wrap::Repeat,
    })];
    model.materials = materials
        .iter()
        .enumerate()
        .map(|(k, &material)| ModelMaterial {
            material,
            // Textured matte, and marble veins through a texture.
            base_color_texture: (k == 0 || k == 7).then_some(0),
        })
        .collect();
    model.instances = (0..materials.len())
        .map(|k| MeshInstance {
            mesh: 0,
            material: k as u32,
            model_from_mesh: Mat4::from_translation(Vec3::new(
                (k % 4) as f32 * 1.1 - 2.2,
                (k / 4) as f32 * 1.1 - 1.1,
                -0.3 * (k % 3) as f32,
            )),
            name: format!("instance {k}"),
        })
        .collect();
    let mut scene = ::scene::read_str(
        r#"<scene><camera eye="0 0.3 6" toward="0 0 -1" theta="24" width="20" height="20"/>
           <sky color="0.4 0.4 0.5"/><light position="1 2 3" intensity="6"/>
           <sphere center="1.2 0.2 0.5" radius="0.3" material="matte" color="0.8 0.3 0.3"/>
           <triangle t0="-3 1.5 -1" t1="-1 1.5 -1" t2="-2 2.5 -1" material="matte" emission="3 3 3"/>
           <triangle t0="-4 -1.2 4" t1="4 -1.2 4" t2="0 -1.2 -4" material="matte" color="0.6 0.6 0.6"/>
           <cylinder base="2.6 -1.2 -1" radius="0.3" height="0.6" material="matte"/></scene>"#,
        "mesh.xml",
    )
    .expect("parses");
    scene.objects.push(Object {
        name: Some("model".into()),
        shape: Shape::Mesh {
            source: MeshSource {
                src: "generated".into(),
                model: Arc::new(model),
            },
            translate: None,
            rotate: Vec3::ZERO,
            scale: Vec3::ONE,
        },
        material: None,
        params: Default::default(),
    });
    // In packets (the cylinder tested lane by lane), and every ray through
    // the world's BVH.
    let world = World::from_scene(&scene).expect("valid");
    assert_eq!(
        world.meshes.len(),
        materials.len(),
        "one instance per material"
    );
    assert!(WavefrontScene::new(&world, Method::Robust).shapes.is_some());
    let table = WavefrontScene::new(&world, Method::Robust).objects;
    let on_lanes = |instance: u32| {
        let flags = table.row(table.mesh_row(instance))[Column::Flags as usize].to_bits();
        flags as i32 & LaneBsdf::ON_LANES != 0
    };
    // All but the emitting one.
    let expected: Vec<bool> = (0..materials.len())
        .map(|k| k + 1 < materials.len())
        .collect();
    let shaded: Vec<bool> = (0..materials.len() as u32).map(on_lanes).collect();
    assert_eq!(shaded, expected, "which instances the lanes shade");
    assert_every_pixel_matches(&world, &[(8, 21), (3, 5)], 2);
    assert_every_pixel_matches_in(&world, &[(8, 21)], 2, true);
    // Under an environment map too: the handed-over lane's sky sample goes
    // in the lanes' packet toward the sky.
    scene.sky = Some(sky_map(glam::Vec3::new(0.0, 200.0, 10.0)));
    let world = World::from_scene(&scene).expect("valid");
    assert_every_pixel_matches(&world, &[(8, 21)], 2);
}

#[test]
fn every_material_under_an_environment_map_matches_too() {
    let mut scene = ::scene::read_str(
        r#"<scene>
  <camera eye="0 1.5 7" toward="0 -0.3 -1" up="0 1 0" theta="28" width="20" height="14"/>
  <sphere center="-2.4 0 0" radius="0.7" material="mirror" color="0.9 0.8 0.7"/>
  <sphere center="-0.8 0 0" radius="0.7" material="glass" ior="1.5"/>
  <sphere center="0.8 0 0" radius="0.7" material="plastic" color="0.2 0.4 0.8"/>
  <sphere center="2.4 0 0" radius="0.7" material="marble"/>
  <sphere center="0 -0.3 2" radius="0.4" material="glass" roughness="0.3"/>
  <box center="0 1.6 -1" size="1 0.5 0.5" material="metal" color="0.9 0.6 0.3" roughness="0.2"/>
  <box center="1.5 1.6 -1" size="0.6 0.6 0.6" rotate="0 45 0" material="matte" color="0.7 0.7 0.7" reflectivity="0.3"/>
  <triangle t0="-1 3 -2" t1="1 3 -2" t2="0 3 0" material="matte" emission="6 6 5"/>
  <light position="2 4 3" intensity="20"/>
  <floor y="-0.7" material="matte" color="0.6 0.6 0.6"/>
</scene>"#,
        "map.xml",
    )
    .expect("parses");
    scene.sky = Some(sky_map(glam::Vec3::new(15.0, -40.0, 0.0)));
    let world = World::from_scene(&scene).expect("valid");
    assert!(world.environment.is_sampled());
    assert_every_pixel_matches(&world, &[(12, 4), (3, 8)], 3);
}

#[test]
fn the_film_traces_each_new_world_with_its_own_view() {
    // Each thread keeps the wavefront view of the last world it traced
    // (`trace_samples.rs`): alternating between two worlds of the same
    // shapes but other materials, and between the two methods, every call
    // must still trace the world it is given.
    let scene = |color: &str| {
        format!(
            r#"<scene>
  <camera eye="0 0 4" toward="0 0 -1" up="0 1 0" theta="30" width="8" height="6"/>
  <sphere center="0 0 0" radius="1" material="matte" color="{color}"/>
  <triangle t0="-3 2 -3" t1="3 2 -3" t2="0 2 3" material="matte" emission="4 4 4"/>
  <triangle t0="-3 -1 3" t1="3 -1 3" t2="0 -1 -3" material="matte" color="0.5 0.5 0.5"/>
</scene>"#
        )
    };
    let red = world_from(&scene("0.9 0.1 0.1"), 8, 6);
    let blue = world_from(&scene("0.1 0.1 0.9"), 8, 6);
    assert_ne!(red.id(), blue.id(), "two worlds, two ids");
    assert_ne!(red.clone().id(), red.id(), "a clone has its own id");
    let samples = all_samples(8, 6, 2);
    for (world, method) in [
        (&red, Method::Robust),
        (&blue, Method::Robust),
        (&blue, Method::Lecture),
        (&red, Method::Robust),
    ] {
        let options = RenderOptions {
            method,
            ..path_options(Sampling::Sobol, 6, 1)
        };
        let mut results = vec![SampleResult::default(); samples.len()];
        crate::integrator::trace_samples(world, &options, &samples, &mut results);
        for (s, result) in samples.iter().zip(&results) {
            let scalar = sample_pixel(world, &options, s.i, s.j, s.sample);
            assert_eq!(
                result.radiance.to_array().map(f32::to_bits),
                scalar.to_array().map(f32::to_bits),
                "{method:?} sample {s:?}"
            );
        }
    }
}

#[test]
fn a_tree_world_of_every_smooth_material_and_mixed_emitters_matches_too() {
    // More shapes than the brute-force limit (a tree), every material the
    // lanes shade (matte, with a mirror lobe, mirror, metal, glass) beside
    // ones handed over, and emitters of three kinds: triangles drawn on
    // lanes, a sphere and a box drawn by the scalar code, in one group.
    let materials = [
        r#"material="matte" color="0.7 0.5 0.3""#,
        r#"material="matte" color="0.3 0.6 0.7" reflectivity="0.4""#,
        r#"material="mirror" color="0.9 0.9 0.8""#,
        r#"material="metal" color="0.95 0.64 0.54""#,
        r#"material="glass" ior="1.5""#,
        r#"material="plastic" color="0.2 0.3 0.8""#,
    ];
    let mut xml = String::from(
        r#"<scene>
  <camera eye="0 2.5 7" toward="0 -0.35 -1" up="0 1 0" theta="30" width="16" height="12"/>
  <sky color="0.2 0.25 0.3"/>
  <triangle t0="-6 -0.5 6" t1="6 -0.5 6" t2="6 -0.5 -6" material="matte" color="0.6 0.6 0.6"/>
  <triangle t0="-6 -0.5 6" t1="6 -0.5 -6" t2="-6 -0.5 -6" material="matte" color="0.6 0.6 0.6"/>
  <triangle t0="-1 3 -1" t1="1 3 -1" t2="0 3 1" material="matte" emission="5 5 4"/>
  <sphere center="-2.5 2 -1.5" radius="0.3" material="matte" emission="6 5 4"/>
  <box center="2.5 2 -1.5" size="0.4 0.2 0.4" material="matte" emission="4 5 6"/>
"#,
    );
    for k in 0..24 {
        let angle = k as f32 * std::f32::consts::TAU / 24.0;
        let (x, z) = (2.2 * angle.cos(), 2.2 * angle.sin() - 0.5);
        xml.push_str(&format!(
            "  <sphere center=\"{x} -0.1 {z}\" radius=\"0.35\" {}/>\n",
            materials[k % materials.len()]
        ));
    }
    xml.push_str("</scene>");
    let world = world_from(&xml, 16, 12);
    let scene = WavefrontScene::new(&world, Method::Robust);
    assert!(
        scene.shapes.as_ref().is_some_and(|s| s.len() > 20),
        "packets through a tree"
    );
    assert_every_pixel_matches(&world, &[(12, 4), (3, 8)], 3);
}

#[test]
fn packets_where_the_world_allows_them_else_the_bvh() {
    // Packets for lone spheres (marble or not) and up to eight cylinders,
    // cones or tori (tested lane by lane); through the BVH for the
    // lecture's formulas.
    let scene = |body: &str| {
        world_from(
            &format!(
                r#"<scene>
  <camera eye="0 2 9" toward="0 -0.3 -1" up="0 1 0" theta="30" width="8" height="6"/>
  <sphere center="0 3 -1" radius="0.5" material="matte" emission="8 8 8"/>
  {body}
</scene>"#
            ),
            8,
            6,
        )
    };
    let lone = scene(r#"<sphere center="0 0 0" radius="1" material="glass"/>"#);
    let other = scene(r#"<cylinder base="0 -1 0" radius="0.6" height="1.5" material="matte"/>"#);
    let marble = scene(r#"<sphere center="0 0 0" radius="1" material="marble"/>"#);
    let other_marble =
        scene(r#"<cylinder base="0 -1 0" radius="0.6" height="1.5" material="marble"/>"#);
    let packets = |world: &World, method| WavefrontScene::new(world, method).shapes.is_some();
    assert!(packets(&lone, Method::Robust));
    assert!(!packets(&lone, Method::Lecture), "through the BVH");
    assert!(packets(&other, Method::Robust));
    assert!(packets(&marble, Method::Robust));
    assert!(!packets(&marble, Method::Lecture), "through the BVH");
    assert!(packets(&other_marble, Method::Robust));
    // Marble on lanes, under a sky, beside a glass cone, in packets (both
    // tested lane by lane) and through the BVH.
    let lit_marble = scene(
        r#"<sky color="0.5 0.6 0.7"/>
  <cylinder base="0 -1 0" radius="1.5" height="1.5" material="marble"/>
  <cone base="1.8 -1 1" radius="0.6" height="1.6" material="glass"/>"#,
    );
    assert!(packets(&lit_marble, Method::Robust));
    assert_every_pixel_matches(&lit_marble, &[(4, 1)], 2);
    assert_every_pixel_matches_in(&lit_marble, &[(4, 1)], 2, true);
}

#[test]
fn a_world_of_nine_hundred_spheres_goes_in_packets_and_matches_the_scalar_samples() {
    // Past the old limit of 512 primitives: a 30 × 30 grid of spheres of
    // every material the lanes shade, on a floor of two triangles, lit by
    // an emitting sphere.
    let materials = [
        r#"material="matte" color="0.7 0.3 0.2""#,
        r#"material="mirror" color="0.9 0.8 0.7""#,
        r#"material="glass" ior="1.5""#,
        r#"material="metal" color="0.8 0.6 0.3" roughness="0.4""#,
    ];
    let mut xml = String::from(
        r#"<scene>
  <camera eye="0 9 16" toward="0 -9 -16" up="0 1 0" theta="22" width="8" height="6"/>
  <triangle t0="-40 0 40" t1="40 0 40" t2="40 0 -40" material="matte" color="0.5 0.5 0.5"/>
  <triangle t0="-40 0 40" t1="40 0 -40" t2="-40 0 -40" material="matte" color="0.5 0.5 0.5"/>
  <sphere center="0 8 0" radius="1" material="matte" color="0 0 0" emission="20 20 20"/>
"#,
    );
    for k in 0..900 {
        let (x, z) = ((k % 30) as f32 * 0.5 - 7.5, (k / 30) as f32 * 0.5 - 7.5);
        xml += &format!(
            "  <sphere center=\"{x} 0.2 {z}\" radius=\"0.2\" {}/>\n",
            materials[k % 4]
        );
    }
    xml += "</scene>";
    let world = world_from(&xml, 8, 6);
    assert!(world.objects.len() > 512);
    let options = path_options(Sampling::Sobol, 8, 3);
    assert!(
        WavefrontScene::new(&world, Method::Robust).shapes.is_some(),
        "packets through the tree"
    );
    assert_wavefront_equals_scalar(&world, &options, &all_samples(8, 6, 2));
}
