//! The pixel inspector re-traces path-traced samples: the same colour bit for
//! bit as the film, contributions that add up to it, and the path's BSDF
//! samples, light samples, emission weights and roulette decisions recorded
//! as they happened.

use glam::Vec3;
use renderer::inspect::{Inspection, ShadowTarget};
use renderer::integrator::sampler::Sampling;
use renderer::integrator::{Integrator, RayKind, sample_pixel};
use renderer::shading::bsdf::Lobe;
use renderer::{Film, Method, RenderOptions, World, inspect_pixel};
mod common;

/// A small closed room lit by an emissive sphere, an emissive triangle and a
/// point light, with every BSDF the path tracer has: matte, plastic with a
/// highlight and a mirror part, mirror, metal, rough metal, smooth and rough
/// glass, and a sky seen through an opening.
const ROOM: &str = r#"<scene>
  <camera eye="0 1 4.5" toward="0 0 -1" theta="30" width="24" height="18"/>
  <light type="point" position="-1 2.2 1" intensity="3"/>
  <sky color="0.2 0.3 0.5"/>
  <floor material="matte" color="0.7 0.7 0.7"/>
  <triangle name="back" t0="-3 0 -2" t1="3 0 -2" t2="0 3 -2" material="plastic" color="0.6 0.5 0.4" reflectivity="0.2" specular="0.3"/>
  <triangle name="lamp" t0="-0.5 2.5 -1" t1="0.5 2.5 -1" t2="0 2.5 0" emission="6 6 5"/>
  <sphere name="bulb" center="1.6 2 -1" radius="0.2" emission="8 7 6"/>
  <sphere name="glass" center="-1 0.6 0" radius="0.6" material="glass"/>
  <sphere name="frosted" center="1 0.5 0.5" radius="0.5" material="glass" roughness="0.4"/>
  <sphere name="mirror" center="0 0.5 -1" radius="0.5" material="mirror"/>
  <box name="brushed" center="1.8 0.4 -0.5" size="0.6 0.8 0.6" rotate="0 30 0" material="metal" roughness="0.5"/>
  <box name="gold" center="-1.9 0.3 -1" size="0.5 0.6 0.5" material="metal" color="1 0.8 0.3"/>
</scene>"#;

fn room() -> World {
    let scene = scene::read_str(ROOM, "room.xml").expect("the room parses");
    World::from_scene(&scene).expect("the room is valid")
}

/// The room under an environment map (the reference scenes' sky and sun,
/// dimmed and turned) instead of a constant sky: the path tracer samples it
/// as a light.
fn room_under_map() -> World {
    let map = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/reference/sky_map.exr"
    );
    let xml = ROOM.replace(
        r#"<sky color="0.2 0.3 0.5"/>"#,
        &format!(r#"<sky map="{map}" color="0.2 0.2 0.2" rotate="0 60 0"/>"#),
    );
    assert_ne!(xml, ROOM);
    let scene = scene::read_str(&xml, "room.xml").expect("the room parses");
    World::from_scene(&scene).expect("the room is valid")
}

/// A reference scene shipped with raylab, at `width` × `height`.
fn reference(name: &str, width: u32, height: u32) -> World {
    common::asset_world("reference", name, width, height)
}

fn path_options(sampling: Sampling, method: Method) -> RenderOptions {
    RenderOptions {
        integrator: Integrator::Path,
        method,
        sampling,
        seed: 11,
        ..Default::default()
    }
}

fn inspect(world: &World, options: &RenderOptions, i: u32, j: u32, k: Option<u32>) -> Inspection {
    inspect_pixel(world, options, i, j, k).expect("pixel inside the image")
}

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

