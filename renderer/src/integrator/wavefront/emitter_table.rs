//! The world's emitters laid out for lanes: the alias table that chooses
//! one ([`Emitters::choose`]) and, per emitter, what drawing a point on a
//! triangle needs, read by each lane with gathers (or, for a few
//! emitters, picked by comparisons).

use crate::packet::{FloatLanes, IntLanes, MaskLanes, Vec3s};
use crate::world::emitters::Emitters;

/// Per emitter, a row of [`ROW`] numbers ([`Column`]), and the alias
/// table's bins, for lanes.
#[derive(Clone, Debug, Default)]
pub(crate) struct EmitterTable {
    /// Per alias bin, the probability of keeping its own index.
    keep: Vec<f32>,
    /// Per alias bin, the index taken otherwise.
    alias: Vec<i32>,
    /// The rows, [`ROW`] numbers each.
    rows: Vec<f32>,
}

/// The numbers in a row of an [`EmitterTable`].
const ROW: usize = 17;

/// Up to this many emitters, a lane's number is picked by comparing its
/// index with each emitter's (a broadcast and a blend per emitter) instead
/// of gathered: a light of one quad is two rows, and the nineteen
/// sixteen-lane gathers of a bounce's light sample cost more than that.
const PICK_AT_MOST: usize = 4;

/// Where each number sits in a row of an [`EmitterTable`].
#[derive(Clone, Copy, Debug)]
enum Column {
    /// What the emitter is: [`NOT_DRAWN`], [`TRIANGLE`] or [`OTHER`].
    Kind = 0,
    /// The probability of choosing it times its triangle's 1/area (pmf ·
    /// pdf_area, the first product of `Emitters::sample`'s density).
    Density = 1,
    /// The triangle's corner t0 (three numbers).
    Corner = 2,
    /// t1 − t0 (three numbers).
    Edge1 = 5,
    /// t2 − t0 (three numbers).
    Edge2 = 8,
    /// The triangle's unit normal (three numbers).
    Normal = 11,
    /// The radiance it emits (three numbers).
    Radiance = 14,
}

/// [`Column::Kind`] of an emitter never drawn (no probability).
const NOT_DRAWN: f32 = 0.0;
/// [`Column::Kind`] of a triangle, drawn on lanes.
const TRIANGLE: f32 = 1.0;
/// [`Column::Kind`] of another shape, drawn by `Emitters::sample`.
const OTHER: f32 = 2.0;

/// Each lane's emitter, as [`EmitterTable::choose`] draws it.
pub(super) struct Chosen<F: FloatLanes> {
    /// The emitter's index.
    index: F::Ints,
    /// Lanes whose emitter is a triangle.
    pub(super) triangle: F::Mask,
    /// Lanes whose emitter is another shape.
    pub(super) other: F::Mask,
}

/// The points drawn on each lane's triangle need these.
pub(super) struct TriangleLanes<F: FloatLanes> {
    /// pmf · pdf_area.
    pub(super) density: F,
    /// t0.
    pub(super) corner: Vec3s<F>,
    /// t1 − t0.
    pub(super) edge1: Vec3s<F>,
    /// t2 − t0.
    pub(super) edge2: Vec3s<F>,
    /// The unit normal.
    pub(super) normal: Vec3s<F>,
    /// The radiance it emits.
    pub(super) radiance: Vec3s<F>,
}

impl EmitterTable {
    /// The table of `emitters`; empty when none can be drawn.
    pub(crate) fn new(emitters: &Emitters) -> Self {
        let Some((choice, pmf)) = emitters.choice() else {
            return Self::default();
        };
        let (keep, alias) = choice.bins().map(|(k, a)| (k, a as i32)).unzip();
        let mut rows = Vec::with_capacity(pmf.len() * ROW);
        for (index, &p) in pmf.iter().enumerate() {
            let mut row = [0.0f32; ROW];
            let kind = match emitters.triangle(index) {
                _ if !(p > 0.0) => NOT_DRAWN,
                Some((triangle, radiance)) => {
                    row[Column::Density as usize] = p * triangle.pdf_area;
                    let [corner, edge1, edge2] = triangle.corner_and_edges();
                    for (column, v) in [
                        (Column::Corner, corner),
                        (Column::Edge1, edge1),
                        (Column::Edge2, edge2),
                        (Column::Normal, triangle.normal()),
                        (Column::Radiance, radiance),
                    ] {
                        let at = column as usize;
                        row[at..at + 3].copy_from_slice(&v.to_array());
                    }
                    TRIANGLE
                }
                None => OTHER,
            };
            row[Column::Kind as usize] = kind;
            rows.extend_from_slice(&row);
        }
        Self { keep, alias, rows }
    }

