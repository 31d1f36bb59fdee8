//! Lines on standard output that survive a reader going away: `raylab … |
//! head` closes the pipe after a few lines, and Rust's `println!` then
//! panics. A Unix tool ends quietly there; so does raylab, with exit code 0
//! (what it was asked to do is done: files are written before they are
//! announced). Any other failure to write is an error on stderr, exit code 2.

use std::io::{ErrorKind, Write};

/// Writes `args` and a newline to standard output (see the module's doc).
pub fn line(args: std::fmt::Arguments) {
    let mut out = std::io::stdout().lock();
    let written = out
        .write_fmt(args)
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush());
    if let Err(error) = written {
        if error.kind() == ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("error: cannot write to standard output: {error}");
        std::process::exit(2);
    }
}

/// `println!` through [`line`]: a closed pipe ends the program quietly
/// instead of a panic.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::io::stdout::line(format_args!($($arg)*))
    };
}
pub(crate) use say;
