//! The progressive session's contract: previews first, then passes that add
//! up to exactly the offline render; a new job hides every older frame; pause
//! stops refinement; dropping the session stops its thread.

use renderer::progressive::{COARSEST_STRIDE, Job, ProgressiveRenderer, RenderedFrame, Step};
use renderer::{Film, RenderOptions, World};
use scene::{Object, Scene, Shape};
use std::sync::Arc;
use std::time::{Duration, Instant};

fn world(width: u32, height: u32, radius: f32) -> Arc<World> {
    let scene = Scene {
        camera: scene::Camera {
            width,
            height,
            ..Default::default()
        },
        objects: vec![
            Object {
                name: None,
                shape: Shape::Sphere {
                    center: None,
                    radius,
                },
                material: Some("glass".into()),
                params: Default::default(),
            },
            Object {
                name: None,
                shape: Shape::Floor { y: 0.0 },
                material: Some("marble".into()),
                params: Default::default(),
            },
        ],
        ..Default::default()
    };
    Arc::new(World::from_scene(&scene).expect("valid"))
}

/// Polls until `until` accepts a frame or 60 s pass; returns every frame seen.
fn frames_until(
    session: &ProgressiveRenderer,
    until: impl Fn(&RenderedFrame) -> bool,
) -> Vec<RenderedFrame> {
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut seen = Vec::new();
    while Instant::now() < deadline {
        if let Some(frame) = session.take_frame() {
            let stop = until(&frame);
            seen.push(frame);
            if stop {
                return seen;
            }
        } else {
            std::thread::sleep(Duration::from_millis(1));
        }
    }
    panic!(
        "no accepted frame within 60 s; saw {:?}",
        seen.iter().map(|f| f.step).collect::<Vec<_>>()
    );
}

#[test]
fn previews_come_first_and_passes_add_up_to_the_offline_render() {
    let session = ProgressiveRenderer::new(|| {});
    let world = world(48, 32, 1.0);
    let options = RenderOptions::default();
    // A target of no passes: the session traces its previews and stops, so
    // the frames taken cannot race past them (the slot keeps only the newest).
    session.submit(Job {
        world: Arc::clone(&world),
        options,
        target_spp: Some(0),
    });
    let mut frames = frames_until(&session, |f| f.step == Step::Preview { stride: 2 });
    std::thread::sleep(Duration::from_millis(100));
    assert!(
        session.take_frame().is_none(),
        "no pass before the target asks for one"
    );
    assert!(
        frames
            .iter()
            .all(|f| matches!(f.step, Step::Preview { .. })),
        "{:?}",
        frames.iter().map(|f| f.step).collect::<Vec<_>>()
    );
    session.set_target_spp(Some(3));
    frames.extend(frames_until(&session, |f| {
        f.step == Step::Passes { spp: 3 }
    }));
    // Newest wins: frames may be skipped, but they never go backwards:
    // previews ever finer, then passes.
    let order = |s: Step| match s {
        Step::Preview { stride } => {
            assert!(stride.is_power_of_two() && (2..=COARSEST_STRIDE).contains(&stride));
            COARSEST_STRIDE - stride
        }
        Step::Passes { spp } => COARSEST_STRIDE + spp,
    };
    assert!(
        frames
            .windows(2)
            .all(|w| order(w[0].step) < order(w[1].step))
    );
    let last = frames.last().expect("a frame");
    assert_eq!(
        last.pixels,
        Film::render(&world, &options, 3).linear(),
        "bit for bit"
    );
    assert!(last.samples_per_second > 0.0);
    // Every traced sample is at least its camera ray.
    assert!(last.rays_per_second >= last.samples_per_second);
    assert!(
        frames
            .iter()
            .all(|f| matches!(f.step, Step::Passes { .. }) || f.rays_per_second == 0.0)
    );
}

