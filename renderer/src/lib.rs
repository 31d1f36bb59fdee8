//! raylab's CPU ray tracer. No GUI dependencies.
//!
//! The camera follows the course lecture's formulas and names (P0, t, u, r,
//! θ, d, H_d, W_d, C00, P_ij, v_ij); every primitive of the lecture has its
//! own intersection file under [`shapes`].

pub mod accel;
pub mod adaptive;
pub mod aov;
pub mod blas_cache;
pub mod bsdf;
pub mod camera;
pub mod colormap;
pub mod convergence;
pub mod display;
pub mod display_image;
pub mod emitters;
pub mod film;
pub mod frame;
pub mod generate;
pub mod heatmap;
pub mod image_memory;
pub mod image_texture;
pub mod inspect;
pub mod integrator;
pub mod light;
pub mod metrics;
pub mod offset;
pub mod optics;
pub mod pixel_stats;
pub mod placed_mesh;
pub mod preview;
pub mod progressive;
pub mod ray;
pub mod ray_count;
pub mod reference_image;
pub mod sampler;
pub mod shape_tests;
pub mod shapes;
pub mod stability;
pub mod texture;
pub mod throughput;
pub mod world;

pub use camera::Camera;
pub use film::Film;
pub use inspect::{Inspection, inspect_pixel};
pub use integrator::RenderOptions;
pub use sampler::Sampling;
pub use shapes::Method;
pub use world::{RenderError, World};
