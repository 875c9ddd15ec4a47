//! Where a run's right-hand sides spend their time, when a scenario asks
//! (`profile = true`).

use std::time::Instant;

use serde::Serialize;

/// Wall time spent in each part of the right-hand sides so far \[s\].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RhsProfile {
    /// Evaluations timed.
    pub evaluations: u64,
    /// Steering and the wheels' kinematics (positions, velocities, axes).
    pub wheels_s: f64,
    /// The contact search.
    pub contact_s: f64,
    /// The controller's torques, the wheel law and its reduction to loads.
    pub law_s: f64,
    /// The plant's accelerations and the controller's integral rates.
    pub plant_s: f64,
}

/// A clock read at the boundaries of the parts of one evaluation.
pub(crate) struct Lap(Instant);

impl Lap {
    pub(crate) fn start() -> Lap {
        Lap(Instant::now())
    }

    /// Seconds since the last lap, and a new lap.
    pub(crate) fn next(&mut self) -> f64 {
        let now = Instant::now();
        let dt = now.duration_since(self.0).as_secs_f64();
        self.0 = now;
        dt
    }
}

/// A run's profile in its summary: where its wall time went \[s\] and as
/// shares of it. Reading the clock costs a few percent of a right-hand side.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Profile {
    /// Right-hand sides timed (the integrator's, and one per output row).
    pub evaluations: u64,
    /// Wheels' kinematics and steering \[s\].
    pub wheels_s: f64,
    /// Contact search \[s\].
    pub contact_s: f64,
    /// Controller torques, wheel law, loads \[s\].
    pub law_s: f64,
    /// Plant (dynamics) \[s\].
    pub plant_s: f64,
    /// Everything else: the integrator's own work (Newton, Jacobian
    /// assembly, LU, error control), the run driver and the output \[s\].
    pub integrator_and_output_s: f64,
}

impl Profile {
    /// The profile of a run of `wall` seconds whose right-hand sides took `rhs`.
    pub fn new(rhs: &RhsProfile, wall: f64) -> Profile {
        let parts = rhs.wheels_s + rhs.contact_s + rhs.law_s + rhs.plant_s;
        Profile {
            evaluations: rhs.evaluations,
            wheels_s: rhs.wheels_s,
            contact_s: rhs.contact_s,
            law_s: rhs.law_s,
            plant_s: rhs.plant_s,
            integrator_and_output_s: (wall - parts).max(0.0),
        }
    }

    /// The whole time accounted for \[s\].
    pub fn total_s(&self) -> f64 {
        self.wheels_s + self.contact_s + self.law_s + self.plant_s + self.integrator_and_output_s
    }
}
