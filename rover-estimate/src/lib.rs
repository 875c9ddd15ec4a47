//! The rover as an observer in its own control loop (F. Chen and G. Genta,
//! Acta Astronautica 81 (2012) 288–305, §1: "an observer in the control
//! loop of autonomous rovers"), from the same declaration as the plant:
//!
//! - [`sensors`]: what a rover's sensors read, declared in datasheet units
//!   ([`SensorConfig`]) and held in SI; one instant's readings
//!   ([`SensorSample`]);
//! - [`process`]: what the filter needs of the rover model
//!   ([`ProcessModel`]): the right-hand side under commanded torques and
//!   steering, its Jacobian, and the wheels' spin rates;
//! - [`simulate`]: the readings of the declared sensors when the motion is
//!   known ([`SensorSimulator`]), with seeded noise: what a simulated run
//!   gives a filter to read;
//! - [`dead_reckoning`]: the baseline without a model, a complementary
//!   filter on the gyros and accelerometers and the wheels' odometry;
//! - [`filter`]: the model-based error-state extended Kalman filter
//!   ([`Estimator`]) over any process model;
//! - `runtime` (feature `runtime`, with std): the rover runtime's
//!   `RoverSystem` as a process model.
//!
//! The crate is `#![no_std]` with `alloc`: buffers are sized once, when a
//! filter is built, and no step allocates. The repository's
//! `docs/ESTIMATE.md` gives the equations as implemented.
#![no_std]
#![warn(missing_docs)]

extern crate alloc;

pub mod consistency;
pub mod dead_reckoning;
pub mod filter;
pub mod process;
mod rotation;
#[cfg(feature = "runtime")]
pub mod runtime;
pub mod sensors;
pub mod simulate;

pub use dead_reckoning::{DeadReckoning, DeadReckoningConfig};
pub use filter::{EstimateError, Estimator, FilterConfig, InitialSigma};
pub use process::ProcessModel;
pub use sensors::{SensorConfig, SensorSample};
pub use simulate::{SensorSimulator, Truth};
