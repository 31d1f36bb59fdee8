//! Arbitrary output variables: what the primary ray through each pixel
//! centre P_ij sees, beside the final colour.

use crate::shading::texture::albedo_at;
use crate::shapes::Method;
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;

/// The per-pixel quantities raylab can output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Aov {
    /// α along the unit ray v_ij to the first hit; +∞ on a miss.
    Depth,
    /// The unit geometric normal at the first hit; zero on a miss.
    Normal,
    /// The material's albedo at the first hit; zero on a miss.
    Albedo,
    /// The index of the object hit; −1 on a miss.
    Object,
}

impl Aov {
    /// Values per pixel: 1 for depth and object id, 3 otherwise.
    pub fn channels(self) -> usize {
        match self {
            Aov::Depth | Aov::Object => 1,
            Aov::Normal | Aov::Albedo => 3,
        }
    }
}

/// The AOV at pixel (i, j), padded to three values.
pub fn aov_at(world: &World, aov: Aov, method: Method, i: u32, j: u32) -> [f32; 3] {
    let ray = world.camera.center_ray(i, j);
    let hit = world.intersect(&ray, method);
    match (aov, hit) {
        (Aov::Depth, Some(h)) => [h.alpha, 0.0, 0.0],
        (Aov::Depth, None) => [f32::INFINITY, 0.0, 0.0],
        (Aov::Object, Some(h)) => [h.object as f32, 0.0, 0.0],
        (Aov::Object, None) => [-1.0, 0.0, 0.0],
        (Aov::Normal, Some(h)) => world.surface(&ray, h).normal.to_array(),
        (Aov::Albedo, Some(h)) => {
            let at = world.hit_surface(&ray, &h);
            albedo_at(at.material.base, at.color, at.surface.point).to_array()
        }
        (Aov::Normal | Aov::Albedo, None) => [0.0; 3],
    }
}

/// The whole AOV image, row by row from the top, `aov.channels()` values per pixel.
pub fn render_aov(world: &World, aov: Aov, method: Method) -> Vec<f32> {
    render_aov_unless(world, aov, method, &|| false).unwrap_or_default()
}

/// Like [`render_aov`], but rows not yet started are skipped once
/// `cancelled()` returns true, and then the result is `None`.
pub fn render_aov_unless(
    world: &World,
    aov: Aov,
    method: Method,
    cancelled: &(dyn Fn() -> bool + Sync),
) -> Option<Vec<f32>> {
    let (w, h) = (world.camera.w, world.camera.h);
    let channels = aov.channels();
    let mut values = vec![0.0; w as usize * h as usize * channels];
    let skipped = values
        .par_chunks_mut(w as usize * channels)
        .enumerate()
        .map(|(j, row)| {
            if cancelled() {
                return 1;
            }
            for (i, out) in row.chunks_exact_mut(channels).enumerate() {
                let value = aov_at(world, aov, method, i as u32, j as u32);
                out.copy_from_slice(&value[..channels]);
            }
            0
        })
        .sum::<u32>();
    (skipped == 0).then_some(values)
}

/// A viewable picture of an AOV as linear RGB: depth as nearness (white is
/// nearest, black a miss), normals as ½n + ½ (black a miss), albedo as is,
/// object ids as distinct colours.
pub fn visualize(aov: Aov, values: &[f32]) -> Vec<Vec3> {
    match aov {
        Aov::Depth => {
            let finite = values.iter().copied().filter(|d| d.is_finite());
            let (lo, hi) = finite.fold((f32::INFINITY, 0.0f32), |(lo, hi), d| {
                (lo.min(d), hi.max(d))
            });
            let span = (hi - lo).max(f32::MIN_POSITIVE);
            values
                .iter()
                .map(|&d| {
                    if d.is_finite() {
                        Vec3::splat(1.0 - 0.85 * (d - lo) / span)
                    } else {
                        Vec3::ZERO
                    }
                })
                .collect()
        }
        Aov::Normal => values
            .chunks_exact(3)
            .map(|n| {
                let n = Vec3::from_slice(n);
                if n == Vec3::ZERO { n } else { 0.5 * n + 0.5 }
            })
            .collect(),
        Aov::Albedo => values.chunks_exact(3).map(Vec3::from_slice).collect(),
        Aov::Object => values.iter().map(|&id| object_color(id)).collect(),
    }
}

/// A distinct colour per object id (golden-ratio hues); black for a miss.
fn object_color(id: f32) -> Vec3 {
    if id < 0.0 {
        return Vec3::ZERO;
    }
    let hue = (id * 0.618_034).fract() * 6.0;
    let x = 1.0 - (hue % 2.0 - 1.0).abs();
    let rgb = match hue as u32 {
        0 => Vec3::new(1.0, x, 0.0),
        1 => Vec3::new(x, 1.0, 0.0),
        2 => Vec3::new(0.0, 1.0, x),
        3 => Vec3::new(0.0, x, 1.0),
        4 => Vec3::new(x, 0.0, 1.0),
        _ => Vec3::new(1.0, 0.0, x),
    };
    0.15 + 0.7 * rgb
}
