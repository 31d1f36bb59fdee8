//! The BVH against brute force: a ray aimed exactly at a shared edge or
//! vertex of a tiled floor must hit it, at the same α either way — the
//! boxes' slab tests must not lose what the triangles' watertight test finds.

use super::measure::{Tally, measure, timed};
use super::{Case, Effort, Row};
use crate::accel::{MeshBvh, reference};
use crate::diagnostics::generate::{rays_at_shared_edges, tiled_floor};

/// The case.
pub const CASE: Case = Case {
    name: "BVH: lost hits",
    about: "rays aimed at shared edges and vertices of an n × n tiled floor, \
            steep to grazing: no hit, or a different α than brute force, is a failure",
    run,
};

const CONDITION: &str = "triangles in the mesh";

/// Floor sizes n swept (2n² triangles).
const SIDES: [u32; 3] = [8, 32, 128];

fn run(effort: Effort) -> Vec<Row> {
    let mut rows = Vec::new();
    for n in SIDES {
        let floor = tiled_floor(n, n, 0.0);
        let (positions, triangles) = (&floor.positions, &floor.triangles);
        let bvh = MeshBvh::build(positions, triangles);
        // Brute force costs O(triangles) a ray: fewer rays, the same for both.
        let rays = rays_at_shared_edges(n, effort.trials.min(2_000), u64::from(n));
        let count = triangles.len() as f64;
        // Brute force's answers are the truth the BVH must equal.
        let (truth, ns) = timed(&rays, |ray| {
            reference::closest_hit(positions, triangles, ray).map(|h| h.alpha)
        });
        let mut tally = Tally::default();
        for alpha in &truth {
            tally.judge(alpha.is_some(), None);
        }
        rows.push(tally.row(CASE.name, CONDITION, count, "brute force", ns));
        let aimed: Vec<_> = rays.into_iter().zip(truth).collect();
        let (tally, ns) = measure(
            &aimed,
            |(ray, _)| bvh.closest_hit(ray).map(|h| h.alpha),
            |(_, truth), alpha, tally| tally.judge(alpha.is_some() && alpha == truth, None),
        );
        rows.push(tally.row(CASE.name, CONDITION, count, "bvh", ns));
    }
    rows
}
