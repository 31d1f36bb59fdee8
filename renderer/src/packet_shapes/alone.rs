//! One lane of a packet searching part of the tree alone (`tree.rs`): its
//! ray against a leaf's primitives with the scalar tests, which give each
//! lane's α bit for bit, and the same rules for taking a hit as the packet
//! tests ([`super::Nearest`]): a hit must be strictly nearer, except that
//! at the same α a triangle of a lower key wins over one of a higher key.

use super::tree::{LaneVisitor, Leaf};
use super::{PacketShapes, Triangles};
use crate::geometry::ray::Ray;
use crate::shapes::WatertightRay;

/// A lane's ray and what its triangle tests need of it.
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneRay {
    /// P0 and v, over (0, t_max).
    pub(super) ray: Ray,
    /// Its watertight permutation and shear.
    watertight: WatertightRay,
}

impl LaneRay {
    /// `ray` prepared.
    #[inline(always)]
    pub(super) fn new(ray: Ray) -> Self {
        Self {
            ray,
            watertight: WatertightRay::new(&ray),
        }
    }
}

/// One lane's nearest-hit search.
pub(super) struct ClosestLane<'a> {
    pub(super) shapes: &'a PacketShapes,
    pub(super) ray: LaneRay,
    /// Hits must lie below this: t_max, then the nearest α so far.
    pub(super) limit: f32,
    /// The object hit nearest so far (−1: none yet).
    pub(super) object: i32,
    /// The key of the triangle hit nearest so far (−1: none, or the
    /// nearest hit is no triangle).
    pub(super) triangle: i32,
    /// Primitives tested.
    pub(super) tests: i32,
}

impl LaneVisitor for ClosestLane<'_> {
    #[inline(always)]
    fn ray(&self) -> Ray {
        self.ray.ray.with_t_max(self.limit)
    }

    #[inline(always)]
    fn limit(&self) -> f32 {
        self.limit
    }

    /// The leaf's triangles, boxes, then spheres, as the packet tests them.
    #[inline(always)]
    fn leaf(&mut self, leaf: &Leaf) -> bool {
        self.tests += leaf.len() as i32;
        let shapes = self.shapes;
        if let Some(pack) = &leaf.pack {
            // Up to the next float above the limit when the nearest hit is
            // a triangle: at its α, a lower key still wins.
            let bound = if self.triangle >= 0 {
                f32::from_bits(self.limit.to_bits() + 1)
            } else {
                self.limit
            };
            if let Some(hit) = pack.nearest(&self.ray.watertight, 0.0, bound) {
                let (object, key) =
                    object_and_key(&shapes.triangles, &shapes.triangle_at, pack.id(hit.lane));
                if hit.alpha < self.limit || key < self.triangle {
                    self.limit = hit.alpha;
                    self.object = object;
                    self.triangle = key;
                }
            }
        }
        for index in leaf.boxes.clone() {
            if let Some(alpha) = shapes.boxes.alone(index, &self.ray()) {
                self.take(alpha, shapes.boxes.object(index));
            }
        }
        for index in leaf.spheres.clone() {
            if let Some(alpha) = shapes.spheres.alone(index, &self.ray()) {
                self.take(alpha, shapes.spheres.object(index));
            }
        }
        false
    }
}

impl ClosestLane<'_> {
    /// Takes a hit at `alpha` (below the limit) on `object`, no triangle.
    #[inline(always)]
    fn take(&mut self, alpha: f32, object: i32) {
        self.limit = alpha;
        self.object = object;
        self.triangle = -1;
    }
}

/// The object and key of the triangle of key `key`.
#[inline(always)]
fn object_and_key(triangles: &Triangles, triangle_at: &[u32], key: u32) -> (i32, i32) {
    triangles.object_and_key(triangle_at[key as usize] as usize)
}

/// One lane's any-hit search.
pub(super) struct OccludedLane<'a> {
    pub(super) shapes: &'a PacketShapes,
    pub(super) ray: LaneRay,
    /// Whether something blocks the ray.
    pub(super) blocked: bool,
    /// Primitives tested.
    pub(super) tests: i32,
}

impl LaneVisitor for OccludedLane<'_> {
    #[inline(always)]
    fn ray(&self) -> Ray {
        self.ray.ray
    }

    #[inline(always)]
    fn limit(&self) -> f32 {
        self.ray.ray.t_max
    }

    /// True once a primitive of the leaf blocks the ray.
    #[inline(always)]
    fn leaf(&mut self, leaf: &Leaf) -> bool {
        self.tests += leaf.len() as i32;
        let (shapes, ray) = (self.shapes, &self.ray.ray);
        self.blocked = leaf
            .pack
            .as_ref()
            .is_some_and(|pack| pack.nearest(&self.ray.watertight, 0.0, ray.t_max).is_some())
            || leaf
                .boxes
                .clone()
                .any(|index| shapes.boxes.alone(index, ray).is_some())
            || leaf
                .spheres
                .clone()
                .any(|index| shapes.spheres.alone(index, ray).is_some());
        self.blocked
    }
}
