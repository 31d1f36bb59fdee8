//! One binary split of a set of primitive boxes by the binned surface area
//! heuristic (Wald, "On fast construction of SAH-based bounding volume
//! hierarchies", 2007): centroids are sorted into [`BINS`] equal slices of
//! their bounds along each axis, every slice boundary is priced as
//! area(left) · blocks(left) + area(right) · blocks(right), where a block is
//! a leaf pack of four triangles, and the cheapest boundary partitions the
//! primitives in place. The boxes of both sides come out exact (unions of
//! the primitives' boxes), as conservative traversal needs.

use glam::{BVec3, BVec3A, Mat3A, UVec3, Vec3A, Vec4};
use rayon::prelude::*;
use wide::f32x4;

/// Slices per axis.
pub const BINS: usize = 32;

/// Primitives at or above which one thread bins into two sets of bins
/// ([`Bins::add`]).
const TWO_SETS: usize = 1024;

/// Primitives at or above which a set is binned by several threads.
const PARALLEL_BINNING: usize = 1 << 16;

/// A primitive as the builder sees it: its box and the caller's index, in
/// two aligned SIMD registers' worth (the index is spread over the spare
/// fourth lanes as the mantissas of two numbers in [1, 2), so that no
/// arithmetic on those lanes ever meets a denormal or NaN).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimRef {
    lo: Vec4,
    hi: Vec4,
}

/// The mantissa bits of an f32.
const MANTISSA: u32 = (1 << 23) - 1;
/// The bits of 1.0f32.
const ONE: u32 = 0x3F80_0000;

impl PrimRef {
    /// The primitive `id` with the box `lo`..`hi`.
    pub fn new(id: u32, lo: Vec3A, hi: Vec3A) -> PrimRef {
        PrimRef {
            lo: lo.extend(f32::from_bits(ONE | (id & MANTISSA))),
            hi: hi.extend(f32::from_bits(ONE | (id >> 23))),
        }
    }

    /// The caller's index of the primitive.
    pub fn id(&self) -> u32 {
        (self.lo.w.to_bits() & MANTISSA) | ((self.hi.w.to_bits() & MANTISSA) << 23)
    }

    /// The box's lower corner.
    #[inline(always)]
    pub fn lo(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo)
    }

    /// The box's upper corner.
    #[inline(always)]
    pub fn hi(&self) -> Vec3A {
        Vec3A::from_vec4(self.hi)
    }

    /// Twice the box's centre (the factor never matters to binning).
    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        self.lo() + self.hi()
    }
}

/// An axis-aligned box as two corners (empty: +∞ / −∞).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Lower corner.
    pub lo: Vec3A,
    /// Upper corner.
    pub hi: Vec3A,
}

impl Bounds {
    /// The box holding nothing.
    pub const EMPTY: Bounds = Bounds {
        lo: Vec3A::INFINITY,
        hi: Vec3A::NEG_INFINITY,
    };

    /// Grows the box to hold `lo`..`hi`.
    #[inline(always)]
    fn grow(&mut self, lo: Vec3A, hi: Vec3A) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    /// Grows the box to hold the point `p`.
    #[inline(always)]
    fn grow_point(&mut self, p: Vec3A) {
        self.grow(p, p);
    }

    /// The smallest box holding both.
    #[inline(always)]
    fn union(mut self, other: Bounds) -> Bounds {
        self.grow(other.lo, other.hi);
        self
    }

    /// Half the surface area (only meaningful for a non-empty box).
    #[inline(always)]
    pub fn half_area(&self) -> f32 {
        let d = self.hi - self.lo;
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// A contiguous run of the builder's primitives with its boxes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    /// Index of the first primitive in the builder's array.
    pub begin: usize,
    /// One past the last.
    pub end: usize,
    /// The union of the primitives' boxes.
    pub bounds: Bounds,
    /// The box around the primitives' (doubled) centroids.
    pub centroids: Bounds,
}

impl Span {
    /// The span of all of `refs`, whose first element has index `begin`.
    /// Few primitives are bounded on the calling thread: a world of a few
    /// shapes is prepared by the UI thread, which must not wait for rayon's
    /// workers.
    pub fn around(refs: &[PrimRef], begin: usize) -> Span {
        let grow = |(mut b, mut c): (Bounds, Bounds), r: &PrimRef| {
            b.grow(r.lo(), r.hi());
            c.grow_point(r.centroid());
            (b, c)
        };
        let empty = (Bounds::EMPTY, Bounds::EMPTY);
        let (bounds, centroids) = if refs.len() < PARALLEL_BINNING {
            refs.iter().fold(empty, grow)
        } else {
            refs.par_iter()
                .fold(|| empty, grow)
                .reduce(|| empty, |a, b| (a.0.union(b.0), a.1.union(b.1)))
        };
        Span {
            begin,
            end: begin + refs.len(),
            bounds,
            centroids,
        }
    }

