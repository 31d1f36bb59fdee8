//! The command line: the arguments (clap), what the commands share, and one
//! module per command (`raylab render`, `chart`, `stability`, `inspect`,
//! `bench`, `export-meshes`, `merge`), each with a `run` that `main` calls.

mod args;
pub mod bench;
pub mod chart;
pub mod export_meshes;
pub mod inspect;
pub mod interrupt;
pub mod merge;
mod prepare;
pub mod progress;
pub mod render;
pub mod stability;

pub use args::{Cli, Command};
