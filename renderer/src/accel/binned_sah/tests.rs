//! Tests of the binned-SAH split: boxes kept, clusters separated, every
//! primitive on exactly one side.

use super::*;
use proptest::prelude::*;

fn refs_from(boxes: &[([f32; 3], [f32; 3])]) -> Vec<PrimRef> {
    boxes
        .iter()
        .enumerate()
        .map(|(i, (a, b))| {
            let (a, b) = (Vec3A::from(*a), Vec3A::from(*b));
            PrimRef::new(i as u32, a.min(b), a.max(b))
        })
        .collect()
}

#[test]
fn prim_refs_keep_every_index_and_their_box() {
    for id in [0, 1, 12345, (1 << 23) - 1, 1 << 23, u32::MAX] {
        let r = PrimRef::new(id, Vec3A::new(-1.0, 2.0, 3.0), Vec3A::new(4.0, 5.0, 6.5));
        assert_eq!(r.id(), id);
        assert_eq!(
            (r.lo(), r.hi()),
            (Vec3A::new(-1.0, 2.0, 3.0), Vec3A::new(4.0, 5.0, 6.5))
        );
        assert!(r.centroid().extend(0.0).is_finite());
    }
}

#[test]
fn two_far_apart_clusters_are_split_between_them() {
    let mut boxes = Vec::new();
    for k in 0..10 {
        let x = k as f32 * 0.01;
        boxes.push(([x, 0.0, 0.0], [x + 0.1, 0.1, 0.1]));
        boxes.push(([100.0 + x, 0.0, 0.0], [100.1 + x, 0.1, 0.1]));
    }
    let mut refs = refs_from(&boxes);
    let span = Span::around(&refs, 0);
    let (left, right) = Splitter::default().split(&mut refs, &span);
    assert_eq!((left.len(), right.len()), (10, 10));
    assert!(refs[..10].iter().all(|r| r.lo().x < 50.0));
    assert!(refs[10..].iter().all(|r| r.lo().x > 50.0));
}

#[test]
fn coinciding_centroids_are_halved_by_count() {
    let mut refs = refs_from(&[([0.0; 3], [1.0; 3]); 9]);
    let span = Span::around(&refs, 5);
    let (left, right) = Splitter::default().split(&mut refs, &span);
    assert_eq!(
        (left.begin, left.end, right.begin, right.end),
        (5, 9, 9, 14)
    );
    assert_eq!(left.bounds, span.bounds);
    assert_eq!(right.bounds, span.bounds);
}

