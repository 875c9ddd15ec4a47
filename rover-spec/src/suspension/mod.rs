//! The suspension library (MODEL.md §3): exact kinematics of each kind.

mod double_wishbone;
mod kinematics;
mod rocker;
mod rocker_bogie;
mod swing_arm;

pub use double_wishbone::DoubleWishbone;
pub use kinematics::Kinematics;
pub use rocker::Rocker;
pub use rocker_bogie::RockerBogie;
pub use swing_arm::SwingArm;
