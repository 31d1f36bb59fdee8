//! A bounce's random numbers, drawn on lanes from each lane's stream
//! ([`StreamLanes`]: the scalar streams' numbers bit for bit), what they
//! become: a point on an emitter (chosen and, on a triangle, drawn on
//! lanes from the [`EmitterTable`]) and a cosine-weighted direction, each
//! with the scalar path tracer's operations.

use super::emitter_table::EmitterTable;
use crate::integrator::sampler::lanes::StreamLanes;
use crate::integrator::sampler::{BounceDraw, bounce_draw, environment_draw};
use crate::packet::polar::sin_cos_quarters;
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Vec3s, WIDTH, lane_set, mask_from};
use crate::world::World;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_PI_4;

/// Each lane's point drawn on an emitter, as seen from its shading point.
pub(super) struct EmitterDraws<F: FloatLanes> {
    /// Lanes that drew a point (`Emitters::sample` gave one).
    pub(super) found: F::Mask,
    /// Unit directions toward the points.
    pub(super) to_light: Vec3s<F>,
    /// Distances to the points.
    pub(super) distance: F,
    /// Radiance arriving from them.
    pub(super) radiance: Vec3s<F>,
    /// Densities in solid angle, the choice of emitter included.
    pub(super) pdf: F,
}

/// Each lane's draw `at + offset` of its bounce `depth`.
#[inline(always)]
fn draw_at<F: FloatLanes>(depth: &[u32; WIDTH], at: BounceDraw, offset: u32) -> F::Ints {
    let mut draws = [0i32; WIDTH];
    for k in 0..WIDTH {
        draws[k] = (bounce_draw(depth[k], at) + offset) as i32;
    }
    F::Ints::from_array(draws)
}

/// For each lane of `lanes`, its light sample at bounce `depth`: the
/// bounce's light numbers — which emitter and where (three numbers) — and
/// the point on it as seen from `point`. The emitter is chosen and a
/// triangle drawn on lanes, with `Emitters::sample`'s arithmetic
/// ([`EmitterTable`]); other shapes (a sphere's cone of directions) by
/// `Emitters::sample` itself.
#[inline(always)]
pub(super) fn emitter_draws<F: FloatLanes>(
    world: &World,
    table: &EmitterTable,
    lanes: F::Mask,
    streams: &StreamLanes<F>,
    depth: &[u32; WIDTH],
    point: Vec3s<F>,
) -> EmitterDraws<F> {
    let mut draws = EmitterDraws {
        found: F::Mask::NONE,
        to_light: Vec3s::splat(Vec3::X),
        distance: F::ZERO,
        radiance: Vec3s::ZERO,
        pdf: F::ONE,
    };
    if table.is_empty() || !lanes.any() {
        return draws;
    }
    let u_select = streams.number(draw_at::<F>(depth, BounceDraw::Light, 0));
    let (ux, uy) = streams.numbers(draw_at::<F>(depth, BounceDraw::Light, 1));
    let chosen = table.choose(u_select);
    let other = lanes & chosen.other;
    if other.any() {
        draws = other_emitter_draws(world, other, u_select, [ux, uy], point);
    }
    let on_triangle = lanes & chosen.triangle;
    if !on_triangle.any() {
        return draws;
    }
    let triangle = table.triangles(&chosen);
    // `TriangleSampler::sample`: barycentrics from the square folded along
    // its diagonal, the point t0 + b v1 + c v2.
    let fold = (ux + uy).simd_gt(F::ONE);
    let b = fold.select(F::ONE - ux, ux);
    let c = fold.select(F::ONE - uy, uy);
    let on = triangle.corner + triangle.edge1 * b + triangle.edge2 * c;
    // The rest of `Emitters::sample` for an area sample.
    let to = on - point;
    let distance_sq = to.length_squared();
    let distance = distance_sq.sqrt();
    let to_light = to.div_lanes(distance);
    let cos_light = -to_light.dot(triangle.normal);
    let pdf = triangle.density * distance_sq / cos_light;
    let drawn = on_triangle & distance_sq.simd_gt(F::ZERO) & cos_light.simd_gt(F::ZERO);
    draws.found = draws.found | drawn;
    draws.to_light = Vec3s::select(on_triangle, to_light, draws.to_light);
    draws.distance = on_triangle.select(distance, draws.distance);
    draws.radiance = Vec3s::select(on_triangle, triangle.radiance, draws.radiance);
    draws.pdf = on_triangle.select(pdf, draws.pdf);
    draws
}

