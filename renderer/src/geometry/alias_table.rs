//! Walker's alias method (Vose's construction): draws index i with
//! probability wᵢ / Σw in constant time, one uniform number, whatever the
//! number of entries — for choosing among thousands of emissive triangles
//! where a binary search over a CDF costs a dozen unpredictable branches.

/// One bin: keep its own index with probability `keep`, else take `alias`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bin {
    keep: f32,
    alias: u32,
}

/// A discrete distribution over 0..n, sampled in O(1).
#[derive(Clone, Debug, PartialEq)]
pub struct AliasTable {
    bins: Vec<Bin>,
}

impl AliasTable {
    /// The table of `weights` (negative or non-finite weights count as 0);
    /// `None` when no weight is positive.
    pub fn new(weights: &[f32]) -> Option<AliasTable> {
        let clean = |w: f32| {
            if w.is_finite() && w > 0.0 {
                f64::from(w)
            } else {
                0.0
            }
        };
        let total: f64 = weights.iter().map(|&w| clean(w)).sum();
        if !(total > 0.0) || weights.len() > u32::MAX as usize {
            return None;
        }
        let n = weights.len();
        // Each bin's share scaled so that the mean is 1.
        let mut scaled: Vec<f64> = weights
            .iter()
            .map(|&w| clean(w) * n as f64 / total)
            .collect();
        let mut bins: Vec<Bin> = (0..n as u32)
            .map(|i| Bin {
                keep: 1.0,
                alias: i,
            })
            .collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            bins[s] = Bin {
                keep: scaled[s] as f32,
                alias: l as u32,
            };
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // What is left is 1 up to rounding: those bins keep themselves.
        Some(AliasTable { bins })
    }

    /// The number of entries.
    pub fn len(&self) -> usize {
        self.bins.len()
    }

    /// True when there are no entries (never: [`AliasTable::new`] refuses that).
    pub fn is_empty(&self) -> bool {
        self.bins.is_empty()
    }

    /// Each bin, in order: the probability of keeping its own index and
    /// the index taken otherwise (what [`AliasTable::sample`] reads).
    pub fn bins(&self) -> impl Iterator<Item = (f32, u32)> + '_ {
        self.bins.iter().map(|bin| (bin.keep, bin.alias))
    }

    /// The index drawn with the uniform number `u` in [0, 1).
    #[inline]
    pub fn sample(&self, u: f32) -> usize {
        let n = self.bins.len();
        let x = u * n as f32;
        let i = (x as usize).min(n - 1);
        let bin = self.bins[i];
        if x - (i as f32) < bin.keep {
            i
        } else {
            bin.alias as usize
        }
    }

    /// The index drawn with `u`, as [`AliasTable::sample`] draws it, and a
    /// fresh uniform number in [0, 1) made of what is left of `u` (where in
    /// its bin's kept or aliased part it fell), so one number also places
    /// a point within the drawn entry.
    #[inline]
    pub fn sample_with_remainder(&self, u: f32) -> (usize, f32) {
        const BELOW_ONE: f32 = 1.0 - f32::EPSILON / 2.0;
        let n = self.bins.len();
        let x = u * n as f32;
        let i = (x as usize).min(n - 1);
        let bin = self.bins[i];
        let f = x - i as f32;
        if f < bin.keep {
            (i, (f / bin.keep).min(BELOW_ONE))
        } else {
            let rest = ((f - bin.keep) / (1.0 - bin.keep)).clamp(0.0, BELOW_ONE);
            (bin.alias as usize, rest)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The exact probability of each index under the table (in f64).
    fn probabilities(table: &AliasTable) -> Vec<f64> {
        let n = table.len() as f64;
        let mut p = vec![0.0; table.len()];
        for (i, bin) in table.bins.iter().enumerate() {
            p[i] += f64::from(bin.keep) / n;
            p[bin.alias as usize] += (1.0 - f64::from(bin.keep)) / n;
        }
        p
    }

    /// The remainder places points evenly: drawing with `u` on a fine grid,
    /// each index's remainders cover [0, 1) uniformly.
    #[test]
    fn remainders_are_uniform_within_each_drawn_index() {
        let table = AliasTable::new(&[1.0, 3.0, 0.5, 2.5]).expect("positive weights");
        let n = 100_000;
        let mut sums = [(0.0f64, 0usize); 4];
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            let (i, rest) = table.sample_with_remainder(u);
            assert_eq!(i, table.sample(u));
            assert!((0.0..1.0).contains(&rest), "{rest}");
            sums[i].0 += f64::from(rest);
            sums[i].1 += 1;
        }
        for (i, (sum, count)) in sums.into_iter().enumerate() {
            let mean = sum / count as f64;
            assert!(
                (mean - 0.5).abs() < 0.01,
                "index {i}: mean remainder {mean}"
            );
        }
    }

    proptest! {
        #[test]
        fn each_index_is_drawn_in_proportion_to_its_weight(
            weights in prop::collection::vec(prop_oneof![Just(0.0f32), 0.0f32..100.0], 1..200)
        ) {
            let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
            let table = AliasTable::new(&weights);
            prop_assume!(total > 0.0);
            let table = table.expect("a positive weight");
            for (i, p) in probabilities(&table).into_iter().enumerate() {
                let want = f64::from(weights[i]) / total;
                prop_assert!((p - want).abs() <= 1e-6, "index {}: {} vs {}", i, p, want);
            }
        }
    }

    #[test]
    fn zero_weights_are_never_drawn_and_draws_cover_the_unit_interval() {
        let table = AliasTable::new(&[0.0, 3.0, 0.0, 1.0, f32::NAN, -2.0]).expect("weights");
        let mut counts = [0usize; 6];
        let n = 100_000;
        for k in 0..n {
            counts[table.sample(k as f32 / n as f32)] += 1;
        }
        assert_eq!(
            (counts[0], counts[2], counts[4], counts[5]),
            (0, 0, 0, 0),
            "{counts:?}"
        );
        let share = counts[1] as f64 / n as f64;
        assert!((share - 0.75).abs() < 1e-3, "{counts:?}");
        // The largest number below 1 still lands on a drawable index.
        assert!([1, 3].contains(&table.sample(1.0 - f32::EPSILON / 2.0)));
    }

    #[test]
    fn no_positive_weight_gives_no_table() {
        assert_eq!(AliasTable::new(&[]), None);
        assert_eq!(AliasTable::new(&[0.0, -1.0, f32::INFINITY]), None);
    }
}
