//! Numbers as scene files write them: finite, within ±[`MAX_MAGNITUDE`], and
//! triples of them separated by spaces or commas (vectors, linear colours).
//! The reader's attribute parsers and the colour parser build on these.

use glam::Vec3;

/// The largest magnitude of any number in a scene file (a kilometre in
/// millimetres). Beyond it 32-bit arithmetic loses a scene's detail (the
/// spacing of f32 values near 1e6 is 0.06), and the torus's quartic, whose
/// coefficients grow as the fourth power of sizes and distances, overflows.
pub const MAX_MAGNITUDE: f32 = 1.0e6;

/// A finite `f32` within ±[`MAX_MAGNITUDE`]; the reason otherwise (without
/// the attribute name).
pub(crate) fn finite(token: &str) -> Result<f32, &'static str> {
    match token.parse::<f32>() {
        Ok(x) if x.abs() <= MAX_MAGNITUDE => Ok(x),
        Ok(x) if x.is_finite() => Err("must lie within ±1e6"),
        Ok(_) => Err("must be a finite number"),
        Err(_) => Err("is not a number"),
    }
}

/// Exactly three finite numbers separated by whitespace and/or single commas;
/// the reason otherwise.
pub(crate) fn parse_triple(text: &str) -> Result<Vec3, String> {
    let mut numbers = Vec::new();
    let parts: Vec<&str> = text.split(',').collect();
    for part in &parts {
        let mut tokens = part.split_whitespace().peekable();
        if tokens.peek().is_none() && parts.len() > 1 {
            return Err("a comma must stand between two numbers".into());
        }
        for token in tokens {
            numbers.push(finite(token).map_err(|why| format!("{token:?} {why}"))?);
        }
    }
    match numbers[..] {
        [x, y, z] => Ok(Vec3::new(x, y, z)),
        _ => Err(format!("found {} numbers", numbers.len())),
    }
}
