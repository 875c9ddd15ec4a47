//! The workspace's integration tests, one binary (STYLE.md §6).

mod support;

mod breakpoints;
mod cli;
mod codegen;
mod commands;
mod control;
#[cfg(feature = "drive")]
mod drive;
mod failures;
mod fidelity;
mod fixed_step;
mod free_flight;
mod generated_ground;
mod ground;
mod hand_built_models;
mod hostile;
mod jacobian;
mod linearize;
mod no_std;
mod paper_accuracy;
mod profile;
#[cfg(feature = "reproduce")]
mod reproduction;
mod sweep;
mod wheel_law;
