//! Estimating an image's memory before allocating it: a w × h that would not
//! fit is refused with a message, never attempted (and killed by the system).
//!
//! A [`World`] can be built for any camera (tests build small ones by the
//! thousand); whoever renders a world made from a user's scene calls
//! [`check_world_fits`] first, before the first [`Film`] of it is allocated:
//! the window on every edit, the command line on every scene it reads.

use crate::film::Film;
use crate::world::{RenderError, World};

/// Bytes per pixel of everything a render of the image holds at once: the
/// film, the copy of it the window shows, the linear image made from it and
/// a 4 × f32 display texture.
pub fn bytes_per_pixel() -> u64 {
    let film = Film::bytes_per_pixel();
    2 * film + 12 + 16
}

/// Estimated bytes for rendering a `w` × `h` image.
pub fn image_bytes(w: u32, h: u32) -> u64 {
    u64::from(w) * u64::from(h) * bytes_per_pixel()
}

/// The share of the available memory an image may take; the rest is left to
/// the scene, its BVH and everything else on the machine.
const USABLE_SHARE: f64 = 0.75;

/// Memory the system can still give the program (Linux's MemAvailable),
/// `None` where it is not known.
pub fn available_bytes() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Refuses a `w` × `h` image whose estimate is more than three quarters of
/// `available` bytes, saying how much it needs and how much there is.
pub fn check_fits_in(w: u32, h: u32, available: u64) -> Result<(), String> {
    let need = image_bytes(w, h);
    if need as f64 <= available as f64 * USABLE_SHARE {
        return Ok(());
    }
    let gib = |bytes: u64| bytes as f64 / f64::from(1u32 << 30);
    Err(format!(
        "a {w} × {h} image needs about {:.1} GiB to render, but only {:.1} GiB of memory is \
         available; choose a smaller width and height",
        gib(need),
        gib(available)
    ))
}

/// [`check_fits_in`] with this machine's available memory (always Ok where
/// that is unknown).
pub fn check_fits(w: u32, h: u32) -> Result<(), String> {
    available_bytes().map_or(Ok(()), |available| check_fits_in(w, h, available))
}

/// [`check_fits`] for the image of `world`'s camera, as the error that says
/// why the scene cannot be rendered.
pub fn check_world_fits(world: &World) -> Result<(), RenderError> {
    check_fits(world.camera.w, world.camera.h).map_err(RenderError::Memory)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_counts_every_per_pixel_buffer() {
        assert_eq!(image_bytes(10, 20), 200 * bytes_per_pixel());
        assert!(
            bytes_per_pixel() >= 2 * 12 + 12 + 16,
            "two films hold at least a Vec3 sum"
        );
        // The maximum size the scene format allows does not overflow.
        assert_eq!(image_bytes(16384, 16384), 16384 * 16384 * bytes_per_pixel());
    }

    #[test]
    fn an_image_that_would_not_fit_is_refused_with_both_sizes() {
        let gib = 1u64 << 30;
        assert!(check_fits_in(1920, 1080, 8 * gib).is_ok());
        let e = check_fits_in(16384, 16384, 8 * gib).expect_err("16384² needs more than 6 GiB");
        assert!(
            e.contains("16384 × 16384") && e.contains("only 8.0 GiB of memory is available"),
            "{e}"
        );
        assert!(!e.contains('\n'));
        // Exactly three quarters fits; a byte more does not.
        let need = image_bytes(100, 100);
        assert!(check_fits_in(100, 100, need * 4 / 3 + 1).is_ok());
        assert!(check_fits_in(100, 100, need).is_err());
    }

    #[test]
    fn this_machine_reports_its_available_memory() {
        if cfg!(target_os = "linux") {
            let available = available_bytes().expect("MemAvailable in /proc/meminfo");
            assert!(available > 1 << 20, "{available}");
        }
    }
}
