//! Wheel–ground force laws (MODEL.md §7, paper §4.2).

mod chen_genta;
mod law;
mod magic_formula;

pub use chen_genta::ChenGenta;
pub use law::{
    DAMPING_RAMP, PatchForces, PatchMotion, ROLLING_V_EPS, Tyre, WheelLaw, WheelLawConfig,
    normal_force as normal_force_of, rolling_resistance,
};
pub use magic_formula::MagicFormula;
