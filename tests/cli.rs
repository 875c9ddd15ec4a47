//! The command line end to end: every output file of both paper
//! rovers, located errors for bad scenario files, exit codes.

use std::path::{Path, PathBuf};
use std::process::Command;

use rover::cli::{CheckArgs, LinearizeArgs, SimulateArgs, check, linearize_cmd, simulate};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn simulate_writes_every_output_for_both_paper_rovers() {
    for rover in ["exomars", "swing4"] {
        let dir = scratch(rover);
        let scenario = write(
            &dir,
            "s.toml",
            "duration = 3.0\nsettle = 1.0\n[control.speed]\nspeed = 0.05\n[integrator.bdf]\nrtol = 1e-5\n",
        );
        let out = dir.join("out");
        let args = SimulateArgs {
            rover: Some(rover.into()),
            scenario,
            out: out.clone(),
            quiet: true,
            no_plots: false,
            generic: false,
            mcap: false,
        };
        let report = simulate(&args).unwrap();
        assert!(report.summary.complete);
        let mut expected = vec!["run.csv".to_string(), "summary.json".to_string()];
        for stem in [
            "trajectory_xz",
            "trajectory_xy",
            "coordinates",
            "torques",
            "speed",
            "forces",
        ] {
            expected.push(format!("{stem}.png"));
            expected.push(format!("{stem}.svg"));
        }
        for f in &expected {
            let p = out.join(f);
            assert!(
                p.metadata().map(|m| m.len() > 0).unwrap_or(false),
                "{rover}: {f} missing or empty"
            );
        }
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["status"], "completed");
        assert_eq!(summary["final_state"]["t"], 3.0);
        // Driving as commanded (0.05 m/s for the 2 s after settling): no stall.
        let (went, asked) = (&summary["distance_m"], &summary["commanded_distance_m"]);
        assert!((asked.as_f64().unwrap() - 0.1).abs() < 1e-9, "{asked}");
        assert!((went.as_f64().unwrap() - 0.1).abs() < 0.03, "{went}");
        assert!(summary.get("stalled").is_none(), "{summary}");
        assert!(
            summary["plant"].as_str().unwrap().starts_with("generated"),
            "built-in rovers run their generated plant"
        );
        // The integrator's work adds up: BDF differentiates by differences,
        // one right-hand side per state component for each Jacobian, and
        // every step attempt evaluates at least once more; a Jacobian is
        // always followed by a factorization.
        let count = |k: &str| {
            summary[k]
                .as_u64()
                .unwrap_or_else(|| panic!("{k}: {summary}"))
        };
        let (evals, jacs, lus) = (
            count("rhs_evals"),
            count("jacobian_evals"),
            count("lu_decompositions"),
        );
        let attempts = count("steps") + count("rejected_steps");
        let dim = report.summary.final_state.len() as u64 - 1; // less `t`
        assert!(jacs >= 1 && lus >= jacs, "{summary}");
        assert!(evals >= attempts + jacs * dim, "{summary}");
        let csv = std::fs::read_to_string(out.join("run.csv")).unwrap();
        assert_eq!(
            csv.lines().count(),
            1 + 61,
            "{rover}: header + 61 rows at 20 Hz over 3 s"
        );
    }
}

fn bad_scenario(text: &str) -> String {
    bad_scenario_in("bad", text)
}

/// The error of simulating swing4 with scenario `text` in scratch folder
/// `name` (outputs in `name/out`).
fn bad_scenario_in(name: &str, text: &str) -> String {
    let dir = scratch(name);
    let scenario = write(&dir, "bad.toml", text);
    let args = SimulateArgs {
        rover: Some("swing4".into()),
        scenario,
        out: dir.join("out"),
        quiet: true,
        no_plots: true,
        generic: false,
        mcap: false,
    };
    let e = simulate(&args).expect_err("the scenario is bad");
    e.to_string().replace(&dir.display().to_string(), "<dir>")
}

