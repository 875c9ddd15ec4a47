//! A rover declared in Rust and driven from its derived type alone: a
//! six-wheeled rocker-bogie on Mars, 20 s on random ground, slip-steered
//! to the left. No TOML file and no loading: the plant is generated at
//! compile time and carries its description, from which the run takes the
//! model its terrain contact and controllers read.
//! Run: `cargo run --release --example derive_simulate`.

use rover_derive::Rover;
use rover_runtime::RoverDescription;
use rover_runtime::control::{Profile, SpeedConfig, Steering};
use rover_runtime::terrain::TerrainConfig;
use rover_scenario::Simulation;

#[derive(Rover)]
#[rover(
    name = "six",
    gravity = 3.71,
    body = { mass = 100.0, inertia = [14.0, 18.0, 28.0] },
    wheel_defaults = { mass = 2.0, radius = 0.15, stiffness = 50000.0, damping = 500.0, mu_x = 0.5,
        mu_y = 0.5, cornering_stiffness = 500.0, max_torque = 30.0, motor = "hub" },
    suspension = [{ name = "rb", kind = "rocker_bogie", pivot = [0.15, 0.45, -0.05],
        front_wheel = [0.6, 0.55, -0.3], bogie_pivot = [-0.25, 0.5, -0.15],
        middle_wheel = [0.0, 0.55, -0.3], rear_wheel = [-0.55, 0.55, -0.3],
        rocker = { name = "rocker", rest_deg = 0.0, min_deg = -25.0, max_deg = 25.0 },
        bogie_left = { name = "bogie_left", rest_deg = 0.0, min_deg = -35.0, max_deg = 35.0 },
        bogie_right = { name = "bogie_right", rest_deg = 0.0, min_deg = -35.0, max_deg = 35.0 },
        fit = { method = "least_squares", terms = 5 } }],
    wheel = [
        { name = "front_left", suspension = "rb", point = "front_left" },
        { name = "front_right", suspension = "rb", point = "front_right" },
        { name = "middle_left", suspension = "rb", point = "middle_left" },
        { name = "middle_right", suspension = "rb", point = "middle_right" },
        { name = "rear_left", suspension = "rb", point = "rear_left" },
        { name = "rear_right", suspension = "rb", point = "rear_right" },
    ],
)]
struct Six;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // What `rover check` prints (masses, the fits and their errors, the
    // rest geometry); its first lines here.
    for line in Six::report()?.lines().take(2) {
        println!("{line}");
    }

    // 2 s of settling, then 0.1 m/s with a torque difference of 2 N·m to the
    // left. The speed loop's gain suits this 112 kg rover: its motors' full
    // 30 N·m at 0.1 m/s below the set-point (the default, 10, is Example 1's).
    let speed = SpeedConfig {
        speed: Profile::Constant(0.1),
        kp: 300.0,
        ..Default::default()
    };
    let summary = Simulation::new(Six::plant())
        .terrain(TerrainConfig::random(0.2))
        .settle(2.0)
        .speed(speed)
        .steering(Steering::slip(2.0))
        .run(20.0)?;

    println!(
        "\nafter {} s, {:.2} m driven ({} right-hand sides):",
        summary.t_end, summary.distance_m, summary.rhs_evals
    );
    for (name, value) in &summary.final_state {
        println!("  {name:>6} = {value:10.4}");
    }
    Ok(())
}
