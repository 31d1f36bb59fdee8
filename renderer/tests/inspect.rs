//! The pixel inspector against the image and against hand computations.

use glam::Vec3;
use renderer::film::aov::{Aov, aov_at};
use renderer::inspect::{Inspection, RayNode, ShadowTarget, SurfaceHit};
use renderer::integrator::RayKind;
use renderer::integrator::sample_pixel;
use renderer::{Film, Method, RenderOptions, World, inspect_pixel};
mod common;

const METHODS: [Method; 2] = [Method::Lecture, Method::Robust];

fn world_from_xml(xml: &str) -> World {
    let scene = scene::read_str(xml, "test.xml").expect("the test scene parses");
    World::from_scene(&scene).expect("the test scene is valid")
}

/// A shipped scene rendered at `width` × `height`.
fn shipped(name: &str, width: u32, height: u32) -> World {
    common::asset_world("scenes", name, width, height)
}

fn inspect(world: &World, options: &RenderOptions, i: u32, j: u32, k: Option<u32>) -> Inspection {
    inspect_pixel(world, options, i, j, k).expect("pixel inside the image")
}

fn hit_of(ray: &RayNode) -> &SurfaceHit {
    ray.hit.as_ref().expect("the ray hits something")
}

/// Diffuse surfaces with shadows (a point light, a directional light, a
/// blocker), a mirror, glass (refraction and total internal reflection), a
/// reflective plastic, metal, a triangle, an emitter and ambient light.
const EVERYTHING: &str = r#"<scene>
  <camera eye="0 2.5 8" toward="0 -0.3 -1" theta="28" width="32" height="20"/>
  <light type="point" position="-3 6 4" intensity="120"/>
  <light type="directional" direction="1 -2 -1" intensity="0.8"/>
  <light type="ambient" intensity="0.15"/>
  <floor material="plastic" color="0.8 0.8 0.8" reflectivity="0.2"/>
  <sphere name="glass ball" center="-1.5 1 0.5" radius="1" material="glass"/>
  <sphere name="mirror ball" center="1.5 1 -0.5" radius="1" material="mirror"/>
  <sphere name="shiny ball" center="0 0.6 2" radius="0.6" material="plastic" reflectivity="0.3"/>
  <box name="water block" center="-3.2 0.6 1.5" size="1 1.2 1" rotate="0 25 0" material="glass" ior="1.33"/>
  <box name="metal box" center="3 0.5 1" size="1 1 1" material="metal"/>
  <triangle name="green triangle" t0="-3 0 -2" t1="-1 0 -2" t2="-2 2 -2" color="0.2 0.9 0.3"/>
  <sphere name="lamp" center="0 3.5 -3" radius="0.4" emission="2 2 1.5"/>
</scene>"#;

#[test]
fn inspected_sample_reproduces_the_image_sample_bit_for_bit() {
    let options = RenderOptions {
        seed: 7,
        ..Default::default()
    };
    for name in ["seed.xml", "glass.xml"] {
        let world = shipped(name, 40, 25);
        for (i, j) in [(0, 0), (20, 12), (39, 24), (8, 20), (31, 5), (17, 16)] {
            for k in [0, 1, 2, 15, 1000] {
                let inspected = inspect(&world, &options, i, j, Some(k)).color;
                let traced = sample_pixel(&world, &options, i, j, k);
                assert_eq!(
                    inspected.to_array().map(f32::to_bits),
                    traced.to_array().map(f32::to_bits),
                    "{name} pixel ({i}, {j}) sample {k}: {inspected} vs {traced}"
                );
            }
        }
        // One pass of the film is sample 0 of every pixel.
        let film = Film::render(&world, &options, 1);
        for j in 0..25 {
            for i in 0..40 {
                let inspected = inspect(&world, &options, i, j, Some(0)).color;
                assert_eq!(
                    inspected.to_array().map(f32::to_bits),
                    film.pixel(i, j).to_array().map(f32::to_bits),
                    "{name} pixel ({i}, {j}): inspector {inspected} vs film {}",
                    film.pixel(i, j)
                );
            }
        }
    }
}

