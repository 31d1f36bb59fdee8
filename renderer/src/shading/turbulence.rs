//! Marble's turbulence: fractal Perlin noise, the `noise` crate's
//! `Fbm<Perlin>` of seed 7 (its permutation tables, gradients, quintic fade,
//! six octaves, lacunarity 2π/3 and persistence ½), evaluated in `f32` with
//! octaves side by side in SIMD lanes, table reads as gathers. For one point
//! ([`Turbulence::at`]) lane k is octave k and lanes 6 to 15 weigh nothing;
//! for many ([`Turbulence::at_each`]) the lanes hold (point, octave) pairs,
//! sixteen to a step, each lane computing what lane `octave` of `at` does.
//! The crate works in `f64` through generic vector code, one octave after
//! another: its octaves were 31–39% of a full Whitted pass of `seed.xml`.

use crate::simd::{FloatLanes, IntLanes, MaskLanes, WIDTH, WithLanes, dispatch};
use std::sync::LazyLock;

/// Octaves summed, the crate's default six.
pub const OCTAVES: usize = 6;

/// The seed of the first octave's table (`Fbm::new(7)`); octave k uses 7 + k.
const SEED: u32 = 7;

/// Each octave's frequency over the last one's (the crate's default).
const LACUNARITY: f64 = std::f64::consts::PI * 2.0 / 3.0;

/// Each octave's amplitude over the last one's (the crate's default).
const PERSISTENCE: f64 = 0.5;

/// 2/√3: scales a 3D Perlin octave into (−1, 1) (the crate's constant).
const PERLIN_SCALE: f32 = 1.154_700_5;

/// Where the octaves clamp coordinates: 2²⁴. Past it an `f32` holds only
/// even integers, where Perlin noise is zero anyway; clamped there, a point
/// scaled past `f32`'s range stays finite.
const FAR: f32 = 16_777_216.0;

/// The twelve edge directions of a cube indexed by a hash's low four bits,
/// four of them twice, in the crate's order.
const GRADIENTS: [[i32; 3]; 16] = [
    [1, 1, 0],
    [-1, 1, 0],
    [1, -1, 0],
    [-1, -1, 0],
    [1, 0, 1],
    [-1, 0, 1],
    [1, 0, -1],
    [-1, 0, -1],
    [0, 1, 1],
    [0, -1, 1],
    [0, 1, -1],
    [0, -1, -1],
    [1, 1, 0],
    [-1, 1, 0],
    [0, -1, 1],
    [0, -1, -1],
];

/// Entries of a table read by lanes: 256 per lane.
const LANE_TABLE: usize = 256 * WIDTH;

/// The fractal noise's tables, lane k's at `k·256 .. (k + 1)·256`.
pub struct Turbulence {
    /// Lane k's permutation T of 0..256: the crate's table for seed 7 + k.
    permutation: [i32; LANE_TABLE],
    /// Lane k's gradient for the hash T[i], packed by [`pack_gradient`]: the
    /// hash chain's last read gives the gradient at once.
    gradient: [i32; LANE_TABLE],
    /// Lane k's frequency, (2π/3)^k.
    frequency: [f32; WIDTH],
    /// Lane k's weight in the sum: ½^(k+1) over Σ ½^j (j = 1..=6), as the
    /// crate normalises; zero past the octaves.
    weight: [f32; WIDTH],
}

/// The turbulence every marble surface shares.
pub static TURBULENCE: LazyLock<Turbulence> = LazyLock::new(Turbulence::new);

impl Turbulence {
    /// The crate's tables for seeds 7, 8, …: a table's entry i is what its
    /// hash of the one-dimensional point i is.
    fn new() -> Self {
        use noise::permutationtable::{NoiseHasher, PermutationTable};
        let mut permutation = [0; LANE_TABLE];
        let mut gradient = [0; LANE_TABLE];
        for lane in 0..WIDTH {
            let table = PermutationTable::new(SEED + lane as u32);
            for i in 0..256 {
                let hash = table.hash(&[i as isize]) as i32;
                permutation[lane * 256 + i] = hash;
                gradient[lane * 256 + i] = pack_gradient(GRADIENTS[(hash & 0x0f) as usize]);
            }
        }
        let normalisation: f64 = (1..=OCTAVES as i32).map(|k| PERSISTENCE.powi(k)).sum();
        let octave = |k: usize| k < OCTAVES;
        Self {
            permutation,
            gradient,
            frequency: std::array::from_fn(|k| LACUNARITY.powi(k as i32) as f32),
            weight: std::array::from_fn(|k| {
                if octave(k) {
                    (PERSISTENCE.powi(k as i32 + 1) / normalisation) as f32
                } else {
                    0.0
                }
            }),
        }
    }

