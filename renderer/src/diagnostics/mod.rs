//! Measuring the tracer rather than rendering with it: error metrics and
//! reference images, convergence curves (`raylab chart`), ray-casting
//! throughput (`raylab bench`), generated hard cases for the BVH, and the
//! suite of numerical failure cases (`raylab stability`).

pub mod convergence;
pub mod generate;
pub mod metrics;
pub mod reference_image;
pub mod stability;
pub mod throughput;
