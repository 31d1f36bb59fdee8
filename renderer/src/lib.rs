//! raylab's CPU ray tracer. No GUI dependencies.
//!
//! The camera follows the course lecture's formulas and names (P0, t, u, r,
//! θ, d, H_d, W_d, C00, P_ij, v_ij); every primitive of the lecture has its
//! own intersection file under [`shapes`].
//!
//! The folders follow the data flow: [`geometry`] (rays) → [`shapes`] and
//! [`accel`] (what a ray hits) → [`world`] (a scene prepared for rendering:
//! objects, lights, the BVH) → [`shading`] and [`integrator`] (the radiance of
//! a pixel's sample) → [`film`] (passes accumulated per pixel) → [`display`]
//! (what the window shows) → [`progressive`] (the render session). [`inspect`]
//! re-traces one sample; [`diagnostics`] measures speed and error.
//! `ARCHITECTURE.md` at the top of the repository maps them.

pub mod accel;
pub mod camera;
pub mod diagnostics;
pub mod display;
pub mod film;
pub mod geometry;
pub mod inspect;
pub mod integrator;
pub mod packet;
pub mod packet_shapes;
pub mod progressive;
pub mod shading;
pub mod shapes;
pub mod simd;
pub mod world;

pub use camera::Camera;
pub use film::{Film, Region};
pub use inspect::{Inspection, inspect_pixel};
pub use integrator::RenderOptions;
pub use integrator::sampler::Sampling;
pub use shapes::Method;
pub use world::{Environment, MapOrientation, RenderError, World};
