//! The numeric rover model: every number the equations read, already
//! validated (MODEL.md §3–§4, §7).
//!
//! `rover-spec` turns a description (TOML or Rust) into this value; the
//! generic plant interprets it at run time and the code generator folds it
//! into constants. Nothing here is checked again: build it through
//! `rover-spec`, or keep to the invariants stated on each field.

use alloc::vec::Vec;

use crate::poly::{PolyVec, ScalarPoly};

/// A whole rover: the body, the suspension coordinates, the bodies the
/// suspensions carry and the wheels.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    /// Gravitational acceleration g [m/s²], acting along −e_Z.
    pub gravity: f64,
    /// The rover body (the sprung mass).
    pub body: RigidBody,
    /// Suspension coordinates y_1 … y_m, in order.
    pub coordinates: Vec<Coordinate>,
    /// Bodies carried by the suspensions (wheels, arms with mass), j = 1 … n.
    pub bodies: Vec<CarriedBody>,
    /// Wheels, in the description's order (CSV columns follow it).
    pub wheels: Vec<Wheel>,
}

/// Mass and inertia of the body, at G, body components.
#[derive(Clone, Debug, PartialEq)]
pub struct RigidBody {
    /// Mass m_B \[kg\], > 0.
    pub mass: f64,
    /// Inertia tensor J_B about G in body components [kg·m²], symmetric
    /// positive definite.
    pub inertia: [[f64; 3]; 3],
}

/// One suspension coordinate y_i and the forces that act along it.
#[derive(Clone, Debug, PartialEq)]
pub struct Coordinate {
    /// Rest value y_c [rad or m]: the initial value and the centre of the
    /// polynomial expansions (the "rest configuration" of MODEL.md §9).
    pub rest: f64,
    /// Neutral value y_0 of the spring (eq. 21): the spring force is zero there.
    pub neutral: f64,
    /// The spring.
    pub spring: Spring,
    /// Linear damping c_i [N·m·s/rad or N·s/m], ≥ 0.
    pub damping: f64,
    /// Lower travel limit y_min.
    pub min: f64,
    /// Upper travel limit y_max, > `min`.
    pub max: f64,
    /// Bump-stop stiffness beyond the travel limits, > 0.
    pub stop_stiffness: f64,
    /// Bump-stop damping beyond the travel limits, ≥ 0.
    pub stop_damping: f64,
}

/// The elastic law of a suspension coordinate.
#[derive(Clone, Debug, PartialEq)]
pub enum Spring {
    /// No spring (a free rocker or differential).
    None,
    /// Linear spring: generalized force `−k·(y − y_0)`; k ≥ 0.
    Linear {
        /// Stiffness k [N·m/rad or N/m].
        stiffness: f64,
    },
    /// Nonlinear spring given as a table of the restoring generalized force
    /// against the deflection `y − y_0`, interpolated linearly and extended
    /// linearly with the end slopes beyond the table. The deflections are
    /// strictly increasing; the table passes through (0, 0).
    Table {
        /// Deflections `y − y_0` [rad or m], strictly increasing, ≥ 2 points.
        deflection: Vec<f64>,
        /// Spring force at each deflection [N·m or N]: positive pushes y up,
        /// so a stiffening spring has `force` decreasing.
        force: Vec<f64>,
    },
}

/// A body carried by the suspensions: its centre G_j, its mass and the
/// member (arm, rocker, bogie, upright) that holds it.
#[derive(Clone, Debug, PartialEq)]
pub struct CarriedBody {
    /// Mass m_j \[kg\], ≥ 0 (the paper's arms are massless).
    pub mass: f64,
    /// Optional inertia J_j about G_j [kg·m²], in body components at the rest
    /// configuration; it turns with the member (MODEL.md §3). Only allowed
    /// when `member` has at most one rotation.
    pub inertia: Option<[[f64; 3]; 3]>,
    /// Position of G_j in body components, `u_j(y)` (eq. 6, 32).
    pub position: PolyVec,
    /// Rotations of the member carrying G_j relative to the body, one per
    /// coordinate it depends on (eq. 16): the member's angular velocity is
    /// `Ω + Σ_i axis_i·angle_i'(y_i)·ẏ_i`. Empty: the body carries it.
    pub member: Vec<MemberRotation>,
}