#[test]
fn a_rover_against_a_wall_is_reported_stalled() {
    // A 30 cm step 0.6 m ahead: swing4's wheels push against it, at their
    // torque limit with the default speed loop, far below it with a weak one.
    for (kp, cause) in [
        ("", "at their torque limit"),
        ("kp = 0.5\n", "below their torque limit"),
    ] {
        let dir = scratch(&format!("stalled{}", kp.len()));
        let scenario = write(
            &dir,
            "wall.toml",
            &format!(
                "duration = 15.0\n[terrain]\nkind = \"step\"\nheight = 0.3\nposition = [0.6, 0.0]\nramp_width = 0.02\n[control.speed]\nspeed = 0.2\n{kp}"
            ),
        );
        let out = dir.join("out");
        let run = Command::new(env!("CARGO_BIN_EXE_rover"))
            .args(["simulate", "swing4", "--quiet", "--no-plots", "--scenario"])
            .arg(&scenario)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&run.stderr);
        // The run is valid and complete; the warning says it is not the
        // traverse asked for, and why.
        assert_eq!(run.status.code(), Some(0), "{err}");
        assert!(err.contains("warning: swing4 stalled"), "{err}");
        assert!(err.contains(cause), "{kp}: {err}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["status"], "completed");
        let stall = &summary["stalled"];
        let moved = stall["progress_m"].as_f64().unwrap().abs();
        let asked = stall["commanded_m"].as_f64().unwrap();
        assert!(
            (asked - 2.0).abs() < 1e-9,
            "0.2 m/s over the last 10 s: {stall}"
        );
        assert!(moved < 0.01, "{stall}");
        assert_eq!(stall["final_torques"].as_array().unwrap().len(), 4);
    }
}

#[test]
fn a_run_that_cannot_start_leaves_a_failed_summary_and_no_csv() {
    let text = bad_scenario_in(
        "cannot_start",
        "duration = 5.0\n[control.steering]\nkind = \"ackermann\"\nradius = 2.0\n",
    );
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli/cannot_start/out");
    assert!(!out.join("run.csv").exists(), "an empty CSV is left behind");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "failed");
    assert_eq!(summary["complete"], false);
    let error = summary["error"].as_str().unwrap();
    assert!(error.contains("steerable"), "{error} (CLI: {text})");
}

/// `rover simulate` of a scenario with `[sensors]`: `sensors.csv` beside
/// `run.csv`, its columns those of the declaration, a row at every sensor
/// instant (t = 0 to the end at 50 Hz), read back by `read_sensor_log`; a
/// later run without `[sensors]` in the same folder removes it, and so
/// does a scenario that cannot start.
#[test]
fn simulate_writes_the_sensor_log_beside_the_run() {
    let dir = scratch("sensors");
    let sensors = "[sensors]\nseed = 2\nrate = 50.0\n\
        [sensors.imu]\ngyro_noise_deg_per_sqrt_h = 0.2\ngyro_bias_deg_per_h = 10.0\n\
        accel_noise_ug_per_sqrt_hz = 100.0\naccel_bias_mg = 0.1\nposition = [0.1, 0.0, 0.05]\n\
        [sensors.suspension_encoders]\nresolution = 0.0017453292519943296\n\
        [sensors.heading_fix]\nrate = 1.0\nsigma = 0.01\n";
    let base = "duration = 1.5\nsettle = 0.5\n[control.speed]\nspeed = 0.05\n";
    let scenario = write(&dir, "s.toml", &format!("{base}{sensors}"));
    let out = dir.join("out");
    let args = SimulateArgs {
        rover: Some("swing4".into()),
        scenario: scenario.clone(),
        out: out.clone(),
        quiet: true,
        no_plots: true,
        generic: false,
        mcap: false,
    };
    let report = simulate(&args).unwrap();
    assert!(report.summary.complete);
    let log = out.join("sensors.csv");
    assert!(report.files.contains(&log), "{:?}", report.files);
    let text = std::fs::read_to_string(&log).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "t,gx,gy,gz,ax,ay,az,susp1,susp2,susp3,susp4,fix_psi,tau1,tau2,tau3,tau4,delta1,delta2,delta3,delta4"
    );
    let config = rover_scenario::scenario::Scenario::load(&scenario)
        .unwrap()
        .sensors
        .unwrap();
    let samples = rover_scenario::read_sensor_log(&log, &config, 4, 4).unwrap();
    assert_eq!(samples.len(), 76, "t = 0, 0.02, …, 1.5");
    assert_eq!(samples.last().unwrap().t, 1.5);
    let headings = samples.iter().filter(|s| s.heading.is_some()).count();
    assert_eq!(headings, 2, "heading fixes at t = 0 and 1");
    // The same folder, the run without [sensors]: no sensor log is left.
    std::fs::write(&scenario, base).unwrap();
    let report = simulate(&args).unwrap();
    assert!(!log.exists() && !report.files.contains(&log));
    // A scenario that cannot start leaves none either.
    std::fs::write(&scenario, format!("{base}{sensors}")).unwrap();
    simulate(&args).unwrap();
    assert!(log.exists());
    std::fs::write(
        &scenario,
        format!("{base}[control.steering]\nkind = \"ackermann\"\nradius = 2.0\n{sensors}"),
    )
    .unwrap();
    simulate(&args).expect_err("swing4 has no steerable wheels");
    assert!(!log.exists());
}

