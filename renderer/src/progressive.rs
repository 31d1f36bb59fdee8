//! A progressive render session: a worker thread refines the image of the
//! newest job — coarse previews first (one pixel in s × s, then s/2 × s/2,
//! … down to 2 × 2, the first s chosen so that it fits a display frame at
//! the speed the last step measured), then full passes that accumulate
//! samples — and hands each finished step over in a
//! one-frame slot where the newest frame wins. Submitting a job cancels the
//! stale one at once: no frame of an older job is handed out after
//! [`ProgressiveRenderer::submit`] returns. Nothing here ever blocks the caller
//! on rendering.
//!
//! Each frame is shown in the session's [`Display`] mode, converted here on
//! the render thread; switching the mode re-publishes the current state at
//! the end of the step in progress and never restarts the refinement.

use crate::display::DisplayImage;
use crate::display::image::{Source, display_image};
use crate::display::{Display, Legend};
use crate::film::Film;
use crate::film::aov::{Aov, render_aov_unless};
use crate::film::preview::{PreviewSamples, expand_blocks};
use crate::integrator::RenderOptions;
use crate::world::World;
use glam::Vec3;
use scene::View;
use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The coarsest preview: one sample per 32 × 32 block.
pub const COARSEST_STRIDE: u32 = 32;

/// The first preview's stride before anything has been measured.
pub const UNMEASURED_STRIDE: u32 = 8;

/// What the first preview of an edit may take on the render thread, its
/// tracing and its conversion for display together: 10 ms of a 60 Hz
/// display frame, leaving the rest for the stale job's last band of rows,
/// the hand-over, the texture upload and drawing.
pub const PREVIEW_BUDGET: Duration = Duration::from_millis(10);

/// The first preview's stride for a `width` × `height` image when the last
/// step took `per_sample` per traced sample (wall-clock, every worker
/// counted) and its conversion for display took `publish`: the finest
/// power of two, from 2 to [`COARSEST_STRIDE`], whose preview fits
/// [`PREVIEW_BUDGET`]; 1 when a whole pass does (no previews then);
/// [`UNMEASURED_STRIDE`] when nothing was measured.
pub fn first_preview_stride(
    width: u32,
    height: u32,
    per_sample: Option<Duration>,
    publish: Duration,
) -> u32 {
    let Some(per_sample) = per_sample else {
        return UNMEASURED_STRIDE;
    };
    let left = PREVIEW_BUDGET.saturating_sub(publish).as_secs_f64();
    let fits = |stride: u32| {
        let samples = width.div_ceil(stride) as f64 * height.div_ceil(stride) as f64;
        samples * per_sample.as_secs_f64() <= left
    };
    if fits(1) {
        return 1;
    }
    let mut stride = 2;
    while stride < COARSEST_STRIDE && !fits(stride) {
        stride *= 2;
    }
    stride
}

/// What to render: a prepared scene snapshot and how far to refine it.
#[derive(Clone, Debug)]
pub struct Job {
    /// The immutable render copy of the scene.
    pub world: Arc<World>,
    /// Integrator settings.
    pub options: RenderOptions,
    /// Stop after this many samples per pixel; `None` refines until a new job.
    pub target_spp: Option<u32>,
}

/// Which step of refinement a frame shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// One ray per `stride` × `stride` block.
    Preview {
        /// Block size in pixels.
        stride: u32,
    },
    /// The mean of `spp` full passes.
    Passes {
        /// Samples per pixel so far.
        spp: u32,
    },
}

/// A finished refinement step, ready to show.
#[derive(Clone, Debug)]
pub struct RenderedFrame {
    /// Which job it belongs to (increases with every submit).
    pub generation: u64,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear radiance (the colour, whatever the display mode), row by row
    /// from the top: every pixel after a pass; a preview's one value per
    /// block (⌈width/stride⌉ × ⌈height/stride⌉), so that showing a preview
    /// costs no full-resolution image besides `srgba8`. Read pixels with
    /// [`RenderedFrame::linear_at`] or [`RenderedFrame::linear_image`].
    pub pixels: Vec<Vec3>,
    /// The picture of the display mode as 8-bit sRGB RGBA (opaque),
    /// converted on the render thread so that showing a frame costs the UI
    /// only a copy.
    pub srgba8: Vec<[u8; 4]>,
    /// What `srgba8`'s colours mean, for a legend.
    pub legend: Legend,
    /// The exposure and tone curve `srgba8`'s colour was shown with.
    pub view: View,
    /// Which step this is.
    pub step: Step,
    /// Time from the submit to this frame.
    pub since_submit: Duration,
    /// Full-pass camera samples per second so far, counting only those the
    /// passes traced (0 for previews).
    pub samples_per_second: f64,
    /// Full-pass rays per second so far, every kind of ray counted (0 for previews).
    pub rays_per_second: f64,
    /// Samples left out because they were NaN or infinite.
    pub discarded: u64,
}

