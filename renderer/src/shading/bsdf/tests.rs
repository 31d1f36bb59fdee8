//! Analytic properties of every material's BSDF: energy conservation (the
//! directional albedo never exceeds 1), reciprocity, and that sampling
//! agrees with `eval` and `pdf`.

use super::*;
use crate::integrator::sampler::Sampler;
use glam::Vec3;
use proptest::prelude::*;
use scene::BaseMaterial;
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
    for roughness in [0.1, 0.5, 1.0] {
        out.extend(rough_materials(roughness));
    }
    out
}

/// Rough white mirror, gold metal and clear glass (IOR 1.5 and 1.33).
fn rough_materials(roughness: f32) -> Vec<(String, Material)> {
    let rough = |base, color| Material {
        color,
        roughness,
        ..builtin(base)
    };
    vec![
        (
            format!("rough white mirror {roughness}"),
            rough(BaseMaterial::Mirror, Vec3::ONE),
        ),
        (
            format!("rough gold metal {roughness}"),
            rough(BaseMaterial::Metal, Vec3::new(1.0, 0.78, 0.34)),
        ),
        (
            format!("rough glass {roughness}"),
            rough(BaseMaterial::Glass, Vec3::ONE),
        ),
        (
            format!("rough water {roughness}"),
            Material {
                ior: 1.33,
                ..rough(BaseMaterial::Glass, Vec3::ONE)
            },
        ),
    ]
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

#[test]
fn roughness_makes_mirror_metal_and_glass_microfacet_surfaces() {
    for (name, material) in rough_materials(0.3) {
        let bsdf = Bsdf::new(&material, material.color, true);
        assert!(
            matches!(bsdf, Bsdf::RoughConductor(_) | Bsdf::RoughDielectric(_)),
            "{name}: {bsdf:?}"
        );
        assert!(bsdf.has_smooth(), "{name}: light sampling helps");
    }
    let smooth = Material {
        roughness: 0.0,
        ..builtin(BaseMaterial::Metal)
    };
    assert!(matches!(
        Bsdf::new(&smooth, smooth.color, true),
        Bsdf::Conductor { .. }
    ));
}

/// A nearly smooth rough surface converges to the smooth one: its
/// directional albedo approaches the smooth BSDF's (a mirror's reflectance,
/// glass's Fresnel split).
#[test]
fn slightly_rough_surfaces_scatter_like_smooth_ones() {
    for (name, rough) in rough_materials(0.05) {
        let smooth = Material {
            roughness: 0.0,
            ..rough
        };
        for front in [true, false] {
            let (r, s) = (
                Bsdf::new(&rough, rough.color, front),
                Bsdf::new(&smooth, smooth.color, front),
            );
            for cos in [1.0f32, 0.6, 0.3] {
                let wo = direction(cos, 0.2);
                let (ar, as_) = (albedo(&r, wo, 20_000), albedo(&s, wo, 20_000));
                assert!(
                    (ar - as_).abs().max_element() < 0.02,
                    "{name} front {front} cos {cos}: rough {ar}, smooth {as_}"
                );
            }
        }
    }
}

/// Single-scattering microfacets lose the light that would scatter again
/// among them. Head-on at roughness 1 (α = 1) the visible normals are
/// cosine-distributed, wi.z = 2x − 1 for x = cos²θ_h uniform, and
/// G1(c) = 2c / (1 + c), so a white rough mirror's albedo is
/// ∫_{1/2}^{1} G1(2x − 1) dx = ∫ (2 − 1/x) dx = 1 − ln 2 ≈ 0.307; at
/// roughness 0.1 almost nothing is lost.
#[test]
fn white_rough_mirror_albedo_is_analytic() {
    let white = |roughness| Material {
        color: Vec3::ONE,
        roughness,
        ..builtin(BaseMaterial::Mirror)
    };
    let a = albedo(&Bsdf::new(&white(0.1), Vec3::ONE, true), Vec3::Z, 20_000);
    assert!(a.x > 0.99, "roughness 0.1: {a}");
    let a = albedo(&Bsdf::new(&white(1.0), Vec3::ONE, true), Vec3::Z, 100_000);
    let expected = 1.0 - std::f32::consts::LN_2;
    assert!(
        (a.x - expected).abs() < 0.005,
        "roughness 1: {a}, expected {expected}"
    );
}

/// ∫ pdf(wo, wi) dωi over the sphere equals the fraction of samples that
/// succeed: `pdf` is the density `sample` draws from, no more, no less.
#[test]
fn rough_pdfs_integrate_to_the_sampled_fraction() {
    // Lobes wide enough for a 1500 × 256 grid over the sphere.
    for (name, material) in rough_materials(0.5)
        .into_iter()
        .chain(rough_materials(0.35))
    {
        for front in [true, false] {
            let bsdf = Bsdf::new(&material, material.color, front);
            for cos in [0.9f32, 0.4] {
                let wo = direction(cos, 0.0);
                let (nt, np) = (1500, 256);
                let mut integral = 0.0f64;
                for a in 0..nt {
                    let theta = (a as f32 + 0.5) / nt as f32 * std::f32::consts::PI;
                    for b in 0..np {
                        let phi = (b as f32 + 0.5) / np as f32 * std::f32::consts::TAU;
                        let wi = direction(theta.cos(), phi);
                        let d_omega = theta.sin()
                            * (std::f32::consts::PI / nt as f32)
                            * (std::f32::consts::TAU / np as f32);
                        integral += f64::from(bsdf.pdf(wo, wi) * d_omega);
                    }
                }
                let n = 40_000;
                let mut sampler = Sampler::for_sample(3, 0, 0, 0);
                let drawn = (0..n)
                    .filter(|_| {
                        let u_lobe = sampler.next_f32();
                        bsdf.sample(wo, u_lobe, sampler.next_2d()).is_some()
                    })
                    .count() as f64
                    / f64::from(n);
                assert!(
                    (integral - drawn).abs() < 0.01,
                    "{name} front {front} cos {cos}: ∫pdf {integral}, sampled {drawn}"
                );
            }
        }
    }
}

/// f(wo, wi) = f(wi, wo) for a reflection-only BSDF (eval carries cos θ_i).
fn check_reciprocal(bsdf: &Bsdf, wo: Vec3, wi: Vec3) -> Result<(), TestCaseError> {
    let f_oi = bsdf.eval(wo, wi) / wi.z;
    let f_io = bsdf.eval(wi, wo) / wo.z;
    let scale = f_oi.max_element().max(1.0);
    prop_assert!(
        (f_oi - f_io).abs().max_element() <= 1e-4 * scale,
        "{} vs {}",
        f_oi,
        f_io
    );
    Ok(())
}

proptest! {
    #[test]
    fn rough_conductors_are_reciprocal(
        cos_o in 0.01f32..1.0, phi_o in 0.0f32..std::f32::consts::TAU,
        cos_i in 0.01f32..1.0, phi_i in 0.0f32..std::f32::consts::TAU,
        roughness in 0.05f32..1.0,
    ) {
        let material = Material { roughness, ..builtin(BaseMaterial::Mirror) };
        let (wo, wi) = (direction(cos_o, phi_o), direction(cos_i, phi_i));
        check_reciprocal(&Bsdf::new(&material, material.color, true), wo, wi)?;
    }

    /// Refraction obeys generalised reciprocity: the radiance-scaled f
    /// satisfies f(wo→wi) / η_wo² = f(wi→wo) / η_wi², with η_wo the index
    /// on wo's side (Veach 1997, §5.2).
    #[test]
    fn rough_glass_refraction_is_reciprocal(
        cos_o in 0.05f32..1.0, phi_o in 0.0f32..std::f32::consts::TAU,
        cos_i in 0.05f32..1.0, phi_i in 0.0f32..std::f32::consts::TAU,
        roughness in 0.1f32..1.0,
    ) {
        let material = Material { roughness, ..builtin(BaseMaterial::Glass) };
        // From outside (front) wo is above; wi inside is below the surface.
        let outside = Bsdf::new(&material, Vec3::ONE, true);
        let inside = Bsdf::new(&material, Vec3::ONE, false);
        let wo = direction(cos_o, phi_o);
        let wi = -direction(cos_i, phi_i);
        // Seen from inside, the frame flips: both directions mirror in z.
        let flip = |v: Vec3| Vec3::new(v.x, v.y, -v.z);
        let f_out = outside.eval(wo, wi).x / wi.z.abs();
        let f_in = inside.eval(flip(wi), flip(wo)).x / wo.z.abs();
        // wo is outside (index 1) for f_out, inside (1.5) for f_in.
        let (unscaled_out, unscaled_in) = (f_out, f_in / (1.5 * 1.5));
        let scale = unscaled_out.max(1.0);
        prop_assert!(
            (unscaled_out - unscaled_in).abs() <= 1e-3 * scale,
            "{} vs {}", unscaled_out, unscaled_in
        );
    }

    #[test]
    fn rough_sampled_weight_is_eval_over_pdf(
        cos_o in 0.05f32..1.0, u_lobe in 0.0f32..1.0, u1 in 0.0f32..1.0, u2 in 0.0f32..1.0,
        roughness in 0.05f32..1.0, front: bool, which in 0usize..4,
    ) {
        let (_, material) = rough_materials(roughness).swap_remove(which);
        let bsdf = Bsdf::new(&material, material.color, front);
        let wo = direction(cos_o, 0.3);
        if let Some(s) = bsdf.sample(wo, u_lobe, Vec2::new(u1, u2)) {
            prop_assert!(!s.is_delta());
            let pdf = bsdf.pdf(wo, s.wi);
            prop_assert!((pdf - s.pdf).abs() <= 1e-4 * pdf.max(1.0));
            let expected = bsdf.eval(wo, s.wi) / pdf;
            prop_assert!(
                (expected - s.weight).abs().max_element()
                    <= 1e-3 * expected.max_element().max(1.0),
                "{} vs {}", expected, s.weight
            );
        }
    }

    #[test]
    fn layered_bsdfs_are_reciprocal(
        cos_o in 0.01f32..1.0, phi_o in 0.0f32..std::f32::consts::TAU,
        cos_i in 0.01f32..1.0, phi_i in 0.0f32..std::f32::consts::TAU,
        specular in 0.0f32..1.0, shininess in 0.0f32..500.0,
    ) {
        let material = Material { specular, shininess, ..builtin(BaseMaterial::Plastic) };
        let (wo, wi) = (direction(cos_o, phi_o), direction(cos_i, phi_i));
        check_reciprocal(&Bsdf::new(&material, material.color, true), wo, wi)?;
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
            && !s.is_delta()
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
