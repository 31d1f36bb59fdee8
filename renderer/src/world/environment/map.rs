//! An environment map prepared for tracing: its radiance in any direction
//! (bilinear between texels, as Mitsuba 3's `envmap` interpolates them) and
//! a distribution that draws directions in proportion to radiance × solid
//! angle (a piecewise-constant 2D distribution sampled with alias tables).
//!
//! Directions are in the map's own frame; [`super::Environment`] turns them.
//! The mapping is Mitsuba's: a unit direction v has azimuth
//! φ = atan2(v.x, −v.z) (u = φ / 2π, from 0 at −z toward +x) and polar
//! angle θ = acos(v.y) (v = θ / π, 0 at +y). Texel centres lie at
//! u = (x + ½) / W across and at θ = π y / (H − 1) down, the first and last
//! rows on the poles.

use super::alias_lanes::AliasLanes;
use crate::geometry::alias_table::AliasTable;
use crate::geometry::polar::{atan2, sin_cos_turns};
use crate::packet::polar::{atan2s, sin_cos_turns_lanes};
use crate::packet::{FloatLanes, IntLanes, MaskLanes, Vec3s};
use glam::{Vec2, Vec3};
use scene::EnvImage;
use scene::color::luminance;
use std::f32::consts::{PI, TAU};

/// A map ready to look up and sample.
#[derive(Debug)]
pub struct EnvMap {
    /// W, texels across.
    width: u32,
    /// H, texels down.
    height: u32,
    /// (W + 1) × H texels, each row followed by a copy of its first texel
    /// so that interpolation wraps around in azimuth.
    texels: Vec<Vec3>,
    /// The (H − 1) bands between texel rows, by weight.
    bands: Option<AliasTable>,
    /// Per band, its W cells by weight (`None` for a black band).
    cells: Vec<Option<AliasTable>>,
    /// [`EnvMap::bands`] for lanes.
    band_lanes: Option<AliasLanes>,
    /// [`EnvMap::cells`] for lanes, band after band.
    cell_lanes: AliasLanes,
    /// Per band, 1 when it has cells to draw (not black), else 0.
    drawn_bands: Vec<i32>,
    /// Per cell (band-major), the density in solid angle of directions drawn in it.
    density: Vec<f32>,
    /// cos θ of each texel row.
    row_cos: Vec<f32>,
    /// The mean radiance over the sphere.
    mean: Vec3,
}

/// A direction drawn from the map, in its own frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapSample {
    /// The unit direction.
    pub dir: Vec3,
    /// Its density in solid angle.
    pub pdf: f32,
    /// The radiance arriving from it.
    pub radiance: Vec3,
}

impl EnvMap {
    /// The map of `image` (at least 2 × 2 texels, as the reader ensures).
    pub fn new(image: &EnvImage) -> EnvMap {
        let (w, h) = (image.width as usize, image.height as usize);
        assert!(
            w >= 2 && h >= 2,
            "an environment map has at least 2 × 2 texels"
        );
        let mut texels = Vec::with_capacity((w + 1) * h);
        for row in image.texels.chunks_exact(w) {
            texels.extend(row.iter().map(|&t| Vec3::from(t)));
            texels.push(Vec3::from(row[0]));
        }
        let row_cos: Vec<f32> = (0..h)
            .map(|y| (f64::from(y as u32) * std::f64::consts::PI / (h - 1) as f64).cos() as f32)
            .collect();
        // Each cell between four texels weighs its mean luminance times
        // its solid angle (Δφ · (cos θ₀ − cos θ₁)): the integral of the
        // interpolated luminance over it, up to the variation of sin θ.
        let d_phi = std::f64::consts::TAU / w as f64;
        let band_solid: Vec<f64> = (0..h - 1)
            .map(|y| d_phi * (f64::from(row_cos[y]) - f64::from(row_cos[y + 1])))
            .collect();
        let mut weights = vec![0.0f32; w * (h - 1)];
        let mut band_weights = vec![0.0f32; h - 1];
        let mut cells = Vec::with_capacity(h - 1);
        let mut total_rgb = [0.0f64; 3];
        let mut total = 0.0f64;
        for (y, &solid) in band_solid.iter().enumerate() {
            let mut band = 0.0f64;
            for x in 0..w {
                let corners = [
                    texels[y * (w + 1) + x],
                    texels[y * (w + 1) + x + 1],
                    texels[(y + 1) * (w + 1) + x],
                    texels[(y + 1) * (w + 1) + x + 1],
                ];
                let mean = corners.iter().fold(Vec3::ZERO, |a, &c| a + c) * 0.25;
                let weight = f64::from(luminance(mean)).max(0.0) * solid;
                for (sum, c) in total_rgb.iter_mut().zip(mean.to_array()) {
                    *sum += f64::from(c) * solid;
                }
                weights[y * w + x] = weight as f32;
                band += weight;
            }
            band_weights[y] = band as f32;
            total += band;
            cells.push(AliasTable::new(&weights[y * w..(y + 1) * w]));
        }
        let density = weights
            .iter()
            .enumerate()
            .map(|(i, &weight)| {
                let solid = band_solid[i / w];
                if total > 0.0 && solid > 0.0 {
                    (f64::from(weight) / total / solid) as f32
                } else {
                    0.0
                }
            })
            .collect();
        let mean = Vec3::from_array(total_rgb.map(|s| (s / (4.0 * std::f64::consts::PI)) as f32));
        let bands = AliasTable::new(&band_weights);
        EnvMap {
            width: w as u32,
            height: h as u32,
            texels,
            band_lanes: bands.as_ref().map(|b| AliasLanes::new([Some(b)], h - 1)),
            bands,
            cell_lanes: AliasLanes::new(cells.iter().map(Option::as_ref), w),
            drawn_bands: cells.iter().map(|c| i32::from(c.is_some())).collect(),
            cells,
            density,
            row_cos,
            mean,
        }
    }

