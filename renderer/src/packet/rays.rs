//! Sixteen rays.

use super::{FloatLanes, Vec3s, WIDTH};
use crate::geometry::ray::Ray;

/// Sixteen rays R = (P0, v) over (0, t_max), one per lane. Dead lanes hold a
/// harmless ray (any origin, a unit direction, t_max = 0: it hits nothing).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rays<F: FloatLanes> {
    /// P0, the origins.
    pub origin: Vec3s<F>,
    /// v, the directions.
    pub dir: Vec3s<F>,
    /// Hits at α ≥ t_max are ignored (α ≤ 0 always).
    pub t_max: F,
}

impl<F: FloatLanes> Rays<F> {
    /// The packet of sixteen rays, each over (0, its t_max); `t_min` must be 0.
    #[inline(always)]
    pub fn from_lanes(rays: &[Ray; WIDTH]) -> Self {
        debug_assert!(
            rays.iter().all(|r| r.t_min == 0.0),
            "packets start at α = 0"
        );
        Self {
            origin: Vec3s::from_lanes(&rays.map(|r| r.origin)),
            dir: Vec3s::from_lanes(&rays.map(|r| r.dir)),
            t_max: F::from_array(rays.map(|r| r.t_max)),
        }
    }

    /// Lane `k`'s ray.
    #[inline(always)]
    pub fn lane(&self, k: usize) -> Ray {
        Ray::new(self.origin.lane(k), self.dir.lane(k)).with_t_max(self.t_max.as_array()[k])
    }

    /// The points P0 + α v, lane by lane.
    #[inline(always)]
    pub fn at(&self, alpha: F) -> Vec3s<F> {
        self.origin + self.dir * alpha
    }
}
