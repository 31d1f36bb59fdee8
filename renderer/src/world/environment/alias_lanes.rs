//! Alias tables of one length laid end to end, drawn from on lanes: lane k
//! draws from its own table, [`AliasTable::sample_with_remainder`]'s
//! arithmetic bit for bit, with its bins gathered and both of a bin's
//! outcomes computed and selected (no branch per lane).

use crate::geometry::alias_table::AliasTable;
use crate::packet::{FloatLanes, IntLanes, MaskLanes};

/// Tables of `len` bins each, one after the other.
#[derive(Clone, Debug)]
pub(super) struct AliasLanes {
    /// Each bin's probability of keeping its own index.
    keep: Vec<f32>,
    /// Each bin's other index.
    alias: Vec<i32>,
    /// Bins per table.
    len: usize,
}

impl AliasLanes {
    /// `tables` laid end to end, each of `len` bins; a missing table takes
    /// bins that keep their own index (its lanes must be set aside: they
    /// draw from no distribution).
    pub(super) fn new<'a>(
        tables: impl IntoIterator<Item = Option<&'a AliasTable>>,
        len: usize,
    ) -> AliasLanes {
        assert!(len >= 1, "an alias table has bins");
        let (mut keep, mut alias) = (Vec::new(), Vec::new());
        for table in tables {
            match table {
                Some(t) => {
                    assert_eq!(t.len(), len, "tables of one length");
                    for (k, a) in t.bins() {
                        keep.push(k);
                        alias.push(a as i32);
                    }
                }
                None => {
                    keep.extend(std::iter::repeat_n(1.0, len));
                    alias.extend(0..len as i32);
                }
            }
        }
        assert!(!keep.is_empty(), "at least one table");
        AliasLanes { keep, alias, len }
    }

    /// Each lane's index drawn from its table `table` with the uniform
    /// number `u` in [0, 1), and what is left of `u` as a fresh uniform
    /// number: [`AliasTable::sample_with_remainder`] in every lane.
    #[inline(always)]
    pub(super) fn sample_with_remainder<F: FloatLanes>(
        &self,
        table: F::Ints,
        u: F,
    ) -> (F::Ints, F) {
        const BELOW_ONE: f32 = 1.0 - f32::EPSILON / 2.0;
        let n = self.len as i32;
        let x = u * F::splat(n as f32);
        // `x as usize` for x in [0, n]: truncation.
        let i = x.trunc_to_ints();
        let last = F::Ints::splat(n - 1);
        let i = F::Ints::select(i.simd_gt(last), last, i);
        let bin = table * F::Ints::splat(n) + i;
        let keep = F::gather_from(&self.keep, bin);
        let alias = F::Ints::gather_from(&self.alias, bin);
        let f = x - i.to_floats();
        let kept = f.simd_lt(keep);
        // Both outcomes (each finite where it is taken), then the lane's.
        let kept_rest = (f / keep).min(F::splat(BELOW_ONE));
        let alias_rest = ((f - keep) / (F::ONE - keep))
            .max(F::ZERO)
            .min(F::splat(BELOW_ONE));
        (
            F::Ints::select(kept, i, alias),
            kept.select(kept_rest, alias_rest),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::packet::WIDTH;
    use crate::simd::{WithLanes, on_every_lane_type};
    use proptest::prelude::*;

    /// Every lane's draw from its own table, on lanes `F`.
    #[derive(Clone)]
    struct Draw<'a>(&'a AliasLanes, [i32; WIDTH], [f32; WIDTH]);

    impl WithLanes for Draw<'_> {
        type Output = ([i32; WIDTH], [u32; WIDTH]);
        fn run<F: FloatLanes>(self) -> Self::Output {
            let (index, rest) = self
                .0
                .sample_with_remainder(F::Ints::from_array(self.1), F::from_array(self.2));
            (index.to_array(), rest.to_array().map(f32::to_bits))
        }
    }

    proptest! {
        /// Each lane draws the index and remainder that its own table's
        /// scalar `sample_with_remainder` draws, bit for bit, on every lane
        /// type; a missing table between the others changes nothing.
        #[test]
        fn every_lane_draws_what_its_table_draws_alone(
            weights in prop::collection::vec(prop::collection::vec(0.0f32..10.0, 7), 1..5),
            picks in prop::array::uniform16(0usize..8),
            u in prop::array::uniform16(0.0f32..1.0),
            edge in any::<bool>(),
        ) {
            let tables: Vec<Option<AliasTable>> = weights.iter().map(|w| AliasTable::new(w)).collect();
            let mut laid = tables.clone();
            laid.insert(0, None);
            let lanes = AliasLanes::new(laid.iter().map(Option::as_ref), 7);
            // Lanes on tables that exist (one past the missing first).
            let present: Vec<usize> = (0..tables.len()).filter(|&t| tables[t].is_some()).collect();
            prop_assume!(!present.is_empty());
            let table: [usize; WIDTH] = picks.map(|p| present[p % present.len()]);
            // Numbers on bin boundaries too.
            let u = if edge { u.map(|x| (x * 7.0).floor() / 7.0) } else { u };
            let expected: Vec<(i32, u32)> = (0..WIDTH)
                .map(|k| {
                    let (i, r) = tables[table[k]].as_ref().expect("present").sample_with_remainder(u[k]);
                    (i as i32, r.to_bits())
                })
                .collect();
            let rows = table.map(|t| t as i32 + 1);
            for (index, rest) in on_every_lane_type(Draw(&lanes, rows, u)) {
                let got: Vec<(i32, u32)> = index.into_iter().zip(rest).collect();
                prop_assert_eq!(&got, &expected);
            }
        }
    }
}
