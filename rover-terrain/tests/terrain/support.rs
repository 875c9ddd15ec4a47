//! Helpers shared by the terrain tests: scratch files, a bumpy grid,
//! queries that unwrap, finite-difference gradients.

use std::path::{Path, PathBuf};

use rover_dynamics::height_field::*;
use rover_terrain::*;

/// A scratch file path under Cargo's per-target temporary directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("terrain");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir.join(name)
}

/// Writes `text` to a scratch file and returns its path.
pub fn file(name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = scratch(name);
    std::fs::write(&path, bytes).expect("write scratch file");
    path
}

/// A deterministic pseudo-random grid (heights in [−0.5, 0.5] m).
pub fn bumpy_grid(nx: usize, ny: usize) -> Grid {
    let mut g = prng::SplitMix64::new(7);
    let heights = (0..nx * ny).map(|_| g.next_f64() - 0.5).collect();
    Grid::new([-1.0, 2.0], [0.25, 0.4], nx, ny, heights).unwrap()
}

pub fn h(t: &impl HeightField, x: f64, y: f64) -> f64 {
    t.height(x, y).unwrap()
}

pub fn hg(t: &impl HeightField, x: f64, y: f64) -> (f64, [f64; 2]) {
    t.height_gradient(x, y).unwrap()
}

/// Central finite-difference gradient.
pub fn fd_gradient(t: &impl HeightField, x: f64, y: f64, step: f64) -> [f64; 2] {
    [
        (h(t, x + step, y) - h(t, x - step, y)) / (2.0 * step),
        (h(t, x, y + step) - h(t, x, y - step)) / (2.0 * step),
    ]
}

pub fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual}, expected {expected} (tolerance {tol})"
    );
}

/// The error's full message.
pub fn message<T: std::fmt::Debug>(result: Result<T, TerrainError>) -> String {
    result.expect_err("expected an error").to_string()
}
