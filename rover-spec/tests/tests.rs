//! Integration tests of rover-spec (one binary).

mod errors;
mod fig1;
mod fuzz;
mod jet;
mod library;
mod builtin_models;
mod roundtrip;
