//! Wheels: tyre, motor, steering, and the suspension point they sit on.

use serde::{Deserialize, Serialize};

use super::Inertia;

/// Where the drive motor's stator is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MotorMountDesc {
    /// In the hub: the reaction acts on the wheel carrier.
    Hub,
    /// On the body (the paper's formulation).
    Body,
}

/// A wheel: the suspension point its centre sits on, and its properties
/// (each may come from `[wheel_defaults]` instead).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// The suspension carrying it.
    pub suspension: String,
    /// The suspension's point at the wheel centre (optional when the
    /// suspension has a single wheel point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
    /// Wheel mass \[kg\] ≥ 0, radius \[m\] > 0, tyre, motor and steering.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Inertia about the wheel centre [kg·m²] (no spin energy), optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<Inertia>,
    /// Radius R_w \[m\], > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Width b \[m\], > 0 and narrower than the rover's track: what the
    /// soil law presses on (required on a soil, unused on rigid ground).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Moment of inertia about the axle [kg·m²], > 0: the wheel's and
    /// the drive train's, reflected to the wheel (on a soil the wheel's spin
    /// is a state; default ½·mass·radius², a uniform disc).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin_inertia: Option<f64>,
    /// Radial stiffness k_w [N/m], > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Radial damping c_w [N·s/m], ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Longitudinal friction limit μx_max, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_x: Option<f64>,
    /// Lateral friction limit μy_max, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_y: Option<f64>,
    /// Cornering stiffness C [N/rad], > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cornering_stiffness: Option<f64>,
    /// Maximum motor torque M_sat [N·m], ≥ 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_torque: Option<f64>,
    /// The motor's no-load speed ω₀ [rad/s], > 0: with it the motor
    /// follows the DC line τ_stall·(1 − ω/ω₀) (absent: a pure torque
    /// source up to `max_torque` at any speed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_load_speed: Option<f64>,
    /// The motor's stall torque τ_stall [N·m], > 0 (needs `no_load_speed`;
    /// default `max_torque`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stall_torque: Option<f64>,
    /// `hub` or `body`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor: Option<MotorMountDesc>,
    /// Whether a steering angle is commanded on this wheel.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steerable: Option<bool>,
}

/// The `[wheel_defaults]` table: any wheel property, taken by every wheel
/// that does not set it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WheelFields {
    /// Wheel mass \[kg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// Inertia about the wheel centre [kg·m²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<Inertia>,
    /// Radius \[m\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// Width \[m\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// Moment of inertia about the axle [kg·m²].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spin_inertia: Option<f64>,
    /// Radial stiffness [N/m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Radial damping [N·s/m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// μx_max.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_x: Option<f64>,
    /// μy_max.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_y: Option<f64>,
    /// Cornering stiffness [N/rad].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cornering_stiffness: Option<f64>,
    /// M_sat [N·m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_torque: Option<f64>,
    /// No-load speed ω₀ [rad/s].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub no_load_speed: Option<f64>,
    /// Stall torque τ_stall [N·m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stall_torque: Option<f64>,
    /// `hub` or `body`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motor: Option<MotorMountDesc>,
    /// Steerable.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steerable: Option<bool>,
}