/// What a set of inspections exercised, so the sum test can insist on coverage.
#[derive(Default, Debug)]
struct Seen {
    blocked_shadows: usize,
    lit_shadows: usize,
    reflections: usize,
    refractions: usize,
    total_internal_reflections: usize,
    depth_limits: usize,
    misses: usize,
}

fn assert_contributions_add_up(inspection: &Inspection, what: &str, seen: &mut Seen) {
    let (sum, color) = (inspection.contribution_sum(), inspection.color);
    for c in 0..3 {
        let error = (sum[c] - color[c]).abs();
        assert!(
            error <= 1e-5 * color[c].abs() + f32::MIN_POSITIVE,
            "{what}: Σ contributions {sum} vs colour {color} (channel {c}, error {error})"
        );
    }
    for ray in &inspection.rays {
        match (ray.kind, &ray.shadow, &ray.hit) {
            (RayKind::Shadow, Some(s), _) if s.blocked => seen.blocked_shadows += 1,
            (RayKind::Shadow, Some(_), _) => seen.lit_shadows += 1,
            (RayKind::Reflection, ..) => seen.reflections += 1,
            (RayKind::Refraction, ..) => seen.refractions += 1,
            _ => {}
        }
        if let Some(hit) = &ray.hit {
            seen.total_internal_reflections += hit.total_internal_reflection as usize;
            seen.depth_limits += hit.depth_limited as usize;
        } else if ray.kind != RayKind::Shadow {
            seen.misses += 1;
        }
    }
}

#[test]
fn contributions_of_all_rays_add_up_to_the_sample_colour_for_both_methods() {
    let everything = world_from_xml(EVERYTHING);
    let glass = shipped("glass.xml", 32, 20);
    let mut seen = Seen::default();
    for (name, world) in [("everything", &everything), ("glass.xml", &glass)] {
        for method in METHODS {
            for max_depth in [0, 1, 3, 8] {
                let options = RenderOptions {
                    method,
                    max_depth,
                    seed: 3,
                    ..Default::default()
                };
                for j in 0..20 {
                    for i in 0..32 {
                        for k in [None, Some(0), Some(5)] {
                            let inspection = inspect(world, &options, i, j, k);
                            let what = format!(
                                "{name} {method:?} max_depth {max_depth} pixel ({i}, {j}) sample {k:?}"
                            );
                            assert_contributions_add_up(&inspection, &what, &mut seen);
                        }
                    }
                }
            }
        }
    }
    // The scenes must exercise every kind of term, or the test proves little.
    assert!(
        seen.blocked_shadows > 0
            && seen.lit_shadows > 0
            && seen.reflections > 0
            && seen.refractions > 0
            && seen.total_internal_reflections > 0
            && seen.depth_limits > 0
            && seen.misses > 0,
        "{seen:?}"
    );
}

