//! Runs a test alone in a child process of this test binary, so that what it
//! measures of the process (threads, resident memory) is its own and not
//! that of the tests running beside it, and so that a deadlock is caught by
//! a time limit instead of hanging the run.

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Set in the child to the test it runs.
const CHILD: &str = "RAYLAB_OWN_PROCESS_TEST";

/// True in the child process, where the test's body runs. In the parent it
/// runs test `name` (its path without the crate, e.g. `gui::x::y`) in a
/// child, passes on its output, fails if it fails or outlives `limit`, and
/// returns false.
pub fn in_own_process(name: &str, limit: Duration) -> bool {
    if std::env::var(CHILD).is_ok_and(|n| n == name) {
        return true;
    }
    let exe = std::env::current_exe().expect("the test binary's path");
    let mut child = Command::new(exe)
        .args([name, "--exact", "--include-ignored", "--nocapture"])
        .args(["--test-threads", "1"])
        .env(CHILD, name)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the test binary runs again");
    let (mut out, mut err) = (
        child.stdout.take().expect("stdout"),
        child.stderr.take().expect("stderr"),
    );
    let readers = (
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = out.read_to_string(&mut s);
            s
        }),
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = err.read_to_string(&mut s);
            s
        }),
    );
    let deadline = Instant::now() + limit;
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for the child") {
            break Some(status);
        }
        if Instant::now() >= deadline {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let out = readers.0.join().unwrap_or_default();
    let err = readers.1.join().unwrap_or_default();
    print!("{out}");
    eprint!("{err}");
    match status {
        None => panic!("{name} did not finish within {limit:?}: a deadlock?"),
        Some(status) => assert!(
            status.success(),
            "{name} failed in its own process: {status}"
        ),
    }
    assert!(
        out.contains("1 passed"),
        "{name} did not run in the child process"
    );
    false
}

/// The path of a test function in this binary, without the crate name:
/// `test_path(module_path!(), "f")`.
pub fn test_path(module: &str, function: &str) -> String {
    let module = module.split_once("::").map_or("", |(_, rest)| rest);
    format!("{module}::{function}")
}
