//! Whitted's adaptive tree depth (`RenderOptions::min_weight`): a bounce
//! whose weight in the pixel is negligible is not traced but taken to see
//! the background. Against the full trees (`min_weight` 0) of the same
//! samples.

mod common;

use glam::Vec3;
use renderer::inspect::inspect_pixel;
use renderer::integrator::{Integrator, MIN_WEIGHT};
use renderer::{Film, RenderOptions, World};

fn whitted(min_weight: f32) -> RenderOptions {
    RenderOptions {
        integrator: Integrator::Whitted,
        min_weight,
        ..Default::default()
    }
}

/// The shipped scenes with glass, mirrors and reflective marble.
fn worlds() -> Vec<(&'static str, World)> {
    ["glass.xml", "seed.xml", "primitives.xml"]
        .into_iter()
        .map(|name| (name, common::asset_world("scenes", name, 200, 125)))
        .collect()
}

/// The cut-off trees trace fewer rays, and no pixel moves by more than 2%
/// of its full tree's radiance (or of 1, for a dark one; the largest change
/// measured is 1.24%, on glass.xml at 400 × 250); over the image, the mean
/// change stays below a tenth of a display step. What is left out weighs
/// less than 1/255 per ray, and sees the background instead of nothing, so
/// a tree keeps nearly all its energy.
#[test]
fn cut_off_trees_trace_fewer_rays_and_change_no_pixel_visibly() {
    for (name, world) in worlds() {
        let full = Film::render(&world, &whitted(0.0), 1);
        let cut = Film::render(&world, &whitted(MIN_WEIGHT), 1);
        assert!(
            cut.rays() <= full.rays(),
            "{name}: {} rays cut, {} full",
            cut.rays(),
            full.rays()
        );
        let (full_pixels, cut_pixels) = (full.linear(), cut.linear());
        let mut total = 0.0f64;
        for (k, (f, c)) in full_pixels.iter().zip(&cut_pixels).enumerate() {
            let change = (*f - *c).abs().max_element();
            let bound = 0.02 * f.max_element().max(1.0);
            assert!(change <= bound, "{name}, pixel {k}: {f} full, {c} cut");
            total += f64::from(change);
        }
        let mean = total / full_pixels.len() as f64;
        assert!(mean < 0.1 / 255.0, "{name}: mean change {mean}");
    }
    // The glass scene's trees are where the work goes: cut, it needs far fewer rays.
    let glass = common::asset_world("scenes", "glass.xml", 200, 125);
    let full = Film::render(&glass, &whitted(0.0), 1).rays();
    let cut = Film::render(&glass, &whitted(MIN_WEIGHT), 1).rays();
    assert!(
        (cut as f64) < 0.8 * full as f64,
        "glass.xml: {cut} rays cut against {full} full"
    );
}

/// A weight of 0 traces every bounce: no hit of any inspected tree notes
/// a bounce left out. With the default, some glass hit does, and the
/// inspector's tree still gives the film's colour bit for bit.
#[test]
fn the_inspector_shows_where_a_tree_was_cut() {
    let world = common::asset_world("scenes", "glass.xml", 80, 50);
    let mut noted = 0;
    for (min_weight, film) in [0.0, MIN_WEIGHT].map(|w| (w, Film::render(&world, &whitted(w), 1))) {
        for j in 0..world.camera.h {
            for i in 0..world.camera.w {
                let inspection = inspect_pixel(&world, &whitted(min_weight), i, j, Some(0))
                    .expect("the pixel is in the image");
                let notes = inspection
                    .rays
                    .iter()
                    .filter(|r| r.hit.as_ref().is_some_and(|h| h.negligible))
                    .count();
                if min_weight == 0.0 {
                    assert_eq!(notes, 0, "({i}, {j})");
                } else {
                    noted += notes;
                }
                assert_eq!(
                    inspection.color.to_array().map(f32::to_bits),
                    film.pixel(i, j).to_array().map(f32::to_bits),
                    "({i}, {j}), min weight {min_weight}"
                );
            }
        }
    }
    assert!(noted > 0, "no cut-off in glass.xml's trees");
}

/// With a weight of 1, no bounce off clear glass (Fresnel reflectance and
/// transmittance both below 1) is traced: each is taken to see the sky, so
/// under a uniform sky every pixel is the sky's radiance (Fresnel's split
/// keeps it), and only the camera rays are traced.
#[test]
fn a_weight_of_one_stops_every_tree_at_its_first_hit() {
    let sky = 0.75;
    let world = common::glass_sphere_under_sky(sky, 24);
    let film = Film::render(&world, &whitted(1.0), 1);
    assert_eq!(film.rays(), 24 * 24, "camera rays only");
    for value in film.linear() {
        assert!(
            (value - Vec3::splat(sky)).abs().max_element() < 1e-6,
            "{value}"
        );
    }
}