    /// The noise at `p`, in (−1, 1): the same bits on every lane type.
    #[inline]
    pub fn at(&self, p: [f32; 3]) -> f32 {
        dispatch(Octaves { noise: self, p })
    }
}

/// A gradient's components as bits: component a is nonzero where bit 2a is
/// set and negative where bit 2a + 1 is.
const fn pack_gradient(g: [i32; 3]) -> i32 {
    let mut bits = 0;
    let mut axis = 0;
    while axis < 3 {
        if g[axis] != 0 {
            bits |= 1 << (2 * axis);
        }
        if g[axis] < 0 {
            bits |= 2 << (2 * axis);
        }
        axis += 1;
    }
    bits
}

/// [`Turbulence::at`] on lanes of one type: every octave of the point at once.
#[derive(Clone, Copy)]
struct Octaves<'a> {
    noise: &'a Turbulence,
    p: [f32; 3],
}

impl WithLanes for Octaves<'_> {
    type Output = f32;

    #[inline(always)]
    fn run<F: FloatLanes>(self) -> f32 {
        let noise = self.noise;
        let [x, y, z] = self.p.map(F::splat);
        let base = <F::Ints as IntLanes>::from_array(LANE_BASE);
        let octave = octave_lanes(noise, [x, y, z], F::from_array(noise.frequency), base);
        let weighted = (octave * F::from_array(noise.weight)).to_array();
        let mut sum = 0.0;
        for value in &weighted[..OCTAVES] {
            sum += value;
        }
        sum
    }
}

impl Turbulence {
    /// [`Turbulence::at`] of each of `points` (at most [`WIDTH`]), written
    /// to `out` (same length), bit for bit, in lanes `F` of the caller's
    /// dispatch: the lanes hold (point, octave) pairs, sixteen at a time,
    /// where `at` fills six lanes of sixteen with one point's octaves. Each
    /// lane computes what lane `octave` of `at` computes for its point, and
    /// each point's weighted octaves are summed in the same order.
    #[inline(always)]
    pub fn at_each<F: FloatLanes>(&self, points: &[[f32; 3]], out: &mut [f32]) {
        assert!(points.len() <= WIDTH && points.len() == out.len());
        let pairs = points.len() * OCTAVES;
        let mut weighted = [0.0f32; WIDTH * OCTAVES];
        for (step, values) in weighted.chunks_mut(WIDTH).enumerate() {
            let first = step * WIDTH;
            if first >= pairs {
                break;
            }
            // Lane j: pair first + j, of point (first + j) / 6 at octave
            // (first + j) % 6; a spare lane repeats the last point, its
            // value not read. (Plain loops: `array::from_fn` was not inlined.)
            let (mut x, mut y, mut z) = ([0.0; WIDTH], [0.0; WIDTH], [0.0; WIDTH]);
            let (mut frequency, mut weight, mut base) = ([0.0; WIDTH], [0.0; WIDTH], [0; WIDTH]);
            for j in 0..WIDTH {
                let pair = first + j;
                let [px, py, pz] = points[pair.min(pairs - 1) / OCTAVES];
                let octave = pair % OCTAVES;
                (x[j], y[j], z[j]) = (px, py, pz);
                (frequency[j], weight[j]) = (self.frequency[octave], self.weight[octave]);
                base[j] = LANE_BASE[octave];
            }
            let p = [F::from_array(x), F::from_array(y), F::from_array(z)];
            let (frequency, base) = (F::from_array(frequency), F::Ints::from_array(base));
            let value = octave_lanes(self, p, frequency, base) * F::from_array(weight);
            values.copy_from_slice(value.as_array());
        }
        for (i, out) in out.iter_mut().enumerate() {
            let mut sum = 0.0;
            for value in &weighted[i * OCTAVES..(i + 1) * OCTAVES] {
                sum += value;
            }
            *out = sum;
        }
    }
}

