//! Colours in scene files: parsing (CSS names, `#rrggbb`, three linear numbers),
//! formatting, the sRGB ↔ linear conversions and luminance.
//!
//! Everything in the model is linear RGB. Names and hex codes are sRGB-encoded,
//! as on the web, and are converted with the exact sRGB EOTF.

use glam::Vec3;

/// The sRGB EOTF: an sRGB-encoded value in [0, 1] to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The inverse: a linear value in [0, 1] to sRGB encoding.
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Rec. 709 luminance Y of linear RGB.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// Parses a colour as written in a scene file, giving linear RGB:
/// - a CSS named colour (`red`, `gold`, `rebeccapurple`, …; case-insensitive),
/// - `#rrggbb` or `#rgb` (sRGB, case-insensitive hex digits),
/// - three linear numbers separated by whitespace and/or commas (finite, ≥ 0).
///
/// Names and hex codes are converted with [`srgb_to_linear`]. The upper bound
/// of the numbers is the caller's business (a `color` is at most 1, an
/// `emission` may be brighter). The error says what was expected; for a
/// near-miss name it suggests the closest colour name.
pub fn parse_color(text: &str) -> Result<Vec3, String> {
    let t = text.trim();
    if let Some(digits) = t.strip_prefix('#') {
        return parse_hex(digits).ok_or_else(|| {
            format!("expected \"#rrggbb\" or \"#rgb\" with hexadecimal digits, got {text:?}")
        });
    }
    if let Some(rgb) = named_color(t) {
        return Ok(srgb_bytes_to_linear(rgb));
    }
    if t.starts_with(|c: char| c.is_ascii_alphabetic()) {
        let hint =
            crate::suggest::suggest(t, csscolorparser::NAMED_COLORS.keys().map(|k| k.as_str()))
                .map(|s| format!("; did you mean \"{s}\"?"))
                .unwrap_or_default();
        return Err(format!(
            "unknown colour name {text:?}{hint} (expected a CSS colour name such as \"red\", \
             \"#rrggbb\", or three linear numbers)"
        ));
    }
    let v = crate::numbers::parse_triple(t).map_err(|why| {
        format!(
            "expected a colour name such as \"red\", \"#rrggbb\", or three linear numbers \
             separated by spaces or commas, got {text:?} ({why})"
        )
    })?;
    if v.min_element() < 0.0 {
        return Err(format!(
            "colour components must not be negative, got {text:?}"
        ));
    }
    Ok(v)
}

/// Formats a linear colour for a scene file: `#rrggbb` when every channel is
/// exactly `srgb_to_linear(b / 255)` for some byte `b` (so it reads back
/// bit-for-bit), otherwise the three numbers in shortest round-trip form.
pub fn format_color(c: Vec3) -> String {
    match (exact_byte(c.x), exact_byte(c.y), exact_byte(c.z)) {
        (Some(r), Some(g), Some(b)) => format!("#{r:02x}{g:02x}{b:02x}"),
        _ => format!("{} {} {}", c.x, c.y, c.z),
    }
}

/// The byte `b` with `srgb_to_linear(b / 255) == c` exactly, if there is one.
fn exact_byte(c: f32) -> Option<u8> {
    if !(0.0..=1.0).contains(&c) {
        return None;
    }
    let guess = (linear_to_srgb(c) * 255.0).round() as i32;
    (guess - 1..=guess + 1)
        .filter_map(|b| u8::try_from(b).ok())
        .find(|&b| byte_to_linear(b) == c)
}

/// An sRGB byte to linear.
fn byte_to_linear(b: u8) -> f32 {
    srgb_to_linear(f32::from(b) / 255.0)
}

/// Three sRGB bytes to linear RGB.
fn srgb_bytes_to_linear([r, g, b]: [u8; 3]) -> Vec3 {
    Vec3::new(byte_to_linear(r), byte_to_linear(g), byte_to_linear(b))
}

/// `rrggbb` or `rgb` (without `#`) to linear RGB.
fn parse_hex(digits: &str) -> Option<Vec3> {
    if !(digits.len() == 3 || digits.len() == 6) || !digits.chars().all(|c| c.is_ascii_hexdigit()) {
        return None;
    }
    let c = csscolorparser::parse(&format!("#{digits}")).ok()?;
    let [r, g, b, _] = c.to_rgba8();
    Some(srgb_bytes_to_linear([r, g, b]))
}

/// The sRGB bytes of a CSS named colour (case-insensitive), from csscolorparser's table.
fn named_color(name: &str) -> Option<[u8; 3]> {
    csscolorparser::NAMED_COLORS.get(name.into()).copied()
}
