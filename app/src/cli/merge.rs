//! `raylab merge OUT.exr PART.exr…`: joins the parts of a split render. A
//! sample is seeded by (seed, pixel, sample index), so parts rendered apart
//! — rectangles of pixels (`render --crop`), ranges of sample indices
//! (`render --samples`), or both — are exactly the whole render's pieces:
//! a rectangle is copied as it is (bit for bit the whole render's pixels),
//! and parts of one rectangle with disjoint sample ranges are averaged,
//! each weighted by its sample count (the whole render's mean within float
//! rounding). Parts that overlap, leave pixels out, hold different sample
//! ranges in different rectangles, or come from another scene, camera or
//! image size are errors that name them.

use super::args::MergeArgs;
use super::prepare::UserError;
use crate::io::output::{Provenance, read_exr_provenance, write_exr};
use anyhow::Result;
use glam::{DVec3, Vec3};
use renderer::Region;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// One part as read: its pixels and what its provenance says of it.
struct Part {
    path: PathBuf,
    width: u32,
    height: u32,
    pixels: Vec<Vec3>,
    /// The pixels it rendered (the whole image without `raylab:region`).
    region: Region,
    /// The sample indices it rendered.
    samples: Range<u32>,
    /// Its scene file and camera, which every part must share.
    scene: String,
    camera: String,
    /// Everything it recorded (the merged image keeps the first part's).
    provenance: Provenance,
}

/// Merges `args.parts` into `args.output`; returns the output's path.
pub fn run(args: &MergeArgs) -> Result<PathBuf> {
    if !args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
    {
        return Err(UserError(format!(
            "{}: the merged image is written as a linear EXR (.exr)",
            args.output.display()
        ))
        .into());
    }
    let parts: Vec<Part> = args
        .parts
        .iter()
        .map(|p| read_part(p))
        .collect::<Result<_>>()?;
    let first = &parts[0];
    for part in &parts[1..] {
        let mismatch = if (part.width, part.height) != (first.width, first.height) {
            Some("image size")
        } else if part.camera != first.camera {
            Some("camera")
        } else if file_name(&part.scene) != file_name(&first.scene) {
            // By name: machines of a farm may keep the scene in different folders.
            Some("scene file")
        } else {
            None
        };
        if let Some(what) = mismatch {
            return Err(UserError(format!(
                "{} and {}: different {what}s; the parts must come from one render",
                first.path.display(),
                part.path.display()
            ))
            .into());
        }
    }
    let groups = by_region(&parts)?;
    check_tiling(&groups, first.width, first.height)?;
    let (width, height) = (first.width, first.height);
    let mut pixels = vec![Vec3::ZERO; (width * height) as usize];
    for group in &groups {
        let total: u32 = group.iter().map(|p| p.samples.len() as u32).sum();
        let r = group[0].region;
        for j in r.y0..r.y1 {
            for i in r.x0..r.x1 {
                let k = (j * width + i) as usize;
                pixels[k] = match group.as_slice() {
                    // One part: its pixels as they are.
                    [only] => only.pixels[k],
                    _ => {
                        let sum: DVec3 = group
                            .iter()
                            .map(|p| p.pixels[k].as_dvec3() * p.samples.len() as f64)
                            .sum();
                        (sum / f64::from(total)).as_vec3()
                    }
                };
            }
        }
    }
    // The first part's record (software, camera, scene, view) with the
    // merged image's own samples in place of the part's.
    let samples = sample_set(&groups[0]);
    let spp: u32 = samples.iter().map(|r| r.len() as u32).sum();
    let mut provenance = first.provenance.clone();
    provenance.entries.retain(|(k, _)| {
        !matches!(
            k.as_str(),
            "raylab:spp" | "raylab:samples" | "raylab:region"
        )
    });
    provenance
        .entries
        .push(("raylab:spp".into(), spp.to_string()));
    if let [range] = samples.as_slice() {
        provenance.entries.push((
            "raylab:samples".into(),
            format!("{}..{}", range.start, range.end),
        ));
    }
    provenance
        .entries
        .push(("raylab:merged".into(), format!("{} parts", parts.len())));
    let values: Vec<f32> = pixels.iter().flat_map(|p| p.to_array()).collect();
    write_exr(
        &args.output,
        width,
        height,
        &["R", "G", "B"],
        &values,
        &provenance,
    )?;
    Ok(args.output.clone())
}