/// One octave of 3D Perlin noise per lane, as the crate's `perlin_3d`
/// computes it: the point `p` at the lane's `frequency`, through the lane's
/// tables (those starting at `base`): a gradient at each corner of the unit
/// cell, dotted with the offset to the point, blended by the quintic fade,
/// scaled into [−1, 1].
#[inline(always)]
fn octave_lanes<F: FloatLanes>(noise: &Turbulence, p: [F; 3], frequency: F, base: F::Ints) -> F {
    let x = scaled(p[0], frequency);
    let y = scaled(p[1], frequency);
    let z = scaled(p[2], frequency);
    let (x_floor, y_floor, z_floor) = (x.floor(), y.floor(), z.floor());
    // The offsets from the cell's near corner and from its far one.
    let (dx, dy, dz) = (x - x_floor, y - y_floor, z - z_floor);
    let (ex, ey, ez) = (dx - F::ONE, dy - F::ONE, dz - F::ONE);
    // The crate hashes a corner's coordinates by their low byte:
    // hash(x, y, z) = T[T[T[x] ^ y] ^ z].
    let [x0, x1] = cell_bytes::<F>(x_floor);
    let [y0, y1] = cell_bytes::<F>(y_floor);
    let [z0, z1] = cell_bytes::<F>(z_floor);
    let table = &noise.permutation;
    let a0 = F::Ints::gather(table, x0 + base);
    let a1 = F::Ints::gather(table, x1 + base);
    let b00 = F::Ints::gather(table, (a0 ^ y0) + base);
    let b01 = F::Ints::gather(table, (a0 ^ y1) + base);
    let b10 = F::Ints::gather(table, (a1 ^ y0) + base);
    let b11 = F::Ints::gather(table, (a1 ^ y1) + base);
    let g = &noise.gradient;
    let c000 = corner::<F>(g, (b00 ^ z0) + base, dx, dy, dz);
    let c001 = corner::<F>(g, (b00 ^ z1) + base, dx, dy, ez);
    let c010 = corner::<F>(g, (b01 ^ z0) + base, dx, ey, dz);
    let c011 = corner::<F>(g, (b01 ^ z1) + base, dx, ey, ez);
    let c100 = corner::<F>(g, (b10 ^ z0) + base, ex, dy, dz);
    let c101 = corner::<F>(g, (b10 ^ z1) + base, ex, dy, ez);
    let c110 = corner::<F>(g, (b11 ^ z0) + base, ex, ey, dz);
    let c111 = corner::<F>(g, (b11 ^ z1) + base, ex, ey, ez);
    let (u, v, w) = (quintic(dx), quintic(dy), quintic(dz));
    let near = lerp(v, lerp(u, c000, c100), lerp(u, c010, c110));
    let far = lerp(v, lerp(u, c001, c101), lerp(u, c011, c111));
    (lerp(w, near, far) * F::splat(PERLIN_SCALE))
        .fast_max(-F::ONE)
        .fast_min(F::ONE)
}

/// Lane k's first entry in a lane table (256 k, for any lane count).
const LANE_BASE: [i32; WIDTH] = {
    let mut base = [0; WIDTH];
    let mut k = 0;
    while k < WIDTH {
        base[k] = (k * 256) as i32;
        k += 1;
    }
    base
};

/// The coordinate `x` at each lane's frequency, clamped to ±[`FAR`].
#[inline(always)]
fn scaled<F: FloatLanes>(x: F, frequency: F) -> F {
    (x * frequency)
        .fast_max(F::splat(-FAR))
        .fast_min(F::splat(FAR))
}

/// The low bytes of a cell's near and far coordinate, from its floor (an
/// integer of at most 2²⁴).
#[inline(always)]
fn cell_bytes<F: FloatLanes>(floor: F) -> [F::Ints; 2] {
    let near = floor.trunc_to_ints();
    let byte = F::Ints::splat(0xff);
    [near & byte, (near + F::Ints::splat(1)) & byte]
}

