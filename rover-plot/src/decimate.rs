//! Thinning long runs before drawing, so that a run of a million samples
//! gives a plot of a sensible file size; short runs are drawn sample by sample.

/// Most points drawn per time-history line.
pub(crate) const MAX_POINTS: usize = 4000;

/// Most points drawn per trajectory path (a figure holds `2n + 1` of them).
pub(crate) const MAX_PATH_POINTS: usize = 2000;

/// Indices of the samples to draw out of `n`: all of them when `n <= max`,
/// else evenly strided, always with the first and the last.
pub(crate) fn stride_indices(n: usize, max: usize) -> Vec<usize> {
    if n <= max.max(2) {
        return (0..n).collect();
    }
    let step = n.div_ceil(max - 1);
    let mut indices: Vec<usize> = (0..n).step_by(step).collect();
    if indices.last() != Some(&(n - 1)) {
        indices.push(n - 1);
    }
    indices
}

/// The points `(t[i], y[i])` to draw: all of them when there are at most
/// `max`, else the smallest and the largest `y` of each of `max / 2` buckets
/// of consecutive samples, in time order, so that no peak is lost.
pub(crate) fn min_max(t: &[f64], y: &[f64], max: usize) -> Vec<(f64, f64)> {
    let n = t.len().min(y.len());
    let buckets = (max / 2).max(1);
    if n <= max.max(2) {
        return (0..n).map(|i| (t[i], y[i])).collect();
    }
    let size = n.div_ceil(buckets);
    let mut points = Vec::with_capacity(2 * buckets);
    for start in (0..n).step_by(size) {
        let end = (start + size).min(n);
        let (mut lo, mut hi) = (start, start);
        for i in start..end {
            if y[i] < y[lo] {
                lo = i;
            }
            if y[i] > y[hi] {
                hi = i;
            }
        }
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        points.push((t[a], y[a]));
        if b != a {
            points.push((t[b], y[b]));
        }
    }
    points
}

/// `points` without the interior points of flat stretches (equal value
/// before and after): a constant set-point becomes a few points. Drawing is
/// unchanged.
pub(crate) fn drop_flat(points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    let n = points.len();
    let keep = |i: usize| {
        i == 0 || i + 1 == n || points[i - 1].1 != points[i].1 || points[i + 1].1 != points[i].1
    };
    (0..n).filter(|&i| keep(i)).map(|i| points[i]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_stretches_keep_their_ends() {
        let p = vec![
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 1.0),
            (4.0, 1.0),
            (5.0, 1.0),
        ];
        assert_eq!(
            drop_flat(p),
            vec![(0.0, 0.0), (2.0, 0.0), (3.0, 1.0), (5.0, 1.0)]
        );
        assert_eq!(drop_flat(vec![(0.0, 2.0)]), vec![(0.0, 2.0)]);
    }

    #[test]
    fn short_series_are_kept_whole() {
        assert_eq!(stride_indices(5, 10), vec![0, 1, 2, 3, 4]);
        let t = [0.0, 1.0, 2.0];
        assert_eq!(min_max(&t, &[5.0, 6.0, 7.0], 10).len(), 3);
    }

    #[test]
    fn strides_keep_first_and_last_and_the_limit() {
        let idx = stride_indices(10_001, 100);
        assert_eq!(idx[0], 0);
        assert_eq!(*idx.last().unwrap(), 10_000);
        assert!(idx.len() <= 101, "{}", idx.len());
        assert!(idx.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn min_max_keeps_a_one_sample_spike() {
        let n = 100_000;
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
        let mut y = vec![0.0; n];
        y[54_321] = 9.0;
        y[77_777] = -4.0;
        let p = min_max(&t, &y, 1000);
        assert!(p.len() <= 1000);
        assert!(p.contains(&(t[54_321], 9.0)));
        assert!(p.contains(&(t[77_777], -4.0)));
        assert!(p.windows(2).all(|w| w[0].0 < w[1].0));
    }
}