    /// Whether no emitter can be drawn.
    #[inline(always)]
    pub(super) fn is_empty(&self) -> bool {
        self.keep.is_empty()
    }

    /// Each lane's emitter drawn with `u` ∈ [0, 1): `AliasTable::sample`
    /// with its operations, lane by lane. The table must not be empty.
    #[inline(always)]
    pub(super) fn choose<F: FloatLanes>(&self, u: F) -> Chosen<F> {
        let n = self.keep.len();
        let x = u * F::splat(n as f32);
        // `(x as usize).min(n − 1)`: x is never negative.
        let last = F::Ints::splat(n as i32 - 1);
        let i = x.trunc_to_ints();
        let i = F::Ints::select(i.simd_gt(last), last, i);
        let (keep, alias) = if n <= PICK_AT_MOST {
            let bins = i.to_floats();
            let mut alias = F::Ints::splat(self.alias[0]);
            for bin in 1..n {
                let here = bins.simd_eq(F::splat(bin as f32));
                alias = F::Ints::select(here, F::Ints::splat(self.alias[bin]), alias);
            }
            (pick(&self.keep, 1, 0, bins), alias)
        } else {
            (
                F::gather_from(&self.keep, i),
                F::Ints::gather_from(&self.alias, i),
            )
        };
        let index = F::Ints::select((x - i.to_floats()).simd_lt(keep), i, alias);
        let kind: F = self.column(index, Column::Kind);
        Chosen {
            index,
            triangle: kind.simd_eq(F::splat(TRIANGLE)),
            other: kind.simd_eq(F::splat(OTHER)),
        }
    }

    /// What drawing a point on each lane's chosen triangle needs (anything
    /// in lanes whose emitter is not a triangle).
    #[inline(always)]
    pub(super) fn triangles<F: FloatLanes>(&self, chosen: &Chosen<F>) -> TriangleLanes<F> {
        let at = chosen.index;
        TriangleLanes {
            density: self.column(at, Column::Density),
            corner: self.vec3s(at, Column::Corner),
            edge1: self.vec3s(at, Column::Edge1),
            edge2: self.vec3s(at, Column::Edge2),
            normal: self.vec3s(at, Column::Normal),
            radiance: self.vec3s(at, Column::Radiance),
        }
    }

    /// Number `column` of each lane's row `index`.
    #[inline(always)]
    fn column<F: FloatLanes>(&self, index: F::Ints, column: Column) -> F {
        self.number(index, column as i32)
    }

    /// Number `at` of each lane's row `index`.
    #[inline(always)]
    fn number<F: FloatLanes>(&self, index: F::Ints, at: i32) -> F {
        if self.rows.len() / ROW <= PICK_AT_MOST {
            return pick(&self.rows, ROW, at as usize, index.to_floats());
        }
        let row = F::Ints::splat(ROW as i32);
        F::gather_from(&self.rows, index * row + F::Ints::splat(at))
    }

    /// Numbers `column`, `column + 1` and `column + 2` of each lane's row.
    #[inline(always)]
    fn vec3s<F: FloatLanes>(&self, index: F::Ints, column: Column) -> Vec3s<F> {
        let c = column as i32;
        Vec3s {
            x: self.number(index, c),
            y: self.number(index, c + 1),
            z: self.number(index, c + 2),
        }
    }
}

