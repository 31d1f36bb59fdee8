//! When a group gives its finished lanes new samples: at once, so every
//! lane is always busy, or once a cohort of [`COHORTS`]`[1]` lanes has
//! finished, so that the new samples (neighbouring pixels, taken in order)
//! start together and their rays, the bounce rays from nearby points and
//! the shadow rays toward the same lights, share the packet's walks.
//!
//! Which is faster depends on the scene, so it is measured while rendering
//! (path tracer, 16 spp, 512×384, 2 threads; time with cohorts of 8 against
//! refilling at once, medians of 2 runs): a sphere of 3,480 mesh triangles
//! 0.77, the same as lone triangles 0.90, spheres.xml 0.94, 900 spheres on
//! a floor 1.06, the Cornell box 1.25 and rough.xml 1.25 — where paths are
//! long, lanes wait idle for their cohort. (Refilling only once all sixteen
//! had finished: 0.87, 0.95, 1.07, 1.18, 1.53, 1.47.)
//!
//! Each thread keeps a [`RefillChoice`] per world. Chunks of samples
//! differ too much to compare one traced one way with another traced the
//! other (a chunk of sky costs a tenth of one on the mesh), so a trial
//! splits one chunk in two, the even samples and the odd ones (the same
//! pixels, alternately), traces each half one way and compares the times.
//! Trials run on a thread's first chunks of a world, then on one chunk in
//! [`TRIAL_EVERY`] in case the machine's load changed; the other chunks go
//! the faster way so far. A sample's result is the same either way, bit
//! for bit (the tests hold it), so the choice changes only the time.

use std::cell::Cell;
use std::time::Duration;

/// Finished lanes a group waits for before it refills them: at once, or
/// by cohorts.
pub(super) const COHORTS: [u32; 2] = [1, 8];

/// Samples each way traces in trials before the faster is chosen.
const TRIAL_SAMPLES: u64 = 8192;

/// After the first trials, one chunk in this many is a trial.
const TRIAL_EVERY: u64 = 32;

/// How to trace a chunk of samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Plan {
    /// Half of it each way, timed.
    Trial,
    /// All of it one way (an index into [`COHORTS`]).
    Way(usize),
}

/// The time each way of refilling took in trials, on one thread, for one
/// world.
#[derive(Debug, Default)]
pub(crate) struct RefillChoice {
    /// Per way ([`COHORTS`]): samples traced in trials and their time.
    spent: [Cell<(u64, Duration)>; 2],
    /// Chunks planned.
    chunks: Cell<u64>,
}

impl RefillChoice {
    /// How to trace the next chunk.
    pub(super) fn plan(&self) -> Plan {
        let chunks = self.chunks.get() + 1;
        self.chunks.set(chunks);
        let [(a, time_a), (b, time_b)] = [self.spent[0].get(), self.spent[1].get()];
        if a.min(b) < TRIAL_SAMPLES || chunks.is_multiple_of(TRIAL_EVERY) {
            return Plan::Trial;
        }
        // Time per sample, compared without dividing: tb / b < ta / a.
        let (a, b) = (a as f64, b as f64);
        Plan::Way(usize::from(
            time_b.as_secs_f64() * a < time_a.as_secs_f64() * b,
        ))
    }

    /// Records that `samples` samples of a trial took `time` the way `way`.
    pub(super) fn record(&self, way: usize, samples: usize, time: Duration) {
        let (n, t) = self.spent[way].get();
        self.spent[way].set((n + samples as u64, t + time));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trials_come_first_then_the_faster_way_with_a_trial_now_and_then() {
        let choice = RefillChoice::default();
        let ms = Duration::from_millis;
        let mut trials = 0;
        while choice.plan() == Plan::Trial {
            trials += 1;
            // Half a chunk each way; cohorts take half the time.
            choice.record(0, 512, ms(10));
            choice.record(1, 512, ms(5));
        }
        assert_eq!(
            trials,
            TRIAL_SAMPLES / 512,
            "trials until both ways have enough samples"
        );
        let plans: Vec<Plan> = (0..2 * TRIAL_EVERY).map(|_| choice.plan()).collect();
        let count = |p: Plan| plans.iter().filter(|&&q| q == p).count();
        assert_eq!(
            count(Plan::Trial),
            2,
            "one chunk in {TRIAL_EVERY} is a trial: {plans:?}"
        );
        assert_eq!(
            count(Plan::Way(1)),
            plans.len() - 2,
            "the rest go the faster way"
        );
    }
}
