//! Analytic properties of every material's BSDF: energy conservation (the
//! directional albedo never exceeds 1), reciprocity, and that sampling
//! agrees with `eval` and `pdf`.

use super::*;
use crate::sampler::Sampler;
use glam::Vec3;
use proptest::prelude::*;
use scene::materials::builtin;

fn every_material() -> Vec<(String, Material)> {
    let mut out: Vec<(String, Material)> = BaseMaterial::ALL
        .iter()
        .map(|&b| (b.name().to_string(), builtin(b)))
        .collect();
    let white = |base| Material {
        color: Vec3::ONE,
        ..builtin(base)
    };
    out.push(("white matte".into(), white(BaseMaterial::Matte)));
    out.push((
        "white plastic, reflective, rough highlight".into(),
        Material {
            specular: 1.0,
            shininess: 2.0,
            reflectivity: 0.3,
            ..white(BaseMaterial::Plastic)
        },
    ));
    out.push(("white mirror".into(), white(BaseMaterial::Mirror)));
    out.push(("white metal".into(), white(BaseMaterial::Metal)));
    out
}

fn direction(cos_theta: f32, phi: f32) -> Vec3 {
    let sin = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(sin * phi.cos(), sin * phi.sin(), cos_theta)
}

/// The directional albedo ∫ f cos dωi for `wo`, by importance sampling
/// (`radiance_scale` divided out, so glass counts energy, not radiance).
fn albedo(bsdf: &Bsdf, wo: Vec3, n: u32) -> Vec3 {
    let mut sampler = Sampler::for_sample(11, 0, 0, 0);
    let mut sum = glam::DVec3::ZERO;
    for _ in 0..n {
        let u_lobe = sampler.next_f32();
        if let Some(s) = bsdf.sample(wo, u_lobe, sampler.next_2d()) {
            sum += (s.weight / s.radiance_scale).as_dvec3();
        }
    }
    (sum / f64::from(n)).as_vec3()
}

#[test]
fn no_material_reflects_more_energy_than_arrives() {
    for (name, material) in every_material() {
        for front in [true, false] {
            let bsdf = Bsdf::new(&material, material.color, front);
            for cos in [1.0f32, 0.7, 0.3, 0.05] {
                let a = albedo(&bsdf, direction(cos, 0.4), 20_000);
                assert!(
                    a.max_element() <= 1.0 + 1e-3,
                    "{name} (front {front}) at cos θ_o = {cos} reflects {a}"
                );
            }
        }
    }
}

#[test]
fn white_lossless_materials_keep_all_energy() {
    // A white Lambertian surface, a white mirror and clear glass lose nothing.
    let lossless = [
        builtin(BaseMaterial::Glass),
        Material {
            color: Vec3::ONE,
            ..builtin(BaseMaterial::Mirror)
        },
        Material {
            color: Vec3::ONE,
            ..builtin(BaseMaterial::Matte)
        },
    ];
    for material in lossless {
        for front in [true, false] {
            let bsdf = Bsdf::new(&material, material.color, front);
            for cos in [1.0f32, 0.5, 0.1] {
                let a = albedo(&bsdf, direction(cos, 1.0), 4_000);
                assert!(
                    (a - Vec3::ONE).abs().max_element() < 1e-5,
                    "{:?} front {front} cos {cos}: {a}",
                    material.base
                );
            }
        }
    }
}

#[test]
fn lambertian_albedo_is_its_colour() {
    let material = builtin(BaseMaterial::Matte);
    let bsdf = Bsdf::new(&material, material.color, true);
    let a = albedo(&bsdf, direction(0.6, 0.0), 10_000);
    assert!((a - material.color).abs().max_element() < 1e-5, "{a}");
}

#[test]
fn glass_reflects_four_percent_head_on() {
    let bsdf = Bsdf::new(&builtin(BaseMaterial::Glass), Vec3::ONE, true);
    let n = 100_000;
    let mut sampler = Sampler::for_sample(5, 0, 0, 0);
    let reflected = (0..n)
        .filter(|_| {
            bsdf.sample(Vec3::Z, sampler.next_f32(), Vec2::ZERO)
                .expect("sample")
                .wi
                .z
                > 0.0
        })
        .count();
    let fraction = reflected as f32 / n as f32;
    assert!((fraction - 0.04).abs() < 3e-3, "{fraction}");
}

proptest! {
    #[test]
    fn layered_bsdfs_are_reciprocal(
        cos_o in 0.01f32..1.0, phi_o in 0.0f32..std::f32::consts::TAU,
        cos_i in 0.01f32..1.0, phi_i in 0.0f32..std::f32::consts::TAU,
        specular in 0.0f32..1.0, shininess in 0.0f32..500.0,
    ) {
        let material = Material { specular, shininess, ..builtin(BaseMaterial::Plastic) };
        let bsdf = Bsdf::new(&material, material.color, true);
        let (wo, wi) = (direction(cos_o, phi_o), direction(cos_i, phi_i));
        let f_oi = bsdf.eval(wo, wi) / wi.z;
        let f_io = bsdf.eval(wi, wo) / wo.z;
        let scale = f_oi.max_element().max(1.0);
        prop_assert!((f_oi - f_io).abs().max_element() <= 1e-4 * scale, "{} vs {}", f_oi, f_io);
    }

    #[test]
    fn sampled_weight_is_eval_over_pdf(
        cos_o in 0.05f32..1.0, u_lobe in 0.0f32..1.0, u1 in 0.0f32..1.0, u2 in 0.0f32..1.0,
        specular in 0.0f32..1.0, shininess in 1.0f32..200.0,
    ) {
        let material = Material { specular, shininess, reflectivity: 0.2, ..builtin(BaseMaterial::Plastic) };
        let bsdf = Bsdf::new(&material, material.color, true);
        let wo = direction(cos_o, 0.3);
        if let Some(s) = bsdf.sample(wo, u_lobe, Vec2::new(u1, u2))
            && !s.delta
        {
            let pdf = bsdf.pdf(wo, s.wi);
            prop_assert!((pdf - s.pdf).abs() <= 1e-5 * pdf.max(1.0));
            let expected = bsdf.eval(wo, s.wi) / pdf;
            prop_assert!(
                (expected - s.weight).abs().max_element()
                    <= 1e-4 * expected.max_element().max(1.0)
            );
        }
    }
}
