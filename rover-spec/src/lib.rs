//! Rover descriptions, validated into a [`rover_dynamics::Model`].
#![warn(missing_docs)]

pub mod linkage;