/// How a member turns with one suspension coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct MemberRotation {
    /// Index i of the coordinate.
    pub coord: usize,
    /// Unit axis a in body components.
    pub axis: [f64; 3],
    /// Member angle about `axis` relative to the rest configuration, as a
    /// polynomial in `y_i` (zero at the rest value). For an arm on a pivot
    /// this is `y_i − y_ic`; for a wishbone upright it is `γ(y) − γ(y_c)`.
    pub angle: ScalarPoly,
}

/// Where the motor's stator is, hence where its reaction torque acts (MODEL.md §7).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotorMount {
    /// In the wheel hub: the reaction acts on the member carrying the wheel.
    Hub,
    /// On the body (the paper's formulation, eq. 23).
    Body,
}

/// A DC motor's torque–speed characteristic: at full drive voltage the
/// torque falls on the line τ_stall·(1 − ω/ω₀) from the stall torque at
/// rest to zero at the no-load speed ω₀ (docs/DESCRIPTION.md, "Motors").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotorCurve {
    /// Stall torque τ_stall [N·m], > 0: the torque at ω = 0 on the line.
    pub stall_torque: f64,
    /// No-load speed ω₀ [rad/s], > 0: the wheel's spin rate at which the
    /// line reaches zero torque.
    pub no_load_speed: f64,
}

impl MotorCurve {
    /// The torques the motor can give at the wheel's spin rate `omega`
    /// [rad/s] (positive rolling forward), `(lo, hi)` with lo ≤ 0 ≤ hi:
    /// - in the direction of the spin, τ_stall·(1 − |ω|/ω₀) clamped to
    ///   [0, τ_stall] (nothing more at or beyond the no-load speed);
    /// - against it (braking, or reversing), τ_stall·(1 + |ω|/ω₀) clamped
    ///   to τ_stall: the full stall torque, as a DC motor driven against
    ///   its back-EMF gives up to its current limit.
    ///
    /// Symmetric: the reverse direction sees the mirrored line. The drive's
    /// `max_torque` caps both sides on top of this.
    pub fn limits(&self, omega: f64) -> (f64, f64) {
        let line = |w: f64| self.stall_torque * (1.0 - w / self.no_load_speed).clamp(0.0, 1.0);
        (-line(-omega), line(omega))
    }
}

/// A wheel: its centre is a carried body; its tyre, motor and orientation.
#[derive(Clone, PartialEq)]
pub struct Wheel {
    /// Index j of the carried body at the wheel centre.
    pub body: usize,
    /// Radius R_w \[m\], > 0.
    pub radius: f64,
    /// Width b \[m\], > 0, when the description gives one: the soil law
    /// needs it (docs/MODEL.md, "Soft soil"); rigid ground does not.
    pub width: Option<f64>,
    /// Moment of inertia about the axle [kg·m²], ≥ 0: the inertia of the
    /// wheel's spin, a state on a soil.
    pub spin_inertia: f64,
    /// Radial stiffness k_w [N/m], > 0 (eq. 36).
    pub stiffness: f64,
    /// Radial damping c_w [N·s/m], ≥ 0 (eq. 37).
    pub damping: f64,
    /// Longitudinal friction limit μx_max, > 0 (eq. 39).
    pub mu_x: f64,
    /// Lateral friction limit μy_max, > 0 (eq. 40).
    pub mu_y: f64,
    /// Cornering stiffness C [N/rad], > 0 (eq. 40).
    pub cornering_stiffness: f64,
    /// Maximum motor torque M_sat [N·m], ≥ 0.
    pub max_torque: f64,
    /// The motor's torque–speed line, when the description gives one;
    /// `None`: a pure torque source up to `max_torque` at any speed.
    pub motor_curve: Option<MotorCurve>,
    /// Stator location of the drive motor.
    pub motor: MotorMount,
    /// Whether a steering angle δ_j is commanded on this wheel.
    pub steerable: bool,
    /// Camber γ_j(y) \[rad\] (MODEL.md §3, wheel orientation).
    pub camber: ScalarPoly,
    /// Suspension-induced steer ε_j(y) \[rad\].
    pub toe: ScalarPoly,
}

