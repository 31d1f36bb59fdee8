//! How fast a render approaches a reference: progressive passes, timed, with
//! the error after each — one curve of a speed-against-accuracy chart.

use crate::diagnostics::metrics::{rel_mse, rmse};
use crate::film::Film;
use crate::integrator::RenderOptions;
use crate::world::World;
use glam::Vec3;
use std::time::{Duration, Instant};

/// The state of a render after one more pass.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ConvergencePoint {
    /// Passes so far (samples of the pixels that never stopped).
    pub spp: u32,
    /// Samples per pixel on average (below `spp` once adaptive sampling
    /// stops pixels).
    pub mean_spp: f64,
    /// Render time so far (error measurement excluded), in seconds.
    pub seconds: f64,
    /// Relative MSE against the reference ([`rel_mse`]).
    pub rel_mse: f64,
    /// Root mean squared error against the reference.
    pub rmse: f64,
    /// A perceptual error measured by the caller (the chart's FLIP), if any.
    pub perceptual: Option<f64>,
}

/// When to stop refining.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Stop once this much render time is spent.
    pub time: Duration,
    /// Stop at this many samples per pixel at the latest.
    pub max_spp: u32,
}

/// Another error measure of an image (linear RGB, the reference's size).
pub type ErrorMeasure<'a> = &'a dyn Fn(&[Vec3]) -> f64;

/// Renders `world` pass by pass until `budget` is spent, measuring the error
/// against `reference` (the same size, linear RGB) after every pass while
/// there are few, then once the passes have grown by an eighth
/// ([`next_measurement`]), and after the last; the time spent measuring is
/// not counted. `perceptual` adds another error measure of each measured
/// image. Stops early once adaptive sampling has stopped every pixel.
/// Returns the curve and the last film.
pub fn converge(
    world: &World,
    options: &RenderOptions,
    reference: &[Vec3],
    budget: Budget,
    perceptual: Option<ErrorMeasure<'_>>,
) -> (Vec<ConvergencePoint>, Film) {
    let mut film = Film::new(world.camera.w, world.camera.h);
    assert_eq!(
        reference.len(),
        film.width() as usize * film.height() as usize,
        "the reference must be the render's size"
    );
    let mut curve = Vec::new();
    let mut spent = Duration::ZERO;
    let going_on = |film: &Film, spent: Duration| {
        spent < budget.time && film.passes() < budget.max_spp && !film.converged()
    };
    let mut next = 1;
    while going_on(&film, spent) {
        let start = Instant::now();
        film.add_pass(world, options);
        spent += start.elapsed();
        if film.passes() < next && going_on(&film, spent) {
            continue;
        }
        next = next_measurement(film.passes());
        let image = film.linear();
        curve.push(ConvergencePoint {
            spp: film.passes(),
            mean_spp: film.mean_spp(),
            seconds: spent.as_secs_f64(),
            rel_mse: rel_mse(&image, reference),
            rmse: rmse(&image, reference),
            perceptual: perceptual.map(|measure| measure(&image)),
        });
    }
    (curve, film)
}

/// The passes at which [`converge`] measures next after measuring at
/// `spp`: the next pass up to 16, then an eighth more (44 points up to 400
/// passes; [`time_to_reach`] interpolates between them, exactly for an
/// error that falls as a power of the time). Not after
/// every pass, because measuring slows the render: the measure's memory
/// traffic made the pass after it 22–41% slower (spheres.xml path-traced,
/// medians of 16–17.5 ms a pass back to back, 20.5–23 ms after 20 ms of
/// image-sized work on the calling thread, six runs), and a chart of such
/// passes charts the measurement.
pub fn next_measurement(spp: u32) -> u32 {
    spp + (spp / 8).max(1)
}

/// The first time a curve reaches `target` relative MSE, linearly
/// interpolated in log–log between the passes either side; `None` if it never does.
pub fn time_to_reach(curve: &[ConvergencePoint], target: f64) -> Option<f64> {
    let k = curve.iter().position(|p| p.rel_mse <= target)?;
    let after = curve[k];
    let Some(before) = k.checked_sub(1).map(|b| curve[b]) else {
        return Some(after.seconds);
    };
    let (le0, le1, lt) = (before.rel_mse.ln(), after.rel_mse.ln(), target.ln());
    let f = if le0 != le1 {
        (le0 - lt) / (le0 - le1)
    } else {
        1.0
    };
    let (ls0, ls1) = (before.seconds.ln(), after.seconds.ln());
    Some((ls0 + f * (ls1 - ls0)).exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(seconds: f64, rel_mse: f64) -> ConvergencePoint {
        ConvergencePoint {
            spp: 1,
            mean_spp: 1.0,
            seconds,
            rel_mse,
            rmse: 0.0,
            perceptual: None,
        }
    }

    #[test]
    fn measurements_follow_every_pass_up_to_16_then_an_eighth_apart() {
        let mut ladder = vec![1];
        while *ladder.last().expect("a point") < 400 {
            ladder.push(next_measurement(*ladder.last().expect("a point")));
        }
        assert!(ladder[..16].iter().copied().eq(1..=16), "{ladder:?}");
        for pair in ladder[16..].windows(2) {
            // An eighth, rounded down to whole passes.
            let growth = f64::from(pair[1]) / f64::from(pair[0]);
            assert!(growth > 1.06 && growth <= 1.125, "{pair:?}");
        }
    }

    #[test]
    fn time_to_reach_interpolates_a_power_law_exactly() {
        // error = 1 / seconds: reaching 0.25 takes 4 s.
        let curve = [point(1.0, 1.0), point(2.0, 0.5), point(8.0, 0.125)];
        let t = time_to_reach(&curve, 0.25).expect("reached");
        assert!((t - 4.0).abs() < 1e-9, "{t}");
        assert_eq!(time_to_reach(&curve, 0.01), None);
        assert_eq!(time_to_reach(&curve, 2.0), Some(1.0));
    }
}
