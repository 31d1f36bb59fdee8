//! Attribute values: numbers, vectors, integers and their ranges. Each parser
//! returns the message (naming the attribute) on failure.

use crate::numbers::{finite, parse_triple};
use glam::{DVec3, Vec3};

/// The accepted range of a number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Range {
    /// Any finite number.
    Any,
    /// Greater than 0.
    Positive,
    /// 0 or more.
    NonNegative,
    /// From 0 to 1, inclusive.
    Unit,
    /// An angle in degrees strictly between 0 and 90.
    OpenQuarterTurn,
    /// An index of refraction from 0.1 to 10 (real materials lie within 1 to
    /// 4; below 1 models a thinner medium inside a denser one).
    Ior,
    /// An exposure in stops, within ±[`View::MAX_EXPOSURE`](crate::View::MAX_EXPOSURE).
    Exposure,
}

impl Range {
    /// Whether `x` lies in the range.
    fn contains(self, x: f32) -> bool {
        match self {
            Range::Any => true,
            Range::Positive => x > 0.0,
            Range::NonNegative => x >= 0.0,
            Range::Unit => (0.0..=1.0).contains(&x),
            Range::OpenQuarterTurn => x > 0.0 && x < 90.0,
            Range::Ior => (0.1..=10.0).contains(&x),
            Range::Exposure => x.abs() <= crate::View::MAX_EXPOSURE,
        }
    }

    /// What a number in the range is called in messages.
    fn expected(self) -> &'static str {
        match self {
            Range::Any => "a finite number",
            Range::Positive => "a positive number",
            Range::NonNegative => "a number ≥ 0",
            Range::Unit => "a number from 0 to 1",
            Range::OpenQuarterTurn => "an angle in degrees strictly between 0 and 90",
            Range::Ior => "an index of refraction from 0.1 to 10",
            Range::Exposure => "an exposure in stops from -20 to 20",
        }
    }
}

/// A number of attribute `name` in `range`.
pub(crate) fn number(name: &str, text: &str, range: Range) -> Result<f32, String> {
    match finite(text.trim()) {
        Ok(x) if range.contains(x) => Ok(x),
        Ok(_) => Err(format!("{name} must be {}, got {text:?}", range.expected())),
        Err(why) => Err(format!(
            "{name} must be {}, got {text:?} (it {why})",
            range.expected()
        )),
    }
}

/// A vector of attribute `name`: three finite numbers.
pub(crate) fn vector(name: &str, text: &str) -> Result<Vec3, String> {
    parse_triple(text).map_err(|why| {
        format!(
            "{name} must be three finite numbers separated by spaces or commas, got {text:?} ({why})"
        )
    })
}

/// A vector of attribute `name` whose components are all positive.
pub(crate) fn positive_vector(name: &str, text: &str) -> Result<Vec3, String> {
    let v = vector(name, text)?;
    if v.min_element() > 0.0 {
        Ok(v)
    } else {
        Err(format!(
            "{name} must be three positive numbers, got {text:?}"
        ))
    }
}

/// A vector of attribute `name` that is not the zero vector.
pub(crate) fn nonzero_vector(name: &str, text: &str) -> Result<Vec3, String> {
    let v = vector(name, text)?;
    if v == Vec3::ZERO {
        Err(format!("{name} must not be the zero vector, got {text:?}"))
    } else {
        Ok(v)
    }
}

/// An image side in pixels: an integer from 1 to `max`.
pub(crate) fn pixels(name: &str, text: &str, max: u32) -> Result<u32, String> {
    match text.trim().parse::<u32>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "{name} must be a whole number of pixels from 1 to {max}, got {text:?}"
        )),
    }
}

/// Whether two non-zero vectors are parallel (|â × b̂| < 1e-6), computed in f64
/// so that huge or tiny components neither overflow nor underflow.
pub(crate) fn parallel(a: Vec3, b: Vec3) -> bool {
    let (a, b) = (a.as_dvec3(), b.as_dvec3());
    a.normalize_or_zero().cross(b.normalize_or_zero()).length() < 1e-6
}

/// Whether the triangle is degenerate: its doubled area |(t1−t0)×(t2−t0)| is
/// zero or tiny relative to the squared lengths of the edges from t0.
pub(crate) fn degenerate_triangle(t0: Vec3, t1: Vec3, t2: Vec3) -> bool {
    let (e1, e2): (DVec3, DVec3) = (t1.as_dvec3() - t0.as_dvec3(), t2.as_dvec3() - t0.as_dvec3());
    let area2 = e1.cross(e2).length();
    let scale = e1.length_squared().max(e2.length_squared());
    !(area2 > 1e-7 * scale)
}
