//! Integration tests of rover-spec (one binary).

mod errors;
mod fig1;
mod fuzz;
mod library;
mod models;
mod roundtrip;
