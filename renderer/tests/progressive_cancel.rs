//! `ProgressiveRenderer::cancel`, in a process of its own: its long passes
//! would otherwise hold the global rayon pool that the other session tests
//! share (a paused session's last step waited behind them).

mod session;

use renderer::RenderOptions;
use renderer::progressive::{Job, ProgressiveRenderer, Step};
use session::{frames_until, world};
use std::time::{Duration, Instant};

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