#[test]
fn an_output_path_that_is_a_file_is_refused_with_a_fix() {
    let dir = scratch("out_is_a_file");
    let out = write(&dir, "taken", "not a folder");
    let args = SimulateArgs {
        rover: Some("swing4".into()),
        scenario: write(&dir, "s.toml", "duration = 0.1\n"),
        out: out.clone(),
        quiet: true,
        no_plots: true,
        generic: false,
        mcap: false,
    };
    let e = simulate(&args)
        .expect_err("the output is a file")
        .to_string();
    assert!(e.contains("taken: is a file") && e.contains("--out"), "{e}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "not a folder");
}

#[test]
fn bad_scenario_files_get_located_errors() {
    insta::assert_snapshot!(
        "unknown_field",
        bad_scenario("duration = 5.0\nsettel = 1.0\n")
    );
    insta::assert_snapshot!(
        "wrong_type",
        bad_scenario("duration = 5.0\n[control.speed]\nspeed = \"fast\"\n")
    );
    insta::assert_snapshot!("negative_duration", bad_scenario("duration = -5.0\n"));
    insta::assert_snapshot!(
        "suspension_length",
        bad_scenario("duration = 5.0\n[initial]\nsuspension = [0.1, 0.2]\n")
    );
    insta::assert_snapshot!(
        "terrain_parameter",
        bad_scenario("duration = 5.0\n[terrain]\nkind = \"slope\"\nangle_deg = 95.0\n")
    );
    insta::assert_snapshot!(
        "ackermann_without_steerable_wheels",
        bad_scenario("duration = 5.0\n[control.steering]\nkind = \"ackermann\"\nradius = 2.0\n")
    );
    insta::assert_snapshot!(
        "integrator_step",
        bad_scenario("duration = 5.0\n[integrator.rk4]\nstep = 0.0\n")
    );
    insta::assert_snapshot!(
        "rolling_resistance",
        bad_scenario("duration = 5.0\n[contact]\nrolling_resistance = -0.1\n")
    );
    insta::assert_snapshot!(
        "heading_gain",
        bad_scenario(
            "duration = 5.0\n[control.speed]\nspeed = 0.1\n[control.steering]\nkind = \"heading\"\nkp = -1.0\n"
        )
    );
    insta::assert_snapshot!(
        "malformed_toml",
        bad_scenario("duration = 5.0\n[terrain\nkind = \"flat\"\n")
    );
}

#[test]
fn check_prints_the_rover_and_bad_files_exit_with_status_2() {
    let report = check(&CheckArgs {
        rover: "swing4".into(),
    })
    .unwrap();
    assert!(report.contains("10 DOF"), "{report}");
    let dir = scratch("check");
    let bad = write(
        &dir,
        "bad.toml",
        "name = \"x\"\ngravity = 1.62\n[body]\nmass = -3.0\ninertia = [1.0, 1.0, 1.0]\n",
    );
    let out = Command::new(env!("CARGO_BIN_EXE_rover"))
        .arg("check")
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:4:8") && err.contains("mass"),
        "{err}"
    );
    // One `error:` per diagnostic, not the CLI's prefix on top of it.
    assert!(
        err.starts_with("error: body.mass") && !err.contains("error: error"),
        "{err}"
    );
    let ok = Command::new(env!("CARGO_BIN_EXE_rover"))
        .args(["check", "exomars"])
        .output()
        .unwrap();
    assert_eq!(ok.status.code(), Some(0));
}

