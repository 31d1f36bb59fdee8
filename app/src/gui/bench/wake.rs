//! How the benchmarks' UI loop sleeps between frames: as eframe's event
//! loop does, until egui is asked to repaint (the tracer handing over a
//! step calls `request_repaint`) or a delayed request comes due.

use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::{Duration, Instant};

/// The time the next repaint is due, set by egui's repaint callback.
#[derive(Clone, Default)]
pub struct RepaintWake {
    due: Arc<(Mutex<Option<Instant>>, Condvar)>,
}

impl RepaintWake {
    /// A wake that `ctx`'s repaint requests set (replacing any other
    /// callback of `ctx`).
    pub fn of(ctx: &egui::Context) -> Self {
        let wake = Self::default();
        let due = Arc::clone(&wake.due);
        ctx.set_request_repaint_callback(move |info| {
            // A delay past what an Instant holds is no request at all.
            let Some(at) = Instant::now().checked_add(info.delay) else {
                return;
            };
            let (lock, signal) = &*due;
            let mut due = lock.lock().unwrap_or_else(PoisonError::into_inner);
            *due = Some(due.map_or(at, |d| d.min(at)));
            signal.notify_all();
        });
        wake
    }

    /// Sleeps until a repaint is due or `longest` has passed, whichever
    /// comes first, and clears the request it woke for.
    pub fn sleep(&self, longest: Duration) {
        let deadline = Instant::now() + longest;
        let (lock, signal) = &*self.due;
        let mut due = lock.lock().unwrap_or_else(PoisonError::into_inner);
        loop {
            let now = Instant::now();
            let until = due.map_or(deadline, |d| d.min(deadline));
            if now >= until {
                if due.is_some_and(|d| d <= now) {
                    *due = None;
                }
                return;
            }
            due = signal
                .wait_timeout(due, until - now)
                .unwrap_or_else(PoisonError::into_inner)
                .0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A repaint request wakes the sleeper long before its longest sleep,
    /// and is then used up: the next sleep lasts its whole length.
    #[test]
    fn a_repaint_request_wakes_the_sleeper_once() {
        let ctx = egui::Context::default();
        let wake = RepaintWake::of(&ctx);
        let requester = ctx.clone();
        let started = Instant::now();
        let thread = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(20));
            requester.request_repaint();
        });
        wake.sleep(Duration::from_secs(20));
        let woke = started.elapsed();
        thread.join().expect("the requesting thread");
        assert!(
            woke >= Duration::from_millis(20) && woke < Duration::from_secs(10),
            "woke after {woke:?}"
        );
        let started = Instant::now();
        wake.sleep(Duration::from_millis(30));
        assert!(started.elapsed() >= Duration::from_millis(30));
    }
}
