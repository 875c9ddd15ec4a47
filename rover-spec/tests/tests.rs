//! Integration tests of rover-spec (one binary).

mod builtin_models;
mod errors;
mod fig1;
mod fuzz;
mod jet;
mod library;
mod roundtrip;