/// The corner's gradient, read at `index` of the gradient table, dotted with
/// the offset (x, y, z) from the corner to the point.
#[inline(always)]
fn corner<F: FloatLanes>(gradients: &[i32; LANE_TABLE], index: F::Ints, x: F, y: F, z: F) -> F {
    let g = F::Ints::gather(gradients, index);
    let sign = F::Ints::splat(i32::MIN);
    let zero = F::Ints::splat(0);
    // Each component ±1 or 0: the offset with its sign flipped, or +0.
    // (Written out, not through a closure, which might not be inlined into
    // the dispatched SIMD function.)
    let gx = (g & F::Ints::splat(1))
        .simd_gt(zero)
        .select(x ^ (g.shl::<30>() & sign).bits_to_floats(), F::ZERO);
    let gy = (g & F::Ints::splat(4))
        .simd_gt(zero)
        .select(y ^ (g.shl::<28>() & sign).bits_to_floats(), F::ZERO);
    let gz = (g & F::Ints::splat(16))
        .simd_gt(zero)
        .select(z ^ (g.shl::<26>() & sign).bits_to_floats(), F::ZERO);
    gx + gy + gz
}

/// a + t (b − a).
#[inline(always)]
fn lerp<F: FloatLanes>(t: F, a: F, b: F) -> F {
    a + t * (b - a)
}

/// Perlin's fade 6t⁵ − 15t⁴ + 10t³.
#[inline(always)]
fn quintic<F: FloatLanes>(t: F) -> F {
    t * t * t * (t * (t * F::splat(6.0) - F::splat(15.0)) + F::splat(10.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simd::{on_every_lane_type, run_portable};
    use noise::{Fbm, NoiseFn, Perlin};

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

    /// The noise is the crate's `Fbm::new(7)` but for `f32` rounding.
    #[test]
    fn the_turbulence_is_the_crates_fbm() {
        let fbm = Fbm::<Perlin>::new(SEED);
        let turbulence = Turbulence::new();
        let mut worst = 0.0f64;
        for p in points() {
            let ours = turbulence.at(p) as f64;
            worst = worst.max((ours - fbm.get(p.map(f64::from))).abs());
        }
        assert!(worst < 2e-5, "largest difference {worst}");
    }

    /// The portable lanes and every other lane type this CPU has give the same bits,
    /// so an image does not depend on the CPU's instruction set.
    #[test]
    fn every_lane_type_gives_the_same_bits() {
        let turbulence = Turbulence::new();
        for p in points().chain([[1e11, -3e38, 0.5], [f32::NAN, 0.0, 1.0]]) {
            let octaves = Octaves {
                noise: &turbulence,
                p,
            };
            let portable = run_portable(octaves);
            for other in on_every_lane_type(octaves) {
                assert!(
                    portable.to_bits() == other.to_bits() || portable.is_nan() && other.is_nan(),
                    "{p:?}: {portable} against {other}"
                );
            }
        }
    }

    /// [`Turbulence::at_each`] of up to sixteen points at once, on each lane type.
    #[derive(Clone, Copy)]
    struct Each<'a> {
        noise: &'a Turbulence,
        points: &'a [[f32; 3]],
    }

    impl WithLanes for Each<'_> {
        type Output = Vec<f32>;
        fn run<F: FloatLanes>(self) -> Vec<f32> {
            let mut out = vec![0.0; self.points.len()];
            self.noise.at_each::<F>(self.points, &mut out);
            out
        }
    }

    /// Points in (point, octave) lanes give each point's `at` bit for bit,
    /// however many share the call (every count from 1 to 16, so the last
    /// step is full or has spare lanes), on every lane type.
    #[test]
    fn many_points_at_once_give_each_points_noise_bit_for_bit() {
        let turbulence = Turbulence::new();
        let all: Vec<[f32; 3]> = points()
            .take(3_000)
            .chain([[1e11, -3e38, 0.5], [8_388_607.5, -1e7, 0.0]])
            .collect();
        let mut compared = 0;
        for n in 1..=WIDTH {
            for group in all.chunks(n) {
                let alone: Vec<u32> = group.iter().map(|&p| turbulence.at(p).to_bits()).collect();
                for together in on_every_lane_type(Each {
                    noise: &turbulence,
                    points: group,
                }) {
                    let together: Vec<u32> = together.iter().map(|v| v.to_bits()).collect();
                    assert_eq!(together, alone, "{group:?}");
                    compared += group.len();
                }
            }
        }
        assert!(compared >= 16 * all.len(), "{compared}");
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
}
