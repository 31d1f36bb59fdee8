//! Rays: the lecture's half-line (P0, v), restricted to an interval of α.

use glam::Vec3;

/// A ray R = (P0, v): points P0 + α v for α in the open interval (t_min, t_max).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// P0, the origin.
    pub origin: Vec3,
    /// v, the direction; unit length for camera and secondary rays.
    pub dir: Vec3,
    /// Hits at α ≤ t_min are ignored.
    pub t_min: f32,
    /// Hits at α ≥ t_max are ignored.
    pub t_max: f32,
}

impl Ray {
    /// A ray that hits nothing (t_max = 0): the stand-in for an unused
    /// SIMD lane.
    pub const NOTHING: Ray = Ray {
        origin: Vec3::ZERO,
        dir: Vec3::Z,
        t_min: 0.0,
        t_max: 0.0,
    };

    /// A ray over (0, ∞).
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        debug_assert!(origin.is_finite() && dir.is_finite(), "ray {origin} {dir}");
        Self {
            origin,
            dir,
            t_min: 0.0,
            t_max: f32::INFINITY,
        }
    }

    /// The same ray over (0, t_max).
    pub fn with_t_max(self, t_max: f32) -> Self {
        Self { t_max, ..self }
    }

    /// The point P0 + α v.
    pub fn at(&self, alpha: f32) -> Vec3 {
        self.origin + alpha * self.dir
    }

    /// True when α lies inside (t_min, t_max).
    pub fn contains(&self, alpha: f32) -> bool {
        alpha > self.t_min && alpha < self.t_max
    }
}