/// `rover codegen swing4 --out <out>`: the full model with its Jacobian.
fn codegen_swing4(out: &Path) -> Result<String, rover::error::CliError> {
    rover::cli::codegen(&rover::cli::CodegenArgs {
        rover: "swing4".into(),
        out: Some(out.to_path_buf()),
        fidelity: rover::cli::CodegenLevel::Full,
        type_name: None,
        no_jacobian: false,
    })
}

#[test]
fn codegen_writes_a_module_that_names_its_source() {
    let dir = scratch("codegen");
    let out = dir.join("swing4_plant.rs");
    let text = codegen_swing4(&out).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), text);
    assert!(
        text.contains("models/swing4.toml"),
        "the header names the source"
    );
    assert!(
        text.contains("impl") && text.contains("Plant for"),
        "it implements the plant trait"
    );
    assert!(
        !text.contains("Vec<") && !text.contains("unwrap()"),
        "no heap, no panics"
    );
}

#[test]
fn codegen_at_a_reduced_level_is_the_checked_in_module() {
    use rover::cli::{CodegenArgs, CodegenLevel, codegen};
    // The CLI freezes reduced levels where `simulate` does (the loaded
    // equilibrium), so for swing4 it writes the checked-in modules exactly.
    for (level, name, file) in [
        (
            CodegenLevel::Simplified,
            "Swing4Simplified",
            "swing4_simplified.rs",
        ),
        (
            CodegenLevel::Linearized,
            "Swing4Linearized",
            "swing4_linearized.rs",
        ),
    ] {
        let text = codegen(&CodegenArgs {
            rover: "swing4".into(),
            out: Some(scratch("codegen_level").join(file)),
            fidelity: level,
            type_name: Some(name.into()),
            no_jacobian: false,
        })
        .unwrap();
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let checked_in =
            std::fs::read_to_string(root.join("models/src/generated").join(file)).unwrap();
        assert!(
            text == checked_in,
            "{file}: the CLI and the checked-in module differ"
        );
    }
    // Any rover, without the Jacobian; a bad type name is refused, not emitted.
    let text = codegen(&CodegenArgs {
        rover: "mer".into(),
        out: Some(scratch("codegen_level").join("mer.rs")),
        fidelity: CodegenLevel::Linearized,
        type_name: None,
        no_jacobian: true,
    })
    .unwrap();
    assert!(text.contains("// Fidelity: Linearized") && text.contains("pub struct Mer"));
    assert!(!text.contains("jacobian"));
    let err = codegen(&CodegenArgs {
        rover: "mer".into(),
        out: None,
        fidelity: CodegenLevel::Full,
        type_name: Some("mer plant".into()),
        no_jacobian: false,
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("--type-name") && err.contains("MyRover"),
        "{err}"
    );
}

#[test]
fn reduced_levels_of_example_2_run_their_generated_plant_and_match_the_generic_one() {
    let dir = scratch("levels");
    let scenario = write(
        &dir,
        "s.toml",
        "duration = 4.0\nsettle = 1.0\nfidelity = \"simplified\"\n[control.speed]\nspeed = 0.1\n\
         [control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n[integrator.bdf]\nrtol = 1e-8\natol = 1e-10\n",
    );
    let run = |generic: bool| {
        let out = dir.join(if generic { "generic" } else { "generated" });
        let args = SimulateArgs {
            rover: Some("swing4".into()),
            scenario: scenario.clone(),
            out,
            quiet: true,
            no_plots: true,
            generic,
            mcap: false,
        };
        simulate(&args).unwrap().summary
    };
    let (generated, generic) = (run(false), run(true));
    assert_eq!(
        generated.plant,
        "generated (rover_models::generated::swing4_simplified::Swing4Simplified)"
    );
    assert_eq!(generic.plant, "generic (simplified level)");
    let state = |s: &rover_scenario::output::Summary| {
        s.final_state.iter().map(|(_, v)| *v).collect::<Vec<f64>>()
    };
    for (a, b) in state(&generated).iter().zip(state(&generic)) {
        assert!(
            (a - b).abs() < 1e-6 * (1.0 + b.abs()),
            "final states differ: {a} vs {b}"
        );
    }
}

/// `rover linearize`: the table for a built-in rover (generated plant), the
/// JSON for the same rover loaded from a file (generic plant), the same
/// modes from both; a missing file exits with status 2.
#[test]
fn linearize_prints_the_modes_and_writes_them_as_json() {
    let report = linearize_cmd(&LinearizeArgs {
        rover: "exomars".into(),
        out: None,
        generic: false,
        scenario: None,
        speed: 0.0,
    })
    .unwrap();
    assert!(
        report.contains("oscillatory modes")
            && report.contains("-25.0000")
            && report.contains("neutral: 4"),
        "{report}"
    );
    assert!(report.contains("generated plant"), "{report}");
    let dir = scratch("linearize");
    let file = write(
        &dir,
        "exomars.toml",
        rover_models::builtin("exomars").unwrap(),
    );
    let json = dir.join("modes.json");
    let from_file = linearize_cmd(&LinearizeArgs {
        rover: file.display().to_string(),
        out: Some(json.clone()),
        generic: false,
        scenario: None,
        speed: 0.0,
    })
    .unwrap();
    assert!(from_file.contains("generic plant"), "{from_file}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let states = v["states"].as_array().unwrap().len();
    assert_eq!(states, 2 * 9, "X … y3, vx … dy3");
    assert_eq!(v["a"].as_array().unwrap().len(), states);
    let eigen = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|l| l.starts_with("  ") && !l.contains('='))
            .map(str::to_string)
            .collect()
    };
    assert_eq!(
        eigen(&report),
        eigen(&from_file),
        "generated and generic plants, same modes to the printed digits"
    );
    // At speed, with the scenario's speed loop and line following closed:
    // only X is left without a restoring force.
    let scenario = write(
        &dir,
        "drive.toml",
        "duration = 1.0\n[control.speed]\nspeed = 0.1\n[control.steering]\nkind = \"heading\"\n\
         kp = 5.0\nkd = 0.5\ncross_track = 2.0\n",
    );
    let driving = linearize_cmd(&LinearizeArgs {
        rover: "swing4".into(),
        out: None,
        generic: false,
        scenario: Some(scenario),
        speed: 0.1,
    })
    .unwrap();
    assert!(
        driving.contains("driving straight at 0.1 m/s")
            && driving.contains("controllers in the loop")
            && driving.contains("neutral: 1"),
        "{driving}"
    );
    // A line integral too strong for its loop: the line mode grows, and the
    // table says so (k_y = 1 rad/(m·s) here; 0.2 is stable, ζ = 0.29).
    let windy = write(
        &dir,
        "windy.toml",
        "duration = 1.0\n[control.speed]\nspeed = 0.1\n[control.steering]\nkind = \"heading\"\n\
         kp = 5.0\nkd = 0.5\ncross_track = 2.0\ncross_track_integral = 1.0\n",
    );
    let unstable = linearize_cmd(&LinearizeArgs {
        rover: "swing4".into(),
        out: None,
        generic: false,
        scenario: Some(windy),
        speed: 0.1,
    })
    .unwrap();
    assert!(
        unstable.contains("∂(x, w, zeta_line), 21 × 21")
            && unstable.contains("(grows: an unstable oscillation)")
            && !driving.contains("grows"),
        "{unstable}"
    );
    let missing = Command::new(env!("CARGO_BIN_EXE_rover"))
        .args(["linearize", "no_such_rover.toml"])
        .output()
        .unwrap();
    assert_eq!(missing.status.code(), Some(2));
}

