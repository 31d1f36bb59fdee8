//! Every lane type gives the same bits for every operation, and the same as
//! scalar `f32` arithmetic lane by lane.

use super::*;

/// Awkward values: zeros of both signs, subnormals, infinities, NaN,
/// extremes and ordinary numbers.
const VALUES: [f32; 2 * WIDTH] = [
    0.0,
    -0.0,
    1.0e-40,
    -1.0e-40,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::NAN,
    f32::MAX,
    f32::MIN_POSITIVE,
    1.0,
    -1.5,
    0.3,
    7.25,
    -1.0e30,
    2.5e-20,
    -0.1,
    -0.0,
    0.0,
    f32::NAN,
    -f32::MAX,
    -f32::MIN_POSITIVE,
    2.5,
    -2.5,
    3.0e9,
    -3.0e9,
    1.0e-45,
    0.5,
    -7.75,
    f32::INFINITY,
    1.0e20,
    -0.3,
    4.0,
];

/// NaN lanes compare equal to NaN lanes (payloads may differ), all others by bits.
fn same(a: [f32; WIDTH], b: [f32; WIDTH]) -> bool {
    a.iter()
        .zip(&b)
        .all(|(x, y)| (x.is_nan() && y.is_nan()) || x.to_bits() == y.to_bits())
}

/// How many arrays [`Results`] gives for each pair of operands.
const RESULTS_PER_PAIR: usize = 40;

/// Every operation of `F` on every pair of chunks of [`VALUES`], as arrays.
struct Results;

impl WithLanes for Results {
    type Output = Vec<[f32; WIDTH]>;

    fn run<F: FloatLanes>(self) -> Vec<[f32; WIDTH]> {
        let mut out = Vec::new();
        let mut pairs = 0;
        for shift in 0..VALUES.len() {
            let a: [f32; WIDTH] = std::array::from_fn(|k| VALUES[k]);
            let b: [f32; WIDTH] = std::array::from_fn(|k| VALUES[(k + shift) % VALUES.len()]);
            let c: [f32; WIDTH] = std::array::from_fn(|k| VALUES[WIDTH + k]);
            for (a, b) in [(a, b), (c, b), (b, c)] {
                let (x, y) = (F::from_array(a), F::from_array(b));
                pairs += 1;
                let mask = x.simd_lt(y);
                let bitmask = f32::from_bits(
                    mask.to_bitmask() | u32::from(mask.any()) << 8 | u32::from(mask.all()) << 9,
                );
                let ints = <F::Ints as IntLanes>::from_array(std::array::from_fn(|k| k as i32 - 3));
                let int_select = <F::Ints as IntLanes>::select(
                    mask,
                    ints,
                    ints + <F::Ints as IntLanes>::splat(10),
                );
                let int_gt = ints.simd_gt(<F::Ints as IntLanes>::splat(0));
                // A mask's lanes as numbers (1 where set): what every lane
                // type must agree on, whatever it keeps a mask in.
                let flags = |m: F::Mask| m.select(F::ONE, F::ZERO).to_array();
                out.extend([
                    (x + y).to_array(),
                    (x - y).to_array(),
                    (x * y).to_array(),
                    (x / y).to_array(),
                    (-x).to_array(),
                    flags(mask),
                    flags(x.simd_le(y)),
                    flags(x.simd_gt(y)),
                    flags(x.simd_ge(y)),
                    flags(x.simd_eq(y)),
                    flags(x.simd_ne(y)),
                    flags(mask & x.simd_eq(y) | !x.simd_ge(y) ^ mask),
                    flags(mask.select_mask(x.simd_eq(y), x.simd_gt(y))),
                    flags(F::Mask::from_bitmask(mask.to_bitmask() ^ 0xa5a5)),
                    mask.select(x, y).to_array(),
                    [bitmask; WIDTH],
                    x.max(y).to_array(),
                    x.min(y).to_array(),
                    x.fast_max(y).to_array(),
                    x.fast_min(y).to_array(),
                    x.abs().to_array(),
                    x.sqrt().to_array(),
                    x.floor().to_array(),
                    flags(x.is_finite()),
                    flags(x.is_sign_negative()),
                    F::splat(a[3]).to_array(),
                    F::ZERO.to_array(),
                    F::ONE.to_array(),
                    F::INFINITY.to_array(),
                    F::NEG_INFINITY.to_array(),
                    int_select.to_array().map(|i| i as f32),
                    flags(int_gt),
                    x.trunc_to_ints()
                        .to_array()
                        .map(|i| f32::from_bits(i as u32)),
                ]);
                let (xi, yi) = (x.bits(), y.bits());
                let as_floats = |i: F::Ints| i.bits_to_floats().to_array();
                out.extend([
                    as_floats(xi + yi),
                    as_floats(xi * yi),
                    as_floats(xi.shr::<7>()),
                    as_floats(xi.shl::<9>()),
                    as_floats(xi & yi | xi ^ yi),
                    xi.shr::<9>().to_floats().to_array(),
                    xi.simd_gt(yi).select(x, F::ZERO).to_array(),
                ]);
            }
        }
        assert_eq!(out.len(), pairs * RESULTS_PER_PAIR);
        out
    }
}

