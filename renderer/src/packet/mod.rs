//! Sixteen rays, points or paths at once, one per SIMD lane: the vocabulary of
//! the wavefront path tracer ([`crate::integrator::wavefront`]).
//!
//! A packet keeps each quantity as a structure of arrays (`Vec3s` is three
//! lanes of coordinates, not sixteen `Vec3`s), so that one instruction works
//! on all sixteen. The code is written over a lane type `F: FloatLanes`
//! ([`crate::simd`]) and runs with the widest this CPU has ([`crate::simd::dispatch`]).
//! Lanes never mix: every operation is lane by lane and uses no fused
//! multiply–add, so a lane's result is the same bit for bit whatever its
//! neighbours hold and whichever instruction set runs it.

pub mod polar;
mod rays;
pub(crate) mod triangle;
mod vec3s;

pub use crate::simd::{
    FloatLanes, IntLanes, Mask, MaskLanes, Portable, WIDTH, WithLanes, dispatch, first_lanes,
    lane_set, mask_from,
};
pub use rays::Rays;
pub(crate) use triangle::ShearedRays;
pub use vec3s::Vec3s;
