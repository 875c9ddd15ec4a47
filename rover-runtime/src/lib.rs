//! The rover runtime: everything around the plant.
#![warn(missing_docs)]
pub mod integrate;