#[test]
fn the_lane_types_give_the_same_bits_for_every_operation() {
    let portable = run_portable(Results);
    for lanes in LaneType::available() {
        let other = lanes.run(Results);
        assert_eq!(portable.len(), other.len());
        for (k, (p, o)) in portable.iter().zip(&other).enumerate() {
            // Bit for bit, NaN payloads included: the same instructions run.
            assert_eq!(
                p.map(f32::to_bits),
                o.map(f32::to_bits),
                "result {k}: portable {p:?} vs {lanes:?} {o:?}"
            );
        }
    }
}

#[test]
fn arithmetic_is_scalar_f32_lane_by_lane() {
    let lanes = run_portable(Results);
    for shift in 0..VALUES.len() {
        let a: [f32; WIDTH] = std::array::from_fn(|k| VALUES[k]);
        let b: [f32; WIDTH] = std::array::from_fn(|k| VALUES[(k + shift) % VALUES.len()]);
        let first = &lanes[shift * 3 * RESULTS_PER_PAIR..];
        let scalar: [[f32; WIDTH]; 4] = [
            std::array::from_fn(|k| a[k] + b[k]),
            std::array::from_fn(|k| a[k] - b[k]),
            std::array::from_fn(|k| a[k] * b[k]),
            std::array::from_fn(|k| a[k] / b[k]),
        ];
        for (op, want) in scalar.iter().enumerate() {
            assert!(same(first[op], *want), "op {op}, shift {shift}");
        }
        let max: [f32; WIDTH] = std::array::from_fn(|k| a[k].max(b[k]));
        let min: [f32; WIDTH] = std::array::from_fn(|k| a[k].min(b[k]));
        let sqrt: [f32; WIDTH] = std::array::from_fn(|k| a[k].sqrt());
        // f32::max and f32::min may return either zero of ±0: compare those by value.
        let by_value = |x: [f32; WIDTH], y: [f32; WIDTH]| {
            x.iter()
                .zip(&y)
                .all(|(x, y)| (x.is_nan() && y.is_nan()) || x == y)
        };
        assert!(by_value(first[16], max), "max, shift {shift}");
        assert!(by_value(first[17], min), "min, shift {shift}");
        assert!(same(first[21], sqrt), "sqrt, shift {shift}");
        // cvttps: toward zero, i32::MIN where NaN or out of range.
        let truncated: [f32; WIDTH] = std::array::from_fn(|k| {
            let t = if a[k].abs() < 2_147_483_648.0 {
                a[k] as i32
            } else {
                i32::MIN
            };
            f32::from_bits(t as u32)
        });
        assert!(same(first[32], truncated), "trunc_to_ints, shift {shift}");
        // Integer lanes wrap and shift as u32, bit for bit.
        let int_ops: [fn(u32, u32) -> u32; 5] = [
            u32::wrapping_add,
            u32::wrapping_mul,
            |x, _| x >> 7,
            |x, _| x << 9,
            |x, y| x & y | x ^ y,
        ];
        for (op, scalar) in int_ops.iter().enumerate() {
            let got = first[33 + op];
            for k in 0..WIDTH {
                let want = scalar(a[k].to_bits(), b[k].to_bits());
                assert_eq!(
                    got[k].to_bits(),
                    want,
                    "int op {op}, lane {k}, shift {shift}"
                );
            }
        }
    }
}

