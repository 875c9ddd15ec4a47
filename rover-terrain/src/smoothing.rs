//! A terrain as an orbital map would give it: features shorter than a
//! cutoff wavelength removed by a Gaussian low-pass filter of the grid's
//! heights. A state estimator carries such a map when it has no better
//! one (docs/ESTIMATE.md).

use crate::error::TerrainError;
use crate::grid::Grid;
use crate::terrain::Terrain;

/// The Gaussian's standard deviation \[m\] whose response
/// `exp(−2π²σ²/λ²)` is one half at the wavelength `cutoff`:
/// `σ = cutoff·√(ln 2 / 2)/π`. Features at half the cutoff keep 1/16 of
/// their height, at twice it 84 %.
pub fn gaussian_sigma(cutoff: f64) -> f64 {
    cutoff * (core::f64::consts::LN_2 / 2.0).sqrt() / core::f64::consts::PI
}

impl Grid {
    /// The grid with its heights low-pass filtered: a separable Gaussian of
    /// [`gaussian_sigma`]`(cutoff)` over the nodes, truncated at 4σ, the
    /// nodes beyond an edge taken equal to the edge's. Same nodes,
    /// interpolant and edge policy.
    pub fn smoothed(&self, cutoff: f64) -> Result<Grid, TerrainError> {
        if !(cutoff.is_finite() && cutoff > 0.0) {
            return Err(TerrainError::parameter(
                "smooth_cutoff",
                format!("the cutoff wavelength must be > 0 m, got {cutoff}"),
                "give the shortest feature the map keeps in metres, e.g. 1.0",
            ));
        }
        let (nx, ny) = (self.nx(), self.ny());
        let [dx, dy] = self.spacing();
        let sigma = gaussian_sigma(cutoff);
        let along_x = blur_rows(self.heights(), nx, ny, &kernel(sigma / dx));
        let transposed = transpose(&along_x, nx, ny);
        let along_y = blur_rows(&transposed, ny, nx, &kernel(sigma / dy));
        let heights = transpose(&along_y, ny, nx);
        Ok(Grid::new(self.origin(), self.spacing(), nx, ny, heights)?
            .with_interpolation(self.interpolation())
            .with_edge_policy(self.edge_policy()))
    }
}

impl Terrain {
    /// The terrain with features shorter than `cutoff` \[m\] removed: a
    /// grid is filtered ([`Grid::smoothed`]); flat ground and a plane have
    /// none. Other analytic shapes are refused: sample them into a grid
    /// file first.
    pub fn smoothed(&self, cutoff: f64) -> Result<Terrain, TerrainError> {
        match self {
            Terrain::Grid(g) => Ok(Terrain::Grid(g.smoothed(cutoff)?)),
            Terrain::Flat(_) | Terrain::Slope(_) => Ok(self.clone()),
            _ => Err(TerrainError::parameter(
                "smooth_cutoff",
                "only a grid terrain (a file or kind = \"random\") can be smoothed".to_string(),
                "write the terrain as a grid file and give that, or estimate on the true map",
            )),
        }
    }
}

/// The normalized Gaussian of `sigma` nodes, truncated at 4σ (at least
/// the centre node).
fn kernel(sigma: f64) -> Vec<f64> {
    let half = (4.0 * sigma).ceil() as usize;
    let mut k: Vec<f64> = (0..=2 * half)
        .map(|i| {
            let d = i as f64 - half as f64;
            if sigma > 0.0 {
                (-0.5 * d * d / (sigma * sigma)).exp()
            } else {
                1.0
            }
        })
        .collect();
    let sum: f64 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= sum);
    k
}

/// Each row of `h` (`rows` rows of `len`) convolved with `k`, clamping
/// indices at the row's ends.
fn blur_rows(h: &[f64], len: usize, rows: usize, k: &[f64]) -> Vec<f64> {
    let half = (k.len() / 2) as isize;
    let mut out = vec![0.0; h.len()];
    for r in 0..rows {
        let row = &h[r * len..(r + 1) * len];
        for (i, o) in out[r * len..(r + 1) * len].iter_mut().enumerate() {
            *o = k
                .iter()
                .enumerate()
                .map(|(m, w)| {
                    let at = (i as isize + m as isize - half).clamp(0, len as isize - 1);
                    w * row[at as usize]
                })
                .sum();
        }
    }
    out
}

/// `h` (`rows` rows of `len`) transposed.
fn transpose(h: &[f64], len: usize, rows: usize) -> Vec<f64> {
    let mut out = vec![0.0; h.len()];
    for r in 0..rows {
        for i in 0..len {
            out[i * rows + r] = h[r * len + i];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of corrugations of wavelength `lambda` along X, amplitude 1.
    fn corrugations(lambda: f64) -> Grid {
        let tau = core::f64::consts::TAU;
        Grid::from_fn([0.0, 0.0], [0.02, 0.05], 1001, 11, |x, _| {
            (tau * x / lambda).cos()
        })
        .unwrap()
    }

    /// The amplitude left in the middle of the grid, far from the edges.
    fn amplitude(g: &Grid) -> f64 {
        let row = &g.heights()[5 * g.nx()..6 * g.nx()];
        row[300..700].iter().fold(0.0f64, |a, h| a.max(h.abs()))
    }

    #[test]
    fn corrugations_keep_the_gaussian_response() {
        let cutoff = 1.0;
        let sigma = gaussian_sigma(cutoff);
        for lambda in [0.5, 1.0, 2.0, 4.0] {
            let g = corrugations(lambda).smoothed(cutoff).unwrap();
            let pi = core::f64::consts::PI;
            let expected = (-2.0 * pi * pi * sigma * sigma / (lambda * lambda)).exp();
            // The sampled kernel's response differs from the continuous
            // one by its truncation and sampling, ~1e-4 at 2 cm nodes.
            assert!(
                (amplitude(&g) - expected).abs() < 1e-3,
                "{lambda}: {} vs {expected}",
                amplitude(&g)
            );
        }
        let half = corrugations(1.0).smoothed(1.0).unwrap();
        assert!((amplitude(&half) - 0.5).abs() < 1e-3);
    }

    #[test]
    fn a_plane_stays_and_bad_cutoffs_are_refused() {
        let g = Grid::from_fn([0.0, 0.0], [0.1, 0.1], 40, 30, |x, y| {
            0.3 * x - 0.2 * y + 1.0
        })
        .unwrap();
        let s = g.smoothed(1.0).unwrap();
        // Inside (4σ = 0.75 m from the edges) a plane is its own average.
        for j in 8..22 {
            for i in 8..32 {
                let k = j * 40 + i;
                assert!((s.heights()[k] - g.heights()[k]).abs() < 1e-12);
            }
        }
        for bad in [0.0, -1.0, f64::NAN] {
            let e = g.smoothed(bad).unwrap_err().to_string();
            assert!(e.contains("smooth_cutoff"), "{e}");
        }
    }
}
