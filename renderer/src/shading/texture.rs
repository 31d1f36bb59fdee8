//! Procedural textures.

use super::turbulence::TURBULENCE;
use glam::Vec3;

/// The albedo at `point` of a material of base `base` and colour `color`
/// there (a mesh's texture applied): the colour, or for marble the solid
/// texture through it.
#[inline]
pub fn albedo_at(base: scene::BaseMaterial, color: Vec3, point: Vec3) -> Vec3 {
    match base {
        scene::BaseMaterial::Marble => marble(point, color),
        _ => color,
    }
}

/// Veins per unit length along x.
const VEIN_FREQUENCY: f32 = 2.0;

/// Marble: a solid texture of dark veins, sin(x + turbulence), through `color`.
pub fn marble(point: Vec3, color: Vec3) -> Vec3 {
    marble_with(point, color, TURBULENCE.at(marble_noise_point(point)))
}

/// Where marble reads its turbulence for `point` (the noise is stretched).
#[inline(always)]
pub fn marble_noise_point(point: Vec3) -> [f32; 3] {
    (point * 0.7).to_array()
}

/// [`marble`] at `point` given the turbulence there (what
/// [`TURBULENCE`] gives at [`marble_noise_point`]), for callers that
/// evaluate the noise of many points at once.
#[inline]
pub fn marble_with(point: Vec3, color: Vec3, turbulence: f32) -> Vec3 {
    let phase = VEIN_FREQUENCY * (point.x + 0.5 * point.z) + 6.0 * turbulence;
    // Sharp, thin veins: 1 on the vein's centre line, falling off fast.
    let vein = (1.0 - phase.sin().abs()).powi(6);
    color * (1.0 - 0.7 * vein)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marble_darkens_but_never_brightens_its_colour() {
        for k in 0..1000 {
            let p = Vec3::new(
                k as f32 * 0.037,
                (k % 17) as f32 * 0.11,
                (k % 5) as f32 * 0.3,
            );
            let c = marble(p, Vec3::splat(0.9));
            assert!(c.max_element() <= 0.9 + 1e-6 && c.min_element() >= 0.9 * 0.3 - 1e-6);
        }
    }
}
