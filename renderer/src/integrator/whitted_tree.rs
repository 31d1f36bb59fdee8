//! Whitted's rays for a batch of camera rays, traced level by level, many at
//! a time: the ray trees of up to sixteen samples are grown breadth first —
//! each hit's reflected and refracted rays recorded, then all the rays of a
//! level tested in SIMD packets against the world's primitives
//! ([`PacketShapes`]) and the marble hits among them given their noise
//! together — their shadow rays tested in packets too, and only then is
//! every hit shaded, deepest first, from the answers.
//!
//! Each hit is shaded by Whitted's own code ([`whitted_at_hit`]) twice: once
//! to record the rays it asks for (its answers ignored: Whitted asks for the
//! same rays whatever they answer), once with the answers. Its children's
//! radiance is then already known, so every sample's radiance is the
//! recursion's bit for bit: the same hits (a packet lane's hit is
//! [`World::intersect`]'s), the same formulas in the same order.

use super::RenderOptions;
use super::recorder::Recorder;
use super::shading_context::ShadingContext;
use super::whitted::{Level, Secondary, background, whitted_at_hit};
use super::whitted_packets::{packet_hits, shading_contexts};
use crate::geometry::counters::{count_ray, count_shape_tests};
use crate::geometry::ray::Ray;
use crate::packet::{FloatLanes, IntLanes, Rays, WIDTH, lane_set};
use crate::packet_shapes::PacketShapes;
use crate::world::{Hit, World};
use glam::Vec3;
use std::ops::Range;

/// One ray of the trees of a batch (its hit and the hit's shading context
/// are kept beside it, in [`Trees`]).
#[derive(Clone)]
struct Node {
    ray: Ray,
    /// Where it is in its tree.
    level: Level,
    /// The camera ray whose tree it is in: its index in the batch.
    sample: u32,
    /// Its reflected and refracted rays, in the order it asks for them.
    children: Range<u32>,
    /// Its shadow rays, in the order it asks for them.
    shadows: Range<u32>,
}

/// The rays a hit asks for, collected while it is shaded the first time.
struct Record<'a> {
    /// Each reflected or refracted ray and where it is in its tree.
    rays: &'a mut Vec<(Ray, Level)>,
    /// Each shadow ray.
    shadows: &'a mut Vec<Ray>,
}

impl Secondary for Record<'_> {
    #[inline(always)]
    fn radiance<R: Recorder>(
        &mut self,
        _: &World,
        ray: &Ray,
        _: &RenderOptions,
        level: Level,
        _: &mut R,
        _: R::Node,
    ) -> Vec3 {
        self.rays.push((*ray, level));
        Vec3::ZERO
    }

    #[inline(always)]
    fn occluded(&mut self, _: &World, ray: &Ray, _: &RenderOptions) -> bool {
        self.shadows.push(*ray);
        // Blocked: the first shading skips the light's formulas.
        true
    }
}

/// The answers to the rays a hit asks for, in the order it asks for them.
struct Replay<'a> {
    radiance: std::slice::Iter<'a, Vec3>,
    blocked: std::slice::Iter<'a, bool>,
}

impl Secondary for Replay<'_> {
    #[inline(always)]
    fn radiance<R: Recorder>(
        &mut self,
        _: &World,
        _: &Ray,
        _: &RenderOptions,
        _: Level,
        _: &mut R,
        _: R::Node,
    ) -> Vec3 {
        *self.radiance.next().expect("a recorded ray")
    }

    #[inline(always)]
    fn occluded(&mut self, _: &World, _: &Ray, _: &RenderOptions) -> bool {
        *self.blocked.next().expect("a recorded shadow ray")
    }
}

/// The lists [`Trees::shade`] grows, kept from one batch to the next.
#[derive(Default)]
pub(super) struct Trees<'w> {
    /// The rays of the trees, level by level: the camera rays first.
    nodes: Vec<Node>,
    /// Each node's hit.
    hits: Vec<Option<Hit>>,
    /// Each node's hit's shading context.
    contexts: Vec<Option<ShadingContext<'w>>>,
    /// Each shadow ray and the camera ray whose tree it is in.
    shadows: Vec<(Ray, u32)>,
    /// Whether each of `shadows` is blocked.
    blocked: Vec<bool>,
    /// Each node's radiance.
    radiance: Vec<Vec3>,
    /// The reflected and refracted rays one hit asks for, with their level.
    asked: Vec<(Ray, Level)>,
    /// The shadow rays one hit asks for.
    asked_shadows: Vec<Ray>,
}