/// Reads a part written by `raylab render`.
fn read_part(path: &Path) -> Result<Part> {
    let image = renderer::diagnostics::reference_image::read_exr_rgb(path)
        .map_err(|e| UserError(e.to_string()))?;
    let provenance = read_exr_provenance(path)?;
    let entry = |key: &str| provenance.get(key).map(str::to_owned);
    let bad = |what: &str| {
        UserError(format!(
            "{}: {what} (not a part written by `raylab render`?)",
            path.display()
        ))
    };
    let spp: u32 = entry("raylab:spp")
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| bad("no sample count (raylab:spp)"))?;
    let samples = match entry("raylab:samples") {
        None => 0..spp,
        Some(text) => text
            .split_once("..")
            .and_then(|(a, b)| Some(a.parse().ok()?..b.parse().ok()?))
            .filter(|r: &Range<u32>| r.start < r.end)
            .ok_or_else(|| bad(&format!("unreadable sample range {text:?}")))?,
    };
    let whole = Region {
        x0: 0,
        y0: 0,
        x1: image.width,
        y1: image.height,
    };
    let region = match entry("raylab:region") {
        None => whole,
        Some(text) => match text
            .split(' ')
            .map(|n| n.parse::<u32>().ok())
            .collect::<Option<Vec<u32>>>()
            .as_deref()
        {
            Some(&[x0, y0, x1, y1]) if x0 < x1 && y0 < y1 && x1 <= whole.x1 && y1 <= whole.y1 => {
                Region { x0, y0, x1, y1 }
            }
            _ => return Err(bad(&format!("unreadable rectangle {text:?}")).into()),
        },
    };
    Ok(Part {
        path: path.to_path_buf(),
        width: image.width,
        height: image.height,
        pixels: image.pixels,
        region,
        samples,
        scene: entry("raylab:scene").unwrap_or_default(),
        camera: entry("raylab:camera").ok_or_else(|| bad("no camera (raylab:camera)"))?,
        provenance,
    })
}

/// The parts grouped by rectangle: rectangles equal or apart (an error when
/// two overlap), each group's sample ranges apart (an error when two
/// overlap) and the same set in every group (an error otherwise).
fn by_region(parts: &[Part]) -> Result<Vec<Vec<&Part>>> {
    let mut groups: Vec<Vec<&Part>> = Vec::new();
    for part in parts {
        match groups.iter_mut().find(|g| g[0].region == part.region) {
            Some(group) => {
                if let Some(other) = group.iter().find(|o| {
                    o.samples.start < part.samples.end && part.samples.start < o.samples.end
                }) {
                    return Err(UserError(format!(
                        "{} and {}: both hold samples of {}..{} and {}..{} — sample ranges of a \
                         rectangle must not overlap",
                        other.path.display(),
                        part.path.display(),
                        other.samples.start,
                        other.samples.end,
                        part.samples.start,
                        part.samples.end
                    ))
                    .into());
                }
                group.push(part);
            }
            None => {
                if let Some(other) = groups
                    .iter()
                    .map(|g| g[0])
                    .find(|o| o.region.overlaps(&part.region))
                {
                    return Err(UserError(format!(
                        "{} and {}: their rectangles overlap",
                        other.path.display(),
                        part.path.display()
                    ))
                    .into());
                }
                groups.push(vec![part]);
            }
        }
    }
    let want = sample_set(&groups[0]);
    if let Some(group) = groups.iter().find(|g| sample_set(g) != want) {
        return Err(UserError(format!(
            "{}: its rectangle holds samples {}, {}'s holds {}; every rectangle needs the same",
            group[0].path.display(),
            ranges_text(&sample_set(group)),
            groups[0][0].path.display(),
            ranges_text(&want)
        ))
        .into());
    }
    Ok(groups)
}

/// The sample ranges of a group, sorted and joined where they meet.
fn sample_set(group: &[&Part]) -> Vec<Range<u32>> {
    let mut ranges: Vec<Range<u32>> = group.iter().map(|p| p.samples.clone()).collect();
    ranges.sort_by_key(|r| r.start);
    let mut joined: Vec<Range<u32>> = Vec::new();
    for r in ranges {
        match joined.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => joined.push(r),
        }
    }
    joined
}

fn ranges_text(ranges: &[Range<u32>]) -> String {
    ranges
        .iter()
        .map(|r| format!("{}..{}", r.start, r.end))
        .collect::<Vec<_>>()
        .join(", ")
}

/// An error naming a pixel no rectangle covers (the rectangles are apart).
fn check_tiling(groups: &[Vec<&Part>], width: u32, height: u32) -> Result<()> {
    let covered: u64 = groups.iter().map(|g| g[0].region.pixels()).sum();
    if covered == u64::from(width) * u64::from(height) {
        return Ok(());
    }
    let missing = (0..height)
        .flat_map(|j| (0..width).map(move |i| (i, j)))
        .find(|&(i, j)| !groups.iter().any(|g| g[0].region.contains(i, j)));
    let (i, j) = missing.unwrap_or_default();
    Err(UserError(format!(
        "the parts leave pixels of the {width}×{height} image out, pixel ({i}, {j}) first: \
         {} of {} pixels covered",
        covered,
        u64::from(width) * u64::from(height)
    ))
    .into())
}

/// The file name of a recorded scene path.
fn file_name(path: &str) -> Option<&std::ffi::OsStr> {
    Path::new(path).file_name()
}
