//! Integration tests of rover-spec (one binary).

mod models;
