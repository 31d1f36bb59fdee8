//! Ctrl+C during `raylab render`: the first one stops the render once the
//! pass being traced is done, and the passes done are written (the report
//! says so); a second one ends the program at once, as Ctrl+C usually does.

use std::sync::Once;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set by the first Ctrl+C.
static REQUESTED: AtomicBool = AtomicBool::new(false);

/// Catches Ctrl+C from now on (once per process: later calls do nothing).
/// Where no handler can be installed, Ctrl+C keeps its usual effect and a
/// warning says so.
pub fn catch() {
    static INSTALLED: Once = Once::new();
    INSTALLED.call_once(|| {
        let installed = ctrlc::set_handler(|| {
            if REQUESTED.swap(true, Ordering::SeqCst) {
                // 128 + SIGINT, what a shell reports for a program Ctrl+C ended.
                std::process::exit(130);
            }
        });
        if let Err(error) = installed {
            eprintln!("warning: Ctrl+C will end the render without writing it: {error}");
        }
    });
}

/// True once Ctrl+C was pressed.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}
