//! The diagnostic modes' numbers against what the scene implies: relative
//! variance, the shape tests the BVH makes, spp that keeps growing across a
//! display switch, and the depth legend's range.

use renderer::display::{Display, Scale};
use renderer::film::aov::{Aov, render_aov};
use renderer::geometry::counters::shape_tests_on_this_thread;
use renderer::integrator::sample_pixel;
use renderer::progressive::{Job, ProgressiveRenderer, RenderedFrame, Step};
use renderer::{Film, Method, RenderOptions, World};
use scene::color::luminance;
use scene::{Tonemap, View};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// A matte unit sphere at the origin seen from z = 5, a point light at
/// z = 10 behind the eye (no ambient: the background is black), and
/// `extra` small spheres far off to the side that nothing sees or hits.
fn sphere_world(size: u32, extra: usize) -> World {
    let extras: String = (0..extra)
        .map(|k| format!(r#"<sphere center="{} 0 0" radius="1"/>"#, 100 + 10 * k))
        .collect();
    let xml = format!(
        r#"<scene>
             <camera eye="0 0 5" toward="0 0 -1" theta="20" width="{size}" height="{size}"/>
             <light type="point" position="0 0 10" intensity="100"/>
             <sphere center="0 0 0" radius="1"/>
             {extras}
           </scene>"#
    );
    let scene = scene::read_str(&xml, "test.xml").expect("parses");
    World::from_scene(&scene).expect("valid")
}

#[test]
fn relative_variance_is_zero_on_the_background_and_matches_the_samples_at_an_edge() {
    let world = sphere_world(24, 0);
    let options = RenderOptions::default();
    let passes = 8;
    let film = Film::render(&world, &options, passes);
    let variance = film.relative_variance().expect("two passes or more");
    let w = world.camera.w;
    assert_eq!(
        variance[0], 0.0,
        "every background sample is the same black"
    );

    // A pixel on the middle row whose samples both hit and miss the sphere.
    let j = w / 2;
    let edge = (0..w)
        .find(|&i| {
            let hits = (0..passes)
                .filter(|&s| sample_pixel(&world, &options, i, j, s) != world.ambient)
                .count();
            hits > 0 && hits < passes as usize
        })
        .expect("the sphere's silhouette crosses the middle row");
    let y: Vec<f64> = (0..passes)
        .map(|s| f64::from(luminance(sample_pixel(&world, &options, edge, j, s))))
        .collect();
    let n = f64::from(passes);
    let mean = y.iter().sum::<f64>() / n;
    let s2 = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let expected = s2 / n / (mean * mean);
    let got = f64::from(variance[(j * w + edge) as usize]);
    assert!(got > 0.0);
    assert!(
        (got - expected).abs() <= 1e-4 * expected,
        "pixel ({edge}, {j}): {got} vs {expected}"
    );
}

#[test]
fn far_off_shapes_cost_nothing_a_miss_costs_nothing_and_a_lit_hit_costs_two() {
    // Traced ray by ray through the BVH (the lecture's formulas take no
    // packets).
    let options = RenderOptions {
        method: Method::Lecture,
        ..RenderOptions::default()
    };
    for n in [1usize, 5] {
        let world = sphere_world(16, n - 1);
        assert_eq!(world.objects.len(), n);
        let film = Film::render(&world, &options, 3);
        let cost = film.cost_per_sample();
        // A corner ray enters no shape's box in the BVH: nothing is tested.
        assert_eq!(cost[0], 0.0, "a miss with {n} shapes");
        // The centre ray enters only the sphere's box, and so does its
        // shadow ray toward the light behind the eye: two tests, whatever
        // the number of spheres far off to the side.
        assert_eq!(cost[8 * 16 + 8], 2.0, "a lit hit with {n} shapes");
    }
}

#[test]
fn rays_in_packets_cost_every_shape_their_packet_tests() {
    // A few spheres (the robust formulas): Whitted's camera rays go
    // sixteen at a time against every sphere, and so do their shadow rays.
    for n in [1usize, 5] {
        let world = sphere_world(16, n - 1);
        let film = Film::render(&world, &RenderOptions::default(), 3);
        let cost = film.cost_per_sample();
        assert_eq!(cost[0], n as f32, "a miss with {n} shapes");
        // Unblocked, the shadow ray is tested against every sphere too.
        assert_eq!(
            cost[8 * 16 + 8],
            2.0 * n as f32,
            "a lit hit with {n} shapes"
        );
    }
}

#[test]
fn only_shapes_whose_boxes_the_ray_enters_are_tested() {
    // Two spheres on the ray's line, one beside it.
    let xml = r#"<scene>
        <sphere center="0 0 -20" radius="1"/>
        <sphere center="0 0 -10" radius="1"/>
        <sphere center="5 0 -10" radius="1"/>
      </scene>"#;
    let world = World::from_scene(&scene::read_str(xml, "t.xml").expect("parses")).expect("valid");
    let ray = renderer::geometry::ray::Ray::new(glam::Vec3::ZERO, glam::Vec3::NEG_Z);
    let count = |f: &dyn Fn()| {
        let before = shape_tests_on_this_thread();
        f();
        shape_tests_on_this_thread() - before
    };
    // Any-hit stops at the first blocker; closest-hit may test both spheres
    // on the line, never the one beside it.
    let any = count(&|| assert!(world.occluded(&ray, Method::Robust)));
    assert!((1..=2).contains(&any), "{any}");
    let closest = count(&|| {
        let hit = world.intersect(&ray, Method::Robust).expect("hits");
        assert_eq!(hit.object, 1, "the nearer sphere");
    });
    assert!((1..=2).contains(&closest), "{closest}");
    // A ray ending before the far sphere's box tests only the near one.
    let short = ray.with_t_max(15.0);
    assert_eq!(
        count(&|| assert!(world.occluded(&short, Method::Robust))),
        1
    );
    // A ray passing above every box tests nothing.
    let past = renderer::geometry::ray::Ray::new(glam::Vec3::new(0.0, 9.0, 0.0), glam::Vec3::NEG_Z);
    assert_eq!(
        count(&|| assert!(!world.occluded(&past, Method::Robust))),
        0
    );
    assert_eq!(
        count(&|| assert!(world.intersect(&past, Method::Robust).is_none())),
        0
    );
}

/// Polls until `until` accepts a frame or 60 s pass; returns that frame.
fn frame_until(
    session: &ProgressiveRenderer,
    until: impl Fn(&RenderedFrame) -> bool,
) -> RenderedFrame {
    let deadline = Instant::now() + Duration::from_secs(60);
    while Instant::now() < deadline {
        match session.take_frame() {
            Some(frame) if until(&frame) => return frame,
            Some(_) => {}
            None => std::thread::sleep(Duration::from_millis(1)),
        }
    }
    panic!("no accepted frame within 60 s");
}

fn spp(frame: &RenderedFrame) -> u32 {
    match frame.step {
        Step::Passes { spp } => spp,
        Step::Preview { .. } => 0,
    }
}

#[test]
fn switching_the_display_mid_render_keeps_refining_the_same_film() {
    let session = ProgressiveRenderer::new(|| {});
    let generation = session.submit(Job {
        world: Arc::new(sphere_world(32, 2)),
        options: RenderOptions::default(),
        target_spp: None,
    });
    let before = frame_until(&session, |f| spp(f) >= 2);
    assert_eq!(before.legend.display, Display::Color);
    session.set_display(Display::Variance);
    let switched = frame_until(&session, |f| f.legend.display == Display::Variance);
    assert_eq!(switched.generation, generation, "no new job");
    assert!(spp(&switched) >= spp(&before), "the film was kept");
    assert_eq!(switched.legend.range.map(|r| r.scale), Some(Scale::Log));
    assert_eq!(switched.pixels.len(), switched.srgba8.len());
    let later = frame_until(&session, |f| spp(f) > spp(&switched) + 1);
    assert_eq!(later.legend.display, Display::Variance, "the mode stays");
    session.set_display(Display::Cost);
    let cost = frame_until(&session, |f| f.legend.display == Display::Cost);
    assert!(spp(&cost) >= spp(&later));
    assert_eq!(
        cost.legend.range.map(|r| r.unit),
        Some("shape tests / sample")
    );
}

#[test]
fn a_finished_render_is_shown_again_at_once_in_a_new_mode() {
    let session = ProgressiveRenderer::new(|| {});
    session.submit(Job {
        world: Arc::new(sphere_world(16, 0)),
        options: RenderOptions::default(),
        target_spp: Some(3),
    });
    let done = frame_until(&session, |f| spp(f) == 3);
    session.set_display(Display::SamplesPerPixel);
    let shown = frame_until(&session, |_| true);
    assert_eq!(shown.legend.display, Display::SamplesPerPixel);
    assert_eq!(shown.step, done.step, "no further pass");
    let range = shown.legend.range.expect("a range");
    assert_eq!((range.min, range.max), (3.0, 3.0));
    assert_eq!(shown.pixels, done.pixels, "the colour stays the film's");
}

/// A new exposure and curve re-show the finished film at once, through the
/// view (each pixel exactly as the sRGB encoding of its scaled radiance),
/// without a new job or another pass; the linear pixels stay the film's.
#[test]
fn a_new_view_is_shown_at_once_without_restarting() {
    let session = ProgressiveRenderer::new(|| {});
    let generation = session.submit(Job {
        world: Arc::new(sphere_world(16, 0)),
        options: RenderOptions::default(),
        target_spp: Some(2),
    });
    let done = frame_until(&session, |f| spp(f) == 2);
    assert_eq!(done.view, View::default());
    let view = View {
        exposure: 1.0,
        tonemap: Tonemap::Clamp,
    };
    session.set_view(view);
    let shown = frame_until(&session, |f| f.view == view);
    assert_eq!(shown.generation, generation, "no new job");
    assert_eq!(shown.step, done.step, "no further pass");
    assert_eq!(shown.pixels, done.pixels, "the colour stays the film's");
    for (rgba, &c) in shown.srgba8.iter().zip(&done.pixels) {
        let [r, g, b] = renderer::display::srgb::linear_to_srgb8(2.0 * c);
        assert_eq!(*rgba, [r, g, b, 255], "{c}");
    }
    assert!(shown.srgba8 != done.srgba8, "a stop brighter");
}

#[test]
fn the_depth_legend_spans_the_finite_alphas_of_the_depth_aov() {
    let world = Arc::new(sphere_world(24, 0));
    let session = ProgressiveRenderer::new(|| {});
    session.set_display(Display::Depth);
    session.submit(Job {
        world: Arc::clone(&world),
        options: RenderOptions::default(),
        target_spp: Some(1),
    });
    let frame = frame_until(&session, |f| spp(f) == 1);
    assert_eq!(frame.legend.display, Display::Depth);
    let depth = render_aov(&world, Aov::Depth, Method::Robust);
    let finite = depth.iter().copied().filter(|d| d.is_finite());
    let lo = finite.clone().fold(f32::INFINITY, f32::min);
    let hi = finite.fold(f32::NEG_INFINITY, f32::max);
    let range = frame.legend.range.expect("a range");
    assert_eq!((range.min, range.max), (lo, hi));
    assert!(lo < hi && hi < 5.0, "the sphere spans α in [{lo}, {hi}]");
    assert_eq!(frame.srgba8[0], [0, 0, 0, 255], "a miss is black");
}