    /// Number of primitives.
    pub fn len(&self) -> usize {
        self.end - self.begin
    }
}

/// How centroids map to bins: bin = ⌊(c − origin) · scale⌋ per axis,
/// clamped to the bins in use.
#[derive(Clone, Copy, Debug)]
struct Mapping {
    origin: Vec3A,
    /// 0 on an axis where all centroids coincide (not binned).
    scale: Vec3A,
    /// Bins in use: fewer for small sets, whose bins would mostly be empty.
    bins: usize,
}

impl Mapping {
    fn new(centroids: &Bounds, primitives: usize) -> Mapping {
        let bins = primitives.clamp(4, BINS);
        let extent = centroids.hi - centroids.lo;
        // Slightly fewer slices than bins so the largest centroid lands in
        // the last bin rather than one past it (the clamp catches rounding).
        let scale = Vec3A::select(
            extent.cmpgt(Vec3A::ZERO),
            Vec3A::splat(bins as f32 * (1.0 - 1e-5)) / extent,
            Vec3A::ZERO,
        );
        let scale = Vec3A::select(scale.is_finite_mask(), scale, Vec3A::ZERO);
        Mapping {
            origin: centroids.lo,
            scale,
            bins,
        }
    }

    /// The bin of centroid `c` on each axis (then a spare lane).
    #[inline(always)]
    fn bins(&self, c: Vec3A) -> [i32; 4] {
        // Clamped in floating point (NaN becomes 0), then truncated four
        // lanes at once.
        let b = ((c - self.origin) * self.scale)
            .max(Vec3A::ZERO)
            .min(Vec3A::splat((self.bins - 1) as f32));
        f32x4::from(b.extend(0.0).to_array())
            .fast_trunc_int()
            .to_array()
    }

    /// Whether a primitive's bin on `axis` is `last` or lower: the same
    /// arithmetic as [`Mapping::bins`] on that one axis, so the partition
    /// agrees with the bins exactly. Below the clamp to the last bin,
    /// truncation gives at most `last` exactly when the scaled offset is
    /// below `last + 1`; an offset clamped to 0 (negative or NaN) is left.
    #[inline(always)]
    fn left_of(&self, axis: usize, last: usize) -> impl Fn(&PrimRef) -> bool {
        debug_assert!(last + 1 < self.bins);
        let (origin, scale, bound) = (self.origin[axis], self.scale[axis], (last + 1) as f32);
        move |r: &PrimRef| {
            let offset = (r.lo()[axis] + r.hi()[axis] - origin) * scale;
            offset < bound || offset.is_nan()
        }
    }

    fn axis_binned(&self, axis: usize) -> bool {
        self.scale[axis] > 0.0
    }
}

/// Per bin and axis: the union of the boxes and their number (bin-major, so
/// that the sweep of [`cheapest`] prices the three axes at once).
#[derive(Clone, Debug)]
struct Bins {
    bounds: [[Bounds; 3]; BINS],
    counts: [[u32; 3]; BINS],
}

impl Bins {
    const EMPTY: Bins = Bins {
        bounds: [[Bounds::EMPTY; 3]; BINS],
        counts: [[0; 3]; BINS],
    };

    fn add(&mut self, refs: &[PrimRef], mapping: &Mapping) {
        if refs.len() < TWO_SETS {
            for r in refs {
                self.add_one(r, mapping);
            }
            return;
        }
        // Neighbouring primitives often fall in the same bins, and one's
        // update then waits for the other's stores to land: alternate
        // primitives go to two sets of bins, merged at the end (unions and
        // sums, so the bins are the same).
        let mut other = Bins::EMPTY;
        let mut pairs = refs.chunks_exact(2);
        for pair in &mut pairs {
            self.add_one(&pair[0], mapping);
            other.add_one(&pair[1], mapping);
        }
        for r in pairs.remainder() {
            self.add_one(r, mapping);
        }
        self.merge_from(&other);
    }

    /// Adds one primitive to its bin on each axis.
    #[inline(always)]
    fn add_one(&mut self, r: &PrimRef, mapping: &Mapping) {
        let (lo, hi) = (r.lo(), r.hi());
        let bins = mapping.bins(lo + hi);
        for (axis, &bin) in bins[..3].iter().enumerate() {
            self.bounds[bin as usize][axis].grow(lo, hi);
            self.counts[bin as usize][axis] += 1;
        }
    }