    /// The direction (map frame) of the texel of highest luminance; the
    /// first of equals, on the equator row's first column for a black map.
    pub fn brightest_direction(&self) -> Vec3 {
        let stride = self.width as usize + 1;
        let mut best = (f32::NEG_INFINITY, 0, (self.height as usize - 1) / 2);
        for y in 0..self.height as usize {
            for x in 0..self.width as usize {
                let l = luminance(self.texels[y * stride + x]);
                if l > best.0 {
                    best = (l, x, y);
                }
            }
        }
        let (_, x, y) = best;
        let phi = TAU * (x as f32 + 0.5) / self.width as f32;
        let theta = PI * y as f32 / (self.height - 1) as f32;
        Vec3::new(
            theta.sin() * phi.sin(),
            theta.cos(),
            -theta.sin() * phi.cos(),
        )
    }

    /// The mean radiance over all directions (1/4π ∫ L dω).
    pub fn mean(&self) -> Vec3 {
        self.mean
    }

    /// The continuous texel coordinates of a unit direction: x across
    /// (texel centres at integers, wrapping at W) and y down (0 to H − 1).
    #[inline]
    fn coordinates(&self, v: Vec3) -> (f32, f32) {
        let (w, h) = (self.width as f32, self.height as f32);
        let u = atan2(v.x, -v.z) * (0.5 / PI) - 0.5 / w;
        let x = (u - u.floor()) * w;
        // θ = acos v.y, as the angle of (v.y, √(x² + z²)): exact near the poles.
        let theta = atan2((v.x * v.x + v.z * v.z).sqrt(), v.y);
        let y = theta * (1.0 / PI) * (h - 1.0);
        (x, y.clamp(0.0, h - 1.0))
    }

    /// The cell (column, band) holding texel coordinates (x, y).
    #[inline]
    fn cell(&self, x: f32, y: f32) -> (usize, usize) {
        let column = (x as usize).min(self.width as usize - 1);
        let band = (y as usize).min(self.height as usize - 2);
        (column, band)
    }

    /// The radiance toward unit direction `v` (map frame): the bilinear
    /// interpolation of the four texels around it.
    #[inline]
    pub fn radiance(&self, v: Vec3) -> Vec3 {
        self.radiance_and_pdf(v).0
    }

    /// The density in solid angle with which [`EnvMap::sample`] draws `v`.
    #[inline]
    pub fn pdf(&self, v: Vec3) -> f32 {
        self.radiance_and_pdf(v).1
    }

    /// [`EnvMap::radiance`] and [`EnvMap::pdf`] of `v`, its texel
    /// coordinates found once (an escaping ray needs both: the arc tangent
    /// and cosine were a fifth of a path-traced pass under a map).
    #[inline]
    pub fn radiance_and_pdf(&self, v: Vec3) -> (Vec3, f32) {
        let (x, y) = self.coordinates(v);
        self.radiance_and_pdf_at(x, y)
    }

