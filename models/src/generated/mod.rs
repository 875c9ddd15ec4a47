//! The built-in rovers as generated plants (written by rover-codegen; the
//! golden test in rover-codegen/tests/golden.rs keeps them current).

pub mod exomars;
pub mod lrv;
pub mod mer;
pub mod swing4;
pub mod swing4_linearized;
pub mod swing4_simplified;
