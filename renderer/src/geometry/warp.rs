//! Warping uniform numbers onto shapes: the maps that BSDF sampling and
//! light sampling on shapes share.

use glam::Vec2;
use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};

/// A point of the unit disk from [0, 1)², area-preserving (Shirley–Chiu's concentric map).
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let p = 2.0 * u - Vec2::ONE;
    if p == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, phi) = if p.x.abs() > p.y.abs() {
        (p.x, FRAC_PI_4 * (p.y / p.x))
    } else {
        (p.y, FRAC_PI_2 - FRAC_PI_4 * (p.x / p.y))
    };
    r * Vec2::new(phi.cos(), phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_points_stay_inside_the_unit_disk() {
        for a in 0..20 {
            for b in 0..20 {
                let u = Vec2::new(a as f32 / 20.0, b as f32 / 20.0);
                assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
            }
        }
    }
}
