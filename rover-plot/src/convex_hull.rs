//! The convex hull of a few points: the body outline sketched from the wheel
//! centres on the trajectory plots.

/// The convex hull of `points`, counter-clockwise, without repeated or
/// collinear points (Andrew's monotone chain). Fewer than three distinct
/// points give those points; collinear points give the two ends.
pub(crate) fn convex_hull(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * sorted.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(sorted.iter())
        } else {
            Box::new(sorted.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        // The last point of each chain starts the other one.
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_with_an_inner_point() {
        let pts = [(1.0, 1.0), (0.0, 0.0), (0.5, 0.5), (1.0, 0.0), (0.0, 1.0)];
        assert_eq!(
            convex_hull(&pts),
            vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        );
    }

    #[test]
    fn collinear_and_tiny_sets() {
        assert_eq!(
            convex_hull(&[(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (2.0, 0.0)]),
            vec![(0.0, 0.0), (2.0, 0.0)]
        );
        assert_eq!(convex_hull(&[(3.0, 4.0)]), vec![(3.0, 4.0)]);
        assert!(convex_hull(&[]).is_empty());
    }
}
