//! Shared helpers of the integration tests.

pub mod hand_models;
pub mod lagrange;
pub mod rng;
pub mod run;
