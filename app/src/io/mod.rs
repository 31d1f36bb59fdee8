//! Files raylab writes: replaced atomically, images with their provenance,
//! and names that never overwrite an earlier result unasked; and lines on
//! standard output that survive a closed pipe.

pub mod atomic_file;
pub mod output;
pub mod output_path;
pub mod stdout;
