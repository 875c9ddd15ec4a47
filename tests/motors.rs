//! Motors with a torque–speed line, and runs whose rover runs away: a
//! light rover whose slip-steering torque difference spins it out is
//! flagged in the summary and on the console; with a no-load speed its
//! motors cannot drive it past the no-load rim speed; the summary of the
//! `Simulation` builder names the plant that ran.

use std::path::PathBuf;
use std::process::Command;

use rover_scenario::Simulation;
use rover_scenario::output::Summary;
use rover_scenario::scenario::ContactConfig;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rover-motors-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Wheel radius of the light rover \[m\].
const RADIUS: f64 = 0.1;
/// Its motors' limit [N·m].
const MAX_TORQUE: f64 = 3.0;

/// A light four-wheeled rover, 20 kg in all, on Mars; its motors with the
/// no-load speed `no_load` [rad/s] when given.
fn light_rover(no_load: Option<f64>) -> String {
    let mut s = format!(
        "name = \"light\"\ngravity = 3.71\n[body]\nmass = 16.0\ninertia = [0.2, 0.3, 0.4]\n\
         [wheel_defaults]\nmass = 1.0\nradius = {RADIUS:?}\nstiffness = 3000.0\ndamping = 100.0\n\
         mu_x = 0.6\nmu_y = 0.3\ncornering_stiffness = 60.0\nmax_torque = {MAX_TORQUE:?}\n"
    );
    if let Some(w0) = no_load {
        s += &format!("no_load_speed = {w0:?}\n");
    }
    s += &rover_test_support::swing_arm_quad_tables();
    s
}

/// `rover simulate` of the light rover with `control` (TOML tables):
/// its summary and its stderr.
fn run_cli(name: &str, no_load: Option<f64>, control: &str) -> (serde_json::Value, String) {
    let dir = scratch(name);
    let rover = dir.join("light.toml");
    std::fs::write(&rover, light_rover(no_load)).unwrap();
    let scenario = dir.join("s.toml");
    std::fs::write(
        &scenario,
        format!("rover = \"light.toml\"\nduration = 8.0\nsettle = 1.0\n{control}"),
    )
    .unwrap();
    let out = dir.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_rover"))
        .args(["simulate", "--quiet", "--no-plots", "--scenario"])
        .arg(&scenario)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&run.stderr).into_owned();
    assert_eq!(run.status.code(), Some(0), "{err}");
    let summary =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    (summary, err)
}

const SPIN: &str =
    "[control.speed]\nspeed = 0.1\n[control.steering]\nkind = \"slip\"\ndelta_tau = 2.0\n";

#[test]
fn a_light_rover_spun_out_by_its_torque_difference_is_flagged_as_a_runaway() {
    // Past Δτ_spin = 2·μ_y·m·g·x̄·R_w/(n·b) ≈ 1.1 N·m (μ_y = 0.3, 20 kg,
    // wheels 0.39 m ahead or behind G, track 0.4 m; docs/CLI.md) the
    // sideways scrub cannot hold the turn: pure torque sources spin the
    // rover ever faster. (At μ_y = 0.6, Δτ = 0.45 N·m, it turns steadily at
    // 2 °/s.)
    let (summary, err) = run_cli("spin", None, SPIN);
    assert_eq!(summary["status"], "completed");
    let r = &summary["runaway"];
    let yaw = r["yaw_rate_deg_s"].as_f64().unwrap_or(0.0);
    assert!(yaw > 180.0, "{summary}");
    assert!(err.contains("warning: light ran away"), "{err}");
    assert!(err.contains("no speed limit"), "{err}");
}

#[test]
fn a_motor_line_keeps_the_same_torque_difference_from_running_away() {
    // No load at a rim speed of 0.2 m/s: each wheel's rim, hence the spin,
    // is bounded.
    let (summary, err) = run_cli("spin-limited", Some(0.2 / RADIUS), SPIN);
    assert_eq!(summary["status"], "completed");
    assert!(summary.get("runaway").is_none(), "{summary}");
    assert!(!err.contains("ran away"), "{err}");
}

/// The final forward speed of the light rover commanded to 2 m/s for 8 s.
fn top_speed(no_load: Option<f64>) -> f64 {
    let spec = rover_spec::load_str(&light_rover(no_load), "light.toml").unwrap();
    let plant = rover_runtime::GenericPlant::new(spec.model.clone()).unwrap();
    let summary = Simulation::from_parts(plant, spec)
        .contact(ContactConfig {
            rolling_resistance: 0.02,
            ..ContactConfig::default()
        })
        .settle(0.5)
        .speed(2.0)
        .run(8.0)
        .unwrap();
    final_value(&summary, "vx")
}

fn final_value(summary: &Summary, name: &str) -> f64 {
    summary
        .final_state
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, v)| *v)
        .unwrap()
}

#[test]
fn a_rover_on_the_flat_tops_out_below_its_motors_no_load_rim_speed() {
    // ω₀·r = 0.4 m/s: the line gives no torque there, and the rover needs
    // some to roll (rolling resistance 0.02, 1.5 N over the whole rover:
    // 0.04 N·m a wheel of the line's 3 N·m, at 1.3 % below ω₀), so it
    // settles below, but near it.
    let w0 = 4.0;
    let limited = top_speed(Some(w0));
    assert!(limited < w0 * RADIUS, "{limited} m/s");
    assert!(limited > 0.95 * w0 * RADIUS, "{limited} m/s");
    // The same motors without the line keep pushing past it.
    let free = top_speed(None);
    assert!(free > 1.5 * w0 * RADIUS, "{free} m/s");
}

#[test]
fn the_simulation_builder_names_the_plant_that_ran() {
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    fn run<P: rover_dynamics::plant::Plant>(s: Simulation<P>) -> String {
        s.settle(0.2).speed(0.05).run(0.5).unwrap().plant
    }
    let generated = run(Simulation::from_parts(
        rover_models::Swing4::new(),
        spec.clone(),
    ));
    assert_eq!(
        generated,
        "generated (rover_models::generated::swing4::Swing4)"
    );
    let generic = rover_runtime::GenericPlant::new(spec.model.clone()).unwrap();
    assert_eq!(run(Simulation::from_parts(generic, spec)), "generic");
}

#[test]
fn no_shipped_scenario_runs_away() {
    let names = super::support::shipped_scenarios();
    for path in names {
        let scenario = rover_scenario::scenario::Scenario::load(&path).unwrap();
        let plant = rover_models::plant(scenario.rover.as_deref().unwrap()).unwrap();
        let summary = super::support::simulate_shipped(plant, &scenario, &path);
        assert!(
            summary.runaway.is_none(),
            "{}: {:?}",
            path.display(),
            summary.runaway
        );
    }
}
