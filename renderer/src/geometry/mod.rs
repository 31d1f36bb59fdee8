//! Rays and what every intersection routine shares: the lecture's ray
//! (P0, v) on an interval of α, spawning secondary rays off a surface, warps
//! of uniform numbers onto disks, discrete distributions (alias tables),
//! where shadow rays of smooth-shaded meshes start (the shadow terminator),
//! the angles of directions (polar), and the per-thread counters of the tracer's work.

pub mod alias_table;
pub mod counters;
pub mod offset;
pub mod polar;
pub mod ray;
pub mod terminator;
pub mod warp;

pub use ray::Ray;