    /// [`EnvMap::radiance_and_pdf`] of sixteen unit directions at once, all
    /// on lanes: texel coordinates, cells, the four texels gathered and
    /// interpolated, densities; zero in the lanes not in `lanes`. Bit for
    /// bit what each direction gets alone.
    #[inline(always)]
    pub fn radiance_and_pdf_lanes<F: FloatLanes>(
        &self,
        v: Vec3s<F>,
        lanes: F::Mask,
    ) -> (Vec3s<F>, F) {
        let (w, h) = (self.width as f32, self.height as f32);
        let u = atan2s(v.x, -v.z) * F::splat(0.5 / PI) - F::splat(0.5 / w);
        let x = (u - u.floor()) * F::splat(w);
        let theta = atan2s((v.x * v.x + v.z * v.z).sqrt(), v.y);
        let y = theta * F::splat(1.0 / PI) * F::splat(h - 1.0);
        let y = y.max(F::ZERO).min(F::splat(h - 1.0));
        // `radiance_and_pdf_at`, every lane at once.
        let column = saturated_below::<F>(x, self.width as i32 - 1);
        let band = saturated_below::<F>(y, self.height as i32 - 2);
        let radiance =
            self.bilinear_lanes(column, band, x - column.to_floats(), y - band.to_floats());
        let cell = band * F::Ints::splat(self.width as i32) + column;
        let pdf = F::gather_from(&self.density, cell);
        (
            Vec3s::select(lanes, radiance, Vec3s::ZERO),
            lanes.select(pdf, F::ZERO),
        )
    }

    /// [`EnvMap::bilinear`] in every lane: the texels gathered, the same
    /// operations.
    #[inline(always)]
    fn bilinear_lanes<F: FloatLanes>(
        &self,
        column: F::Ints,
        band: F::Ints,
        fx: F,
        fy: F,
    ) -> Vec3s<F> {
        let stride = self.width as i32 + 1;
        let at = band * F::Ints::splat(stride) + column;
        let numbers: &[f32] = bytemuck::cast_slice(&self.texels);
        let below = at + F::Ints::splat(stride);
        let one = F::Ints::splat(1);
        let (one_fx, one_fy) = (F::ONE - fx, F::ONE - fy);
        let top = texel_lanes::<F>(numbers, at) * one_fx + texel_lanes::<F>(numbers, at + one) * fx;
        let bottom =
            texel_lanes::<F>(numbers, below) * one_fx + texel_lanes::<F>(numbers, below + one) * fx;
        top * one_fy + bottom * fy
    }

    /// [`EnvMap::radiance_and_pdf`] at texel coordinates (x, y).
    #[inline]
    fn radiance_and_pdf_at(&self, x: f32, y: f32) -> (Vec3, f32) {
        let (column, band) = self.cell(x, y);
        let radiance = self.bilinear(column, band, x - column as f32, y - band as f32);
        (radiance, self.density[band * self.width as usize + column])
    }

    /// The texels of cell (`column`, `band`) interpolated at (fx, fy) within it.
    #[inline]
    fn bilinear(&self, column: usize, band: usize, fx: f32, fy: f32) -> Vec3 {
        let stride = self.width as usize + 1;
        let at = band * stride + column;
        let t = &self.texels;
        let top = t[at] * (1.0 - fx) + t[at + 1] * fx;
        let bottom = t[at + stride] * (1.0 - fx) + t[at + stride + 1] * fx;
        top * (1.0 - fy) + bottom * fy
    }

    /// A direction drawn with density ∝ radiance (luminance) from the
    /// uniform point `u`: a band and a cell of it by their weights, then a
    /// point uniform in solid angle within the cell. `None` for a black map.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<MapSample> {
        let (band, v) = self.bands.as_ref()?.sample_with_remainder(u.y);
        let (column, s) = self.cells[band].as_ref()?.sample_with_remainder(u.x);
        let w = self.width as f32;
        // φ = 2π (column + s + ½) / W.
        let (sin_phi, cos_phi) = sin_cos_turns((column as f32 + s + 0.5) / w);
        let (cos0, cos1) = (self.row_cos[band], self.row_cos[band + 1]);
        let cos_theta = (cos0 + (cos1 - cos0) * v).clamp(-1.0, 1.0);
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        // The radiance there, read in the drawn cell: across, where the
        // point was placed; down, from its polar angle.
        let y = atan2(sin_theta, cos_theta) * (1.0 / PI) * (self.height as f32 - 1.0);
        let fy = (y - band as f32).clamp(0.0, 1.0);
        Some(MapSample {
            dir: Vec3::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi),
            pdf: self.density[band * self.width as usize + column],
            radiance: self.bilinear(column, band, s, fy),
        })
    }
}

/// Texel `at` of each lane, from the texels' `numbers` (three each).
#[inline(always)]
fn texel_lanes<F: FloatLanes>(numbers: &[f32], at: F::Ints) -> Vec3s<F> {
    let first = at * F::Ints::splat(3);
    Vec3s {
        x: F::gather_from(numbers, first),
        y: F::gather_from(numbers, first + F::Ints::splat(1)),
        z: F::gather_from(numbers, first + F::Ints::splat(2)),
    }
}

