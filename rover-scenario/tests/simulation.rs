//! A rover declared with `#[derive(Rover)]`, run from the derived type
//! alone: its model is the plant's, its report is `rover check`'s, the
//! builder's run is the scenario file's run, and a plant paired with a
//! model of another rover is refused naming what differs.

use std::path::Path;

use rover_derive::Rover;
use rover_dynamics::described::Described;
use rover_dynamics::plant::{Plant, WheelLoad};
use rover_runtime::GenericPlant;
use rover_runtime::RoverDescription;
use rover_runtime::control::Steering;
use rover_runtime::terrain::TerrainConfig;
use rover_scenario::scenario::Scenario;
use rover_scenario::simulate::{SetupError, simulate};
use rover_scenario::{Simulation, SimulationError};

/// Two swing arms a side, the paper's Example 2 geometry, on the Moon.
#[derive(Rover)]
#[rover(
    name = "quad", gravity = 1.62,
    body = { mass = 100.0, inertia = [0.7, 0.9, 1.5] },
    wheel_defaults = { mass = 0.6, radius = 0.15, stiffness = 4000.0, damping = 300.0,
        mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 50.0, max_torque = 3.0 },
    suspension = [
        { name = "fl", kind = "longitudinal_swing_arm", pivot = [0.18, 0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 15.0, damping = 3.5 } },
        { name = "fr", kind = "longitudinal_swing_arm", pivot = [0.18, -0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 15.0, damping = 3.5 } },
        { name = "rl", kind = "longitudinal_swing_arm", pivot = [-0.22, 0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 15.0, damping = 3.5 } },
        { name = "rr", kind = "longitudinal_swing_arm", pivot = [-0.22, -0.2, -0.01], length = 0.2,
          coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 15.0, damping = 3.5 } },
    ],
    wheel = [
        { name = "fl", suspension = "fl" }, { name = "fr", suspension = "fr" },
        { name = "rl", suspension = "rl" }, { name = "rr", suspension = "rr" },
    ],
)]
struct Quad;

/// The same rover as TOML, but for the body mass and the wheel radius when
/// `other` is set.
fn quad_toml(other: bool) -> String {
    let (mass, radius) = if other { (60.0, 0.2) } else { (100.0, 0.15) };
    let mut s = format!(
        "name = \"quad\"\ngravity = 1.62\n[body]\nmass = {mass:?}\ninertia = [0.7, 0.9, 1.5]\n\
         [wheel_defaults]\nmass = 0.6\nradius = {radius:?}\nstiffness = 4000.0\ndamping = 300.0\n\
         mu_x = 0.5\nmu_y = 0.5\ncornering_stiffness = 50.0\nmax_torque = 3.0\n"
    );
    s += &rover_test_support::swing_arm_quad_tables();
    s
}

#[test]
fn the_model_of_a_derived_rover_is_the_model_its_plant_was_generated_from() {
    let model = Quad::model().unwrap();
    assert_eq!(model, QuadPlant::model().unwrap());
    // The TOML written out by hand is the same rover, field for field.
    let spec = rover_spec::load_str(&quad_toml(false), "quad.toml").unwrap();
    assert_eq!(model, spec.model);
    // And the generic plant of that model computes what the derived one does.
    let mut generic = GenericPlant::new(model).unwrap();
    let mut derived = Quad::plant();
    let mut x = [0.0; 10];
    let mut w = [0.0; 10];
    for i in 0..10 {
        x[i] = 0.01 * (i as f64 + 1.0);
        w[i] = 0.02 * (i as f64 - 4.0);
    }
    x[6..].copy_from_slice(&[-0.3, -0.25, 0.3, 0.35]);
    let loads = [WheelLoad {
        force: [1.0, -2.0, 150.0],
        ..Default::default()
    }; 4];
    let (mut xa, mut wa, mut xb, mut wb) = ([0.0; 10], [0.0; 10], [0.0; 10], [0.0; 10]);
    generic
        .derivatives(&x, &w, &loads, &mut xa, &mut wa)
        .unwrap();
    derived
        .derivatives(&x, &w, &loads, &mut xb, &mut wb)
        .unwrap();
    for i in 0..10 {
        assert!((xa[i] - xb[i]).abs() <= 1e-12 * (1.0 + xa[i].abs()), "ẋ{i}");
        assert!((wa[i] - wb[i]).abs() <= 1e-12 * (1.0 + wa[i].abs()), "ẇ{i}");
    }
}

#[test]
fn the_report_of_a_derived_rover_is_what_rover_check_prints() {
    let spec = rover_spec::load_str(&quad_toml(false), "quad.toml").unwrap();
    assert_eq!(
        Quad::report().unwrap(),
        rover_spec::report::check_report(&spec)
    );
    assert!(Quad::report().unwrap().starts_with("rover `quad`: 10 DOF"));
    // Where the derive is written.
    assert!(
        QuadPlant::ORIGIN.ends_with("simulation.rs:20"),
        "{}",
        QuadPlant::ORIGIN
    );
}

