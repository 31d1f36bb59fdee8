//! Whitted's recursive ray tracer: ambient + Σ lights (shadow ray, Lambert +
//! Blinn-Phong), mirror reflection, and refraction with Fresnel and total
//! internal reflection.

use super::RenderOptions;
use crate::offset::offset_ray_origin;
use crate::optics::{fresnel_dielectric, fresnel_schlick, reflect, refract};
use crate::ray::Ray;
use crate::texture;
use crate::world::World;
use glam::Vec3;
use scene::{BaseMaterial, Material};
use std::f32::consts::PI;

/// The radiance arriving along `ray`, recursing at most `options.max_depth` bounces.
pub fn whitted(world: &World, ray: &Ray, options: &RenderOptions) -> Vec3 {
    trace(world, ray, options, 0)
}

fn trace(world: &World, ray: &Ray, options: &RenderOptions, depth: u32) -> Vec3 {
    let Some(hit) = world.intersect(ray, options.method) else {
        return world.ambient;
    };
    let surface = world.surface(ray, hit);
    let material = &world.materials[hit.object as usize];
    let front = ray.dir.dot(surface.normal) < 0.0;
    // The normal on the side the ray came from.
    let n = if front {
        surface.normal
    } else {
        -surface.normal
    };
    let point = surface.point;
    let mut radiance = if front { material.emission } else { Vec3::ZERO };

    let can_recurse = depth < options.max_depth;
    let spawn = |dir: Vec3| {
        let side = if dir.dot(n) >= 0.0 { n } else { -n };
        Ray::new(offset_ray_origin(point, side), dir)
    };

    match material.base {
        BaseMaterial::Matte | BaseMaterial::Plastic | BaseMaterial::Marble => {
            let albedo = albedo_at(material, point);
            let diffuse_weight = 1.0 - material.reflectivity;
            radiance +=
                diffuse_weight * direct(world, options, material, albedo, point, n, -ray.dir);
            if material.reflectivity > 0.0 && can_recurse {
                let mirrored = trace(world, &spawn(reflect(ray.dir, n)), options, depth + 1);
                radiance += material.reflectivity * mirrored;
            }
        }
        BaseMaterial::Mirror | BaseMaterial::Metal => {
            if can_recurse {
                let reflectance = if material.base == BaseMaterial::Metal {
                    fresnel_schlick(-ray.dir.dot(n), material.color)
                } else {
                    material.color
                };
                radiance +=
                    reflectance * trace(world, &spawn(reflect(ray.dir, n)), options, depth + 1);
            }
        }
        BaseMaterial::Glass => {
            if can_recurse {
                // η = η_incident / η_transmitted; the ior is inside the shape.
                let eta = if front {
                    1.0 / material.ior
                } else {
                    material.ior
                };
                let fresnel = fresnel_dielectric(-ray.dir.dot(n), eta);
                let reflected = trace(world, &spawn(reflect(ray.dir, n)), options, depth + 1);
                radiance += fresnel * reflected;
                if let Some(dir) = refract(ray.dir, n, eta) {
                    let transmitted = trace(world, &spawn(dir), options, depth + 1);
                    radiance += (1.0 - fresnel) * material.color * transmitted;
                }
            }
        }
    }
    radiance
}

/// The material's albedo at `point` (marble is a solid texture).
pub fn albedo_at(material: &Material, point: Vec3) -> Vec3 {
    match material.base {
        BaseMaterial::Marble => texture::marble(point, material.color),
        _ => material.color,
    }
}

/// Ambient plus direct light from every point and directional light that the
/// shadow ray finds unblocked: Lambert (albedo/π · E cos θ) plus a normalised
/// Blinn-Phong highlight.
fn direct(
    world: &World,
    options: &RenderOptions,
    material: &Material,
    albedo: Vec3,
    point: Vec3,
    n: Vec3,
    to_eye: Vec3,
) -> Vec3 {
    let mut radiance = albedo * world.ambient;
    let origin = offset_ray_origin(point, n);
    for light in &world.lights {
        let Some(sample) = light.sample(point) else {
            continue;
        };
        let cos = n.dot(sample.to_light);
        if cos <= 0.0 {
            continue;
        }
        let shadow = Ray::new(origin, sample.to_light).with_t_max(sample.distance);
        if world.occluded(&shadow, options.method) {
            continue;
        }
        let irradiance = sample.irradiance * cos;
        radiance += albedo / PI * irradiance;
        if material.specular > 0.0 {
            let half = (sample.to_light + to_eye).normalize_or_zero();
            let lobe = n.dot(half).max(0.0).powf(material.shininess);
            let normalisation = (material.shininess + 8.0) / (8.0 * PI);
            radiance += material.specular * normalisation * lobe * irradiance;
        }
    }
    radiance
}
