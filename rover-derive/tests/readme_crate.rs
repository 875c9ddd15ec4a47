//! A user's first crate, built from the README alone: its `[dependencies]`
//! are the lines of the README's "A rover declared in Rust" (each
//! `name = …` made a path to the workspace's crate), its `main`
//! declares a rover inline with `#[derive(Rover)]` and runs it for 1 s.
//! If the derive's code needs a crate the README does not name, or the
//! README's lines drift from what the code needs, this fails.
//!
//! The crate builds in `<target>/tmp/readme_crate`, kept between runs so
//! that a rerun rebuilds only what changed (a first build compiles the
//! workspace's crates and their dependencies once more, in that directory).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The `[dependencies]` lines of the ```toml block of the README's section
/// `heading`.
fn readme_dependencies(readme: &str, heading: &str) -> Vec<(String, String)> {
    let section = readme
        .split_once(heading)
        .unwrap_or_else(|| panic!("README.md has no section {heading:?}"))
        .1;
    let section = section.split("\n### ").next().unwrap_or(section);
    let block = section
        .split("```toml\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .unwrap_or_else(|| panic!("no ```toml block in the README's {heading:?}"));
    let mut lines = block.lines().map(str::trim).filter(|l| !l.is_empty());
    assert_eq!(lines.next(), Some("[dependencies]"), "{block}");
    lines
        .map(|l| {
            let (name, version) = l
                .split_once('=')
                .unwrap_or_else(|| panic!("not a dependency line: {l:?}"));
            (name.trim().to_string(), version.trim().to_string())
        })
        .collect()
}

/// The workspace directory of crate `name`, from `[workspace.dependencies]`.
fn crate_dir(root: &Path, name: &str) -> PathBuf {
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let line = manifest
        .lines()
        .find(|l| l.starts_with(&format!("{name} = {{ path = ")))
        .unwrap_or_else(|| panic!("the README names `{name}`, not a crate of the workspace"));
    let path = line.split('"').nth(1).unwrap();
    root.join(path)
}

const MAIN: &str = r#"
use rover_runtime::terrain::TerrainConfig;
use rover_scenario::Simulation;

#[derive(rover_derive::Rover)]
#[rover(
    name = "swing4", gravity = 1.62,
    body = { mass = 30.0, inertia = [0.7, 0.9, 1.5] },
    wheel_defaults = { mass = 0.6, radius = 0.09, stiffness = 4000.0, damping = 300.0,
        mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 50.0, max_torque = 1.29 },
    suspension = [
        { name = "fl", kind = "longitudinal_swing_arm", pivot = [0.18, 0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
        { name = "fr", kind = "longitudinal_swing_arm", pivot = [0.18, -0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
        { name = "rl", kind = "longitudinal_swing_arm", pivot = [-0.22, 0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
        { name = "rr", kind = "longitudinal_swing_arm", pivot = [-0.22, -0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
    ],
    wheel = [
        { name = "fl", suspension = "fl" }, { name = "fr", suspension = "fr" },
        { name = "rl", suspension = "rl" }, { name = "rr", suspension = "rr" },
    ],
)]
struct Swing4;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let summary = Simulation::new(Swing4::plant())
        .terrain(TerrainConfig::random(0.1))
        .settle(0.5)
        .speed(0.1)
        .run(1.0)?;
    assert!(summary.complete);
    println!("ran 1 s");
    Ok(())
}
"#;

#[test]
fn a_crate_with_the_readme_dependencies_builds_and_runs_a_derived_rover() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let dependencies = readme_dependencies(&readme, "### A rover declared in Rust");
    let names: Vec<&str> = dependencies.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"rover-derive"), "{names:?}");

    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme_crate");
    std::fs::create_dir_all(dir.join("src")).unwrap();
    let mut manifest = String::from(
        "[package]\nname = \"readme-crate\"\nversion = \"0.1.0\"\nedition = \"2024\"\npublish = false\n\n\
         # Not a member of the workspace it is built under.\n[workspace]\n\n[dependencies]\n",
    );
    for (name, version) in &dependencies {
        // The README's `{ path = "../rover/<crate>" }` is the workspace's
        // crate `<crate>`, wherever this checkout is.
        assert!(
            version.starts_with("{ path = \"../rover/") && version.contains(&format!("/{name}\"")),
            "`{name} = {version}`: the README gives no path to a checkout's crate"
        );
        let path = crate_dir(root, name);
        manifest.push_str(&format!(
            "{name} = {{ path = {:?} }}\n",
            path.display().to_string()
        ));
    }
    std::fs::write(dir.join("Cargo.toml"), manifest).unwrap();
    std::fs::write(dir.join("src/main.rs"), MAIN).unwrap();
    // The workspace's versions of the dependencies, without the network.
    std::fs::copy(root.join("Cargo.lock"), dir.join("Cargo.lock")).unwrap();

    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(&dir)
        .args(["run", "--offline", "--quiet", "--target-dir"])
        .arg(dir.join("target"))
        .env_remove("CARGO_TARGET_DIR")
        .output()
        .expect("run cargo");
    assert!(
        out.status.success(),
        "the README's crate does not build or run:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), "ran 1 s\n");
}