/// The light samples of the lanes `lanes`, whose emitters are not
/// triangles, drawn by `Emitters::sample` lane by lane.
#[inline(always)]
fn other_emitter_draws<F: FloatLanes>(
    world: &World,
    lanes: F::Mask,
    u_select: F,
    u: [F; 2],
    point: Vec3s<F>,
) -> EmitterDraws<F> {
    let (u_select, ux, uy) = (u_select.as_array(), u[0].as_array(), u[1].as_array());
    let mut found = [false; WIDTH];
    let mut to_light = [Vec3::X; WIDTH];
    let mut distance = [0.0f32; WIDTH];
    let mut radiance = [Vec3::ZERO; WIDTH];
    let mut pdf = [1.0f32; WIDTH];
    for k in (0..WIDTH).filter(|&k| lane_set(lanes, k)) {
        let u = Vec2::new(ux[k], uy[k]);
        if let Some(s) = world.emitters.sample(point.lane(k), u_select[k], u) {
            found[k] = true;
            to_light[k] = s.to_light;
            distance[k] = s.distance;
            radiance[k] = s.radiance;
            pdf[k] = s.pdf;
        }
    }
    EmitterDraws {
        found: mask_from::<F>(|k| found[k]),
        to_light: Vec3s::from_lanes(&to_light),
        distance: F::from_array(distance),
        radiance: Vec3s::from_lanes(&radiance),
        pdf: F::from_array(pdf),
    }
}

/// Each lane's direction drawn toward the environment (`<sky>`).
pub(super) struct EnvironmentDraws<F: FloatLanes> {
    /// Lanes that drew a direction (`Environment::sample` gave one).
    pub(super) found: F::Mask,
    /// Unit directions, world space.
    pub(super) dir: Vec3s<F>,
    /// Radiance arriving from them.
    pub(super) radiance: Vec3s<F>,
    /// Densities in solid angle.
    pub(super) pdf: F,
}

/// For each lane of `lanes`, its sample of the environment at bounce
/// `depth`: the bounce's environment numbers (drawn on lanes) warped by
/// `Environment::sample_lanes`, bit for bit the scalar path's.
/// Nothing is drawn when the environment is not sampled (no map, or black).
#[inline(always)]
pub(super) fn environment_draws<F: FloatLanes>(
    world: &World,
    lanes: F::Mask,
    streams: &StreamLanes<F>,
    depth: &[u32; WIDTH],
) -> EnvironmentDraws<F> {
    let environment = &world.environment;
    if !environment.is_sampled() || !lanes.any() {
        return EnvironmentDraws {
            found: F::Mask::NONE,
            dir: Vec3s::splat(Vec3::Y),
            radiance: Vec3s::ZERO,
            pdf: F::ONE,
        };
    }
    let mut draws = [0i32; WIDTH];
    for k in 0..WIDTH {
        draws[k] = environment_draw(depth[k]) as i32;
    }
    let (ux, uy) = streams.numbers(F::Ints::from_array(draws));
    let s = environment.sample_lanes(ux, uy, lanes);
    EnvironmentDraws {
        found: s.found,
        dir: s.dir,
        radiance: s.radiance,
        pdf: s.pdf,
    }
}

/// Each lane's BSDF sample's numbers at bounce `depth`: the lobe's number
/// and the direction's two (a dead lane's are never used).
#[inline(always)]
pub(super) fn scatter_draws<F: FloatLanes>(
    streams: &StreamLanes<F>,
    depth: &[u32; WIDTH],
) -> (F, [F; 2]) {
    let u_lobe = streams.number(draw_at::<F>(depth, BounceDraw::Scatter, 0));
    let (ux, uy) = streams.numbers(draw_at::<F>(depth, BounceDraw::Scatter, 1));
    (u_lobe, [ux, uy])
}

/// Each lane's numbers `u` warped to a cosine-weighted local direction
/// (`z` along the normal): `sample_cosine_hemisphere` on lanes, with the
/// same operations (the concentric map with `sin_cos_quarter`).
#[inline(always)]
pub(super) fn cosine_warps<F: FloatLanes>(u: [F; 2]) -> Vec3s<F> {
    let two = F::splat(2.0);
    let (px, py) = (two * u[0] - F::ONE, two * u[1] - F::ONE);
    let centre = px.simd_eq(F::ZERO) & py.simd_eq(F::ZERO);
    let first = px.abs().simd_gt(py.abs());
    let r = first.select(px, py);
    let ratio = first.select(py / px, px / py);
    let (sin, cos) = sin_cos_quarters(F::splat(FRAC_PI_4) * ratio);
    let x = first.select(r * cos, r * sin);
    let y = first.select(r * sin, r * cos);
    let (x, y) = (centre.select(F::ZERO, x), centre.select(F::ZERO, y));
    let z = (F::ONE - (x * x + y * y))
        .max(F::ZERO)
        .sqrt()
        .max(F::splat(1.0e-6));
    Vec3s { x, y, z }
}

/// Russian roulette's number at bounce `depth` (the bounce's last draw,
/// after the BSDF sample's), when any lane of `lanes` plays it.
#[inline(always)]
pub(super) fn roulette_draws<F: FloatLanes>(
    lanes: F::Mask,
    streams: &StreamLanes<F>,
    depth: &[u32; WIDTH],
) -> F {
    if !lanes.any() {
        return F::ZERO;
    }
    streams.number(draw_at::<F>(depth, BounceDraw::Scatter, 2))
}
