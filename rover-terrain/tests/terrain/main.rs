//! The terrain crate's tests, one module per topic, in one test binary.

mod config;
mod files;
mod library;
mod random_field;
mod robustness;
mod soil_map;
mod support;
