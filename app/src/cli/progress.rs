//! A long command's progress on stderr while a person watches it (stderr is
//! a terminal): how many of its steps are done, the time elapsed and the
//! time left, redrawn in place by `indicatif`. Nothing at all otherwise: a
//! log file or a pipe gets exactly the bytes it got before.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// The progress of one command, or nothing when nobody is watching.
pub struct Progress(Option<ProgressBar>);

impl Progress {
    /// A bar of `total` steps called `unit` ("passes"), shown only when
    /// stderr is a terminal.
    pub fn new(total: u64, unit: &str) -> Progress {
        if !std::io::stderr().is_terminal() {
            return Progress(None);
        }
        let bar = ProgressBar::new(total);
        let template = format!(
            "{{wide_bar}} {{pos}}/{{len}} {unit}, {{elapsed}} elapsed, {{eta}} left {{msg}}"
        );
        if let Ok(style) = ProgressStyle::with_template(&template) {
            bar.set_style(style);
        }
        Progress(Some(bar))
    }

    /// One more step done.
    pub fn step(&self) {
        if let Some(bar) = &self.0 {
            bar.inc(1);
        }
    }

    /// Says what is being done now (a method, a case), beside the bar.
    pub fn say(&self, what: &str) {
        if let Some(bar) = &self.0 {
            bar.set_message(what.to_owned());
        }
    }

    /// Runs `print` (lines on stdout) with the bar taken off the terminal
    /// meanwhile, so that the lines do not land inside it.
    pub fn suspend<R>(&self, print: impl FnOnce() -> R) -> R {
        match &self.0 {
            Some(bar) => bar.suspend(print),
            None => print(),
        }
    }

    /// Takes the bar away, leaving the terminal as it was, before the
    /// command prints its result.
    pub fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
