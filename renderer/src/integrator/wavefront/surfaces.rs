//! What the objects the lanes hit are made of: each lane's row of the
//! [`ObjectTable`], gathered into lanes column by column.

use super::scene::{Column, LaneBsdf, ObjectTable, ROW};
use crate::packet::{FloatLanes, IntLanes, Vec3s, WIDTH};

/// What the objects hit are made of, one lane per hit (the miss row's
/// values in lanes that hit nothing).
pub(super) struct Surfaces<F: FloatLanes> {
    /// Lanes whose BSDF the lanes evaluate.
    pub(super) on_lanes: F::Mask,
    /// Lanes with a layered BSDF (Lambertian, highlight and mirror lobes).
    pub(super) layered: F::Mask,
    /// Layered lanes whose albedo is marble's texture through the colour.
    pub(super) marble: F::Mask,
    /// Lanes with a smooth conductor.
    pub(super) conductor: F::Mask,
    /// Lanes whose conductor, smooth or rough, follows Schlick's
    /// approximation (metal).
    pub(super) schlick: F::Mask,
    /// Lanes with a rough conductor.
    pub(super) rough: F::Mask,
    /// Lanes with rough glass.
    pub(super) rough_glass: F::Mask,
    /// The rough conductor's, glass's or highlight's GGX α.
    pub(super) alpha: F,
    /// Lanes with smooth glass.
    pub(super) dielectric: F::Mask,
    /// The material's colour.
    pub(super) color: Vec3s<F>,
    /// The Lambertian lobe's weight.
    pub(super) diffuse: F,
    /// The white GGX highlight's weight.
    pub(super) glossy: F,
    /// The mirror lobe's weight.
    pub(super) mirror: F,
    /// Glass's η from outside and from inside.
    pub(super) eta: (F, F),
    /// The radiance the front side emits.
    pub(super) emission: Vec3s<F>,
    /// The object's index among the world's emitters, −1 when it is none.
    pub(super) emitter: [i32; WIDTH],
    /// The objects' magnitudes (secondary rays' offsets scale with them).
    pub(super) magnitude: F,
}

impl<F: FloatLanes> Surfaces<F> {
    /// The table's rows of the objects `object` in the lanes of `hit` (the
    /// miss row elsewhere, and for an id past the objects, as
    /// [`ObjectTable::row`] has it), each column gathered into lanes.
    #[inline(always)]
    pub(super) fn gather(table: &ObjectTable, hit: F::Mask, object: F::Ints) -> Self {
        const { assert!(ROW == 16, "a row's first number is its index times 16") };
        let miss = F::Ints::splat(table.miss() as i32);
        let rows = F::Ints::select(hit, object, miss);
        let rows = F::Ints::select(rows.simd_gt(miss), miss, rows);
        let first = rows.shl::<4>();
        // (Functions, not closures: a closure that is not inlined runs its
        // lane operations as calls.)
        let rows = (table.numbers(), first);
        let flags = column::<F>(rows, Column::Flags).bits();
        let emitter = column::<F>(rows, Column::Emitter).bits().to_array();
        Self {
            on_lanes: has::<F>(flags, LaneBsdf::ON_LANES),
            layered: has::<F>(flags, LaneBsdf::LAYERED),
            marble: has::<F>(flags, LaneBsdf::MARBLE),
            conductor: has::<F>(flags, LaneBsdf::CONDUCTOR),
            schlick: has::<F>(flags, LaneBsdf::SCHLICK),
            rough: has::<F>(flags, LaneBsdf::ROUGH),
            rough_glass: has::<F>(flags, LaneBsdf::ROUGH_GLASS),
            alpha: column(rows, Column::Alpha),
            dielectric: has::<F>(flags, LaneBsdf::DIELECTRIC),
            color: vec3s(rows, Column::Color),
            diffuse: column(rows, Column::Diffuse),
            glossy: column(rows, Column::Glossy),
            mirror: column(rows, Column::Mirror),
            eta: (
                column(rows, Column::EtaFront),
                column(rows, Column::EtaBack),
            ),
            emission: vec3s(rows, Column::Emission),
            emitter,
            magnitude: column(rows, Column::Magnitude),
        }
    }
}

/// Column `c` of each lane's row: `rows` is the table's numbers and each
/// lane's first number there.
#[inline(always)]
fn column<F: FloatLanes>((numbers, first): (&[f32], F::Ints), c: Column) -> F {
    F::gather_from(numbers, first + F::Ints::splat(c as i32))
}

/// Columns `c`, `c + 1`, `c + 2` of each lane's row, as vectors.
#[inline(always)]
fn vec3s<F: FloatLanes>((numbers, first): (&[f32], F::Ints), c: Column) -> Vec3s<F> {
    let c = c as i32;
    Vec3s {
        x: F::gather_from(numbers, first + F::Ints::splat(c)),
        y: F::gather_from(numbers, first + F::Ints::splat(c + 1)),
        z: F::gather_from(numbers, first + F::Ints::splat(c + 2)),
    }
}

/// The lanes whose flags include `flag` (one bit).
#[inline(always)]
fn has<F: FloatLanes>(flags: F::Ints, flag: i32) -> F::Mask {
    (flags & F::Ints::splat(flag)).simd_gt(F::Ints::splat(0))
}
