//! The no_std build is part of the test suite (issue 6): the canary crate
//! tests/no_std_canary (`#![no_std]`, its own panic handler, a generated
//! plant) must build alone; a std dependency would fail it with E0152.

use std::path::Path;
use std::process::Command;

#[test]
fn a_generated_plant_builds_in_a_no_std_crate() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(root.join("tests/no_std_canary"))
        .args(["build", "--locked", "--quiet", "--target-dir"])
        .arg(root.join("target/no_std_canary"))
        .output()
        .expect("run cargo");
    assert!(
        out.status.success(),
        "the no_std canary does not build:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
