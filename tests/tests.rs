//! The workspace's integration tests, one binary (one link for the whole
//! suite): whole runs from scenarios, the CLI, the generated plants against
//! the generic one, no_std. Each crate's own tests are in its `tests/`.

mod support;

mod breakpoints;
mod cli;
mod codegen;
mod commands;
mod control;
#[cfg(feature = "drive")]
mod drive;
mod export;
mod failures;
mod fidelity;
mod fixed_step;
mod fuzz_loaders;
mod ground;
mod hostile;
mod linearize;
mod motors;
mod no_std;
mod paper_accuracy;
mod profile;
#[cfg(feature = "reproduce")]
mod reproduction;
#[cfg(feature = "plots")]
mod rut_outputs;
mod ruts;
mod soil;
mod steer_characteristic;
mod sweep;
#[cfg(unix)]
mod untrusted_files;
mod wheel_law;
