//! Wheel–ground force laws (MODEL.md §7, paper §4.2).

mod chen_genta;
mod law;
mod magic_formula;

pub use chen_genta::ChenGenta;
pub use law::WheelLawConfig;
pub use magic_formula::MagicFormula;
