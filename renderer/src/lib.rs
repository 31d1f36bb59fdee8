//! raylab's CPU ray tracer. No GUI dependencies.
//!
//! The camera follows the course lecture's formulas and names (P0, t, u, r,
//! θ, d, H_d, W_d, C00, P_ij, v_ij); every primitive of the lecture has its
//! own intersection file under [`shapes`].

pub mod camera;
pub mod frame;
pub mod ray;
pub mod shapes;