#[test]
fn every_pixel_of_a_path_traced_pass_is_its_inspected_sample_bit_for_bit() {
    let worlds = [
        ("room", room()),
        ("room under a map", room_under_map()),
        ("rough.xml", reference("rough.xml", 20, 20)),
    ];
    for (name, world) in &worlds {
        for sampling in [Sampling::Independent, Sampling::Sobol] {
            for method in [Method::Robust, Method::Lecture] {
                let options = path_options(sampling, method);
                let film = Film::render(world, &options, 1);
                for j in 0..world.camera.h {
                    for i in 0..world.camera.w {
                        let inspection = inspect(world, &options, i, j, Some(0));
                        assert_eq!(inspection.integrator, Integrator::Path);
                        assert_eq!(
                            bits(inspection.color),
                            bits(film.pixel(i, j)),
                            "{name} {sampling:?} {method:?} pixel ({i}, {j}): inspector {} vs film {}",
                            inspection.color,
                            film.pixel(i, j)
                        );
                        for k in [1, 7, 300] {
                            let inspected = inspect(world, &options, i, j, Some(k)).color;
                            let traced = sample_pixel(world, &options, i, j, k);
                            assert_eq!(
                                bits(inspected),
                                bits(traced),
                                "{name} {sampling:?} {method:?} pixel ({i}, {j}) sample {k}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// What the path inspections exercised, so the tests can insist on coverage.
#[derive(Default, Debug)]
struct Seen {
    lobes: [usize; 3],
    refractions: usize,
    light_shadows: [usize; 2],
    emitter_shadows: [usize; 2],
    sky_shadows: [usize; 2],
    weighted_emission: usize,
    roulette: [usize; 2],
    depth_limits: usize,
    misses: usize,
}

fn lobe_index(lobe: Lobe) -> usize {
    match lobe {
        Lobe::Diffuse => 0,
        Lobe::Glossy => 1,
        Lobe::Specular => 2,
    }
}

/// Σ contributions = colour, and each ray's weight follows from its parent's:
/// a BSDF-sampled ray carries parent weight × f·cos/pdf (÷ the roulette's
/// keep probability when it was played), a shadow ray its parent's weight.
fn check_path_inspection(inspection: &Inspection, what: &str, seen: &mut Seen) {
    let (sum, color) = (inspection.contribution_sum(), inspection.color);
    for c in 0..3 {
        let error = (sum[c] - color[c]).abs();
        assert!(
            error <= 1e-5 * color[c].abs() + 1e-30,
            "{what}: Σ contributions {sum} vs colour {color} (channel {c}, error {error})"
        );
    }
    assert_eq!(inspection.primary().weight, Vec3::ONE, "{what}");
    for (index, ray) in inspection.rays.iter().enumerate().skip(1) {
        let parent_index = ray.parent.expect("only the primary has no parent");
        assert!(parent_index < index, "{what}: parents come first");
        let parent = &inspection.rays[parent_index];
        let parent_hit = parent.hit.as_ref().expect("rays leave hits only");
        match ray.kind {
            RayKind::Shadow => {
                assert_eq!(ray.depth, parent.depth, "{what}");
                assert_eq!(ray.weight, parent.weight, "{what}");
                let test = ray.shadow.as_ref().expect("a shadow test");
                let blocked = test.blocked as usize;
                match test.target {
                    ShadowTarget::Light(_) => seen.light_shadows[blocked] += 1,
                    ShadowTarget::Emitter(e) => {
                        seen.emitter_shadows[blocked] += 1;
                        assert!(e.pdf > 0.0, "{what}: {e:?}");
                        assert!((0.0..=1.0).contains(&e.mis_weight), "{what}: {e:?}");
                    }
                    ShadowTarget::Environment(e) => {
                        seen.sky_shadows[blocked] += 1;
                        assert!(e.pdf > 0.0, "{what}: {e:?}");
                        assert!((0.0..=1.0).contains(&e.mis_weight), "{what}: {e:?}");
                    }
                }
                if test.blocked {
                    assert_eq!(ray.contribution, Vec3::ZERO, "{what}");
                }
            }
            RayKind::Reflection | RayKind::Refraction => {
                assert_eq!(ray.depth, parent.depth + 1, "{what}");
                let scatter = ray
                    .scatter
                    .expect("a path tracer's bounce records its sample");
                seen.lobes[lobe_index(scatter.lobe)] += 1;
                seen.refractions += (ray.kind == RayKind::Refraction) as usize;
                assert_eq!(scatter.lobe == Lobe::Specular, scatter.pdf == 0.0, "{what}");
                let keep = parent_hit.roulette.map_or(1.0, |r| {
                    assert!(r.survived, "{what}: a ray after a lost roulette");
                    r.keep
                });
                let expected = parent.weight * scatter.bsdf_weight / keep;
                assert!(
                    (ray.weight - expected).abs().max_element()
                        <= 1e-5 * expected.abs().max_element(),
                    "{what}: weight {} vs {expected}",
                    ray.weight
                );
            }
            RayKind::Primary => panic!("{what}: a second primary ray"),
        }
        if let Some(hit) = &ray.hit {
            seen.weighted_emission += hit.emission_weight.is_some_and(|w| w < 1.0) as usize;
            if let Some(r) = hit.roulette {
                seen.roulette[r.survived as usize] += 1;
            }
            seen.depth_limits += hit.depth_limited as usize;
        } else if ray.kind != RayKind::Shadow {
            seen.misses += 1;
        }
    }
}

#[test]
fn path_traced_contributions_add_up_and_weights_follow_the_samples() {
    let mut seen = Seen::default();
    for world in [room(), room_under_map()] {
        for sampling in [Sampling::Independent, Sampling::Sobol] {
            for max_depth in [1, 2, 4, 12] {
                let options = RenderOptions {
                    max_depth,
                    ..path_options(sampling, Method::Robust)
                };
                for j in 0..world.camera.h {
                    for i in 0..world.camera.w {
                        for k in [None, Some(0), Some(3), Some(40)] {
                            let inspection = inspect(&world, &options, i, j, k);
                            let what = format!(
                                "{sampling:?} max_depth {max_depth} pixel ({i}, {j}) sample {k:?}"
                            );
                            check_path_inspection(&inspection, &what, &mut seen);
                        }
                    }
                }
            }
        }
    }
    // The rooms must exercise every kind of event, or the test proves little.
    assert!(
        seen.lobes.iter().all(|&n| n > 0)
            && seen.refractions > 0
            && seen.light_shadows.iter().all(|&n| n > 0)
            && seen.emitter_shadows.iter().all(|&n| n > 0)
            && seen.sky_shadows.iter().all(|&n| n > 0)
            && seen.weighted_emission > 0
            && seen.roulette.iter().all(|&n| n > 0)
            && seen.depth_limits > 0
            && seen.misses > 0,
        "{seen:?}"
    );
}

#[test]
fn a_directly_seen_emitter_counts_in_full_and_the_sky_fills_misses() {
    let world = room();
    let options = path_options(Sampling::Independent, Method::Robust);
    // The bulb sphere, seen by the camera ray, and a miss through the sky.
    let bulb = world
        .names
        .iter()
        .position(|n| n == "bulb")
        .expect("the bulb");
    let mut bulb_seen = false;
    for j in 0..world.camera.h {
        for i in 0..world.camera.w {
            let inspection = inspect(&world, &options, i, j, None);
            let primary = inspection.primary();
            match &primary.hit {
                Some(hit) if hit.object.index as usize == bulb => {
                    assert_eq!(hit.emission_weight, Some(1.0));
                    assert_eq!(primary.contribution, Vec3::new(8.0, 7.0, 6.0));
                    bulb_seen = true;
                }
                Some(_) => {}
                None => assert_eq!(
                    primary.contribution,
                    world.environment.radiance(primary.direction)
                ),
            }
        }
    }
    assert!(bulb_seen, "the camera sees the bulb");
}
