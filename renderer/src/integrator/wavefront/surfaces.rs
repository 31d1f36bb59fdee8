//! What the objects the lanes hit are made of: each lane's row of the
//! [`ObjectTable`], read once and turned into lanes column by column.

use super::scene::{Column, LaneBsdf, ObjectTable, ROW};
use crate::packet::{FloatLanes, IntLanes, Vec3s, WIDTH, lane_set};

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
    /// The table's rows of the objects `object` in the lanes of `hit`.
    #[inline(always)]
    pub(super) fn gather(table: &ObjectTable, hit: F::Mask, object: F::Ints) -> Self {
        let ids = object.to_array();
        let mut rows = [table.row(table.miss()); WIDTH];
        for (k, row) in rows.iter_mut().enumerate() {
            if lane_set(hit, k) {
                *row = table.row(ids[k] as usize);
            }
        }
        let flags = column::<F>(&rows, Column::Flags as usize).bits();
        let emitter = column::<F>(&rows, Column::Emitter as usize)
            .bits()
            .to_array();
        Self {
            on_lanes: has::<F>(flags, LaneBsdf::ON_LANES),
            layered: has::<F>(flags, LaneBsdf::LAYERED),
            marble: has::<F>(flags, LaneBsdf::MARBLE),
            conductor: has::<F>(flags, LaneBsdf::CONDUCTOR),
            schlick: has::<F>(flags, LaneBsdf::SCHLICK),
            rough: has::<F>(flags, LaneBsdf::ROUGH),
            rough_glass: has::<F>(flags, LaneBsdf::ROUGH_GLASS),
            alpha: column(&rows, Column::Alpha as usize),
            dielectric: has::<F>(flags, LaneBsdf::DIELECTRIC),
            color: vec3s(&rows, Column::Color as usize),
            diffuse: column(&rows, Column::Diffuse as usize),
            glossy: column(&rows, Column::Glossy as usize),
            mirror: column(&rows, Column::Mirror as usize),
            eta: (
                column(&rows, Column::EtaFront as usize),
                column(&rows, Column::EtaBack as usize),
            ),
            emission: vec3s(&rows, Column::Emission as usize),
            emitter,
            magnitude: column(&rows, Column::Magnitude as usize),
        }
    }
}

/// Number `c` of each lane's row.
#[inline(always)]
fn column<F: FloatLanes>(rows: &[&[f32; ROW]; WIDTH], c: usize) -> F {
    let mut lanes = [0.0f32; WIDTH];
    for k in 0..WIDTH {
        lanes[k] = rows[k][c];
    }
    F::from_array(lanes)
}

/// Numbers `c`, `c + 1`, `c + 2` of each lane's row, as vectors.
#[inline(always)]
fn vec3s<F: FloatLanes>(rows: &[&[f32; ROW]; WIDTH], c: usize) -> Vec3s<F> {
    Vec3s {
        x: column(rows, c),
        y: column(rows, c + 1),
        z: column(rows, c + 2),
    }
}

/// The lanes whose flags include `flag` (one bit).
#[inline(always)]
fn has<F: FloatLanes>(flags: F::Ints, flag: i32) -> F::Mask {
    (flags & F::Ints::splat(flag)).simd_gt(F::Ints::splat(0))
}
