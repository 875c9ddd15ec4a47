//! Integration tests of rover-runtime (one binary): the ground, the wheel
//! laws, the controllers and open-loop commands, the assembled system and
//! its Jacobian, conservation in free flight, the generated force path
//! against the runtime's, and the model files against the hand-built rovers.

mod commands;
mod control;
mod free_flight;
mod generated_ground;
mod ground;
mod hand_built_models;
mod jacobian;
mod wheel_law;