#[test]
fn weights_are_products_of_the_factors_along_the_path() {
    let world = world_from_xml(EVERYTHING);
    let options = RenderOptions::default();
    let mut checked = 0;
    for j in 0..20 {
        for i in 0..32 {
            let inspection = inspect(&world, &options, i, j, None);
            assert_eq!(inspection.primary().weight, Vec3::ONE);
            for (index, ray) in inspection.rays.iter().enumerate().skip(1) {
                let parent = &inspection.rays[ray.parent.expect("only the primary has no parent")];
                assert!(ray.parent < Some(index), "parents come first");
                let material = hit_of(parent).material;
                // Every factor lies in [0, 1]: a child never outweighs its parent.
                assert!(ray.weight.cmple(parent.weight).all(), "{ray:?}");
                if ray.kind == RayKind::Shadow {
                    assert_eq!(ray.depth, parent.depth);
                    assert_eq!(ray.weight, parent.weight * (1.0 - material.reflectivity));
                } else {
                    assert_eq!(ray.depth, parent.depth + 1);
                }
                if material.base == "mirror" {
                    assert_eq!(ray.weight, parent.weight * material.color);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 0, "the mirror ball was seen");
}

#[test]
fn centre_inspection_primary_alpha_equals_the_depth_aov() {
    for method in METHODS {
        let options = RenderOptions {
            method,
            ..Default::default()
        };
        for name in ["seed.xml", "glass.xml"] {
            let world = shipped(name, 40, 25);
            for j in 0..25 {
                for i in 0..40 {
                    let inspection = inspect(&world, &options, i, j, None);
                    let depth = aov_at(&world, Aov::Depth, method, i, j)[0];
                    let alpha = inspection
                        .primary()
                        .hit
                        .as_ref()
                        .map_or(f32::INFINITY, |h| h.alpha);
                    assert_eq!(
                        alpha.to_bits(),
                        depth.to_bits(),
                        "{name} {method:?} ({i}, {j})"
                    );
                    assert_eq!(inspection.v_ij, world.camera.center_ray(i, j).dir);
                    assert_eq!(inspection.window_point, inspection.p_ij);
                }
            }
        }
    }
}

#[test]
fn sample_inspection_passes_through_the_jittered_point_of_the_pixel() {
    let world = shipped("seed.xml", 40, 25);
    let inspection = inspect(&world, &RenderOptions::default(), 12, 7, Some(3));
    let camera = &world.camera;
    assert!(
        inspection.offset.cmpge(glam::Vec2::ZERO).all()
            && inspection.offset.cmplt(glam::Vec2::ONE).all()
    );
    assert_eq!(inspection.p_ij, camera.pixel_center(12, 7));
    // v_ij points from P0 at the jittered window point, which is within a pixel of P_ij.
    let to_window = (inspection.window_point - camera.p0).normalize();
    assert!((to_window - inspection.v_ij).length() < 1e-6);
    let pixel = camera.w_d / camera.w as f32;
    assert!((inspection.window_point - inspection.p_ij).length() <= pixel * 0.71);
}

#[test]
fn sphere_straight_ahead_is_hit_at_distance_minus_radius_facing_the_camera() {
    // P0 = (1, 2, 9), C = (1, 2, 1), R = 2; one pixel, so v = t = −z:
    // ‖P0 − C‖ = 8, α = 8 − 2 = 6, n = −v = +z. The lecture's quadratic has
    // u = C − P0 = (0, 0, −8): a = 1, b = −2 u·v = −16, c = 64 − 4 = 60,
    // b² − 4ac = 16, roots (16 ∓ 4)/2 = 6 and 10 = ‖P0 − C‖ ∓ R.
    let world = world_from_xml(
        r#"<scene>
  <camera eye="1 2 9" toward="0 0 -1" theta="10" width="1" height="1"/>
  <sphere name="target" center="1 2 1" radius="2"/>
</scene>"#,
    );
    for method in METHODS {
        let options = RenderOptions {
            method,
            ..Default::default()
        };
        let inspection = inspect(&world, &options, 0, 0, None);
        assert_eq!(inspection.v_ij, -Vec3::Z, "{method:?}");
        let hit = hit_of(inspection.primary());
        assert_eq!((hit.object.index, hit.object.name.as_str()), (0, "target"));
        assert_eq!(hit.shape, "sphere");
        assert_eq!(hit.alpha, 6.0, "{method:?}");
        assert_eq!(hit.point, Vec3::new(1.0, 2.0, 3.0), "{method:?}");
        assert_eq!(hit.normal, -inspection.v_ij, "{method:?}");
        assert!(hit.front);
        let q = hit.sphere.expect("a sphere reports its quadratic");
        assert_eq!(
            (q.a, q.b, q.c, q.discriminant),
            (1.0, -16.0, 60.0, 16.0),
            "{method:?}"
        );
        let roots = q.roots.expect("two real roots");
        assert_eq!(
            (roots.near, roots.far),
            (8.0 - 2.0, 8.0 + 2.0),
            "{method:?}"
        );
        assert!(hit.barycentrics.is_none());
    }
}

#[test]
fn triangle_hit_reports_the_lectures_beta_and_gamma() {
    // The lecture's triangle t0 = (−1, 0, 0), t1 = (1, 0, 0), t2 = (0, 1, 0),
    // seen straight on from (0.2, 0.3, 3): the hit (0.2, 0.3, 0) at α = 3 is
    // t0 + β (2, 0, 0) + γ (1, 1, 0), so γ = 0.3 and 2β + γ = 1.2, β = 0.45.
    let world = world_from_xml(
        r#"<scene>
  <camera eye="0.2 0.3 3" toward="0 0 -1" theta="10" width="1" height="1"/>
  <triangle name="lecture triangle" t0="-1 0 0" t1="1 0 0" t2="0 1 0"/>
</scene>"#,
    );
    for method in METHODS {
        let options = RenderOptions {
            method,
            ..Default::default()
        };
        let inspection = inspect(&world, &options, 0, 0, None);
        let hit = hit_of(inspection.primary());
        assert_eq!(hit.shape, "triangle");
        assert!((hit.alpha - 3.0).abs() < 1e-6, "{method:?} {}", hit.alpha);
        let b = hit.barycentrics.expect("a triangle reports β and γ");
        assert!(
            (b.beta - 0.45).abs() < 1e-6 && (b.gamma - 0.3).abs() < 1e-6,
            "{method:?} {b:?}"
        );
        assert_eq!(hit.normal, Vec3::Z);
        assert!(hit.sphere.is_none());
    }
}

#[test]
fn shadow_ray_blocked_by_a_sphere_reports_that_sphere_as_blocker() {
    // A floor point under a light at (0, 4, 0), with a ball of radius 0.5 at
    // (0, 2, 0) between them: the shadow ray from ≈(0, 0, 0) straight up meets
    // the ball at α ≈ 2 − 0.5 = 1.5 and the sample is black.
    let world = world_from_xml(
        r#"<scene>
  <camera eye="3 5 0" toward="-3 -5 0" theta="0.05" width="1" height="1"/>
  <light type="point" position="0 4 0" intensity="40"/>
  <floor color="0.5 0.5 0.5"/>
  <sphere name="blocker" center="0 2 0" radius="0.5"/>
</scene>"#,
    );
    for method in METHODS {
        let options = RenderOptions {
            method,
            ..Default::default()
        };
        let inspection = inspect(&world, &options, 0, 0, None);
        assert_eq!(hit_of(inspection.primary()).object.index, 0, "the floor");
        let shadows: Vec<_> = inspection.children(0).collect();
        assert_eq!(shadows.len(), 1, "one light, one shadow ray");
        let (_, ray) = shadows[0];
        assert_eq!(ray.kind, RayKind::Shadow);
        let test = ray.shadow.as_ref().expect("a shadow test");
        assert_eq!(test.target, ShadowTarget::Light(0));
        assert!(test.blocked);
        let blocker = test.blocker.as_ref().expect("the blocker");
        assert_eq!(
            (blocker.object.index, blocker.object.name.as_str()),
            (1, "blocker")
        );
        assert!((blocker.alpha - 1.5).abs() < 1e-3, "{}", blocker.alpha);
        assert!(
            (ray.t_max - 4.0).abs() < 1e-3,
            "t_max is the light's distance"
        );
        assert_eq!(ray.contribution, Vec3::ZERO);
        assert_eq!(inspection.color, Vec3::ZERO);
    }
}

#[test]
fn pixel_outside_the_image_is_refused_with_the_valid_range() {
    let world = shipped("seed.xml", 40, 25);
    let options = RenderOptions::default();
    for (i, j) in [(40, 0), (0, 25), (u32::MAX, 3)] {
        let error = inspect_pixel(&world, &options, i, j, None).expect_err("outside");
        let message = error.to_string();
        assert!(
            message.contains("40×25") && message.contains("0..=39") && message.contains("0..=24"),
            "{message}"
        );
    }
}
