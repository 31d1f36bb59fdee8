//! The tracer's threads run below the UI: the window builds rayon's global
//! pool with every worker at the lowest normal priority (on Linux a nice
//! value of 19, through the `thread-priority` crate; the lowest thread
//! priority on Windows and macOS), so that input, layout and the software
//! rasteriser (lavapipe's threads, started by the UI thread at its normal
//! priority) take a core the moment they need one, while the workers soak
//! up every cycle left over. The command line keeps normal priority: a
//! render there is the job in hand.

use std::sync::atomic::{AtomicBool, Ordering};

/// Whether every worker that started managed to lower its priority.
static LOWERED: AtomicBool = AtomicBool::new(true);

/// Builds rayon's global pool with low-priority workers. Call it before
/// anything uses rayon; if the pool already exists (a test harness started
/// it), nothing changes and that is said on stderr.
pub fn lower_tracer_priority() {
    let built = rayon::ThreadPoolBuilder::new()
        .thread_name(|k| format!("raylab-trace-{k}"))
        .start_handler(|_| {
            if thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min)
                .is_err()
            {
                LOWERED.store(false, Ordering::Relaxed);
            }
        })
        .build_global();
    if let Err(error) = built {
        eprintln!("note: the tracer's threads keep their priority ({error})");
    }
}

/// Whether the workers run below the UI: the pool was built here and every
/// worker lowered its priority.
pub fn tracer_priority_lowered() -> bool {
    LOWERED.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    /// A thread at the lowest priority can do it (no privilege is needed to
    /// lower one's own priority), and on Linux that is nice 19.
    #[test]
    fn a_thread_can_lower_its_own_priority_to_the_lowest() {
        std::thread::spawn(|| {
            thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min)
                .expect("lowering needs no privilege");
            #[cfg(target_os = "linux")]
            {
                // proc(5): the 19th field of a task's stat is its nice value
                // (the 2nd, the name in parentheses, holds no ") ").
                let stat = std::fs::read_to_string("/proc/thread-self/stat").expect("stat");
                let after_name = &stat[stat.rfind(") ").expect("a name") + 2..];
                let nice: i32 = after_name
                    .split(' ')
                    .nth(16)
                    .and_then(|f| f.parse().ok())
                    .expect("field 19");
                assert_eq!(nice, 19, "the thread's nice value");
            }
        })
        .join()
        .expect("the thread ran");
    }
}