    /// Adds `other`'s boxes and counts to these.
    fn merge_from(&mut self, other: &Bins) {
        for bin in 0..BINS {
            for axis in 0..3 {
                self.bounds[bin][axis] = self.bounds[bin][axis].union(other.bounds[bin][axis]);
                self.counts[bin][axis] += other.counts[bin][axis];
            }
        }
    }

    fn merge(mut self, other: Bins) -> Bins {
        self.merge_from(&other);
        self
    }

    /// Empties the first `used` bins.
    fn empty(&mut self, used: usize) {
        self.bounds[..used].fill([Bounds::EMPTY; 3]);
        self.counts[..used].fill([0; 3]);
    }

    /// Bins `refs` into these (empty) bins: in place, since a set of bins
    /// is kilobytes that a returned value would copy at every split.
    fn fill(&mut self, refs: &[PrimRef], mapping: &Mapping) {
        if refs.len() >= PARALLEL_BINNING {
            *self = refs
                .par_chunks(PARALLEL_BINNING / 4)
                .map(|chunk| {
                    let mut bins = Bins::EMPTY;
                    bins.add(chunk, mapping);
                    bins
                })
                .reduce(|| Bins::EMPTY, Bins::merge);
        } else {
            self.add(refs, mapping);
        }
    }

    /// The number of primitives in `bin` along each axis.
    #[inline(always)]
    fn count(&self, bin: usize) -> UVec3 {
        UVec3::from_array(self.counts[bin])
    }
}

/// Leaf packs needed for `n` triangles on each axis: the SAH's unit of cost.
#[inline(always)]
fn blocks(n: UVec3) -> Vec3A {
    ((n + UVec3::splat(3)) / 4).as_vec3a()
}

/// Half the surface areas of three boxes, one per lane (each lane the same
/// arithmetic as [`Bounds::half_area`]).
#[inline(always)]
fn half_areas(boxes: &[Bounds; 3]) -> Vec3A {
    let [x, y, z] = boxes.map(|b| b.hi - b.lo);
    let d = Mat3A::from_cols(x, y, z).transpose();
    d.x_axis * d.y_axis + d.y_axis * d.z_axis + d.z_axis * d.x_axis
}

/// An integer comparison's lanes as a mask for float selects.
#[inline(always)]
fn lanes(m: BVec3) -> BVec3A {
    BVec3A::new(m.x, m.y, m.z)
}

/// The cheapest boundary: (axis, last bin on the left, left box, right box).
/// `total` is the number of primitives binned. The three axes are swept
/// together, one per lane; the first cheapest boundary wins (lowest axis,
/// then lowest bin).
fn cheapest(bins: &Bins, mapping: &Mapping, total: u32) -> Option<(usize, usize, Bounds, Bounds)> {
    let used = mapping.bins;
    // right_cost[i]: area · blocks of bins i.. (0 when they are empty).
    let mut right_cost = [Vec3A::ZERO; BINS];
    let (mut acc, mut n) = ([Bounds::EMPTY; 3], UVec3::ZERO);
    for i in (1..used).rev() {
        for (a, b) in acc.iter_mut().zip(&bins.bounds[i]) {
            *a = a.union(*b);
        }
        n += bins.count(i);
        let some = lanes(n.cmpgt(UVec3::ZERO));
        right_cost[i] = Vec3A::select(some, half_areas(&acc) * blocks(n), Vec3A::ZERO);
    }
    let (mut acc, mut left_n) = ([Bounds::EMPTY; 3], UVec3::ZERO);
    // Per axis: the cheapest cost so far, its last left bin (as a float,
    // exact below 2^24, so one mask selects both) and whether any was found.
    let (mut best, mut best_bin, mut found) = (Vec3A::ZERO, Vec3A::ZERO, BVec3A::FALSE);
    for i in 0..used - 1 {
        for (a, b) in acc.iter_mut().zip(&bins.bounds[i]) {
            *a = a.union(*b);
        }
        left_n += bins.count(i);
        // Both sides non-empty.
        let valid = lanes(left_n.cmpgt(UVec3::ZERO) & left_n.cmplt(UVec3::splat(total)));
        let cost = half_areas(&acc) * blocks(left_n) + right_cost[i + 1];
        let better = valid & (!found | cost.cmplt(best));
        best = Vec3A::select(better, cost, best);
        best_bin = Vec3A::select(better, Vec3A::splat(i as f32), best_bin);
        found |= valid;
    }
    let mut choice: Option<(f32, usize)> = None;
    for axis in (0..3).filter(|&a| mapping.axis_binned(a) && found.test(a)) {
        if choice.is_none_or(|(c, _)| best[axis] < c) {
            choice = Some((best[axis], axis));
        }
    }
    let (_, axis) = choice?;
    let last = best_bin[axis] as usize;
    let side = |bins_range: std::ops::Range<usize>| {
        bins.bounds[bins_range]
            .iter()
            .fold(Bounds::EMPTY, |a, b| a.union(b[axis]))
    };
    Some((axis, last, side(0..last + 1), side(last + 1..mapping.bins)))
}

/// Splits sets of primitive boxes in two by the binned SAH. It keeps one
/// set of bins (kilobytes) for all its splits and empties only the bins a
/// split uses: most splits, of a few dozen primitives, use a few.
#[derive(Clone, Debug)]
pub struct Splitter {
    bins: Box<Bins>,
}

impl Default for Splitter {
    fn default() -> Self {
        Splitter {
            bins: Box::new(Bins::EMPTY),
        }
    }
}

impl Splitter {
    /// Splits `span` (whose primitives are `refs`, all of them) in two,
    /// reordering `refs` so the left side comes first. Both sides are
    /// non-empty; primitives whose centroids all coincide are halved by
    /// count. `span` must have at least two primitives.
    pub fn split(&mut self, refs: &mut [PrimRef], span: &Span) -> (Span, Span) {
        debug_assert_eq!(refs.len(), span.len());
        debug_assert!(refs.len() >= 2);
        let mapping = Mapping::new(&span.centroids, refs.len());
        let bins = &mut *self.bins;
        bins.empty(mapping.bins);
        bins.fill(refs, &mapping);
        split_at_cheapest(refs, span, bins, &mapping)
    }
}

/// The split of [`Splitter::split`] once `bins` hold `refs` by `mapping`.
fn split_at_cheapest(
    refs: &mut [PrimRef],
    span: &Span,
    bins: &Bins,
    mapping: &Mapping,
) -> (Span, Span) {
    let Some((axis, last, left_bounds, right_bounds)) = cheapest(bins, mapping, refs.len() as u32)
    else {
        return halve(refs, span);
    };
    let goes_left = mapping.left_of(axis, last);
    let (i, left_c, right_c) = partition(refs, goes_left);
    debug_assert_eq!(
        i as u32,
        bins.counts[..=last].iter().map(|c| c[axis]).sum::<u32>(),
        "the partition must agree with the bins"
    );
    let mid = span.begin + i;
    (
        Span {
            begin: span.begin,
            end: mid,
            bounds: left_bounds,
            centroids: left_c,
        },
        Span {
            begin: mid,
            end: span.end,
            bounds: right_bounds,
            centroids: right_c,
        },
    )
}

/// Reorders `refs` so those that `goes_left` come first: (how many, the box
/// of their centroids, the box of the others' centroids).
fn partition(
    refs: &mut [PrimRef],
    goes_left: impl Fn(&PrimRef) -> bool,
) -> (usize, Bounds, Bounds) {
    let i = hoare(refs, goes_left);
    (i, centroids(&refs[..i]), centroids(&refs[i..]))
}

/// The box around the (doubled) centroids of `refs`: after the partition,
/// each side in a straight pass, which costs less than growing one box or
/// the other inside the partition's loop (a branch on each).
fn centroids(refs: &[PrimRef]) -> Bounds {
    let grow = |mut b: Bounds, r: &PrimRef| {
        b.grow_point(r.centroid());
        b
    };
    if refs.len() < PARALLEL_BINNING {
        refs.iter().fold(Bounds::EMPTY, grow)
    } else {
        refs.par_chunks(PARALLEL_BINNING / 4)
            .map(|chunk| chunk.iter().fold(Bounds::EMPTY, grow))
            .reduce(|| Bounds::EMPTY, Bounds::union)
    }
}

/// Hoare's partition of `refs` (those that `goes_left` first); how many
/// go left.
fn hoare(refs: &mut [PrimRef], goes_left: impl Fn(&PrimRef) -> bool) -> usize {
    let (mut i, mut j) = (0usize, refs.len());
    loop {
        while i < j && goes_left(&refs[i]) {
            i += 1;
        }
        while i < j && !goes_left(&refs[j - 1]) {
            j -= 1;
        }
        if i >= j {
            break;
        }
        refs.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
    i
}

/// Halves `span` by count (its centroids all coincide, so no plane
/// separates them).
fn halve(refs: &[PrimRef], span: &Span) -> (Span, Span) {
    let mid = refs.len() / 2;
    (
        Span::around(&refs[..mid], span.begin),
        Span::around(&refs[mid..], span.begin + mid),
    )
}

#[cfg(test)]
mod tests;
