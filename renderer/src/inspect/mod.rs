//! The pixel inspector: one sample of one pixel re-traced as a ray tree.
//!
//! [`inspect_pixel`] runs the very code the image uses
//! ([`sample_pixel_recorded`], Whitted or the path tracer) with a recorder
//! that keeps every ray: the primary ray R_ij = (P0, v_ij), shadow rays,
//! reflections and refractions (the path tracer's BSDF samples, with lobe,
//! density and weight), each with what it hit (α, the hit point, the normal,
//! β and γ on a triangle, the quadratic's roots on a sphere), its weight and
//! its contribution; the path tracer's emission weights and Russian roulette
//! decisions are kept on the hits. The contributions add up to the sample's
//! colour.

mod node;
mod tree;

pub use node::{
    Barycentrics, Blocker, MaterialInfo, ObjectRef, RayNode, Roulette, Scatter, ShadowTarget,
    ShadowTest, SurfaceHit,
};

use crate::integrator::{Integrator, RenderOptions, sample_pixel_recorded};
use crate::shapes::Method;
use crate::world::World;
use glam::{Vec2, Vec3};
use serde::Serialize;
use tree::TreeRecorder;

/// One traced sample of pixel (i, j) as a tree of rays.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Inspection {
    /// The pixel's column i (0 at the left).
    pub i: u32,
    /// The pixel's row j (0 at the top).
    pub j: u32,
    /// The sample index k re-traced, or `None` for the ray through the pixel centre.
    pub sample: Option<u32>,
    /// (x, y) in [0, 1)² where the ray crosses the pixel: the sample's
    /// jitter, or (½, ½) for the centre.
    pub offset: Vec2,
    /// P_ij = C00 + (i + ½)(W_d/w) r − (j + ½)(H_d/h) u, the centre of pixel (i, j) on the view window.
    pub p_ij: Vec3,
    /// The point of the view window the primary ray passes through: P_ij with
    /// the ½ replaced by the sample's jitter (P_ij itself for the centre).
    pub window_point: Vec3,
    /// v_ij, the unit direction of the primary ray from P0 through `window_point`.
    pub v_ij: Vec3,
    /// The integrator that traced the sample (the image's).
    pub integrator: Integrator,
    /// The intersection formulas used.
    pub method: Method,
    /// The bounce limit used.
    pub max_depth: u32,
    /// The traced colour: for a sample, bit for bit the value
    /// [`sample_pixel`](crate::integrator::sample_pixel) adds to the film.
    pub color: Vec3,
    /// Every ray traced, parents before children; `rays[0]` is the primary ray.
    pub rays: Vec<RayNode>,
}

impl Inspection {
    /// The primary ray R_ij = (P0, v_ij).
    pub fn primary(&self) -> &RayNode {
        &self.rays[0]
    }

    /// The rays spawned at the hit of ray `parent`, with their indices.
    pub fn children(&self, parent: usize) -> impl Iterator<Item = (usize, &RayNode)> {
        self.rays
            .iter()
            .enumerate()
            .filter(move |(_, ray)| ray.parent == Some(parent))
    }

    /// Σ of every ray's contribution: the sample's colour up to rounding.
    pub fn contribution_sum(&self) -> Vec3 {
        self.rays.iter().map(|ray| ray.contribution).sum()
    }
}

/// Why a pixel cannot be inspected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "pixel ({i}, {j}) is outside the {width}×{height} image: i must be in 0..={}, j in 0..={}",
    width - 1,
    height - 1
)]
pub struct PixelOutOfRange {
    /// The column asked for.
    pub i: u32,
    /// The row asked for.
    pub j: u32,
    /// w, the image width.
    pub width: u32,
    /// h, the image height.
    pub height: u32,
}

/// Re-traces pixel (i, j) as a ray tree with the integrator of `options`:
/// with `Some(k)` sample k exactly as
/// [`sample_pixel`](crate::integrator::sample_pixel) traces it (same jitter,
/// same random numbers, same rays, same colour bit for bit); with `None` the
/// ray through the pixel centre P_ij
/// ([`Camera::center_ray`](crate::Camera::center_ray)), the ray of the AOVs
/// (the path tracer then draws sample 0's random numbers).
pub fn inspect_pixel(
    world: &World,
    options: &RenderOptions,
    i: u32,
    j: u32,
    sample: Option<u32>,
) -> Result<Inspection, PixelOutOfRange> {
    let camera = &world.camera;
    if i >= camera.w || j >= camera.h {
        return Err(PixelOutOfRange {
            i,
            j,
            width: camera.w,
            height: camera.h,
        });
    }
    let mut tree = TreeRecorder::new(world, options.method);
    let traced = sample_pixel_recorded(world, options, i, j, sample, &mut tree);
    let (offset, ray, color) = (traced.offset, traced.ray, traced.color);
    Ok(Inspection {
        i,
        j,
        sample,
        offset,
        p_ij: camera.pixel_center(i, j),
        window_point: camera.window_point(i, j, offset),
        v_ij: ray.dir,
        integrator: options.integrator,
        method: options.method,
        max_depth: options.max_depth,
        color,
        rays: tree.rays,
    })
}