#[test]
fn the_builder_runs_what_the_scenario_file_runs() {
    let text = "duration = 3.0\nsettle = 1.0\noutput_rate = 10.0\n\
                [terrain]\nkind = \"random\"\nz_r = 0.1\n\
                [control.speed]\nspeed = 0.1\n\
                [control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n";
    let scenario = Scenario::parse(text, Path::new("s.toml")).unwrap();
    let spec = Quad::spec().unwrap();
    let from_file = simulate(
        Quad::plant(),
        &spec.model,
        &spec.name,
        &scenario,
        Path::new("."),
        std::io::sink(),
        &Default::default(),
        |_| {},
    )
    .unwrap();
    let built = Simulation::new(Quad::plant())
        .terrain(TerrainConfig::random(0.1))
        .settle(1.0)
        .output_rate(10.0)
        .speed(0.1)
        .steering(Steering::slip(0.2))
        .run(3.0)
        .unwrap();
    assert!(built.complete);
    assert_eq!(built.final_state, from_file.final_state);
    assert_eq!(built.rhs_evals, from_file.rhs_evals);
    // It drove: forward and turning left.
    let value = |name: &str| built.final_state.iter().find(|(n, _)| n == name).unwrap().1;
    assert!(
        value("X") > 0.1 && value("psi") > 0.0,
        "{:?}",
        built.final_state
    );
}

#[test]
fn a_scenario_of_a_duration_alone_is_a_file_of_that_line() {
    let parsed = Scenario::parse("duration = 7.0", Path::new("s.toml")).unwrap();
    assert_eq!(Scenario::with_duration(7.0), parsed);
}

#[test]
fn a_bad_setting_is_the_scenario_files_error_naming_the_field() {
    let e = Simulation::new(Quad::plant())
        .settle(5.0)
        .run(2.0)
        .unwrap_err();
    let SimulationError::Scenario(f) = &e else {
        panic!("{e}")
    };
    assert_eq!(f.field, "settle");
    assert!(
        e.to_string()
            .starts_with("settle must lie in [0, duration] = [0, 2] s, got 5"),
        "{e}"
    );
    // One that needs the rover: the setup's error, with its field.
    let e = Simulation::new(Quad::plant())
        .initial(rover_scenario::scenario::InitialState {
            suspension: Some(vec![0.0; 3]),
            ..Default::default()
        })
        .run(1.0)
        .unwrap_err();
    let SimulationError::Setup(s) = &e else {
        panic!("{e}")
    };
    assert_eq!(s.field_path().as_deref(), Some("initial.suspension"));
    assert!(e.to_string().contains("4 suspension coordinates"), "{e}");
}

#[test]
fn a_derived_plant_with_a_model_of_another_rover_is_refused_naming_each_difference() {
    let other = rover_spec::load_str(&quad_toml(true), "quad.toml").unwrap();
    let e = Simulation::with_spec(Quad::plant(), other)
        .run(1.0)
        .unwrap_err();
    let SimulationError::Mismatch(m) = &e else {
        panic!("{e}")
    };
    assert_eq!(
        m.differences,
        [
            "body.mass: 100 in the plant, 60 in the model",
            "wheel `fl`.radius: 0.15 in the plant, 0.2 in the model",
            "wheel `fr`.radius: 0.15 in the plant, 0.2 in the model",
            "wheel `rl`.radius: 0.15 in the plant, 0.2 in the model",
            "wheel `rr`.radius: 0.15 in the plant, 0.2 in the model",
        ]
    );
    assert!(
        e.to_string()
            .starts_with("the plant and the model describe different rovers:\n  - body.mass: 100"),
        "{e}"
    );
    // The same rover written as TOML is accepted.
    let same = rover_spec::load_str(&quad_toml(false), "quad.toml").unwrap();
    let run = Simulation::with_spec(Quad::plant(), same).run(0.5).unwrap();
    assert!(run.complete);
}

#[test]
fn any_plant_run_with_a_model_of_another_mass_or_size_is_refused() {
    let other = rover_spec::load_str(&quad_toml(true), "quad.toml").unwrap();
    // Through the scenario route, which every run takes.
    let e = simulate(
        Quad::plant(),
        &other.model,
        "quad",
        &Scenario::with_duration(1.0),
        Path::new("."),
        std::io::sink(),
        &Default::default(),
        |_| {},
    )
    .unwrap_err();
    let SetupError::Mismatch(m) = &e else {
        panic!("{e}")
    };
    assert_eq!(
        m.differences,
        ["total mass: 102.4 kg in the plant, 62.4 kg in the model"]
    );
    // A generic plant of a smaller rover: its size.
    let mut small = other.clone();
    small.model.wheels.pop();
    let plant = GenericPlant::new(small.model).unwrap();
    let e = Simulation::from_parts(plant, other).run(1.0).unwrap_err();
    assert!(
        e.to_string()
            .contains("wheels: 3 in the plant, 4 in the model"),
        "{e}"
    );
}
