//! Drive a built-in rover from Rust: the generated plant of Example 2 on a
//! random terrain, slip-steered by the speed loop, integrated by BDF, with
//! every output row in hand. Run: `cargo run --release --example drive`.

use std::sync::atomic::AtomicBool;

use rover_dynamics::contact::RimSampling;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{BdfConfig, IntegratorConfig};
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::{RoverSystem, RunOptions, Stop, run};
use rover_runtime::terrain::TerrainConfig;
use rover_runtime::wheel_law::WheelLawConfig;
use rover_scenario::scenario::Scenario;
use rover_scenario::simulate::initial_state;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The description (for the model's numbers) and its generated plant.
    let spec = rover_spec::load_str(
        rover_models::builtin("swing4").ok_or("no swing4")?,
        "models/swing4.toml",
    )?;
    let plant = rover_models::Swing4::new();

    // Ground: MODEL.md §11's random field, gentle (Z_R = 0.1).
    let terrain = toml::from_str::<TerrainConfig>("kind = \"random\"\nz_r = 0.1\nseed = 7")?
        .build(std::path::Path::new("."))?;
    let ground = Ground::new(
        terrain.clone(),
        &spec.model,
        ContactMethod::Meridional,
        RimSampling::default(),
        WheelLawConfig::default(),
    );

    // Control: 0.1 m/s after 3 s of settling, Δτ = 0.1 N·m to the left.
    let control: ControllerConfig =
        toml::from_str("[speed]\nspeed = 0.1\n[steering]\nkind = \"slip\"\ndelta_tau = 0.1")?;
    let control = Controller::new(control, &spec.model, 3.0)?;

    // Start at rest, wheels touching the ground (the scenario defaults).
    let scenario = Scenario::parse("duration = 20.0", std::path::Path::new("inline.toml"))?;
    let mut y = initial_state(&spec.model, &scenario, Some(&terrain))?;

    let mut sys = RoverSystem::new(plant, Some(ground), control);
    let mut integrator = IntegratorConfig::Bdf(BdfConfig {
        rtol: 1e-6,
        atol: Some(1e-8),
        max_order: 2,
        ..Default::default()
    })
    .build(y.len())?;
    let options = RunOptions {
        duration: 20.0,
        output_step: 1.0,
        rollover_limit: 80f64.to_radians(),
    };
    let outcome = run(
        &mut sys,
        &mut integrator,
        &mut y,
        &options,
        &AtomicBool::new(false),
        |row| {
            let normal: f64 = row.system.reports().iter().map(|r| r.normal).sum();
            println!(
                "t = {:4.1} s  X = {:6.3} m  Y = {:6.3} m  yaw = {:6.2}°  ΣF_n = {:5.2} N",
                row.t,
                row.y[0],
                row.y[1],
                row.y[5].to_degrees(),
                normal
            );
            Ok(())
        },
    );
    match outcome.stop {
        Stop::Completed => Ok(()),
        Stop::Interrupted { t } => Err(format!("interrupted at t = {t} s").into()),
        Stop::Failed(e) => Err(e.into()),
    }
}
