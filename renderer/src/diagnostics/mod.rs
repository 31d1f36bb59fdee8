//! Measuring the tracer rather than rendering with it: error metrics and
//! reference images, convergence curves (`raylab chart`), ray-casting
//! throughput (`raylab bench`), generated hard cases for the BVH, and the
//! suite of numerical failure cases (`raylab stability`), and the quantiles
//! their figures are reported by.

pub mod convergence;
pub mod generate;
pub mod metrics;
pub mod quantile;
pub mod reference_image;
pub mod stability;
pub mod throughput;
