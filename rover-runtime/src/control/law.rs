//! The controller's laws as it runs them: the `[control]` table checked
//! once, each choice settled into the variant that carries what it reads
//! (radians, the wheel an angle refers to, the torque weights), so that an
//! evaluation never matches configuration or converts units again.

use super::distribution::{Distribution, add_anti_spin_share, add_share};
use super::profile::Profile;
use super::steering::{HeadingHold, curvature_from_angle};

/// The speed loop: `τ_0 = K_p·(V − v_x) + K_i·ζ`, shared among the wheels.
#[derive(Clone, Debug)]
pub(crate) struct SpeedLaw {
    /// V [m/s] against time after settling.
    pub speed: Profile,
    pub kp: f64,
    pub ki: f64,
    pub shares: Shares,
}

/// How τ_0 is shared among the wheels.
#[derive(Clone, Debug)]
pub(crate) enum Shares {
    /// The same τ_0 on every wheel.
    Even,
    /// In proportion to the wheels' loads at this evaluation.
    MeasuredLoad,
    /// In proportion to the static loads on flat ground, found once.
    StaticLoad(Vec<f64>),
    /// By the anti-spin weights of the wheels' slips at this evaluation.
    AntiSpin { threshold: f64, band: f64 },
}

impl SpeedLaw {
    /// The settled loop of `distribution`, with the static loads when it
    /// needs them (`static_loads`' error when they cannot be found) and the
    /// anti-spin slip threshold and band (checked by the caller).
    pub(crate) fn new<E>(
        speed: Profile,
        (kp, ki): (f64, f64),
        distribution: Distribution,
        (threshold, band): (f64, f64),
        static_loads: impl FnOnce() -> Result<Vec<f64>, E>,
    ) -> Result<Self, E> {
        let shares = match distribution {
            Distribution::Even => Shares::Even,
            Distribution::MeasuredLoad => Shares::MeasuredLoad,
            Distribution::StaticLoad => Shares::StaticLoad(static_loads()?),
            Distribution::AntiSpin => Shares::AntiSpin { threshold, band },
        };
        Ok(Self {
            speed,
            kp,
            ki,
            shares,
        })
    }

    /// Adds τ_0's share to each wheel's torque in `out`, reading the
    /// wheels' normal loads `normals` and slips `slips` of this evaluation.
    pub(crate) fn add_shares(&self, tau0: f64, normals: &[f64], slips: &[f64], out: &mut [f64]) {
        match &self.shares {
            Shares::Even => out.iter_mut().for_each(|o| *o += tau0),
            Shares::MeasuredLoad => add_share(tau0, normals, out),
            Shares::StaticLoad(weights) => add_share(tau0, weights, out),
            Shares::AntiSpin { threshold, band } => {
                add_anti_spin_share(tau0, slips, *threshold, *band, out)
            }
        }
    }

    /// Whether the shares read the wheels' slips.
    pub(crate) fn reads_slip(&self) -> bool {
        matches!(self.shares, Shares::AntiSpin { .. })
    }
}

/// Steering, settled.
#[derive(Clone, Debug)]
pub(crate) enum SteeringLaw {
    /// Straight ahead.
    None,
    /// A torque difference Δτ [N·m] against time after settling.
    Slip { delta_tau: Profile },
    /// Kinematic steering towards a turn centre at body x `centre_x`.
    Ackermann {
        curvature: CurvatureCommand,
        centre_x: f64,
    },
    /// A heading hold through `hold.via`, its set-point in radians.
    Heading {
        hold: HeadingHold,
        /// ψ_ref \[rad\] against time after settling.
        heading: Profile,
        /// The turn centre's body x when it steers by Ackermann.
        centre_x: f64,
    },
}

/// What an Ackermann command gives: the turn radius, or the first
/// steerable wheel's angle.
#[derive(Clone, Debug)]
pub(crate) enum CurvatureCommand {
    /// R \[m\] against time; κ = 1/R (0 for R = 0).
    Radius(Profile),
    /// δ_1 \[rad\] against time, of the wheel at rest body (x, y) `wheel`.
    Angle { radians: Profile, wheel: (f64, f64) },
}

impl CurvatureCommand {
    /// κ = 1/R \[1/m\] at time `tc` after settling, for a turn centre at
    /// body x `centre_x`.
    pub(crate) fn curvature(&self, tc: f64, centre_x: f64) -> f64 {
        match self {
            CurvatureCommand::Radius(r) => {
                let r = r.at(tc);
                if r == 0.0 { 0.0 } else { 1.0 / r }
            }
            CurvatureCommand::Angle { radians, wheel } => {
                curvature_from_angle(radians.at(tc), wheel.0, wheel.1, centre_x)
            }
        }
    }

    /// The profile a set-point replaces: the radius \[m\] or the angle, kept
    /// in radians (`value` is in degrees for an angle, as the scenario's
    /// `front_left_deg`).
    pub(crate) fn hold(&mut self, value: f64) {
        match self {
            CurvatureCommand::Radius(r) => *r = Profile::Constant(value),
            CurvatureCommand::Angle { radians, .. } => {
                *radians = Profile::Constant(value.to_radians())
            }
        }
    }

    /// The command's profile, for its breakpoints.
    pub(crate) fn profile(&self) -> &Profile {
        match self {
            CurvatureCommand::Radius(p) => p,
            CurvatureCommand::Angle { radians, .. } => radians,
        }
    }
}