#[test]
fn no_frame_of_an_older_job_appears_after_a_submit() {
    let session = ProgressiveRenderer::new(|| {});
    let options = RenderOptions::default();
    let old = session.submit(Job {
        world: world(160, 120, 1.0),
        options,
        target_spp: None,
    });
    frames_until(&session, |f| matches!(f.step, Step::Passes { .. }));
    let new = session.submit(Job {
        world: world(40, 30, 0.5),
        options,
        target_spp: Some(2),
    });
    assert!(new > old);
    let frames = frames_until(&session, |f| f.step == Step::Passes { spp: 2 });
    for f in &frames {
        assert_eq!(
            f.generation, new,
            "a stale frame of job {} was shown",
            f.generation
        );
        assert_eq!((f.width, f.height), (40, 30));
    }
}

#[test]
fn pause_stops_refinement_and_resume_continues() {
    let session = ProgressiveRenderer::new(|| {});
    session.submit(Job {
        world: world(32, 24, 1.0),
        options: RenderOptions::default(),
        target_spp: None,
    });
    frames_until(&session, |f| matches!(f.step, Step::Passes { .. }));
    session.set_paused(true);
    std::thread::sleep(Duration::from_millis(100)); // let the step in flight finish
    while session.take_frame().is_some() {}
    std::thread::sleep(Duration::from_millis(200));
    assert!(session.take_frame().is_none(), "no new frame while paused");
    session.set_paused(false);
    frames_until(&session, |f| matches!(f.step, Step::Passes { .. }));
}

#[test]
fn cancel_frees_the_workers_and_the_session_idles_until_the_next_submit() {
    let session = ProgressiveRenderer::new(|| {});
    // Passes of about a second (path traced, 1600×1200): without the
    // cancel, rayon work would wait for most of one.
    let options = RenderOptions {
        integrator: renderer::integrator::Integrator::Path,
        ..Default::default()
    };
    session.submit(Job {
        world: world(1600, 1200, 1.0),
        options,
        target_spp: None,
    });
    frames_until(&session, |f| matches!(f.step, Step::Passes { .. }));
    session.cancel();
    // The workers are free within a band of rows: rayon work from this
    // thread (as a BVH build for the next job) runs at once, and not after
    // the stale pass's remaining bands.
    let started = Instant::now();
    let sum: u64 = rayon::iter::ParallelIterator::sum(
        rayon::iter::IntoParallelIterator::into_par_iter(0..1000u64),
    );
    assert_eq!(sum, 499_500);
    assert!(
        started.elapsed() < Duration::from_millis(300),
        "rayon waited {:?} for the cancelled job",
        started.elapsed()
    );
    // No frame of the cancelled job, and nothing more until a submit.
    std::thread::sleep(Duration::from_millis(200));
    assert!(session.take_frame().is_none(), "a frame after the cancel");
    let next = session.submit(Job {
        world: world(40, 30, 0.5),
        options: RenderOptions::default(),
        target_spp: Some(1),
    });
    let frames = frames_until(&session, |f| f.step == Step::Passes { spp: 1 });
    assert!(frames.iter().all(|f| f.generation == next));
}

#[test]
fn dropping_the_session_stops_a_render_that_never_ends() {
    let session = ProgressiveRenderer::new(|| {});
    session.submit(Job {
        world: world(200, 150, 1.0),
        options: RenderOptions::default(),
        target_spp: None,
    });
    frames_until(&session, |f| matches!(f.step, Step::Passes { .. }));
    let started = Instant::now();
    drop(session);
    assert!(
        started.elapsed() < Duration::from_secs(5),
        "the worker stops within a band of rows"
    );
}

#[test]
fn raising_the_target_continues_the_same_image() {
    let session = ProgressiveRenderer::new(|| {});
    let world = world(32, 24, 1.0);
    let options = RenderOptions::default();
    let generation = session.submit(Job {
        world: Arc::clone(&world),
        options,
        target_spp: Some(1),
    });
    frames_until(&session, |f| f.step == Step::Passes { spp: 1 });
    session.set_target_spp(Some(3));
    let frames = frames_until(&session, |f| f.step == Step::Passes { spp: 3 });
    assert!(
        frames
            .iter()
            .all(|f| f.generation == generation && matches!(f.step, Step::Passes { .. }))
    );
    let last = frames.last().expect("a frame");
    assert_eq!(
        last.pixels,
        Film::render(&world, &options, 3).linear(),
        "continued, not restarted"
    );
}