impl RenderedFrame {
    /// The side of the block of pixels each of `pixels` covers.
    fn block(&self) -> u32 {
        match self.step {
            Step::Preview { stride } => stride.max(1),
            Step::Passes { .. } => 1,
        }
    }

    /// The linear colour shown at pixel (i, j), if the image has it.
    pub fn linear_at(&self, i: u32, j: u32) -> Option<Vec3> {
        let block = self.block();
        let columns = self.width.div_ceil(block) as usize;
        (i < self.width && j < self.height)
            .then(|| {
                self.pixels
                    .get((j / block) as usize * columns + (i / block) as usize)
            })
            .flatten()
            .copied()
    }

    /// The linear colour of every pixel, row by row from the top (a
    /// preview's values repeated over their blocks).
    pub fn linear_image(&self) -> Cow<'_, [Vec3]> {
        match self.block() {
            1 => Cow::Borrowed(&self.pixels),
            block => Cow::Owned(expand_blocks(&self.pixels, self.width, self.height, block)),
        }
    }
}

/// The worker's inbox.
#[derive(Default)]
struct Inbox {
    pending: Option<(u64, Job, Instant)>,
    /// A new target spp for the current job, when one was set.
    target: Option<Option<u32>>,
    /// A new display mode, when one was set.
    display: Option<Display>,
    /// A new view transform, when one was set.
    view: Option<View>,
    paused: bool,
    shutdown: bool,
}

struct Shared {
    generation: AtomicU64,
    inbox: Mutex<Inbox>,
    wake: Condvar,
    slot: Mutex<Option<RenderedFrame>>,
    on_frame: Box<dyn Fn() + Send + Sync>,
}

/// Locks a mutex, recovering the data if a panicking thread poisoned it.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A render session owning one worker thread (which uses rayon for each step).
pub struct ProgressiveRenderer {
    shared: Arc<Shared>,
    worker: Option<JoinHandle<()>>,
}

impl ProgressiveRenderer {
    /// Starts the worker. `on_frame` is called (from the worker) after each
    /// new frame, e.g. to ask the UI for a repaint.
    pub fn new(on_frame: impl Fn() + Send + Sync + 'static) -> Self {
        let shared = Arc::new(Shared {
            generation: AtomicU64::new(0),
            inbox: Mutex::new(Inbox::default()),
            wake: Condvar::new(),
            slot: Mutex::new(None),
            on_frame: Box::new(on_frame),
        });
        let worker_shared = Arc::clone(&shared);
        let worker = std::thread::Builder::new()
            .name("raylab-render".into())
            .spawn(move || work(&worker_shared))
            .expect("the render thread starts");
        Self {
            shared,
            worker: Some(worker),
        }
    }

    /// Replaces the current job; stale work stops at its next band of rows.
    /// Returns the new job's generation.
    pub fn submit(&self, job: Job) -> u64 {
        let generation = {
            let mut slot = lock(&self.shared.slot);
            *slot = None;
            self.shared.generation.fetch_add(1, Ordering::SeqCst) + 1
        };
        lock(&self.shared.inbox).pending = Some((generation, job, Instant::now()));
        self.shared.wake.notify_all();
        generation
    }

    /// Stops the current job at its next band of rows, freeing the workers
    /// at once, and hands out no more of its frames; the session then idles
    /// until the next [`ProgressiveRenderer::submit`]. For an edit whose
    /// world is about to be prepared: its BVH builds need the workers the
    /// stale job would otherwise keep busy to the end of its pass.
    pub fn cancel(&self) {
        {
            let mut slot = lock(&self.shared.slot);
            *slot = None;
            self.shared.generation.fetch_add(1, Ordering::SeqCst);
        }
        self.shared.wake.notify_all();
    }

    /// Pauses or resumes refinement (a paused session finishes its current step).
    pub fn set_paused(&self, paused: bool) {
        lock(&self.shared.inbox).paused = paused;
        self.shared.wake.notify_all();
    }

    /// Changes the current job's target spp without restarting it: raising it
    /// continues refining the image on screen; `None` refines without end.
    pub fn set_target_spp(&self, target_spp: Option<u32>) {
        lock(&self.shared.inbox).target = Some(target_spp);
        self.shared.wake.notify_all();
    }