/// `x as usize` capped at `last`, in every lane (`as` saturates: a
/// negative or NaN x gives 0).
#[inline(always)]
fn saturated_below<F: FloatLanes>(x: F, last: i32) -> F::Ints {
    let i = x.trunc_to_ints();
    let last = F::Ints::splat(last);
    let i = F::Ints::select(i.simd_gt(last), last, i);
    F::Ints::select(F::Ints::splat(0).simd_gt(i), F::Ints::splat(0), i)
}

/// Sixteen directions drawn from the map ([`EnvMap::sample_lanes`]).
#[derive(Clone, Copy, Debug)]
pub struct MapSamples<F: FloatLanes> {
    /// The lanes that drew one (not a black band or cell).
    pub found: F::Mask,
    /// The unit directions, map frame.
    pub dir: Vec3s<F>,
    /// Their densities in solid angle.
    pub pdf: F,
    /// The radiance arriving from them.
    pub radiance: Vec3s<F>,
}

impl EnvMap {
    /// [`EnvMap::sample`] of the points (`ux`, `uy`) in the lanes of
    /// `lanes`, bit for bit: bands and cells drawn from the alias tables,
    /// directions, polar angles and densities on lanes; each lane reads its
    /// cell's texels.
    #[inline(always)]
    pub fn sample_lanes<F: FloatLanes>(&self, ux: F, uy: F, lanes: F::Mask) -> MapSamples<F> {
        let Some(bands) = &self.band_lanes else {
            return MapSamples {
                found: F::Mask::NONE,
                dir: Vec3s::splat(Vec3::Y),
                pdf: F::ONE,
                radiance: Vec3s::ZERO,
            };
        };
        let (band, down) = bands.sample_with_remainder(F::Ints::splat(0), uy);
        let drawn = F::Ints::gather_from(&self.drawn_bands, band).simd_gt(F::Ints::splat(0));
        let found = lanes & drawn;
        let (column, across) = self.cell_lanes.sample_with_remainder(band, ux);
        let (w, h) = (self.width as f32, self.height as f32);
        let (sin_phi, cos_phi) =
            sin_cos_turns_lanes((column.to_floats() + across + F::splat(0.5)) / F::splat(w));
        let cos0 = F::gather_from(&self.row_cos, band);
        let cos1 = F::gather_from(&self.row_cos, band + F::Ints::splat(1));
        let cos_theta = (cos0 + (cos1 - cos0) * down)
            .max(F::splat(-1.0))
            .min(F::ONE);
        let sin_theta = (F::ONE - cos_theta * cos_theta).max(F::ZERO).sqrt();
        let y = atan2s(sin_theta, cos_theta) * F::splat(1.0 / PI) * F::splat(h - 1.0);
        let fy = (y - band.to_floats()).max(F::ZERO).min(F::ONE);
        let cell = band * F::Ints::splat(self.width as i32) + column;
        let pdf = found.select(F::gather_from(&self.density, cell), F::ONE);
        let radiance = Vec3s::select(
            found,
            self.bilinear_lanes(column, band, across, fy),
            Vec3s::ZERO,
        );
        let dir = Vec3s::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi);
        MapSamples {
            found,
            // (Lanes that drew nothing: +y, not whatever their numbers made.)
            dir: Vec3s::select(found, dir, Vec3s::splat(Vec3::Y)),
            pdf,
            radiance,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::sampler::Sampler;

    /// A `w × h` image from `f(x, y)`.
    fn image(w: u32, h: u32, f: impl Fn(u32, u32) -> [f32; 3]) -> EnvImage {
        EnvImage {
            path: "test.exr".into(),
            width: w,
            height: h,
            texels: (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect(),
        }
    }

    /// The direction of azimuth φ and polar angle θ in Mitsuba's mapping.
    fn direction(phi: f32, theta: f32) -> Vec3 {
        Vec3::new(
            theta.sin() * phi.sin(),
            theta.cos(),
            -theta.sin() * phi.cos(),
        )
    }

    #[test]
    fn texel_centres_give_their_own_values_where_mitsuba_puts_them() {
        let map = EnvMap::new(&image(8, 5, |x, y| [x as f32, y as f32, 1.0]));
        for y in 0..5 {
            for x in 0..8 {
                let phi = TAU * (x as f32 + 0.5) / 8.0;
                let theta = PI * y as f32 / 4.0;
                let got = map.radiance(direction(phi, theta));
                // At the poles every azimuth meets, and the row is the texel's.
                let want = Vec3::new(x as f32, y as f32, 1.0);
                let err = (got - want).abs();
                assert!(
                    err.y < 1e-4 && err.z < 1e-6 && (y == 0 || y == 4 || err.x < 1e-3),
                    "texel ({x}, {y}): {got} vs {want}"
                );
            }
        }
        // Column 0 is at the azimuth of −z (shifted by half a texel toward +x).
        assert!((map.radiance(direction(TAU * 0.5 / 8.0, PI / 2.0)).x - 0.0).abs() < 1e-4);
    }

    #[test]
    fn interpolation_wraps_around_in_azimuth() {
        let map = EnvMap::new(&image(4, 3, |x, _| [if x == 0 { 1.0 } else { 0.0 }; 3]));
        // Halfway between the last column and the first, across φ = 0.
        let got = map.radiance(direction(0.0, PI / 2.0));
        assert!((got.x - 0.5).abs() < 1e-5, "{got}");
    }

    /// The pdf of sampling integrates to 1 over the sphere and is what
    /// `sample` reports; radiance / pdf is bounded (no cell is starved).
    #[test]
    fn sampling_density_integrates_to_one_and_matches_its_samples() {
        let map = EnvMap::new(&image(16, 9, |x, y| {
            let sun = if (x, y) == (5, 3) { 200.0 } else { 0.0 };
            [0.2 + sun, 0.5 + 0.1 * y as f32, 1.0 + sun]
        }));
        // ∫ pdf dω by a fine midpoint rule in (φ, cos θ).
        let n = 800;
        let mut integral = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let phi = TAU * (i as f32 + 0.5) / n as f32;
                let z = 1.0 - 2.0 * (j as f32 + 0.5) / n as f32;
                let theta = z.acos();
                integral += f64::from(map.pdf(direction(phi, theta)));
            }
        }
        integral *= 4.0 * std::f64::consts::PI / (n * n) as f64;
        assert!((integral - 1.0).abs() < 2e-3, "∫ pdf = {integral}");
        // A drawn direction falls in the cell it was drawn in (but for
        // rounding on a cell's edge), so `pdf` reports its density.
        let mut sampler = Sampler::for_sample(7, 0, 0, 0);
        let mut agree = 0;
        for _ in 0..2000 {
            let s = map.sample(sampler.next_2d()).expect("a lit map");
            assert!((s.dir.length() - 1.0).abs() < 1e-5 && s.pdf > 0.0);
            agree += usize::from(map.pdf(s.dir) == s.pdf);
        }
        assert!(
            agree >= 1990,
            "{agree} of 2000 drawn directions have their cell's density"
        );
    }

