//! Whitted's rays sixteen at a time: their closest hits tested as one SIMD
//! packet, and the shading contexts of their hits, the marble ones' noise
//! found together. Camera rays (`whitted_batch.rs`) and the later rays of
//! their trees (`whitted_tree.rs`) both go this way.

use super::shading_context::ShadingContext;
use crate::geometry::counters::{count_ray, count_shape_tests};
use crate::geometry::ray::Ray;
use crate::packet::{FloatLanes, IntLanes, Rays, WIDTH};
use crate::packet_shapes::PacketShapes;
use crate::shading::texture::{marble_noise_point, marble_with};
use crate::shading::turbulence::TURBULENCE;
use crate::world::{Hit, World};
use scene::BaseMaterial;

/// The closest hits of the first `n` rays of `rays` tested as one packet
/// against `shapes` (the others are dead), with each ray's shape tests:
/// the primitives of the leaves its own box tests let it into (every
/// primitive, up to [`PacketShapes::BRUTE_FORCE_MAX`]) and every plane,
/// whatever the other lanes do.
#[inline(always)]
pub(super) fn packet_hits<F: FloatLanes>(
    shapes: &PacketShapes,
    rays: &[Ray; WIDTH],
    n: usize,
    hits: &mut [Option<Hit>; WIDTH],
    tests: &mut [u32; WIDTH],
) {
    let mut tested = F::Ints::splat(0);
    let packet = shapes.closest(&Rays::<F>::from_lanes(rays), &mut tested);
    let tested = tested.to_array();
    for k in 0..n {
        hits[k] = shapes.lane_hit(&packet, k, &rays[k]);
        tests[k] = tested[k] as u32;
        count_ray();
        count_shape_tests(tested[k] as usize);
    }
}

/// The shading context of each ray of `rays` that hit (`hits`, as many as
/// there are rays in use) into `contexts` (as long as `hits`; `None` for a
/// miss), the marble ones with their albedo: the noise of
/// every marble hit found at once ([`Turbulence::at_each`]), where shading
/// them one by one would evaluate it hit by hit.
///
/// [`Turbulence::at_each`]: crate::shading::turbulence::Turbulence::at_each
#[inline(always)]
pub(super) fn shading_contexts<'w, F: FloatLanes>(
    world: &'w World,
    rays: &[Ray; WIDTH],
    hits: &[Option<Hit>],
    contexts: &mut [Option<ShadingContext<'w>>],
) {
    let (mut marble, mut noise_points, mut m) = ([0; WIDTH], [[0.0; 3]; WIDTH], 0);
    for (k, (hit, context)) in hits.iter().zip(contexts.iter_mut()).enumerate() {
        *context = None;
        if let Some(hit) = hit {
            let at = ShadingContext::new(world, &rays[k], hit);
            if at.material.base == BaseMaterial::Marble {
                (marble[m], noise_points[m]) = (k, marble_noise_point(at.point()));
                m += 1;
            }
            *context = Some(at);
        }
    }
    if m > 0 {
        let mut noise = [0.0; WIDTH];
        TURBULENCE.at_each::<F>(&noise_points[..m], &mut noise[..m]);
        for (&k, &noise) in marble[..m].iter().zip(&noise) {
            if let Some(at) = &mut contexts[k] {
                *at = at.with_albedo(marble_with(at.point(), at.color, noise));
            }
        }
    }
}
