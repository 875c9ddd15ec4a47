//! The workspace's integration tests, one binary (STYLE.md §6).

mod support;

mod codegen;
mod dynamics;
mod free_flight;
mod ground;
mod models;
mod no_std;
