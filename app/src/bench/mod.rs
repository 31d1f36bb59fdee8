//! Benchmarks without a window: ray-tracing throughput and frame time
//! (`raylab bench SCENE`, `raylab bench suite`), the export of what they
//! cast for other ray tracers, the scenes they name, and a headless wgpu
//! device for timing whole window frames. The window's own benchmarks drive
//! its private state and so live beside it, in [`crate::gui::bench`].

pub mod export;
pub mod headless_gpu;
pub mod scene_spec;
pub mod trace;