// By hand: a wheel without a motor curve prints as it did before the
// field existed, so the model's fingerprint (the generated modules'
// headers) depends only on what the description gives.
impl core::fmt::Debug for Wheel {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let mut d = f.debug_struct("Wheel");
        d.field("body", &self.body)
            .field("radius", &self.radius)
            .field("width", &self.width)
            .field("spin_inertia", &self.spin_inertia)
            .field("stiffness", &self.stiffness)
            .field("damping", &self.damping)
            .field("mu_x", &self.mu_x)
            .field("mu_y", &self.mu_y)
            .field("cornering_stiffness", &self.cornering_stiffness)
            .field("max_torque", &self.max_torque);
        if let Some(curve) = &self.motor_curve {
            d.field("motor_curve", curve);
        }
        d.field("motor", &self.motor)
            .field("steerable", &self.steerable)
            .field("camber", &self.camber)
            .field("toe", &self.toe)
            .finish()
    }
}

impl Wheel {
    /// The torques the motor can give at the wheel's spin rate `omega`
    /// [rad/s], `(lo, hi)`: ±`max_torque`, narrowed by the motor curve
    /// when there is one ([`MotorCurve::limits`]).
    pub fn torque_limits(&self, omega: f64) -> (f64, f64) {
        let cap = self.max_torque;
        match &self.motor_curve {
            None => (-cap, cap),
            Some(c) => {
                let (lo, hi) = c.limits(omega);
                (lo.max(-cap), hi.min(cap))
            }
        }
    }

    /// The tyre's constants for the wheel law, without rolling resistance
    /// (a scenario's option): what the runtime's ground and a generated
    /// plant's `TYRES` both take.
    pub fn tyre(&self) -> crate::wheel_law::Tyre {
        crate::wheel_law::Tyre {
            stiffness: self.stiffness,
            damping: self.damping,
            mu_x: self.mu_x,
            mu_y: self.mu_y,
            cornering_stiffness: self.cornering_stiffness,
            rolling_resistance: 0.0,
        }
    }
}

impl Model {
    /// Number of suspension coordinates m.
    pub fn m(&self) -> usize {
        self.coordinates.len()
    }
    /// Number of generalized coordinates (and of pseudo-velocities), 6 + m.
    pub fn dof(&self) -> usize {
        6 + self.coordinates.len()
    }
    /// Total mass m_B + Σ m_j \[kg\].
    pub fn total_mass(&self) -> f64 {
        self.body.mass + self.bodies.iter().map(|b| b.mass).sum::<f64>()
    }
    /// The rest values y_c of every coordinate.
    pub fn rest(&self) -> Vec<f64> {
        self.coordinates.iter().map(|c| c.rest).collect()
    }

    /// Each wheel centre's body-frame position at rest \[m\], in the
    /// description's wheel order.
    pub fn rest_wheel_centres(&self) -> Vec<[f64; 3]> {
        let rest = self.rest();
        self.wheels
            .iter()
            .map(|w| self.bodies[w.body].position.value(&rest))
            .collect()
    }

    /// Height Z of G at which the rover, level and at rest, has its lowest
    /// wheel just touching flat ground at Z = 0 \[m\].
    pub fn touchdown_height(&self) -> f64 {
        let rest = self.rest();
        let lowest = self
            .wheels
            .iter()
            .map(|w| self.bodies[w.body].position.value(&rest)[2] - w.radius)
            .fold(f64::INFINITY, f64::min);
        -lowest
    }
}

#[cfg(test)]
mod tests {
    use super::MotorCurve;

    #[test]
    fn a_dc_motor_gives_its_stall_torque_at_rest_and_none_at_its_no_load_speed() {
        let m = MotorCurve {
            stall_torque: 2.0,
            no_load_speed: 10.0,
        };
        assert_eq!(m.limits(0.0), (-2.0, 2.0));
        // Driving: the line; nothing at or beyond ω₀.
        assert_eq!(m.limits(2.5).1, 1.5);
        assert_eq!(m.limits(10.0).1, 0.0);
        assert_eq!(m.limits(25.0).1, 0.0);
        // Braking against the spin: the full stall torque at any speed.
        assert_eq!(m.limits(2.5).0, -2.0);
        assert_eq!(m.limits(25.0).0, -2.0);
        // Reversing: the mirrored line.
        assert_eq!(m.limits(-2.5), (-1.5, 2.0));
        assert_eq!(m.limits(-10.0), (0.0, 2.0));
    }
}