impl<'w> Trees<'w> {
    /// The radiance of each of the first `n` camera rays of `rays`, whose
    /// hits are `hits` and their shading contexts `contexts`, with the shape
    /// tests of all the rays of its tree added to its entry of `tests`:
    /// Whitted's recursion's radiance bit for bit, every later ray tested in
    /// packets against `shapes` (`world`'s primitives).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn shade<F: FloatLanes>(
        &mut self,
        world: &'w World,
        shapes: &PacketShapes,
        options: &RenderOptions,
        rays: &[Ray; WIDTH],
        hits: &[Option<Hit>],
        contexts: &[Option<ShadingContext<'w>>; WIDTH],
        tests: &mut [u32; WIDTH],
    ) -> [Vec3; WIDTH] {
        let n = hits.len();
        let Trees {
            nodes,
            hits: node_hits,
            contexts: node_contexts,
            shadows,
            blocked,
            radiance,
            asked,
            asked_shadows,
        } = self;
        nodes.clear();
        shadows.clear();
        nodes.extend((0..n).map(|k| Node {
            ray: rays[k],
            level: Level::CAMERA,
            sample: k as u32,
            children: 0..0,
            shadows: 0..0,
        }));
        node_hits.clear();
        node_hits.extend_from_slice(hits);
        node_contexts.clear();
        node_contexts.extend_from_slice(&contexts[..n]);
        let mut level = 0..n;
        while !level.is_empty() {
            // Each hit of the level shaded once, to record the rays it asks for.
            for index in level.clone() {
                let node = &nodes[index];
                let (Some(hit), Some(at)) = (node_hits[index], &node_contexts[index]) else {
                    continue;
                };
                let (ray, level, sample) = (node.ray, node.level, node.sample);
                let mut record = Record {
                    rays: asked,
                    shadows: asked_shadows,
                };
                whitted_at_hit(world, &ray, hit, at, options, level, &mut record);
                let first_child = nodes.len() as u32;
                let first_shadow = shadows.len() as u32;
                for (ray, level) in asked.drain(..) {
                    nodes.push(Node {
                        ray,
                        level,
                        sample,
                        children: 0..0,
                        shadows: 0..0,
                    });
                }
                shadows.extend(asked_shadows.drain(..).map(|ray| (ray, sample)));
                nodes[index].children = first_child..nodes.len() as u32;
                nodes[index].shadows = first_shadow..shadows.len() as u32;
            }
            // The next level's rays, sixteen at a time.
            let next = level.end..nodes.len();
            node_hits.resize(next.end, None);
            node_contexts.resize(next.end, None);
            for start in next.clone().step_by(WIDTH) {
                let end = (start + WIDTH).min(next.end);
                let batch = &nodes[start..end];
                let mut lanes = [Ray::NOTHING; WIDTH];
                for (lane, node) in lanes.iter_mut().zip(batch) {
                    *lane = node.ray;
                }
                let mut found = [None; WIDTH];
                let mut tested = [0u32; WIDTH];
                packet_hits::<F>(shapes, &lanes, batch.len(), &mut found, &mut tested);
                let found = &found[..batch.len()];
                node_hits[start..end].copy_from_slice(found);
                shading_contexts::<F>(world, &lanes, found, &mut node_contexts[start..end]);
                for (node, tested) in batch.iter().zip(tested) {
                    let total = &mut tests[node.sample as usize];
                    *total = total.saturating_add(tested);
                }
            }
            level = next;
        }
        shadows_blocked::<F>(shapes, shadows, blocked, tests);
        // Every hit shaded again with its answers, deepest first: a node's
        // children come after it in the list.
        radiance.clear();
        radiance.resize(nodes.len(), Vec3::ZERO);
        let range = |r: &Range<u32>| r.start as usize..r.end as usize;
        for (index, node) in nodes.iter().enumerate().rev() {
            radiance[index] = match (node_hits[index], &node_contexts[index]) {
                (Some(hit), Some(at)) => {
                    let mut replay = Replay {
                        radiance: radiance[range(&node.children)].iter(),
                        blocked: blocked[range(&node.shadows)].iter(),
                    };
                    whitted_at_hit(world, &node.ray, hit, at, options, node.level, &mut replay)
                }
                _ => background(world, node.ray.dir),
            };
        }
        let mut out = [Vec3::ZERO; WIDTH];
        out[..n].copy_from_slice(&radiance[..n]);
        out
    }
}

/// Whether each shadow ray of `shadows` (each with its sample) is blocked,
/// into `blocked`, tested sixteen at a time, each one's shape tests added to its sample's
/// entry of `tests`.
#[inline(always)]
fn shadows_blocked<F: FloatLanes>(
    shapes: &PacketShapes,
    shadows: &[(Ray, u32)],
    blocked: &mut Vec<bool>,
    tests: &mut [u32; WIDTH],
) {
    blocked.clear();
    for batch in shadows.chunks(WIDTH) {
        let mut lanes = [Ray::NOTHING; WIDTH];
        for (lane, (ray, _)) in lanes.iter_mut().zip(batch) {
            *lane = *ray;
        }
        let mut tested = F::Ints::splat(0);
        let mask = shapes.occluded(&Rays::<F>::from_lanes(&lanes), &mut tested);
        let tested = tested.to_array();
        for (k, &(_, sample)) in batch.iter().enumerate() {
            blocked.push(lane_set(mask, k));
            let total = &mut tests[sample as usize];
            *total = total.saturating_add(tested[k] as u32);
            count_ray();
            count_shape_tests(tested[k] as usize);
        }
    }
}
