//! Integration tests of rover-spec (one binary).

mod errors;
mod fig1;
mod fuzz;
mod jet;
mod library;
mod models;
mod roundtrip;
