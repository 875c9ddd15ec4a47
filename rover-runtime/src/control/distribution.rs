//! How the mean torque is shared among the wheels (MODEL.md §8).

use serde::{Deserialize, Serialize};

/// Torque distribution: `τ_j = τ_0·n·w_j / Σ w`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Distribution {
    /// w_j = 1: every wheel gets τ_0.
    #[default]
    Even,
    /// w_j = the wheel's load in the rover's static equilibrium on flat
    /// ground, solved once when the controller is built (the quasi-static
    /// solver of MODEL.md §9).
    StaticLoad,
    /// w_j = the wheel's normal load now (from the same right-hand-side
    /// evaluation): wheels in the air get no torque.
    MeasuredLoad,
}

/// Share `tau0` (per wheel, mean) by weights, added to `out`; equal shares
/// when the weights sum to zero (every wheel airborne).
pub fn add_share(tau0: f64, weights: &[f64], out: &mut [f64]) {
    let n = out.len() as f64;
    let total: f64 = weights.iter().sum();
    for (o, w) in out.iter_mut().zip(weights) {
        *o += if total > 0.0 {
            tau0 * n * w / total
        } else {
            tau0
        };
    }
}
