//! Linear radiance to 8-bit sRGB, as every picture raylab shows or writes is
//! encoded: the direct formula (clamp, the sRGB curve of
//! [`scene::color::linear_to_srgb`], round) and a table-driven encoding that
//! gives exactly the same bytes without a `powf` per channel.

use glam::Vec3;
use rayon::prelude::*;
use scene::View;

/// One linear channel to 8-bit sRGB the direct way: clamp to [0, 1], the
/// sRGB transfer curve (`powf`), round. [`linear_to_srgb8`] gives the same bytes faster.
pub fn encode_srgb8_direct(x: f32) -> u8 {
    (scene::color::linear_to_srgb(x.clamp(0.0, 1.0)) * 255.0).round() as u8
}

/// The fast encoding's buckets are the floats of [0, 1] sharing their bits
/// above this one: each octave is cut into 2⁸ buckets, narrower than the
/// gap between any two steps of the encoding, so a bucket holds at most one.
const BUCKET_SHIFT: u32 = 15;

/// Buckets over [0, 1]: the last one holds 1.0 alone.
const BUCKETS: usize = (0x3f80_0000 >> BUCKET_SHIFT) + 1;

/// The tables of the fast sRGB encoding.
struct Srgb8Table {
    /// `thresholds[k]`: the smallest f32 whose [`encode_srgb8_direct`] is ≥ k + 1
    /// (`thresholds[255]`, past the last step, is +∞).
    thresholds: [f32; 256],
    /// `bucket_start[b]`: the code of the bucket's smallest float.
    bucket_start: Box<[u8; BUCKETS]>,
}

/// The thresholds are found by bisection over the bit patterns of [0, 1]
/// (where float order is integer order); the encoding is monotonic, so a
/// value's code is the number of thresholds at or below it.
fn srgb8_table() -> &'static Srgb8Table {
    static TABLE: std::sync::OnceLock<Srgb8Table> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut thresholds = [f32::INFINITY; 256];
        for (k, threshold) in (1u8..=255).zip(thresholds.iter_mut()) {
            let (mut below, mut at) = (0u32, 1.0f32.to_bits());
            while at - below > 1 {
                let middle = below + (at - below) / 2;
                if encode_srgb8_direct(f32::from_bits(middle)) >= k {
                    at = middle;
                } else {
                    below = middle;
                }
            }
            *threshold = f32::from_bits(at);
        }
        let steps = &thresholds[..255];
        assert!(
            steps
                .windows(2)
                .all(|pair| pair[0].to_bits() >> BUCKET_SHIFT != pair[1].to_bits() >> BUCKET_SHIFT),
            "two steps of the sRGB encoding share a bucket"
        );
        let mut bucket_start = Box::new([0u8; BUCKETS]);
        for (b, start) in bucket_start.iter_mut().enumerate() {
            let x = f32::from_bits((b as u32) << BUCKET_SHIFT);
            *start = steps.partition_point(|&t| t <= x) as u8;
        }
        Srgb8Table {
            thresholds,
            bucket_start,
        }
    })
}

/// One channel through the tables: the bucket's code, plus one if the
/// bucket's step (if it has one) is at or below `x`.
#[inline(always)]
fn encode_srgb8_fast(table: &Srgb8Table, x: f32) -> u8 {
    if !(x > 0.0) {
        return 0; // also NaN
    }
    if x >= 1.0 {
        return 255;
    }
    let code = table.bucket_start[(x.to_bits() >> BUCKET_SHIFT) as usize];
    code + u8::from(x >= table.thresholds[code as usize])
}

/// Linear radiance to an 8-bit sRGB pixel, clamping to [0, 1] (NaN gives 0):
/// exactly the bytes of [`encode_srgb8_direct`], from tables instead of `powf`.
pub fn linear_to_srgb8(c: Vec3) -> [u8; 3] {
    let table = srgb8_table();
    [
        encode_srgb8_fast(table, c.x),
        encode_srgb8_fast(table, c.y),
        encode_srgb8_fast(table, c.z),
    ]
}

/// Linear radiance, as `view` shows it, to opaque 8-bit sRGB RGBA, in
/// parallel; a run of equal pixels (a preview's blocks) is converted once.
pub fn srgba8_of_linear(pixels: &[Vec3], view: View) -> Vec<[u8; 4]> {
    const CHUNK: usize = 4096;
    // Decided once, not per pixel: most frames are shown as rendered.
    let identity = view.is_identity();
    let mut out = vec![[0u8, 0, 0, 255]; pixels.len()];
    out.par_chunks_mut(CHUNK)
        .zip(pixels.par_chunks(CHUNK))
        .for_each(|(out, pixels)| {
            let mut last: Option<(Vec3, [u8; 4])> = None;
            for (o, &c) in out.iter_mut().zip(pixels) {
                let rgba = match last {
                    Some((previous, rgba)) if previous == c => rgba,
                    _ => {
                        let shown = if identity {
                            c
                        } else {
                            super::view::apply(view, c)
                        };
                        let [r, g, b] = linear_to_srgb8(shown);
                        let rgba = [r, g, b, 255];
                        last = Some((c, rgba));
                        rgba
                    }
                };
                *o = rgba;
            }
        });
    out
}
