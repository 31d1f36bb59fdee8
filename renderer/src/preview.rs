//! Coarse previews: one ray per block of pixels, so a first image of an edit
//! is on screen within a display frame.

use crate::film::sample_pixel;
use crate::integrator::RenderOptions;
use crate::world::World;
use glam::Vec3;
use rayon::prelude::*;

/// An image where each `stride` × `stride` block shows sample 0 of its
/// top-left pixel, row by row from the top. Stride 1 is one full sample.
pub fn preview(world: &World, options: &RenderOptions, stride: u32) -> Vec<Vec3> {
    let (w, h) = (world.camera.w as usize, world.camera.h as usize);
    let stride = stride.max(1) as usize;
    let mut pixels = vec![Vec3::ZERO; w * h];
    pixels
        .par_chunks_mut(w * stride)
        .enumerate()
        .for_each(|(block_row, rows)| {
            let j = block_row * stride;
            for bi in (0..w).step_by(stride) {
                let value = sample_pixel(world, options, bi as u32, j as u32, 0);
                let value = if value.is_finite() { value } else { Vec3::ZERO };
                for row in rows.chunks_mut(w) {
                    row[bi..(bi + stride).min(w)].fill(value);
                }
            }
        });
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Film;
    use scene::{Object, Scene, Shape};

    fn world() -> World {
        let scene = Scene {
            camera: scene::Camera {
                width: 37,
                height: 21,
                ..Default::default()
            },
            objects: ["cone", "sphere", "box", "floor"]
                .map(|tag| Object {
                    name: None,
                    shape: Shape::default_for_tag(tag).expect("tag"),
                    material: None,
                    params: Default::default(),
                })
                .to_vec(),
            ..Default::default()
        };
        World::from_scene(&scene).expect("valid")
    }

    #[test]
    fn each_block_shows_the_first_sample_of_its_corner_pixel() {
        let world = world();
        let options = RenderOptions::default();
        let coarse = preview(&world, &options, 8);
        for (j, i) in [(0, 0), (8, 16), (20, 36), (19, 33)] {
            let corner = sample_pixel(&world, &options, (i / 8 * 8) as u32, (j / 8 * 8) as u32, 0);
            assert_eq!(coarse[j * 37 + i], corner, "pixel ({i}, {j})");
        }
    }

    #[test]
    fn stride_one_equals_the_first_full_pass() {
        let world = world();
        let options = RenderOptions::default();
        assert_eq!(
            preview(&world, &options, 1),
            Film::render(&world, &options, 1).linear()
        );
    }
}
