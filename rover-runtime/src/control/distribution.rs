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
    /// Anti-spin (Chen & Genta (2012) §5.1: monitor each wheel's slip and
    /// keep wheels from spinning): w_j = [`anti_spin_weight`] of the
    /// wheel's longitudinal slip now (from the same right-hand-side
    /// evaluation), so a wheel slipping beyond `slip_threshold` loses its
    /// share to the wheels that grip. Needs a soil (the rigid law has no
    /// slip).
    AntiSpin,
}

/// Default slip above which an anti-spin distribution cuts a wheel's share.
pub const DEFAULT_SLIP_THRESHOLD: f64 = 0.2;
/// Default width of slip over which the cut share falls to none.
pub const DEFAULT_SLIP_BAND: f64 = 0.2;

/// An anti-spin weight: 1 up to slip `threshold`, falling linearly to 0
/// at `threshold + band`, 0 beyond (continuous, so that an adaptive
/// integrator sees no jump).
pub fn anti_spin_weight(slip: f64, threshold: f64, band: f64) -> f64 {
    (1.0 - (slip - threshold) / band).clamp(0.0, 1.0)
}

/// Share `tau0` (per wheel, mean) by weights, added to `out`; equal shares
/// when the weights sum to zero (every wheel airborne).
pub fn add_share(tau0: f64, weights: &[f64], out: &mut [f64]) {
    add_weighted(tau0, weights.len(), |k| weights[k], out);
}

/// Share `tau0` (per wheel, mean) by the anti-spin weights of `slips`,
/// added to `out`: the total n·τ_0 is kept, taken from the wheels that
/// spin and given to those that grip. Each weight is raised by
/// `1 − max_k w_k`: while a wheel grips fully (w = 1) a spinning wheel
/// gets nothing, and as every wheel spins the shares tend to equal ones
/// (no wheel grips better than another) without a jump. Allocates nothing.
pub fn add_anti_spin_share(tau0: f64, slips: &[f64], threshold: f64, band: f64, out: &mut [f64]) {
    let weight = |k: usize| anti_spin_weight(slips[k], threshold, band);
    let lift = 1.0 - (0..slips.len()).map(weight).fold(0.0, f64::max);
    add_weighted(tau0, slips.len(), |k| weight(k) + lift, out);
}

fn add_weighted(tau0: f64, count: usize, weight: impl Fn(usize) -> f64, out: &mut [f64]) {
    let n = out.len() as f64;
    let total: f64 = (0..count).map(&weight).sum();
    for (k, o) in out.iter_mut().enumerate().take(count) {
        *o += if total > 0.0 {
            tau0 * n * weight(k) / total
        } else {
            tau0
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wheel spinning past the band loses its share to the three that
    /// grip; the total n·τ_0 is kept (no motor saturates here: the limits
    /// are applied after the shares).
    #[test]
    fn a_spinning_wheels_torque_goes_to_the_wheels_that_grip() {
        let (tau0, threshold, band) = (0.6, 0.2, 0.2);
        let mut even = [0.0; 4];
        add_anti_spin_share(tau0, &[0.1; 4], threshold, band, &mut even);
        assert_eq!(even, [tau0; 4]);
        let mut out = [0.0; 4];
        add_anti_spin_share(tau0, &[0.1, 0.9, 0.15, -0.05], threshold, band, &mut out);
        assert_eq!(out[1], 0.0);
        for k in [0, 2, 3] {
            assert!((out[k] - tau0 * 4.0 / 3.0).abs() < 1e-12, "{out:?}");
        }
        // Half-way through the band: half a share.
        let mut half = [0.0; 4];
        add_anti_spin_share(tau0, &[0.0, 0.3, 0.0, 0.0], threshold, band, &mut half);
        assert!((half[1] - 0.5 * tau0 * 4.0 / 3.5).abs() < 1e-12, "{half:?}");
        for shares in [out, half] {
            assert!((shares.iter().sum::<f64>() - 4.0 * tau0).abs() < 1e-12);
        }
    }

    /// As every wheel comes to spin the shares become equal, without a
    /// jump: the last wheel to grip does not take the whole torque.
    #[test]
    fn when_every_wheel_spins_the_shares_tend_to_equal() {
        let (threshold, band) = (0.2, 0.2);
        let mut last: Option<[f64; 3]> = None;
        for k in 0..=200 {
            // Wheel 1 leaves the band last (at s = 0.4).
            let s = 0.3 + 0.001 * k as f64;
            let mut out = [0.0; 3];
            add_anti_spin_share(1.0, &[s, s + 0.05, 1.0], threshold, band, &mut out);
            assert!((out.iter().sum::<f64>() - 3.0).abs() < 1e-12);
            if let Some(prev) = last {
                // Slip steps of 0.001 move a share by at most 3/band of it.
                let largest = out
                    .iter()
                    .zip(prev)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                assert!(largest <= 3.0 * 0.001 / band + 1e-12, "s = {s}: {largest}");
            }
            if s >= 0.4 {
                assert!(
                    out.iter().all(|o| (o - 1.0).abs() < 1e-12),
                    "s = {s}: {out:?}"
                );
            }
            last = Some(out);
        }
    }
}