/// The sweep [`cheapest`] replaced: one axis after the other, one bin at
/// a time, in scalar arithmetic.
fn cheapest_axis_by_axis(
    bins: &Bins,
    mapping: &Mapping,
    total: u32,
) -> Option<(usize, usize, Bounds, Bounds)> {
    let blocks = |n: u32| n.div_ceil(4) as f32;
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in (0..3).filter(|&a| mapping.axis_binned(a)) {
        let used = mapping.bins;
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut n) = (Bounds::EMPTY, 0u32);
        for i in (1..used).rev() {
            acc = acc.union(bins.bounds[i][axis]);
            n += bins.counts[i][axis];
            right_cost[i] = if n > 0 {
                acc.half_area() * blocks(n)
            } else {
                0.0
            };
        }
        let (mut acc, mut left_n) = (Bounds::EMPTY, 0u32);
        for i in 0..used - 1 {
            acc = acc.union(bins.bounds[i][axis]);
            left_n += bins.counts[i][axis];
            if left_n == 0 || left_n == total {
                continue;
            }
            let cost = acc.half_area() * blocks(left_n) + right_cost[i + 1];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, i));
            }
        }
    }
    let (_, axis, last) = best?;
    let side = |r: std::ops::Range<usize>| {
        bins.bounds[r]
            .iter()
            .fold(Bounds::EMPTY, |a, b| a.union(b[axis]))
    };
    Some((axis, last, side(0..last + 1), side(last + 1..mapping.bins)))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    /// Both sides are non-empty, together they hold every primitive
    /// once, and their boxes are exactly the unions of their primitives'
    /// boxes and centroids.
    #[test]
    fn split_sides_are_nonempty_complete_and_their_boxes_exact(
        boxes in prop::collection::vec(
            (prop::array::uniform3(-1e3f32..1e3), prop::array::uniform3(-1e3f32..1e3)),
            2..300,
        ),
        clustered in any::<bool>(),
    ) {
        let boxes: Vec<_> = if clustered {
            // Many equal boxes: coinciding centroids on some axes.
            boxes.iter().map(|(a, b)| ([a[0].round(), 0.0, a[2]], [a[0].round() + 1.0, 0.0, b[2]])).collect()
        } else {
            boxes
        };
        let mut refs = refs_from(&boxes);
        let span = Span::around(&refs, 3);
        let (left, right) = Splitter::default().split(&mut refs, &span);
        prop_assert!(left.len() > 0 && right.len() > 0);
        prop_assert_eq!((left.begin, left.end, right.end), (3, right.begin, span.end));
        let mut ids: Vec<u32> = refs.iter().map(PrimRef::id).collect();
        ids.sort();
        prop_assert!(ids.iter().copied().eq(0..boxes.len() as u32));
        let (l, r) = refs.split_at(left.len());
        for (side, part) in [(left, l), (right, r)] {
            let exact = Span::around(part, side.begin);
            prop_assert_eq!(side.bounds, exact.bounds);
            prop_assert_eq!(side.centroids, exact.centroids);
        }
    }

    /// A splitter that has split other sets (a large one first, whose
    /// bins it keeps) splits a set exactly as a new one does: the bins a
    /// split does not empty are never read.
    #[test]
    fn a_reused_splitter_splits_as_a_new_one(
        first in prop::collection::vec(
            (prop::array::uniform3(-1e3f32..1e3), prop::array::uniform3(-1e3f32..1e3)),
            2..3000,
        ),
        second in prop::collection::vec(
            (prop::array::uniform3(-1e3f32..1e3), prop::array::uniform3(-1e3f32..1e3)),
            2..40,
        ),
    ) {
        let mut reused = Splitter::default();
        let mut refs = refs_from(&first);
        let span = Span::around(&refs, 0);
        reused.split(&mut refs, &span);
        let (mut a, mut b) = (refs_from(&second), refs_from(&second));
        let span = Span::around(&a, 7);
        prop_assert_eq!(reused.split(&mut a, &span), Splitter::default().split(&mut b, &span));
        prop_assert_eq!(a, b);
    }

    /// Sweeping the three axes together, lane by lane, picks exactly the
    /// boundary (and boxes) that sweeping them one after the other does.
    #[test]
    fn all_axes_sweep_picks_the_same_boundary_as_axis_by_axis(
        boxes in prop::collection::vec(
            (prop::array::uniform3(-1e3f32..1e3), prop::array::uniform3(0.0f32..50.0)),
            2..400,
        ),
        flat in 0usize..4,
        snap in any::<bool>(),
    ) {
        // Flatten one axis (or none), and optionally snap the others to
        // a coarse grid so equal costs and empty bins occur.
        let boxes: Vec<_> = boxes
            .iter()
            .map(|(c, e)| {
                let mut lo = *c;
                if snap {
                    lo = lo.map(|v| (v / 100.0).round() * 100.0);
                }
                let mut hi = [lo[0] + e[0], lo[1] + e[1], lo[2] + e[2]];
                if flat < 3 {
                    (lo[flat], hi[flat]) = (1.0, 1.0);
                }
                (lo, hi)
            })
            .collect();
        let refs = refs_from(&boxes);
        let span = Span::around(&refs, 0);
        let mapping = Mapping::new(&span.centroids, refs.len());
        let mut bins = Bins::EMPTY;
        bins.fill(&refs, &mapping);
        let total = refs.len() as u32;
        prop_assert_eq!(
            cheapest(&bins, &mapping, total),
            cheapest_axis_by_axis(&bins, &mapping, total)
        );
    }
}
