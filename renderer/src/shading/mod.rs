//! What surfaces do to light: the BSDFs of the path tracer, the optics
//! (reflection, refraction, Fresnel) both integrators use, and textures
//! (procedural marble, glTF image maps).

pub mod bsdf;
pub mod image_texture;
pub mod optics;
pub mod texture;
pub mod turbulence;
