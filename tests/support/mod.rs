//! Shared helpers of the integration tests.

pub mod hand_models;
pub mod lagrange;
pub mod rng;
pub mod run;

/// Largest |a − b| over the largest |a|, |b| (0 when both are 0): a
/// norm-wise relative difference.
pub fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if scale == 0.0 { diff } else { diff / scale }
}