    /// Shows later frames in `display`, without restarting: the current
    /// state (preview or film) is published again in the new mode as soon
    /// as the step in progress ends, even when the job is done or paused.
    /// The AOV modes trace one primary ray per pixel centre P_ij, once per
    /// job, the first time one is shown.
    pub fn set_display(&self, display: Display) {
        lock(&self.shared.inbox).display = Some(display);
        self.shared.wake.notify_all();
    }

    /// Shows the colour of later frames through `view` (exposure and tone
    /// curve), without restarting: like [`ProgressiveRenderer::set_display`],
    /// the current state is published again as soon as the step in
    /// progress ends.
    pub fn set_view(&self, view: View) {
        lock(&self.shared.inbox).view = Some(view);
        self.shared.wake.notify_all();
    }

    /// The newest frame not yet taken, if any; never blocks on rendering.
    pub fn take_frame(&self) -> Option<RenderedFrame> {
        lock(&self.shared.slot).take()
    }
}

impl Drop for ProgressiveRenderer {
    fn drop(&mut self) {
        lock(&self.shared.inbox).shutdown = true;
        self.shared.generation.fetch_add(1, Ordering::SeqCst);
        self.shared.wake.notify_all();
        if let Some(worker) = self.worker.take() {
            let _ = worker.join();
        }
    }
}

/// The job the worker is refining.
struct Current {
    generation: u64,
    job: Job,
    submitted: Instant,
    /// The passes so far: made at the first pass, so that an edit's
    /// previews do not wait for 30 MB of a 1280×720 film to be allocated
    /// and zeroed (it took 2–15 ms), in the last job's film's memory
    /// ([`Film::recycled`]).
    film: Option<Film>,
    /// The next preview's stride; `None` once the previews are done.
    next_stride: Option<u32>,
    /// The latest preview's samples, until the first pass has taken them.
    preview_samples: Option<PreviewSamples>,
    /// Samples the passes took from a preview instead of tracing them.
    reused: u64,
    pass_time: Duration,
    /// The AOVs shown so far for this job.
    aovs: HashMap<Aov, Vec<f32>>,
    /// The step last published and its speeds, to publish it again.
    shown: Option<(Step, f64, f64)>,
}

impl Current {
    fn done(&self) -> bool {
        let passes = self.film.as_ref().map_or(0, Film::passes);
        self.next_stride.is_none()
            && (self.film.as_ref().is_some_and(Film::converged)
                || self.job.target_spp.is_some_and(|target| passes >= target))
    }
}

/// How the worker shows its frames: the display mode, and the view
/// transform of the colour.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Shown {
    display: Display,
    view: View,
}

fn work(shared: &Shared) {
    let mut current: Option<Current> = None;
    let mut shown = Shown::default();
    // The wall-clock time per traced sample of the last step, any job's,
    // and how long its conversion for display took.
    let mut per_sample: Option<Duration> = None;
    let mut publish_time = Duration::ZERO;
    // The film of the last job dropped, for the next job's first pass to
    // reuse its memory.
    let mut spare: Option<Film> = None;
    loop {
        let mut republish = false;
        {
            let mut inbox = lock(&shared.inbox);
            loop {
                if inbox.shutdown {
                    return;
                }
                if let Some(target) = inbox.target.take()
                    && let Some(c) = current.as_mut()
                {
                    c.job.target_spp = target;
                }
                if let Some(new) = inbox.display.take()
                    && new != shown.display
                {
                    shown.display = new;
                    republish = current.as_ref().is_some_and(|c| c.shown.is_some());
                }
                if let Some(new) = inbox.view.take()
                    && new != shown.view
                {
                    shown.view = new;
                    republish = current.as_ref().is_some_and(|c| c.shown.is_some());
                }
                // A cancelled job is dropped (a submitted one replaces it below).
                if current
                    .as_ref()
                    .is_some_and(|c| c.generation != shared.generation.load(Ordering::SeqCst))
                {
                    spare = current.take().and_then(|c| c.film).or(spare.take());
                }
                if let Some((generation, job, submitted)) = inbox.pending.take() {
                    let (w, h) = (job.world.camera.w, job.world.camera.h);
                    let first = first_preview_stride(w, h, per_sample, publish_time);
                    if let Some(film) = current.take().and_then(|c| c.film) {
                        spare = Some(film);
                    }
                    // A film of another size is no use to this job: its
                    // memory goes back now, not at the first pass.
                    spare = spare.filter(|f| (f.width(), f.height()) == (w, h));
                    current = Some(Current {
                        generation,
                        job,
                        submitted,
                        film: None,
                        next_stride: (first > 1).then_some(first),
                        preview_samples: None,
                        reused: 0,
                        pass_time: Duration::ZERO,
                        aovs: HashMap::new(),
                        shown: None,
                    });
                    republish = false;
                    break;
                }
                if republish || current.as_ref().is_some_and(|c| !c.done()) && !inbox.paused {
                    break;
                }
                inbox = shared
                    .wake
                    .wait(inbox)
                    .unwrap_or_else(PoisonError::into_inner);
            }
        }
        if let Some(c) = current.as_mut() {
            if republish {
                publish(shared, c, shown);
            } else if let Some((traced, published)) = step(shared, c, shown, &mut spare) {
                per_sample = Some(traced);
                publish_time = published;
            }
        }
    }
}

