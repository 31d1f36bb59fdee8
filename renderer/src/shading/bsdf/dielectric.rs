//! A smooth dielectric interface (glass): Fresnel reflection and Snell
//! refraction, chosen at random in proportion to the Fresnel reflectance.

use super::{BsdfSample, Lobe};
use crate::shading::optics::{fresnel_dielectric, refract};
use glam::Vec3;

/// Glass as a ray meets it from one side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothDielectric {
    /// η = η_incident / η_transmitted on the side the ray came from.
    pub eta: f32,
    /// Transmission tint (white for clear glass).
    pub tint: Vec3,
}

impl SmoothDielectric {
    /// Reflects with probability F, else refracts (weight tint · η²: the
    /// radiance a ray carries changes by (η_i / η_t)² across the interface).
    pub fn sample(&self, wo: Vec3, u: f32) -> BsdfSample {
        let fresnel = fresnel_dielectric(wo.z, self.eta);
        let reflect = BsdfSample {
            wi: Vec3::new(-wo.x, -wo.y, wo.z),
            weight: Vec3::ONE,
            pdf: 0.0,
            lobe: Lobe::Specular,
            radiance_scale: 1.0,
        };
        if u < fresnel {
            return reflect;
        }
        match refract(-wo, Vec3::Z, self.eta) {
            Some(wi) => {
                let scale = self.eta * self.eta;
                BsdfSample {
                    wi,
                    weight: self.tint * scale,
                    pdf: 0.0,
                    lobe: Lobe::Specular,
                    radiance_scale: scale,
                }
            }
            // F = 1 on total internal reflection, so u < F above; kept for rounding.
            None => reflect,
        }
    }
}
