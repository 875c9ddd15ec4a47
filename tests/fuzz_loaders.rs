//! No input makes a loader panic (on stable Rust: proptest picks the
//! mutations, with a fixed seed): the shipped scenarios, soils, command
//! files and sweep plans, with a number replaced by a hostile literal or
//! bytes deleted and inserted, either load (and a scenario then builds its
//! whole run: terrain, ground, controller) or give a non-empty error.

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use rover_runtime::control::{CommandSchedule, Interpolation};
use rover_runtime::soil::SoilConfig;
use rover_scenario::prepare::Prepared;
use rover_scenario::sweep::Plan;
use rover_test_support::mutate::{HOSTILE, replace_number, splice};

const SCENARIOS: &[&str] = &[
    include_str!("../scenarios/fig5_turn.toml"),
    include_str!("../scenarios/fig15_active.toml"),
    include_str!("../scenarios/commands.toml"),
    include_str!("../scenarios/waypoints.toml"),
    include_str!("../scenarios/side_slope_line.toml"),
    include_str!("../scenarios/soil_slope.toml"),
    include_str!("../scenarios/free_flight.toml"),
];
const COMMANDS: &str = include_str!("../scenarios/commands.csv");
const PLAN: &str = include_str!("../scenarios/sweeps/soil_slope.toml");
const SOIL: &str = "[soil]\nn = 1.1\nk_c = 990.0\nk_phi = 1528430.0\ncohesion = 1040.0\n\
                    friction_angle_deg = 28.0\nshear_modulus = 0.01\n";

fn config() -> Config {
    Config {
        cases: 160,
        rng_seed: RngSeed::Fixed(2012),
        failure_persistence: None,
        ..Config::default()
    }
}

fn scenarios_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenarios"))
}

/// A scenario's text loads and builds its run, or errs with a message.
fn scenario_survives(text: &str) {
    let dir = scenarios_dir();
    match Prepared::from_text(None, text, &dir.join("fuzz.toml"), dir) {
        Ok(prepared) => {
            if let Err(e) = prepared.stepper(true) {
                assert!(!e.to_string().is_empty());
            }
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

fn soil_survives(text: &str) {
    match SoilConfig::from_toml(text).and_then(|c| c.soil()) {
        Ok(_) => {}
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

fn commands_survive(text: &str) {
    let model = rover_scenario::prepare::load_rover("swing4", None)
        .unwrap()
        .model;
    for interpolation in [Interpolation::Linear, Interpolation::Step] {
        if let Err(e) = CommandSchedule::parse(text, Path::new("c.csv"), &model, interpolation) {
            assert!(!e.to_string().is_empty());
        }
    }
}

fn plan_survives(text: &str) {
    let base = include_str!("../scenarios/soil_slope.toml");
    let dir = scenarios_dir().join("sweeps");
    match Plan::parse_with(text, &dir.join("fuzz.toml"), &dir, Some(base)) {
        Ok(plan) => {
            for index in 0..plan.tasks.len().min(3) {
                if let Err(e) = plan.scenario_text(index) {
                    assert!(!e.to_string().is_empty());
                }
            }
        }
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn scenarios_with_a_hostile_number_never_panic(s in 0..SCENARIOS.len(), which in 0usize..400, hostile in 0..HOSTILE.len()) {
        scenario_survives(&replace_number(SCENARIOS[s], which, hostile));
    }

    #[test]
    fn scenarios_with_bytes_spliced_never_panic(s in 0..SCENARIOS.len(), at in 0usize..5000, len in 0usize..40, insert in "[ -~\n]{0,12}") {
        scenario_survives(&splice(SCENARIOS[s], at, len, &insert));
    }

    #[test]
    fn soils_command_files_and_plans_with_a_hostile_number_never_panic(which in 0usize..400, hostile in 0..HOSTILE.len()) {
        soil_survives(&replace_number(SOIL, which, hostile));
        commands_survive(&replace_number(COMMANDS, which, hostile));
        plan_survives(&replace_number(PLAN, which, hostile));
    }

    #[test]
    fn soils_command_files_and_plans_with_bytes_spliced_never_panic(at in 0usize..2000, len in 0usize..40, insert in "[ -~\n]{0,12}") {
        soil_survives(&splice(SOIL, at, len, &insert));
        commands_survive(&splice(COMMANDS, at, len, &insert));
        plan_survives(&splice(PLAN, at, len, &insert));
    }
}