/// Renders one preview or one full pass of `c` and publishes it unless stale;
/// its film, made at the first pass, takes `spare`'s memory if it can.
/// Each preview traces only the samples the previous one did not, and the
/// first pass only those no preview did: after an edit, every sample 0 is
/// traced once. Returns the step's wall-clock time per sample it traced and
/// the time its publishing took, unless it was cut short.
fn step(
    shared: &Shared,
    c: &mut Current,
    shown: Shown,
    spare: &mut Option<Film>,
) -> Option<(Duration, Duration)> {
    let stale = || shared.generation.load(Ordering::SeqCst) != c.generation;
    let world = Arc::clone(&c.job.world);
    let started = Instant::now();
    let traced;
    if let Some(stride) = c.next_stride {
        c.next_stride = (stride > 2).then_some(stride / 2);
        let known = c.preview_samples.as_ref().map_or(0, PreviewSamples::len);
        let samples = PreviewSamples::trace_unless(
            &world,
            &c.job.options,
            stride,
            c.preview_samples.as_ref(),
            &stale,
        )?;
        traced = samples.len().saturating_sub(known);
        c.preview_samples = Some(samples);
        c.shown = Some((Step::Preview { stride }, 0.0, 0.0));
    } else {
        let film = c
            .film
            .get_or_insert_with(|| Film::recycled(spare.take(), world.camera.w, world.camera.h));
        let samples_before = film.samples();
        let reused_before = c.reused;
        let completed = match c.preview_samples.take() {
            Some(known) => {
                c.reused += known.len() as u64;
                film.add_pass_reusing(&world, &c.job.options, &known, &stale)
            }
            None => film.add_pass_unless(&world, &c.job.options, &stale),
        };
        if !completed {
            return None;
        }
        traced =
            (film.samples() - samples_before).saturating_sub(c.reused - reused_before) as usize;
        c.pass_time += started.elapsed();
        let samples = film.samples() as f64 - c.reused as f64;
        let seconds = c.pass_time.as_secs_f64().max(1e-9);
        let step = Step::Passes { spp: film.passes() };
        c.shown = Some((step, samples / seconds, film.rays() as f64 / seconds));
    }
    let took = started.elapsed();
    let publishing = Instant::now();
    publish(shared, c, shown);
    (traced > 0).then(|| (took / traced as u32, publishing.elapsed()))
}

