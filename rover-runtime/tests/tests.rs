//! Integration tests of rover-runtime (one binary): the ground, the wheel
//! laws, the controllers and open-loop commands, the assembled system and
//! its Jacobian, conservation in free flight, the generated force path
//! against the runtime's, the model files against the hand-built rovers, and
//! the single-wheel testbed against published numbers.

mod commands;
mod control;
mod free_flight;
mod generated_ground;
mod ground;
mod hand_built_models;
mod jacobian;
mod soil_comparison;
mod wheel_law;
