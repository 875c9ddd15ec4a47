//! `rover export`: the C library's example, compiled with the system's C
//! compiler and run, ends where `rover simulate` ends; the FMU's archive
//! holds what FMI asks for; bad arguments are named. (FMPy checks the
//! FMUs themselves: python/tests/test_fmu.py.)

use std::path::{Path, PathBuf};
use std::process::Command;

use rover::cli::{CArgs, ExportArgs, ExportKind, FmiArg, FmuArgs, InputsArg, SimulateArgs};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("export")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The prebuilt plant library: the tests depend on `rover-plant`, so
/// cargo has built it into this profile's `deps/` before them.
fn plant_library(file: &str) -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let p = deps.join(file);
    assert!(
        p.is_file(),
        "{} is missing: cargo builds it as the tests' dependency",
        p.display()
    );
    p
}

#[test]
fn the_c_example_ends_where_rover_simulate_ends() {
    let dir = scratch("c");
    let scenario = root().join("scenarios/export_rough.toml");
    let report = rover::cli::simulate(&SimulateArgs {
        rover: None,
        scenario: scenario.clone(),
        out: dir.join("sim"),
        quiet: true,
        no_plots: true,
        generic: false,
        mcap: false,
    })
    .unwrap();
    assert!(report.summary.complete);
    let csv = std::fs::read_to_string(dir.join("sim/run.csv")).unwrap();
    let names: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last[0], 10.0);

    let out = dir.join("rover-c");
    let written = rover::cli::export(&ExportArgs {
        kind: ExportKind::C(CArgs {
            rover: None,
            scenario,
            out: out.clone(),
            library: Some(plant_library("librover_plant.a")),
        }),
    })
    .unwrap();
    assert_eq!(written.outputs, names.len());
    for f in [
        "rover_plant.h",
        "librover_plant.a",
        "main.c",
        "scenario/scenario.toml",
        "scenario/export_rough.asc",
    ] {
        assert!(out.join(f).is_file(), "{f}");
    }
    // The command the export prints, as a user runs it.
    let compile = rover_export::package::compile_command();
    let status = Command::new("sh")
        .arg("-c")
        .arg(&compile)
        .current_dir(&out)
        .status()
        .unwrap();
    assert!(status.success(), "{compile}");
    let run = Command::new(out.join("rover_main"))
        .current_dir(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let printed = String::from_utf8(run.stdout).unwrap();
    let lines: Vec<(&str, f64)> = printed
        .lines()
        .map(|l| {
            let (n, v) = l.split_once(' ').unwrap();
            (n, v.parse().unwrap())
        })
        .collect();
    assert_eq!(lines.len(), names.len());
    for ((name, value), (csv_name, csv_value)) in lines.iter().zip(names.iter().zip(&last)) {
        assert_eq!(name, csv_name);
        // %.17g and Rust's shortest form name the same double.
        assert_eq!(
            value, csv_value,
            "{name}: the C example's final state is the CLI's"
        );
    }
}

#[test]
fn an_fmu_holds_its_description_library_and_resources() {
    let dir = scratch("fmu");
    let out = dir.join("swing4.fmu");
    let written = rover::cli::export(&ExportArgs {
        kind: ExportKind::Fmu(FmuArgs {
            rover: Some("swing4".into()),
            scenario: root().join("scenarios/export_rough.toml"),
            out: out.clone(),
            fmi: FmiArg::Three,
            inputs: InputsArg::Torques,
            library: Some(plant_library("librover_plant.so")),
        }),
    })
    .unwrap();
    assert_eq!(written.identifier, "swing4_export_rough");
    // Four torques and four spring neutrals: swing4 steers none of its wheels.
    assert_eq!((written.outputs, written.inputs), (69, 4 + 4));
    let zip = std::fs::read(&out).unwrap();
    let text = String::from_utf8_lossy(&zip);
    for entry in [
        "modelDescription.xml",
        "binaries/x86_64-linux/swing4_export_rough.so",
        "resources/scenario.toml",
        "resources/export.toml",
        "resources/export_rough.asc",
    ] {
        if entry.contains("x86_64-linux") && !cfg!(all(target_arch = "x86_64", target_os = "linux"))
        {
            continue;
        }
        assert!(text.contains(entry), "{entry}");
    }
    assert!(text.contains(r#"<Float64 name="tau1_cmd" valueReference="70""#));
}

#[test]
fn export_names_a_missing_library_and_a_bad_scenario() {
    let dir = scratch("bad");
    let fmu = |library: Option<PathBuf>, scenario: &str| {
        rover::cli::export(&ExportArgs {
            kind: ExportKind::Fmu(FmuArgs {
                rover: None,
                scenario: root().join(scenario),
                out: dir.join("x.fmu"),
                fmi: FmiArg::Two,
                inputs: InputsArg::None,
                library,
            }),
        })
        .unwrap_err()
        .user_message()
    };
    let m = fmu(Some(dir.join("nowhere.so")), "scenarios/export_rough.toml");
    assert!(
        m.starts_with("error: --library ")
            && m.contains("no such file")
            && m.contains("cargo build -p rover-plant"),
        "{m}"
    );
    let m = fmu(
        Some(plant_library("librover_plant.so")),
        "scenarios/nowhere.toml",
    );
    assert!(
        m.contains("nowhere.toml") && m.contains("cannot read the scenario file"),
        "{m}"
    );
}
