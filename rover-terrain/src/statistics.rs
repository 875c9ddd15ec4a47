//! Height and slope statistics of a terrain, as quoted in the docs.

use super::error::TerrainError;
use super::grid::Grid;
use super::height_field::{Bounds, HeightField};
use super::param::positive;

/// Roughness statistics over a lattice of sample points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TerrainStatistics {
    /// Number of sample points.
    pub samples: usize,
    /// Mean height \[m\].
    pub mean_height: f64,
    /// RMS height about the mean, `√(mean((Z − Z̄)²))` \[m\].
    pub rms_height: f64,
    /// RMS slope, `√(mean(|∇Z|²))` [m/m] (a tangent, not an angle).
    pub rms_slope: f64,
    /// Steepest slope, `atan(max |∇Z|)` [°].
    pub max_slope_deg: f64,
    /// Correlation lengths along X and Y \[m\]: the lag at which the
    /// autocorrelation `mean((Z(p) − Z̄)(Z(p + τ) − Z̄))/var` first falls below
    /// 1/e (linear between samples); `None` if it does not within half the
    /// sampled span, or the terrain is flat.
    pub correlation_length: [Option<f64>; 2],
}

impl TerrainStatistics {
    /// Statistics over a grid's nodes, heights and gradients from its interpolant.
    pub fn of_grid(grid: &Grid) -> TerrainStatistics {
        let [dx, dy] = grid.spacing();
        let [x0, y0] = grid.origin();
        let (nx, ny) = (grid.nx(), grid.ny());
        let mut slope_sq = 0.0;
        let mut max_slope: f64 = 0.0;
        for j in 0..ny {
            for i in 0..nx {
                // Nodes lie on the grid, so the query cannot be off the map.
                if let Ok((_, g)) = grid.height_gradient(x0 + i as f64 * dx, y0 + j as f64 * dy) {
                    let s2 = g[0] * g[0] + g[1] * g[1];
                    slope_sq += s2;
                    max_slope = max_slope.max(s2.sqrt());
                }
            }
        }
        finish(grid.heights(), nx, ny, [dx, dy], slope_sq, max_slope)
    }

    /// Statistics of any height field sampled at `step` `[sx, sy]` \[m\] over
    /// `bounds` (from the south-west corner, as many whole steps as fit).
    pub fn sample<H: HeightField + ?Sized>(
        field: &H,
        bounds: Bounds,
        step: [f64; 2],
    ) -> Result<TerrainStatistics, TerrainError> {
        positive("statistics.step[0]", step[0], "m")?;
        positive("statistics.step[1]", step[1], "m")?;
        let count = |span: f64, h: f64| -> Result<usize, TerrainError> {
            let n = (span / h + 1e-9).floor();
            if (1.0..1e8).contains(&n) {
                Ok(n as usize + 1)
            } else {
                Err(TerrainError::parameter(
                    "statistics.bounds",
                    format!("a span of {span} m at steps of {h} m is not a usable lattice"),
                    "give finite bounds at least one step wide",
                ))
            }
        };
        let nx = count(bounds.x_max - bounds.x_min, step[0])?;
        let ny = count(bounds.y_max - bounds.y_min, step[1])?;
        let mut heights = Vec::with_capacity(nx.saturating_mul(ny).min(1 << 26));
        let mut slope_sq = 0.0;
        let mut max_slope: f64 = 0.0;
        for j in 0..ny {
            for i in 0..nx {
                let (z, g) = field.height_gradient(
                    bounds.x_min + i as f64 * step[0],
                    bounds.y_min + j as f64 * step[1],
                )?;
                heights.push(z);
                let s2 = g[0] * g[0] + g[1] * g[1];
                slope_sq += s2;
                max_slope = max_slope.max(s2.sqrt());
            }
        }
        Ok(finish(&heights, nx, ny, step, slope_sq, max_slope))
    }
}

fn finish(
    heights: &[f64],
    nx: usize,
    ny: usize,
    step: [f64; 2],
    slope_sq: f64,
    max_slope: f64,
) -> TerrainStatistics {
    let n = heights.len().max(1) as f64;
    let mean = heights.iter().sum::<f64>() / n;
    let var = heights.iter().map(|z| (z - mean) * (z - mean)).sum::<f64>() / n;
    TerrainStatistics {
        samples: heights.len(),
        mean_height: mean,
        rms_height: var.sqrt(),
        rms_slope: (slope_sq / n).sqrt(),
        max_slope_deg: max_slope.atan().to_degrees(),
        correlation_length: [
            correlation_length(heights, mean, var, nx, ny, [1, 0], step[0]),
            correlation_length(heights, mean, var, nx, ny, [0, 1], step[1]),
        ],
    }
}

/// The first lag along `axis` (`[1, 0]` = X) where the autocorrelation drops
/// below 1/e, interpolated linearly between lags.
fn correlation_length(
    heights: &[f64],
    mean: f64,
    var: f64,
    nx: usize,
    ny: usize,
    axis: [usize; 2],
    step: f64,
) -> Option<f64> {
    if var <= 0.0 {
        return None;
    }
    let threshold = (-1.0f64).exp();
    let max_lag = if axis[0] == 1 { nx / 2 } else { ny / 2 };
    let mut previous = 1.0;
    for lag in 1..=max_lag {
        let (lx, ly) = (lag * axis[0], lag * axis[1]);
        let mut sum = 0.0;
        let mut count = 0usize;
        for j in 0..ny - ly {
            for i in 0..nx - lx {
                let a = heights.get(j * nx + i)?;
                let b = heights.get((j + ly) * nx + i + lx)?;
                sum += (a - mean) * (b - mean);
                count += 1;
            }
        }
        let rho = sum / count.max(1) as f64 / var;
        if rho < threshold {
            let fraction = (previous - threshold) / (previous - rho);
            return Some(step * ((lag - 1) as f64 + fraction));
        }
        previous = rho;
    }
    None
}
