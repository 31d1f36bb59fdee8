//! The few shapes without a packet test (cylinders, cones, tori), tested
//! lane by lane with the scalar code's own test, so that one of them does
//! not send every ray of its world lane by lane through the BVH (the cone
//! of `seed.xml` did).
//!
//! Each lane's ray is tested below the lane's nearest hit so far with
//! [`Shape::intersect`] and its hit placed with [`Shape::surface`]: the
//! numbers [`crate::world::World::intersect`] and
//! [`crate::world::World::surface`] give for that ray, bit for bit.

use super::Nearest;
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Rays, Vec3s, WIDTH, lane_set, mask_from};
use crate::shapes::{Method, Shape};
use glam::Vec3;

/// Shapes tested lane by lane, with their object ids.
#[derive(Clone, Debug, Default)]
pub(super) struct Others {
    /// Per shape, its object id.
    objects: Vec<i32>,
    /// The shapes.
    shapes: Vec<Shape>,
}

impl Others {
    /// The most shapes a world in packets may hold: each costs every live
    /// lane a scalar test, where the world's BVH tests only the rays that
    /// come near it. Measured against the BVH (`render --spp 8`, 2 threads,
    /// medians of 5 alternated runs, path / Whitted): seed.xml with one
    /// cone 0.77 / 0.94 of the time (1280×720, 4 spp: 0.76 / 0.94), but
    /// primitives.xml with three shapes 1.05 / 1.13, roughness.xml with
    /// three 0.93 / 1.06, glass.xml with five 1.11 / 1.04.
    pub(super) const MAX: usize = 2;

    /// Adds `shape`, object `object`; returns its index.
    pub(super) fn push(&mut self, object: i32, shape: &Shape) -> u32 {
        self.objects.push(object);
        self.shapes.push(*shape);
        (self.shapes.len() - 1) as u32
    }

    /// How many shapes there are.
    pub(super) fn len(&self) -> usize {
        self.shapes.len()
    }

    /// Tests the lanes `live` of `rays` against every shape, below each
    /// lane's nearest hit so far, taking the nearer hits; counts one test
    /// per shape and live lane.
    #[inline(always)]
    pub(super) fn closest<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        live: F::Mask,
        nearest: &mut Nearest<F>,
        tests: &mut F::Ints,
    ) {
        if self.shapes.is_empty() {
            return;
        }
        for (shape, &object) in self.shapes.iter().zip(&self.objects) {
            let limit = nearest.limit.to_array();
            let mut alpha = [f32::INFINITY; WIDTH];
            for (k, alpha) in alpha.iter_mut().enumerate() {
                if lane_set(live, k) {
                    let ray = rays.lane(k).with_t_max(limit[k]);
                    if let Some(a) = shape.intersect(&ray, Method::Robust) {
                        *alpha = a;
                    }
                }
            }
            let hit = mask_from::<F>(|k| alpha[k] < f32::INFINITY);
            nearest.take(hit, F::from_array(alpha), object);
        }
        *tests = *tests + super::count::<F>(live, self.shapes.len());
    }

    /// Marks as settled the lanes of `rays` not yet settled whose ray any
    /// shape blocks; counts one test per shape and lane tested.
    #[inline(always)]
    pub(super) fn occluded<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        settled: &mut F::Mask,
        tests: &mut F::Ints,
    ) {
        let open = !*settled;
        let mut tested = [0i32; WIDTH];
        let mut blocked = 0u32;
        for (k, tested) in tested.iter_mut().enumerate() {
            if lane_set(open, k) {
                let ray = rays.lane(k);
                for shape in &self.shapes {
                    *tested += 1;
                    if shape.intersect(&ray, Method::Robust).is_some() {
                        blocked |= 1 << k;
                        break;
                    }
                }
            }
        }
        *settled = *settled | F::Mask::from_bitmask(blocked);
        *tests = *tests + F::Ints::from_array(tested);
    }

    /// The hit points and outward normals of the lanes whose hit is the
    /// shape at `index[k]`, at `alpha` (anything in the other lanes).
    #[inline(always)]
    pub(super) fn surface<F: FloatLanes>(
        &self,
        rays: &Rays<F>,
        alpha: F,
        index: &[u32; WIDTH],
        lanes: u32,
    ) -> (Vec3s<F>, Vec3s<F>) {
        let alpha = alpha.to_array();
        let mut points = [Vec3::ZERO; WIDTH];
        let mut normals = [Vec3::Z; WIDTH];
        for k in (0..WIDTH).filter(|&k| lanes & (1 << k) != 0) {
            let surface = self.shapes[index[k] as usize].surface(&rays.lane(k), alpha[k]);
            points[k] = surface.point;
            normals[k] = surface.normal;
        }
        (Vec3s::from_lanes(&points), Vec3s::from_lanes(&normals))
    }
}
