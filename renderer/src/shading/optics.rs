//! Reflection, refraction and Fresnel terms.

use glam::Vec3;

/// The mirror direction of `dir` about the unit normal `n`.
pub fn reflect(dir: Vec3, n: Vec3) -> Vec3 {
    dir - 2.0 * dir.dot(n) * n
}

/// The refracted direction of unit `dir` through a surface with unit normal
/// `n` facing the incoming side, for η = η_incident / η_transmitted; `None`
/// on total internal reflection.
pub fn refract(dir: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -dir.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * dir + (eta * cos_i - cos_t) * n).normalize())
}

/// The unpolarised Fresnel reflectance of a smooth dielectric, for light
/// arriving at `cos_i` (≥ 0) with η = η_incident / η_transmitted; 1 on total
/// internal reflection.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_parallel = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let r_perpendicular = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (r_parallel * r_parallel + r_perpendicular * r_perpendicular)
}

/// Schlick's approximation of a conductor's reflectance, tinted by `f0`.
pub fn fresnel_schlick(cos_i: f32, f0: Vec3) -> Vec3 {
    // (1 − cos)⁵ as x · (x²)², written out (what `powi(5)` compiles to) so
    // that the wavefront's lanes can form it the same way, bit for bit.
    let x = 1.0 - cos_i.clamp(0.0, 1.0);
    let x2 = x * x;
    let m = x * (x2 * x2);
    f0 + (Vec3::ONE - f0) * m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_incidence_reflectance_of_glass_is_four_percent() {
        let r = fresnel_dielectric(1.0, 1.0 / 1.5);
        assert!((r - 0.04).abs() < 1e-6, "{r}");
    }

    #[test]
    fn refraction_obeys_snells_law() {
        let dir = Vec3::new(0.5f32.sqrt(), -(0.5f32.sqrt()), 0.0);
        let t = refract(dir, Vec3::Y, 1.0 / 1.5).expect("refracts");
        let sin_t = t.x;
        assert!((sin_t - 0.5f32.sqrt() / 1.5).abs() < 1e-6);
    }

    #[test]
    fn beyond_the_critical_angle_light_is_totally_reflected() {
        let dir = Vec3::new(0.8, -0.6, 0.0);
        assert!(refract(dir, Vec3::Y, 1.5).is_none());
        assert_eq!(fresnel_dielectric(0.6, 1.5), 1.0);
    }
}