/// Every scenario shipped in scenarios/ loads, and its first 1.5 s run to
/// completion with the rover it names (files it refers to, such as a
/// command CSV, found next to it): the examples the README points to work.
#[test]
fn every_shipped_scenario_runs() {
    let names = super::support::shipped_scenarios();
    assert!(names.len() >= 9, "{names:?}");
    for path in names {
        let mut scenario = rover_scenario::scenario::Scenario::load(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        scenario.duration = scenario.duration.min(1.5);
        let rover = scenario
            .rover
            .clone()
            .expect("a shipped scenario names its rover");
        let spec = rover_spec::load_str(rover_models::builtin(&rover).unwrap(), &rover).unwrap();
        let plant = rover_runtime::GenericPlant::new(spec.model).unwrap();
        let summary = super::support::simulate_shipped(plant, &scenario, &path);
        assert_eq!(
            summary.status,
            rover_scenario::output::Status::Completed,
            "{}",
            path.display()
        );
    }
}

#[test]
fn a_reader_that_goes_away_ends_the_output_without_a_panic() {
    // `rover codegen swing4 | head -1`: the module (hundreds of kB) is far
    // larger than a pipe's buffer, so writing it meets the closed pipe.
    for args in [&["codegen", "swing4"][..], &["check", "exomars"][..]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rover"))
            .args(args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn codegen_into_a_missing_folder_names_the_file_and_leaves_nothing() {
    let dir = scratch("codegen_missing");
    let out = dir.join("no_such_folder").join("plant.rs");
    let err = codegen_swing4(&out).unwrap_err().to_string();
    assert!(err.contains("no_such_folder/plant.rs"), "{err}");
    assert!(!out.exists());
    // Over an existing file the module arrives whole, with no leftovers.
    let out = dir.join("plant.rs");
    std::fs::write(&out, "stale").unwrap();
    let text = codegen_swing4(&out).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), text);
    let names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, [std::ffi::OsString::from("plant.rs")]);
}

/// `rover wheel-test`: the single-wheel testbed's CSV (its first four
/// columns fixed), the pull rising with slip, and bad input refused with
/// the flag named.
#[test]
fn wheel_test_prints_the_testbed_csv_and_refuses_bad_input() {
    let rover = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_rover"))
            .args(args)
            .output()
            .unwrap()
    };
    let base = [
        "wheel-test",
        "--radius",
        "0.4",
        "--width",
        "0.23",
        "--load",
        "250",
    ];
    let ok = rover(
        &[
            &base[..],
            &["--soil", "lunar_nominal", "--slip", "0,0.1,0.3,0.6"],
        ]
        .concat(),
    );
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let text = String::from_utf8(ok.stdout).unwrap();
    let mut lines = text.lines();
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("slip,sinkage,drawbar_pull,torque,")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 4);
    assert!(rows.windows(2).all(|w| w[1][2] > w[0][2]), "{text}");
    assert!(rows.iter().all(|r| r[1] > 0.0 && r[1] < 0.4), "{text}");
    for (extra, expect) in [
        (
            &["--soil", "lunar_nominal", "--slip", "1.2"][..],
            "--slip 1.2",
        ),
        (&["--slip", "0.2", "--soil", "mud"][..], "--soil mud"),
    ] {
        let bad = rover(&[&base[..], extra].concat());
        let err = String::from_utf8_lossy(&bad.stderr);
        assert_eq!(bad.status.code(), Some(2), "{err}");
        assert!(err.starts_with(&format!("error: {expect}")), "{err}");
    }
}