/// Publishes the step last rendered in `display` unless the job is stale
/// (an AOV the mode needs is traced first, and abandoned if it goes stale).
fn publish(shared: &Shared, c: &mut Current, shown: Shown) {
    let Shown { display, view } = shown;
    let stale = || shared.generation.load(Ordering::SeqCst) != c.generation;
    // An edit made while the step ran: its preview should not wait for
    // this step's conversion.
    if stale() {
        return;
    }
    let Some((step, samples_per_second, rays_per_second)) = c.shown else {
        return;
    };
    if let Some(aov) = display.aov()
        && !c.aovs.contains_key(&aov)
    {
        let Some(values) = render_aov_unless(&c.job.world, aov, c.job.options.method, &stale)
        else {
            return;
        };
        c.aovs.insert(aov, values);
    }
    let (pixels, source) = match (step, &c.preview_samples, &c.film) {
        (Step::Preview { .. }, Some(samples), _) => {
            (samples.finite_values(), Source::Preview(samples))
        }
        (Step::Passes { .. }, _, Some(film)) => (film.linear(), Source::Film(film)),
        // Neither can happen: a preview is shown with its samples, a pass with its film.
        _ => return,
    };
    let aov = display
        .aov()
        .and_then(|a| c.aovs.get(&a))
        .map(Vec::as_slice);
    let DisplayImage { srgba8, legend } = display_image(display, view, source, &pixels, aov);
    let frame = RenderedFrame {
        generation: c.generation,
        width: c.job.world.camera.w,
        height: c.job.world.camera.h,
        srgba8,
        legend,
        view,
        pixels,
        step,
        since_submit: c.submitted.elapsed(),
        samples_per_second,
        rays_per_second,
        discarded: c.film.as_ref().map_or(0, Film::discarded),
    };
    {
        let mut slot = lock(&shared.slot);
        if stale() {
            return;
        }
        *slot = Some(frame);
    }
    (shared.on_frame)();
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A frame of a 5 × 3 image whose `pixels` are `values` at `step`.
    fn frame(step: Step, values: Vec<Vec3>) -> RenderedFrame {
        RenderedFrame {
            generation: 1,
            width: 5,
            height: 3,
            pixels: values,
            srgba8: vec![[0, 0, 0, 255]; 15],
            legend: Legend {
                display: Display::Color,
                range: None,
                note: String::new(),
            },
            view: View::default(),
            step,
            since_submit: Duration::ZERO,
            samples_per_second: 0.0,
            rays_per_second: 0.0,
            discarded: 0,
        }
    }

    /// A preview's values cover blocks, the last ones cut by the image's
    /// edge (5 × 3 pixels in blocks of 2 × 2: 3 × 2 values); a pass's
    /// values are the pixels.
    #[test]
    fn frames_read_as_pixels_repeat_a_preview_over_its_blocks() {
        let values: Vec<Vec3> = (0..6).map(|k| Vec3::splat(k as f32)).collect();
        let preview = frame(Step::Preview { stride: 2 }, values);
        let block_of = |i: u32, j: u32| Vec3::splat(((j / 2) * 3 + i / 2) as f32);
        let image = preview.linear_image();
        assert_eq!(image.len(), 15);
        for j in 0..3 {
            for i in 0..5 {
                assert_eq!(preview.linear_at(i, j), Some(block_of(i, j)), "({i}, {j})");
                assert_eq!(image[(j * 5 + i) as usize], block_of(i, j), "({i}, {j})");
            }
        }
        assert_eq!(preview.linear_at(5, 0), None);
        assert_eq!(preview.linear_at(0, 3), None);
        let pixels: Vec<Vec3> = (0..15).map(|k| Vec3::splat(k as f32)).collect();
        let pass = frame(Step::Passes { spp: 1 }, pixels.clone());
        assert_eq!(pass.linear_at(4, 2), Some(pixels[14]));
        assert_eq!(*pass.linear_image(), pixels);
    }

    /// The time one sample would take for a `stride` preview of a
    /// `width` × `height` image to take exactly the budget.
    fn filling(width: u32, height: u32, stride: u32) -> Duration {
        let samples = width.div_ceil(stride) * height.div_ceil(stride);
        PREVIEW_BUDGET / samples
    }

    #[test]
    fn the_first_preview_is_the_finest_that_fits_the_budget() {
        let (w, h) = (1280, 720);
        let free = Duration::ZERO;
        assert_eq!(first_preview_stride(w, h, None, free), UNMEASURED_STRIDE);
        for stride in [2, 4, 8, 16, 32] {
            // Just fits at this stride, and not at the next finer one.
            let per_sample = filling(w, h, stride);
            assert_eq!(first_preview_stride(w, h, Some(per_sample), free), stride);
            let slower = Some(per_sample + Duration::from_nanos(5));
            let coarser = (stride * 2).min(COARSEST_STRIDE);
            assert_eq!(
                first_preview_stride(w, h, slower, free),
                coarser,
                "{stride}"
            );
            // Publishing takes its share of the budget.
            let publish = Duration::from_millis(1);
            assert_eq!(
                first_preview_stride(w, h, Some(per_sample), publish),
                coarser
            );
        }
        // A whole pass fits: no previews.
        assert_eq!(first_preview_stride(w, h, Some(filling(w, h, 1)), free), 1);
        // However slow, or however long publishing takes, never coarser than the coarsest.
        let glacial = Some(Duration::from_secs(1));
        assert_eq!(first_preview_stride(w, h, glacial, free), COARSEST_STRIDE);
        let quick = Some(filling(w, h, 8));
        assert_eq!(
            first_preview_stride(w, h, quick, PREVIEW_BUDGET),
            COARSEST_STRIDE
        );
    }
}
