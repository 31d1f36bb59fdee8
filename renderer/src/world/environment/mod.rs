//! The environment: what a ray that leaves the scene sees (`<sky>`), as a
//! light. A constant colour, or an HDR map turned by the sky's rotation and
//! tinted by its colour. The path tracer samples a map as a light, by
//! radiance, and weighs what its escaping rays see against that by multiple
//! importance sampling. A constant colour is left to BSDF sampling, as
//! pbrt-v4's path tracer leaves its uniform infinite light: drawing
//! directions uniformly over the sphere never beats a BSDF's own sampling
//! of a uniform sky (a cosine-weighted Lambertian sample sees it with no
//! variance at all; weighing in a uniform sample adds variance), which is
//! what MIS compensation (Karlík et al. 2019: sample ∝ max(L − mean L, 0))
//! reduces to for a constant.

mod alias_lanes;
mod cache;
mod map;

pub use map::{EnvMap, MapSamples};

use crate::packet::{FloatLanes, MaskLanes, Vec3s};
use crate::shapes::placement::Placement;
use glam::{Mat3, Vec2, Vec3};
use std::sync::Arc;

/// The environment of a world.
#[derive(Clone, Debug)]
pub struct Environment {
    /// The constant radiance, or the map's tint, times the sky's strength.
    color: Vec3,
    /// The prepared map, if the sky has one.
    map: Option<Arc<EnvMap>>,
    /// World directions into the map's frame (the inverse of `rotate`).
    map_from_world: Mat3,
    /// The map's frame into world directions.
    world_from_map: Mat3,
    /// Whether the path tracer samples it ([`Environment::is_sampled`]),
    /// decided once: it is asked per lane and bounce.
    sampled: bool,
}

/// How a map lies around the scene ([`Environment::map_orientation`]),
/// unit world-space directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapOrientation {
    /// The map's top row (θ = 0).
    pub zenith: Vec3,
    /// Azimuth φ = 0: the centre line of column 0's left edge.
    pub azimuth_zero: Vec3,
    /// Azimuth φ = 90°.
    pub azimuth_quarter: Vec3,
    /// Toward the brightest texel's centre.
    pub brightest: Vec3,
}

/// A direction drawn toward the environment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvironmentSample {
    /// Unit direction, world space.
    pub dir: Vec3,
    /// The radiance arriving from it.
    pub radiance: Vec3,
    /// Its density in solid angle.
    pub pdf: f32,
}

impl Environment {
    /// The environment of a resolved sky (its map prepared once per image).
    pub fn new(sky: &scene::Sky) -> Environment {
        let world_from_map =
            Placement::from_euler_degrees(Vec3::ZERO, sky.rotate).world_from_object;
        let map = sky.map.as_ref().map(|m| cache::map_for(&m.image));
        let color = sky.scale();
        let black = color == Vec3::ZERO || map.as_ref().is_some_and(|m| m.mean() == Vec3::ZERO);
        Environment {
            color,
            sampled: map.is_some() && !black,
            map,
            map_from_world: world_from_map.transpose(),
            world_from_map,
        }
    }

    /// The radiance arriving from direction `dir` (world space, any length).
    #[inline]
    pub fn radiance(&self, dir: Vec3) -> Vec3 {
        match &self.map {
            None => self.color,
            Some(map) => self.color * map.radiance((self.map_from_world * dir).normalize()),
        }
    }

    /// For a map, its frame in world space: where its zenith (θ = 0, the
    /// top row), its azimuth origin (φ = 0, toward the map's −z, column 0)
    /// and φ = 90° (its +x) point once turned, and the direction of its
    /// brightest texel (a sun, say); `None` for a constant colour.
    pub fn map_orientation(&self) -> Option<MapOrientation> {
        let map = self.map.as_ref()?;
        let turn = |v: Vec3| self.world_from_map * v;
        Some(MapOrientation {
            zenith: turn(Vec3::Y),
            azimuth_zero: turn(Vec3::NEG_Z),
            azimuth_quarter: turn(Vec3::X),
            brightest: turn(map.brightest_direction()),
        })
    }

    /// The mean radiance over all directions: Whitted's ambient term from
    /// the sky (the light a white Lambertian surface under it receives,
    /// unshadowed).
    pub fn mean(&self) -> Vec3 {
        match &self.map {
            None => self.color,
            Some(map) => self.color * map.mean(),
        }
    }

    /// True when the path tracer samples it as a light: a map that gives
    /// light (not black, nor tinted black). A constant colour is left to
    /// BSDF sampling.
    #[inline]
    pub fn is_sampled(&self) -> bool {
        self.sampled
    }

    /// The constant radiance of a sky without a map.
    #[inline]
    pub fn constant_radiance(&self) -> Option<Vec3> {
        self.map.is_none().then_some(self.color)
    }

