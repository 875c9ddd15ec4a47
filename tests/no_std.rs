//! The no_std build is part of the test suite: the canary crate
//! tests/no_std_canary (`#![no_std]`, its own panic handler, a generated
//! plant) must build alone; a std dependency would fail it with E0152.
//! And "no panics" is checked on the machine code: no path of the
//! generated plant's entries and of its force path, compiled in release,
//! reaches a panic.

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

/// The release assembly of the canary, whose `rover_canary_<rover>`
/// functions call every entry of each built-in rover's generated plant
/// (both traits, the Jacobian) and `rover_canary_ground` swing4's whole
/// force path (contact search, wheel law, plant) on inputs the compiler
/// cannot see, holds no
/// call or jump to a panicking
/// function of core (bounds checks, unwraps, slice length checks, failed
/// assertions: `core::panicking::*`, `*_fail`, `unwrap_failed`,
/// `expect_failed`). A runtime index `x[len]` added to one makes this fail
/// (`panic_bounds_check`), so it sees what it looks for.
#[test]
fn the_generated_plant_has_no_path_to_a_panic() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target = root.join("target/no_std_canary_asm");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(root.join("tests/no_std_canary"))
        .args([
            "rustc",
            "--locked",
            "--quiet",
            "--release",
            "--lib",
            "--target-dir",
        ])
        .arg(&target)
        .args(["--", "--emit=asm", "-C", "codegen-units=1"])
        .output()
        .expect("run cargo");
    assert!(
        out.status.success(),
        "the no_std canary does not build in release:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let deps = target.join("release/deps");
    let asm = std::fs::read_dir(&deps)
        .expect("the canary's deps folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension().is_some_and(|e| e == "s")
                && p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with("rover_no_std_canary"))
        })
        .max_by_key(|p| std::fs::metadata(p).and_then(|m| m.modified()).ok())
        .expect("the canary's assembly");
    let text = std::fs::read_to_string(&asm).expect("read the assembly");
    // The entries and every generated function they call are compiled here
    // (whole: thousands of instructions), not folded away.
    for rover in ["swing4", "exomars", "mer", "lrv", "ground"] {
        let label = format!("rover_canary_{rover}:");
        assert!(text.contains(&label), "no {label} in {}", asm.display());
    }
    // (`derivatives_array` only picks a copy of the right-hand side, and
    // a no_std build picks at compile time: the portable one.)
    for f in [
        "derivatives_portable",
        "mass_matrix_array",
        "wheels_array",
        "jacobian_array",
    ] {
        assert!(
            text.lines().any(|l| l.ends_with(':') && l.contains(f)),
            "no label of {f} in {}",
            asm.display()
        );
    }
    let body = text.as_str();
    let instructions = body
        .lines()
        .filter(|l| l.starts_with('\t') && !l.starts_with("\t."))
        .count();
    assert!(
        instructions > 40_000,
        "only {instructions} instructions: the plant was folded away"
    );
    let panics: Vec<&str> = body
        .lines()
        .filter(|l| {
            let l = l.trim_start();
            (l.starts_with("call") || l.starts_with('j'))
                && ["panic", "_fail", "unwrap_failed", "expect_failed"]
                    .iter()
                    .any(|p| l.contains(p))
        })
        .collect();
    assert!(
        panics.is_empty(),
        "paths to a panic in {}:\n{}",
        asm.display(),
        panics.join("\n")
    );
}
