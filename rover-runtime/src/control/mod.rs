//! Controllers (MODEL.md §8, paper §5): the speed loop and the torque
//! distribution, kinematic (Ackermann) and slip steering, heading hold with
//! line following (ours: slip steering closed on the heading), active
//! suspension, open-loop command schedules, and the time schedule of
//! set-points that drives them.

mod active_suspension;
mod commands;
mod controller;
mod distribution;
mod law;
mod profile;
mod speed;
mod steering;

pub use active_suspension::{
    ActiveSuspension, ActiveSuspensionConfig, LEVELING_CROSSOVER_PER_UPDATE, Leveling,
    SuspensionLaw,
};
pub use commands::{CommandFileError, CommandFileProblem, CommandSchedule, CommandsConfig};
pub use controller::{
    ControlError, Controller, ControllerConfig, HEADING_INTEGRAL, LINE_INTEGRAL, SPEED_INTEGRAL,
    heading_centre_x,
};
pub use distribution::{
    DEFAULT_SLIP_BAND, DEFAULT_SLIP_THRESHOLD, Distribution, add_anti_spin_share, add_share,
    anti_spin_weight,
};
pub use profile::{Interpolation, Profile, ProfileError};
pub use speed::SpeedConfig;
pub use steering::{
    Ackermann, HeadingActuator, HeadingHold, HeadingIntegrals, LEG_CHECK_PERIOD, LINE_INTEGRAL_CAP,
    Steering, ackermann_angle, curvature_from_angle, wrap_angle,
};
