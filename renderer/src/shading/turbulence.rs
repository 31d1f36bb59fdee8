//! Marble's turbulence: fractal Perlin noise, the `noise` crate's
//! `Fbm<Perlin>` of seed 7 (its permutation tables, gradients, quintic fade,
//! lacunarity 2π/3 and persistence ½) evaluated in `f32` and without its
//! finest octave. The crate works in `f64` through generic vector code:
//! its six octaves were 31–39% of a full Whitted pass of `seed.xml`. Here
//! an octave shares its corners' hash lookups, and the sixth, whose
//! amplitude moves a vein by at most 0.1 radian of phase at 28 cycles per
//! unit, is left out (its change to the picture is measured in the tests
//! and in issue 27's note).

use std::sync::LazyLock;
use wide::f32x8;

/// Octaves summed: the crate's six but the finest.
pub const OCTAVES: usize = 5;

/// The crate's octave count for `Fbm::new`, whose normalisation is kept so
/// that each octave weighs what it did there.
const CRATE_OCTAVES: usize = 6;

/// The seed of the first octave's table (`Fbm::new(7)`); octave k uses 7 + k.
const SEED: u32 = 7;

/// Each octave's frequency over the last one's (the crate's default).
const LACUNARITY: f32 = std::f32::consts::PI * 2.0 / 3.0;

/// Each octave's amplitude over the last one's (the crate's default).
const PERSISTENCE: f32 = 0.5;

/// 2/√3: scales a 3D Perlin octave into (−1, 1) (the crate's constant).
const PERLIN_SCALE: f32 = 1.154_700_5;

/// The twelve edge directions of a cube indexed by a hash's low four bits,
/// four of them twice, in the crate's order.
const GRADIENTS: [[f32; 3]; 16] = [
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [1.0, -1.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, 1.0, 1.0],
    [0.0, -1.0, 1.0],
    [0.0, 1.0, -1.0],
    [0.0, -1.0, -1.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 1.0],
    [0.0, -1.0, -1.0],
];

/// The fractal noise: one permutation of 0..256 per octave.
pub struct Turbulence {
    tables: [[u8; 256]; OCTAVES],
    /// 1 / Σ persistence^k over the crate's octaves, k = 1..=6.
    scale: f32,
}

/// The turbulence every marble surface shares.
pub static TURBULENCE: LazyLock<Turbulence> = LazyLock::new(Turbulence::new);

impl Turbulence {
    /// The crate's tables for seeds 7, 8, …: a table's entry i is what its
    /// hash of the one-dimensional point i is.
    fn new() -> Self {
        use noise::permutationtable::{NoiseHasher, PermutationTable};
        let mut tables = [[0u8; 256]; OCTAVES];
        for (octave, table) in tables.iter_mut().enumerate() {
            let permutation = PermutationTable::new(SEED + octave as u32);
            for (i, entry) in table.iter_mut().enumerate() {
                *entry = permutation.hash(&[i as isize]) as u8;
            }
        }
        let sum: f32 = (1..=CRATE_OCTAVES as i32)
            .map(|k| PERSISTENCE.powi(k))
            .sum();
        Self {
            tables,
            scale: 1.0 / sum,
        }
    }

    /// The noise at `p`, in (−1, 1).
    #[inline]
    pub fn at(&self, p: [f32; 3]) -> f32 {
        let mut p = p;
        let mut amplitude = PERSISTENCE;
        let mut sum = 0.0;
        for table in &self.tables {
            sum += amplitude * perlin(table, p);
            amplitude *= PERSISTENCE;
            p = p.map(|x| x * LACUNARITY);
        }
        sum * self.scale
    }
}

/// One octave of 3D Perlin noise with permutation `table`, as the crate's
/// `perlin_3d` computes it: a gradient at each corner of the unit cell,
/// dotted with the offset to `p`, blended by the quintic fade. The eight
/// corners go together in SIMD lanes, the blend as a weighted sum.
#[inline]
fn perlin(table: &[u8; 256], p: [f32; 3]) -> f32 {
    // Past 2²⁴ an f32 holds only even integers, where the noise is zero
    // anyway: clamped there, a point scaled past f32's range stays finite.
    let p = p.map(|x| x.clamp(-FAR, FAR));
    let corner = p.map(floor);
    // The crate hashes a corner's coordinates by their low byte.
    let cell = corner.map(|c| (c as i32 & 0xff) as usize);
    let next = cell.map(|c| (c + 1) & 0xff);
    let d = [p[0] - corner[0], p[1] - corner[1], p[2] - corner[2]];
    // hash(x, y, z) = T[T[T[x] ^ y] ^ z], corner k = x·4 + y·2 + z: the
    // x and y steps are shared.
    let hx = [table[cell[0]] as usize, table[next[0]] as usize];
    let hxy = [
        table[hx[0] ^ cell[1]] as usize,
        table[hx[0] ^ next[1]] as usize,
        table[hx[1] ^ cell[1]] as usize,
        table[hx[1] ^ next[1]] as usize,
    ];
    let mut gradients = [[0.0f32; 8]; 3];
    for (k, &h) in hxy.iter().enumerate() {
        for (z, &cz) in [cell[2], next[2]].iter().enumerate() {
            let g = GRADIENTS[(table[h ^ cz] & 0x0f) as usize];
            for axis in 0..3 {
                gradients[axis][2 * k + z] = g[axis];
            }
        }
    }
    // Each corner's offset to p and its trilinear weight.
    let offset = |axis: usize| f32x8::splat(d[axis]) - f32x8::from(CORNER[axis]);
    let fade = d.map(quintic);
    let weight = |axis: usize| {
        let far = f32x8::from(CORNER[axis]);
        (f32x8::ONE - far) * f32x8::splat(1.0 - fade[axis]) + far * f32x8::splat(fade[axis])
    };
    let dots = f32x8::from(gradients[0]) * offset(0)
        + f32x8::from(gradients[1]) * offset(1)
        + f32x8::from(gradients[2]) * offset(2);
    let blended = (dots * weight(0) * weight(1) * weight(2)).reduce_add();
    (blended * PERLIN_SCALE).clamp(-1.0, 1.0)
}

