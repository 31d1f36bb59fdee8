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
    let scene = WavefrontScene::new(world).expect("the wavefront covers this world");
    let mut results = vec![SampleResult::default(); samples.len()];
    // The portable lanes first, then the widest this CPU has.
    crate::packet::lanes::run_portable(Trace {
        world,
        scene: &scene,
        options,
        samples,
        results: &mut results,
    });
    let portable = results.clone();
    trace_wavefront(world, &scene, options, samples, &mut results);
    assert_eq!(portable, results, "the portable and the widest lanes agree");
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
        assert!(
            result.shape_tests > 0,
            "sample {s:?} counted no shape tests"
        );
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

#[test]
fn every_cornell_sample_is_the_scalar_path_tracers_bit_for_bit() {
    let world = cornell(24, 24);
    for sampling in [Sampling::Independent, Sampling::Sobol] {
        for (max_depth, seed) in [(8, 0), (2, 5), (1, 1), (30, 9)] {
            let options = path_options(sampling, max_depth, seed);
            assert_wavefront_equals_scalar(&world, &options, &all_samples(24, 24, 2));
        }
    }
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
    for sampling in [Sampling::Independent, Sampling::Sobol] {
        let options = path_options(sampling, 8, 11);
        assert_wavefront_equals_scalar(&world, &options, &all_samples(16, 12, 4));
    }
}

#[test]
fn rough_conductors_and_rough_glass_handed_to_the_scalar_code_match_too() {
    let world = world_from(
        include_str!("../../../../assets/reference/rough.xml"),
        20,
        20,
    );
    for sampling in [Sampling::Independent, Sampling::Sobol] {
        let options = path_options(sampling, 8, 2);
        assert_wavefront_equals_scalar(&world, &options, &all_samples(20, 20, 3));
    }
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
    for sampling in [Sampling::Independent, Sampling::Sobol] {
        for (max_depth, seed) in [(12, 4), (3, 8)] {
            let options = path_options(sampling, max_depth, seed);
            assert_wavefront_equals_scalar(&world, &options, &all_samples(20, 14, 3));
        }
    }
}

#[test]
fn worlds_it_has_no_lanes_for_are_left_to_the_scalar_lanes() {
    let unsupported = [
        r#"<scene><cylinder material="matte"/></scene>"#,
        r#"<scene><plane material="matte"/></scene>"#,
        r#"<scene><light position="0 5 0"/><sphere center="0 0 0" radius="1"/></scene>"#,
    ];
    for xml in unsupported {
        let world = world_from(xml, 4, 4);
        assert!(WavefrontScene::new(&world).is_none(), "{xml}");
    }
    let covered = world_from(
        include_str!("../../../../assets/reference/cornell.xml"),
        4,
        4,
    );
    assert!(WavefrontScene::new(&covered).is_some());
}