    /// A direction drawn from the uniform point `u` with density ∝ the
    /// map's radiance; `None` when it is not sampled ([`Environment::is_sampled`]).
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<EnvironmentSample> {
        if !self.sampled {
            return None;
        }
        let map = self.map.as_ref()?;
        let s = map.sample(u)?;
        Some(EnvironmentSample {
            dir: self.world_from_map * s.dir,
            radiance: self.color * s.radiance,
            pdf: s.pdf,
        })
    }

    /// [`Environment::sample`] of the points (`ux`, `uy`) in the lanes of
    /// `lanes`, bit for bit ([`EnvMap::sample_lanes`], turned to world space
    /// as glam turns it and tinted); none found when it is not sampled.
    #[inline(always)]
    pub fn sample_lanes<F: FloatLanes>(&self, ux: F, uy: F, lanes: F::Mask) -> MapSamples<F> {
        let map = match &self.map {
            Some(map) if self.sampled => map,
            _ => {
                return MapSamples {
                    found: F::Mask::NONE,
                    dir: Vec3s::splat(Vec3::Y),
                    pdf: F::ONE,
                    radiance: Vec3s::ZERO,
                };
            }
        };
        let s = map.sample_lanes(ux, uy, lanes);
        MapSamples {
            dir: turned(self.world_from_map, s.dir),
            radiance: Vec3s::splat(self.color).mul_lanes(s.radiance),
            ..s
        }
    }

    /// [`Environment::radiance_and_pdf`] of sixteen directions at once, in
    /// the lanes of `lanes` (zero elsewhere under a map), bit for bit what
    /// each gets alone: turned into the map's frame and normalised as glam
    /// does it, then [`EnvMap::radiance_and_pdf_lanes`].
    #[inline(always)]
    pub fn radiance_and_pdf_lanes<F: FloatLanes>(
        &self,
        dir: Vec3s<F>,
        lanes: F::Mask,
    ) -> (Vec3s<F>, F) {
        let Some(map) = &self.map else {
            return (Vec3s::splat(self.color), F::ZERO);
        };
        let v = turned(self.map_from_world, dir);
        let v = v * (F::ONE / v.dot(v).sqrt());
        let (radiance, pdf) = map.radiance_and_pdf_lanes(v, lanes);
        let pdf = if self.sampled { pdf } else { F::ZERO };
        (Vec3s::splat(self.color).mul_lanes(radiance), pdf)
    }

    /// [`Environment::radiance`] of `dir` and the density in solid angle
    /// with which [`Environment::sample`] draws it (0 when it is not
    /// sampled), the map's texel coordinates found once.
    #[inline]
    pub fn radiance_and_pdf(&self, dir: Vec3) -> (Vec3, f32) {
        match &self.map {
            None => (self.color, 0.0),
            Some(map) => {
                let (radiance, pdf) = map.radiance_and_pdf((self.map_from_world * dir).normalize());
                (self.color * radiance, if self.sampled { pdf } else { 0.0 })
            }
        }
    }
}

/// `m * v` lane by lane, rounded as glam's `Mat3 * Vec3` rounds it (the
/// columns scaled by x, y, z and summed in that order).
#[inline(always)]
fn turned<F: FloatLanes>(m: Mat3, v: Vec3s<F>) -> Vec3s<F> {
    Vec3s::splat(m.x_axis) * v.x + Vec3s::splat(m.y_axis) * v.y + Vec3s::splat(m.z_axis) * v.z
}

#[cfg(test)]
mod tests {
    use super::*;
    use scene::{EnvImage, Sky, SkyMap};
    use std::f32::consts::PI;

    fn sky_with_map(rotate: Vec3) -> Sky {
        // Bright toward +x in the map's frame (azimuth π/2: column 1 of 4).
        let image = EnvImage {
            path: "m.exr".into(),
            width: 4,
            height: 3,
            texels: (0..12)
                .map(|i| {
                    if i % 4 == 1 {
                        [8.0, 8.0, 8.0]
                    } else {
                        [0.5, 0.5, 0.5]
                    }
                })
                .collect(),
        };
        Sky {
            color: Vec3::new(1.0, 0.5, 0.25),
            map: Some(SkyMap {
                src: "m.exr".into(),
                image: Arc::new(image),
            }),
            rotate,
            strength: 1.0,
        }
    }

