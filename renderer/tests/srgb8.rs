//! The fast 8-bit sRGB encoding gives exactly the bytes of the direct one.

use glam::Vec3;
use renderer::display::srgb::{encode_srgb8_direct, linear_to_srgb8};

fn fast(x: f32) -> u8 {
    linear_to_srgb8(Vec3::splat(x))[0]
}

#[test]
fn threshold_encoding_equals_the_direct_encoding_across_the_floats() {
    // Every 61st bit pattern of the non-negative floats up to 2.0, which
    // includes every threshold's neighbourhood many times over.
    let mut checked = 0u64;
    let mut bits = 0u32;
    while bits <= 2.0f32.to_bits() {
        let x = f32::from_bits(bits);
        assert_eq!(fast(x), encode_srgb8_direct(x), "x = {x:e}");
        bits += 61;
        checked += 1;
    }
    assert!(checked > 10_000_000);
}

#[test]
fn every_step_of_the_encoding_happens_at_the_same_float() {
    // Just below and at each of the 255 steps, found from the direct encoding.
    for k in 1..=255u8 {
        let (mut below, mut at) = (0u32, 1.0f32.to_bits());
        while at - below > 1 {
            let middle = below + (at - below) / 2;
            if encode_srgb8_direct(f32::from_bits(middle)) >= k {
                at = middle;
            } else {
                below = middle;
            }
        }
        for bits in [below, at] {
            let x = f32::from_bits(bits);
            assert_eq!(fast(x), encode_srgb8_direct(x), "step {k}, x = {x:e}");
        }
    }
}

#[test]
fn out_of_range_and_non_finite_values_clamp() {
    for (x, expected) in [
        (f32::NAN, 0),
        (f32::NEG_INFINITY, 0),
        (-1.0, 0),
        (-0.0, 0),
        (1.0, 255),
        (7.5, 255),
        (f32::INFINITY, 255),
    ] {
        assert_eq!(fast(x), expected, "x = {x}");
        assert_eq!(encode_srgb8_direct(x), expected, "direct, x = {x}");
    }
}