/// Where [`perlin`] clamps coordinates: 2²⁴.
const FAR: f32 = 16_777_216.0;

/// Per axis, the cell corners' coordinate (0 or 1), corner k = x·4 + y·2 + z.
const CORNER: [[f32; 8]; 3] = [
    [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
    [0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0],
    [0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0],
];

/// ⌊x⌋, without the library call `f32::floor` makes where the CPU
/// baseline has no rounding instruction (SSE4.1).
#[inline(always)]
fn floor(x: f32) -> f32 {
    // From 2²³ on every f32 is an integer (and `as i32` saturates from 2³¹).
    if !(x.abs() < 8_388_608.0) {
        return x;
    }
    let truncated = x as i32 as f32;
    if truncated > x {
        truncated - 1.0
    } else {
        truncated
    }
}

/// Perlin's fade 6t⁵ − 15t⁴ + 10t³.
#[inline]
fn quintic(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use noise::{Fbm, MultiFractal, NoiseFn, Perlin};

    /// Points spread over a few units around the origin, negative ones and
    /// cell corners among them.
    fn points() -> impl Iterator<Item = [f32; 3]> {
        (0..20_000).map(|k| {
            let h = |s: u32| {
                let x = (k as u32).wrapping_mul(0x9e37_79b9) ^ s;
                let x = (x ^ (x >> 15)).wrapping_mul(0x2c1b_3c6d);
                (x ^ (x >> 12)) as f32 / u32::MAX as f32
            };
            if k % 10 == 0 {
                [(k % 7) as f32 - 3.0, (k % 5) as f32 - 2.0, (k % 3) as f32]
            } else {
                [16.0 * h(1) - 8.0, 4.0 * h(2) - 2.0, 16.0 * h(3) - 8.0]
            }
        })
    }

    /// Every octave is the crate's: with the crate's sixth octave added
    /// back, this sum differs from `Fbm::new(7)` only by f32 rounding.
    #[test]
    fn octaves_are_the_crates_fbm_but_the_finest() {
        let fbm = Fbm::<Perlin>::new(SEED);
        let sixth = Perlin::new(SEED + OCTAVES as u32);
        let turbulence = Turbulence::new();
        let mut worst = 0.0f64;
        for p in points() {
            let q = p.map(f64::from);
            let finest = LACUNARITY.powi(OCTAVES as i32) as f64;
            let sixth_octave = PERSISTENCE.powi(CRATE_OCTAVES as i32) as f64
                * sixth.get(q.map(|x| x * finest))
                * turbulence.scale as f64;
            let ours = turbulence.at(p) as f64 + sixth_octave;
            worst = worst.max((ours - fbm.get(q)).abs());
        }
        assert!(worst < 2e-5, "largest difference {worst}");
    }

    /// Far from the origin, where f32 holds only integers (a floor seen
    /// 10¹¹ away), the noise stays finite and in range.
    #[test]
    fn the_noise_is_finite_at_any_finite_point() {
        let turbulence = Turbulence::new();
        for x in [1e7f32, -3e9, 1e11, 3e38, -3e38, 8_388_607.5, -8_388_608.0] {
            for p in [[x, 0.0, 0.0], [0.5, x, -x], [x, x, x]] {
                let n = turbulence.at(p);
                assert!(n.is_finite() && n.abs() <= 1.0, "{p:?}: {n}");
            }
        }
    }

    /// Leaving out the sixth octave moves the noise by at most its
    /// amplitude, 1/63 of the range.
    #[test]
    fn the_left_out_octave_changes_the_noise_by_at_most_its_amplitude() {
        let fbm = Fbm::<Perlin>::new(SEED).set_octaves(CRATE_OCTAVES);
        let turbulence = Turbulence::new();
        let bound = PERSISTENCE.powi(CRATE_OCTAVES as i32) * turbulence.scale;
        let mut worst = 0.0f32;
        for p in points() {
            worst = worst.max((turbulence.at(p) - fbm.get(p.map(f64::from)) as f32).abs());
        }
        assert!(worst <= bound + 2e-5, "{worst} against {bound}");
        assert!(
            worst > 0.1 * bound,
            "the sixth octave does change something: {worst}"
        );
    }
}