    #[test]
    fn the_orientation_names_where_the_map_and_its_brightest_texel_point() {
        // Only column 1 of the equator row is bright.
        let equator_sun = |rotate| {
            let mut sky = sky_with_map(rotate);
            let map = sky.map.as_mut().expect("a map");
            let mut image = (*map.image).clone();
            for (i, t) in image.texels.iter_mut().enumerate() {
                *t = if i == 5 { [8.0; 3] } else { [0.5; 3] };
            }
            map.image = Arc::new(image);
            Environment::new(&sky)
        };
        let plain = equator_sun(Vec3::ZERO);
        let o = plain.map_orientation().expect("a map");
        assert_eq!((o.zenith, o.azimuth_zero), (Vec3::Y, Vec3::NEG_Z));
        // The bright column 1 is centred at φ = 3π/4 (on the equator row).
        let bright = Vec3::new((0.75 * PI).sin(), 0.0, -(0.75 * PI).cos());
        assert!((o.brightest - bright).length() < 1e-5, "{}", o.brightest);
        let turned = equator_sun(Vec3::new(0.0, 90.0, 0.0));
        let t = turned.map_orientation().expect("a map");
        let r = Mat3::from_rotation_y(PI / 2.0);
        assert!((t.azimuth_zero - r * Vec3::NEG_Z).length() < 1e-6);
        assert!((t.brightest - r * bright).length() < 1e-5);
        assert_eq!(
            Environment::new(&Sky::constant(Vec3::ONE)).map_orientation(),
            None
        );
    }

    #[test]
    fn rotation_turns_the_map_as_a_box_turns() {
        let plain = Environment::new(&sky_with_map(Vec3::ZERO));
        // Column 1's centre is at u = 1.5 / 4: φ = 3π/4, between +x and +z.
        let bright = Vec3::new((0.75 * PI).sin(), 0.0, -(0.75 * PI).cos());
        assert_eq!(plain.radiance(bright), Vec3::new(8.0, 4.0, 2.0));
        // Turned 90° about y, what was toward `bright` is now toward R·bright.
        let turned = Environment::new(&sky_with_map(Vec3::new(0.0, 90.0, 0.0)));
        let r = Mat3::from_rotation_y(PI / 2.0);
        assert!(
            (turned.radiance(r * bright) - Vec3::new(8.0, 4.0, 2.0))
                .abs()
                .max_element()
                < 1e-4
        );
        assert!(
            (turned.radiance(bright) - Vec3::new(8.0, 4.0, 2.0))
                .abs()
                .max_element()
                > 1.0
        );
    }

    #[test]
    fn samples_are_in_world_space_with_their_densities() {
        let env = Environment::new(&sky_with_map(Vec3::new(10.0, 70.0, -30.0)));
        let mut sampler = crate::integrator::sampler::Sampler::for_sample(1, 2, 3, 4);
        let mut agree = 0;
        for _ in 0..1000 {
            let s = env.sample(sampler.next_2d()).expect("lit");
            let radiance = env.radiance(s.dir);
            assert!((s.radiance - radiance).abs().max_element() < 1e-3 * radiance.max_element());
            // The turned direction lands in the drawn cell but for rounding
            // on a cell's edge.
            agree += usize::from((env.radiance_and_pdf(s.dir).1 - s.pdf).abs() < 1e-4 * s.pdf);
        }
        assert!(agree >= 990, "{agree} of 1000");
    }

    #[test]
    fn a_constant_sky_is_left_to_bsdf_sampling_and_a_black_tint_is_not_sampled() {
        let env = Environment::new(&Sky::constant(Vec3::splat(0.5)));
        assert!(!env.is_sampled());
        assert_eq!(env.sample(Vec2::new(0.25, 0.5)), None);
        assert_eq!(
            env.radiance_and_pdf(Vec3::new(0.3, -2.0, 1.0)),
            (Vec3::splat(0.5), 0.0)
        );
        assert_eq!(env.mean(), Vec3::splat(0.5));
        let mut black = sky_with_map(Vec3::ZERO);
        black.color = Vec3::ZERO;
        let black = Environment::new(&black);
        assert!(!black.is_sampled() && black.sample(Vec2::splat(0.5)).is_none());
        assert_eq!(black.radiance_and_pdf(Vec3::X), (Vec3::ZERO, 0.0));
        assert!(Environment::new(&sky_with_map(Vec3::ZERO)).is_sampled());
    }

    #[test]
    fn strength_scales_the_radiance_in_every_direction_and_not_the_density() {
        let plain = Environment::new(&sky_with_map(Vec3::new(0.0, 40.0, 0.0)));
        let mut brighter = sky_with_map(Vec3::new(0.0, 40.0, 0.0));
        brighter.strength = 2.5;
        let brighter = Environment::new(&brighter);
        for dir in [
            Vec3::X,
            Vec3::new(0.3, -2.0, 1.0),
            Vec3::new(-1.0, 0.2, -0.4),
        ] {
            let (l, pdf) = plain.radiance_and_pdf(dir);
            let (l_scaled, pdf_scaled) = brighter.radiance_and_pdf(dir);
            assert!((l_scaled - 2.5 * l).abs().max_element() <= 1e-6 * l.max_element());
            assert_eq!(pdf_scaled, pdf, "the same distribution");
        }
        let mut off = sky_with_map(Vec3::ZERO);
        off.strength = 0.0;
        assert!(!Environment::new(&off).is_sampled(), "strength 0 is black");
        let constant = Sky {
            strength: 3.0,
            ..Sky::constant(Vec3::splat(0.5))
        };
        assert_eq!(Environment::new(&constant).mean(), Vec3::splat(1.5));
    }
}