    /// Estimating the mean radiance by importance sampling agrees with the
    /// mean computed from the texels, and uniform sampling agrees with both.
    #[test]
    fn importance_sampled_mean_agrees_with_the_exact_mean() {
        let map = EnvMap::new(&image(32, 17, |x, y| {
            let sun = if (x, y) == (20, 5) { 500.0 } else { 0.0 };
            [0.3 + sun, 0.6 + 0.05 * x as f32, 0.9]
        }));
        let mut sampler = Sampler::for_sample(3, 0, 0, 0);
        let n = 200_000;
        let mut sum = glam::DVec3::ZERO;
        for _ in 0..n {
            let s = map.sample(sampler.next_2d()).expect("lit");
            sum += (map.radiance(s.dir) / s.pdf).as_dvec3();
        }
        let estimate = sum / (n as f64 * 4.0 * std::f64::consts::PI);
        let exact = map.mean().as_dvec3();
        let rel = ((estimate - exact).abs() / exact).max_element();
        assert!(rel < 0.01, "importance-sampled mean {estimate} vs {exact}");
        let mut uniform = glam::DVec3::ZERO;
        let m = 2_000_000;
        for _ in 0..m {
            let u = sampler.next_2d();
            let z = 1.0 - 2.0 * u.y;
            uniform += map.radiance(direction(TAU * u.x, z.acos())).as_dvec3();
        }
        let uniform = uniform / m as f64;
        let rel = ((uniform - exact).abs() / exact).max_element();
        assert!(rel < 0.02, "uniform mean {uniform} vs {exact}");
    }

    #[test]
    fn a_black_map_draws_nothing() {
        let map = EnvMap::new(&image(4, 3, |_, _| [0.0; 3]));
        assert_eq!(map.sample(Vec2::new(0.3, 0.7)), None);
        assert_eq!(map.pdf(Vec3::Y), 0.0);
        assert_eq!(map.mean(), Vec3::ZERO);
    }
}
