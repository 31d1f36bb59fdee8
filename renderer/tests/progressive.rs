//! The progressive session's contract: previews first, then passes that add
//! up to exactly the offline render; a new job hides every older frame; pause
//! stops refinement; dropping the session stops its thread.

mod session;

use renderer::display::srgb::linear_to_srgb8;
use renderer::film::preview::preview;
use renderer::progressive::{COARSEST_STRIDE, Job, ProgressiveRenderer, Step};
use renderer::{Film, RenderOptions};
use session::{frames_until, world};
use std::sync::Arc;
use std::time::{Duration, Instant};

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
    // A preview frame holds one value per block; read as pixels, it is the
    // preview image, and its picture is that image in sRGB.
    for f in &frames {
        let Step::Preview { stride } = f.step else {
            unreachable!()
        };
        let image = preview(&world, &options, stride);
        assert_eq!(*f.linear_image(), image, "stride {stride}");
        assert_eq!(
            f.pixels.len(),
            (48usize.div_ceil(stride as usize)) * 32usize.div_ceil(stride as usize)
        );
        assert_eq!(f.linear_at(47, 31), Some(image[48 * 32 - 1]));
        assert_eq!(f.linear_at(48, 0), None);
        let srgb: Vec<[u8; 4]> = image
            .iter()
            .map(|&c| {
                let [r, g, b] = linear_to_srgb8(c);
                [r, g, b, 255]
            })
            .collect();
        assert_eq!(f.srgba8, srgb, "stride {stride}");
    }
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
