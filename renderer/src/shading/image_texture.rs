//! Image textures (glTF base-colour maps): bilinear lookup with the
//! sampler's wrap modes, sRGB texels decoded to linear RGB.

use glam::{Vec2, Vec3};
use scene::color::srgb_to_linear;
use scene::{Texture, Wrap};
use std::sync::LazyLock;

/// sRGB-encoded byte → linear value, for every byte ([`srgb_to_linear`] of
/// byte / 255, looked up instead of a `powf` per texel).
static SRGB_TO_LINEAR: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|k| srgb_to_linear(k as f32 / 255.0)));

/// The texel index along one axis of `size` texels for integer coordinate `k`.
fn wrap(k: i64, size: u32, mode: Wrap) -> usize {
    let n = i64::from(size.max(1));
    let index = match mode {
        Wrap::Repeat => k.rem_euclid(n),
        Wrap::ClampToEdge => k.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = k.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
    };
    index as usize
}

/// The linear RGB colour of `texture` at texture coordinate `uv` (u to the
/// right, v down from the image's top row, as glTF defines them), filtered
/// bilinearly between texel centres.
pub fn sample(texture: &Texture, uv: Vec2) -> Vec3 {
    if texture.texels.is_empty() || !uv.is_finite() {
        return Vec3::ONE;
    }
    let x = uv.x * texture.width as f32 - 0.5;
    let y = uv.y * texture.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |dx: i64, dy: i64| {
        let i = wrap(x0 as i64 + dx, texture.width, texture.wrap_u);
        let j = wrap(y0 as i64 + dy, texture.height, texture.wrap_v);
        let [r, g, b, _] = texture.texels[j * texture.width as usize + i];
        let lut = &*SRGB_TO_LINEAR;
        Vec3::new(lut[r as usize], lut[g as usize], lut[b as usize])
    };
    let top = texel(0, 0).lerp(texel(1, 0), fx);
    let bottom = texel(0, 1).lerp(texel(1, 1), fx);
    top.lerp(bottom, fy)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(wrap: Wrap) -> Texture {
        // 2×2: white, black / black, white.
        let (w, b) = ([255u8, 255, 255, 255], [0u8, 0, 0, 255]);
        Texture {
            width: 2,
            height: 2,
            texels: vec![w, b, b, w].into(),
            wrap_u: wrap,
            wrap_v: wrap,
        }
    }

    #[test]
    fn texel_centres_return_their_texel_decoded_to_linear() {
        let t = checker(Wrap::Repeat);
        assert_eq!(sample(&t, Vec2::new(0.25, 0.25)), Vec3::ONE);
        assert_eq!(sample(&t, Vec2::new(0.75, 0.25)), Vec3::ZERO);
        let grey = Texture {
            width: 1,
            height: 1,
            texels: vec![[188, 188, 188, 255]].into(),
            wrap_u: Wrap::Repeat,
            wrap_v: Wrap::Repeat,
        };
        // sRGB 188 is linear ≈ 0.5.
        assert!((sample(&grey, Vec2::splat(0.5)).x - 0.5029).abs() < 1e-3);
    }

    #[test]
    fn wrap_modes_map_outside_coordinates_as_gltf_says() {
        assert_eq!(wrap(-1, 4, Wrap::Repeat), 3);
        assert_eq!(wrap(5, 4, Wrap::Repeat), 1);
        assert_eq!(wrap(-1, 4, Wrap::ClampToEdge), 0);
        assert_eq!(wrap(9, 4, Wrap::ClampToEdge), 3);
        assert_eq!(wrap(4, 4, Wrap::MirroredRepeat), 3);
        assert_eq!(wrap(-1, 4, Wrap::MirroredRepeat), 0);
        // One period to the right repeats, clamps or mirrors.
        let r = sample(&checker(Wrap::Repeat), Vec2::new(1.25, 0.25));
        assert_eq!(r, Vec3::ONE);
        let c = sample(&checker(Wrap::ClampToEdge), Vec2::new(1.75, 0.25));
        assert_eq!(c, Vec3::ZERO);
        let m = sample(&checker(Wrap::MirroredRepeat), Vec2::new(1.25, 0.25));
        assert_eq!(m, Vec3::ZERO);
    }
}
