//! Drive a generated plant from outside, as a hardware-in-the-loop rig or a
//! user's own controller does: every millisecond the controller reads the
//! state and sets the motor torques (`RoverSystem::set_torques`, held until
//! the next call), and the fixed-step RK4 integrator advances one step.
//! Neither allocates (the printing does). Run:
//! `cargo run --release --example external_control`.

use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::TerrainConfig;
use rover_scenario::scenario::Scenario;
use rover_scenario::simulate::initial_state;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let spec = rover_spec::load_str(
        rover_models::builtin("swing4").ok_or("no swing4")?,
        "models/swing4.toml",
    )?;
    let model = &spec.model;
    let terrain = toml::from_str::<TerrainConfig>("kind = \"random\"\nz_r = 0.1\nseed = 7")?
        .build(std::path::Path::new("."))?;
    let scenario = Scenario::parse("duration = 20.0", std::path::Path::new("inline.toml"))?;
    let mut y = initial_state(model, &scenario, Some(&terrain))?;
    let ground = Ground::new(
        terrain,
        model,
        Default::default(),
        Default::default(),
        Default::default(),
    );
    // The built-in loops off: the external controller below is the only one.
    let control = Controller::new(ControllerConfig::default(), model, 0.0)?;
    let mut sys = RoverSystem::new(rover_models::Swing4::new(), Some(ground), control);
    y.resize(sys.dim(), 0.0);

    let step = 1e-3;
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step })?;
    let n = model.dof();
    // The user's controller: a PI loop on the forward speed after 2 s of
    // settling, and a torque difference turning the heading towards 15°.
    let (speed, heading) = (0.1, 15f64.to_radians());
    let (kp, ki, k_psi) = (10.0, 20.0, 2.0);
    let mut integral = 0.0;
    let left: Vec<bool> = model
        .wheels
        .iter()
        .map(|w| model.bodies[w.body].position.value(&model.rest())[1] > 0.0)
        .collect();
    let mut torques = vec![0.0; model.wheels.len()];
    let mut t = 0.0;
    for k in 1..=20_000 {
        if t >= 2.0 {
            let e = speed - y[n];
            integral += e * step;
            let tau0 = kp * e + ki * integral;
            let dt = k_psi * (heading - y[5]);
            for (tau, &l) in torques.iter_mut().zip(&left) {
                *tau = if l { tau0 - dt } else { tau0 + dt };
            }
            sys.set_torques(&torques)?;
        }
        rk4.advance(&mut sys, &mut t, &mut y, k as f64 * step)?;
        if k % 2000 == 0 {
            println!(
                "t = {t:4.1} s  v_x = {:6.3} m/s  yaw = {:6.2}°  τ = {:?} N·m",
                y[n],
                y[5].to_degrees(),
                sys.torques()
                    .iter()
                    .map(|v| (v * 1e3).round() / 1e3)
                    .collect::<Vec<_>>()
            );
        }
    }
    Ok(())
}
