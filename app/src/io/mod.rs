//! Files raylab writes: replaced atomically, images with their provenance,
//! and names that never overwrite an earlier result unasked.

pub mod atomic_file;
pub mod output;
pub mod output_path;
