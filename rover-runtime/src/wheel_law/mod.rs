//! Wheel–ground force laws (MODEL.md §7, paper §4.2).

mod chen_genta;
mod law;
mod magic_formula;

pub use chen_genta::ChenGenta;
pub use law::{PatchForces, PatchMotion, Tyre, WheelLaw, WheelLawConfig};
pub use magic_formula::MagicFormula;
pub use rover_dynamics::wheel_law::{
    DAMPING_RAMP, ROLLING_V_EPS, normal_force as normal_force_of, rolling_resistance,
};