#[test]
fn first_lanes_and_lane_set_read_the_lanes_in_order() {
    let mask = first_lanes::<Portable>(3);
    assert_eq!(mask.to_bitmask(), 0b111);
    assert!(lane_set(mask, 2) && !lane_set(mask, 3));
    let last = mask_from::<Portable>(|k| k == WIDTH - 1);
    assert_eq!(last.to_bitmask(), 1 << (WIDTH - 1));
}

/// Integer bit reversal on lanes, against `u32::reverse_bits`.
#[derive(Clone)]
struct Reverse;

impl WithLanes for Reverse {
    type Output = ();
    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        let mut x = 0x1234_5678u32;
        for _ in 0..1000 {
            let values: [u32; WIDTH] = std::array::from_fn(|k| {
                // SplitMix32-style steps: every bit pattern is likely.
                x = x.wrapping_add(0x9e37_79b9);
                let z = (x ^ (x >> 16)).wrapping_mul(0x21f0_aaad);
                (z ^ (z >> 15)).wrapping_mul(0x735a_2d97) ^ k as u32
            });
            let lanes = <F::Ints as IntLanes>::from_array(values.map(|v| v as i32));
            let reversed = lanes.reverse_bits().to_array();
            for k in 0..WIDTH {
                assert_eq!(
                    reversed[k] as u32,
                    values[k].reverse_bits(),
                    "{:#x}",
                    values[k]
                );
            }
        }
    }
}

#[test]
fn reverse_bits_on_lanes_is_u32_reverse_bits() {
    on_every_lane_type(Reverse);
}

/// Table reads on lanes: lane k reads `table[index_k mod N]`, any index
/// (negative ones too) landing inside the table.
#[derive(Clone)]
struct Gather;

impl WithLanes for Gather {
    type Output = ();
    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        let table: [i32; 64] = std::array::from_fn(|i| (i as i32 * 7919) ^ 0x5a5a);
        for start in [-70i32, -9, 0, 5, 57, 1 << 20, i32::MAX - 8] {
            let index: [i32; WIDTH] = std::array::from_fn(|k| start.wrapping_add(3 * k as i32));
            let read = <F::Ints as IntLanes>::gather(&table, IntLanes::from_array(index));
            let want = index.map(|i| table[(i & 63) as usize]);
            assert_eq!(read.to_array(), want, "indices from {start}");
        }
    }
}

#[test]
fn gather_reads_the_table_at_each_lanes_index_mod_its_length() {
    on_every_lane_type(Gather);
}

/// Reads of tables of any length: lane k reads `table[min(index_k, len − 1)]`
/// with the index taken as unsigned, so no index (negative, past the end,
/// `i32::MAX`) reads outside the table; `f32` and `i32` tables alike.
#[derive(Clone)]
struct GatherFrom;

impl WithLanes for GatherFrom {
    type Output = ();
    #[inline(always)]
    fn run<F: FloatLanes>(self) {
        for len in [1usize, 2, 3, 13, 100] {
            let ints: Vec<i32> = (0..len as i32).map(|i| (i * 7919) ^ 0x5a5a).collect();
            let floats: Vec<f32> = (0..len).map(|i| i as f32 * 0.37 - 5.0).collect();
            for start in [-9i32, -1, 0, 1, 5, len as i32 - 2, 97, i32::MAX - 8] {
                let index: [i32; WIDTH] = std::array::from_fn(|k| start.wrapping_add(k as i32));
                let at = index.map(|i| (i as u32).min(len as u32 - 1) as usize);
                let lanes = <F::Ints as IntLanes>::from_array(index);
                let read = <F::Ints as IntLanes>::gather_from(&ints, lanes);
                assert_eq!(
                    read.to_array(),
                    at.map(|i| ints[i]),
                    "len {len}, from {start}"
                );
                let read = F::gather_from(&floats, lanes);
                assert_eq!(
                    read.to_array(),
                    at.map(|i| floats[i]),
                    "len {len}, from {start}"
                );
            }
        }
    }
}

#[test]
fn gather_from_reads_inside_a_table_of_any_length() {
    on_every_lane_type(GatherFrom);
}