/// Number `at` of each lane's row `index` (a whole number, as an `f32`)
/// of `table`, rows of `stride` numbers, at most [`PICK_AT_MOST`] of them:
/// the first row's number, replaced row by row where the lane's index is
/// that row's (exactly the number a gather reads).
#[inline(always)]
fn pick<F: FloatLanes>(table: &[f32], stride: usize, at: usize, index: F) -> F {
    let mut number = F::splat(table[at]);
    for row in 1..table.len() / stride {
        let here = index.simd_eq(F::splat(row as f32));
        number = here.select(F::splat(table[row * stride + at]), number);
    }
    number
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{Shape, Sphere, Triangle};
    use crate::simd::{MaskLanes, WIDTH, WithLanes, on_every_lane_type};
    use glam::Vec3;

    /// Forty emitters of very different power — triangles of many sizes
    /// and brightnesses, a sphere, and a triangle of no area (never drawn) —
    /// so that the alias table keeps some bins and sends others elsewhere.
    fn emitters() -> Emitters {
        Emitters::new(&emitter_shapes(), &[])
    }

    /// The shapes of [`emitters`]: 38 triangles, the sphere, the flat one.
    fn emitter_shapes() -> Vec<(Option<Shape>, Vec3)> {
        let mut shapes = Vec::new();
        for k in 0..38 {
            let (x, size) = (k as f32 * 3.0, 0.05 + (k % 7) as f32 * 0.4);
            let t = Triangle::new(
                Vec3::new(x, 0.0, 0.0),
                Vec3::new(x + size, 0.0, 0.0),
                Vec3::new(x, size * 1.5, 0.3),
            );
            shapes.push((Some(Shape::Triangle(t)), Vec3::splat(1.0 + (k % 5) as f32)));
        }
        let sphere = Sphere::new(Vec3::new(0.0, 5.0, 0.0), 0.7);
        shapes.push((Some(Shape::Sphere(sphere)), Vec3::new(3.0, 2.0, 1.0)));
        let flat = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        shapes.push((Some(Shape::Triangle(flat)), Vec3::ONE));
        shapes
    }

    /// Every lane chooses the emitter `Emitters::choose` chooses for its
    /// number (thousands of numbers, each bin's edges among them), with
    /// the kind that says how it is drawn, and reads that triangle's
    /// corner, edges, normal, radiance and pmf · 1/area.
    #[derive(Clone)]
    struct ChoosesAsTheScalarCode<'a>(&'a Emitters);

    impl WithLanes for ChoosesAsTheScalarCode<'_> {
        type Output = (usize, usize);
        fn run<F: FloatLanes>(self) -> (usize, usize) {
            let emitters = self.0;
            let table = EmitterTable::new(emitters);
            let n = table.keep.len() as f32;
            let mut numbers: Vec<f32> = (0..4096).map(|k| k as f32 / 4096.0).collect();
            for bin in 0..table.keep.len() {
                let edge = bin as f32 / n;
                numbers.extend([edge, edge.next_up(), (edge + 1.0 / n).next_down()]);
            }
            numbers.extend([0.0, 1.0f32.next_down()]);
            let (mut triangles, mut others) = (0, 0);
            for chunk in numbers.chunks(WIDTH) {
                let mut u = [0.0f32; WIDTH];
                u[..chunk.len()].copy_from_slice(chunk);
                let chosen = table.choose(F::from_array(u));
                let drawn = table.triangles(&chosen);
                let index = chosen.index.to_array();
                for (k, &u) in chunk.iter().enumerate() {
                    let lane = |m: F::Mask| m.to_bitmask() & (1 << k) != 0;
                    match emitters.choose(u) {
                        None => assert!(!lane(chosen.triangle) && !lane(chosen.other), "u {u}"),
                        Some((i, pmf)) => {
                            assert_eq!(index[k] as usize, i, "u {u}");
                            let Some((t, radiance)) = emitters.triangle(i) else {
                                assert!(lane(chosen.other) && !lane(chosen.triangle), "u {u}");
                                others += 1;
                                continue;
                            };
                            assert!(lane(chosen.triangle) && !lane(chosen.other), "u {u}");
                            let [corner, edge1, edge2] = t.corner_and_edges();
                            assert_eq!(drawn.corner.lane(k), corner);
                            assert_eq!(drawn.edge1.lane(k), edge1);
                            assert_eq!(drawn.edge2.lane(k), edge2);
                            assert_eq!(drawn.normal.lane(k), t.normal());
                            assert_eq!(drawn.radiance.lane(k), radiance);
                            assert_eq!(drawn.density.as_array()[k], pmf * t.pdf_area);
                            triangles += 1;
                        }
                    }
                }
            }
            (triangles, others)
        }
    }

    #[test]
    fn lanes_choose_and_read_the_emitters_the_scalar_code_does() {
        let emitters = emitters();
        for (triangles, spheres) in on_every_lane_type(ChoosesAsTheScalarCode(&emitters)) {
            assert!(triangles > 3000, "too few triangles chosen: {triangles}");
            assert!(spheres > 10, "too few spheres chosen: {spheres}");
        }
    }

    #[test]
    fn a_few_emitters_are_picked_without_gathers_as_the_scalar_code_chooses_them() {
        let shapes = emitter_shapes();
        let (sphere, flat) = (shapes[38], shapes[39]);
        let sets: Vec<Vec<_>> = vec![
            shapes[..1].to_vec(),
            shapes[..2].to_vec(),
            vec![shapes[0], sphere],
            vec![shapes[3], flat, shapes[5]],
            shapes[..4].to_vec(),
            shapes[..5].to_vec(),
        ];
        for set in sets {
            let emitters = Emitters::new(&set, &[]);
            for (triangles, others) in on_every_lane_type(ChoosesAsTheScalarCode(&emitters)) {
                assert!(triangles > 0, "{} emitters: no triangle chosen", set.len());
                assert!(
                    triangles + others > 4096,
                    "{} emitters: {triangles} + {others} chosen",
                    set.len()
                );
            }
        }
    }
}
