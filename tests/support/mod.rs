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

/// A file of `text` named `name` in the scratch folder `folder` of the
/// tests; its absolute path.
pub fn scratch_file(folder: &str, name: &str, text: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}
