//! The Lambertian lobe: f = albedo / π, sampled cosine-weighted.

use crate::geometry::warp::concentric_disk;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A local direction (z up) with density cos θ / π (Malley's method). A
/// point that rounds onto the disk's rim keeps z a hair above 0, so that
/// no sample is lost to the horizon.
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    Vec3::new(
        d.x,
        d.y,
        (1.0 - d.length_squared()).max(0.0).sqrt().max(1.0e-6),
    )
}

/// The density of [`sample_cosine_hemisphere`] at local `wi` (solid angle).
#[inline]
pub fn cosine_hemisphere_pdf(wi: Vec3) -> f32 {
    wi.z.max(0.0) * FRAC_1_PI
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_samples_have_mean_cos_two_thirds() {
        // E[cos θ] under cos θ / π is 2/3.
        let n = 64;
        let mut sum = 0.0;
        for a in 0..n {
            for b in 0..n {
                let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
                sum += sample_cosine_hemisphere(u).z;
            }
        }
        let mean = sum / (n * n) as f32;
        assert!((mean - 2.0 / 3.0).abs() < 2e-3, "{mean}");
    }
}
