//! Quantiles of measurements: the median of repeated timings (the machine
//! is shared, so one run says little) and the tails of latency figures.

use std::cmp::Ordering;

/// The `q`-quantile of `values` (0 ≤ q ≤ 1; ½ is the median) in the order
/// `order`: the value of rank round((n − 1) q), which for the median is the
/// upper middle one, `values[n / 2]` once sorted. Sorts `values` in place
/// (stably); `None` when there are none.
pub fn quantile_by<T: Copy>(
    values: &mut [T],
    q: f64,
    order: impl FnMut(&T, &T) -> Ordering,
) -> Option<T> {
    values.sort_by(order);
    let last = values.len().checked_sub(1)?;
    Some(values[((last as f64) * q.clamp(0.0, 1.0)).round() as usize])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn the_median_is_the_upper_middle_value_of_the_sorted_list() {
        for n in 1..=9usize {
            let mut values: Vec<f64> = (0..n).rev().map(|k| k as f64).collect();
            let median = quantile_by(&mut values, 0.5, f64::total_cmp);
            assert_eq!(median, Some((n / 2) as f64), "n = {n}");
        }
    }

    #[test]
    fn quantiles_take_the_nearest_rank_and_none_of_nothing() {
        let mut ms: Vec<Duration> = (1..=21).rev().map(Duration::from_millis).collect();
        assert_eq!(
            quantile_by(&mut ms, 0.95, Duration::cmp),
            Some(Duration::from_millis(20))
        );
        assert_eq!(
            quantile_by(&mut ms, 0.0, Duration::cmp),
            Some(Duration::from_millis(1))
        );
        assert_eq!(
            quantile_by(&mut ms, 1.0, Duration::cmp),
            Some(Duration::from_millis(21))
        );
        assert_eq!(
            quantile_by(&mut [] as &mut [f64], 0.5, f64::total_cmp),
            None
        );
    }
}
