//! The observer in the control loop: swing4 drives the paper's rough
//! terrain (scenarios/fig13_observer.toml) with its speed and heading
//! controllers fed by the model-based filter's estimate, not by the truth.
//!
//! Every 10 ms the rover's computer reads its sensors (a MEMS IMU, wheel
//! and suspension encoders, simulated from the true motion with seeded
//! noise), the filter predicts over the interval with the torques it
//! commanded and takes the readings, and the controllers set the next
//! torques from the estimate: a P loop on the forward speed, and a slip
//! steering loop that holds a heading turning at 1.5°/s after the start.
//! The truth is integrated between ticks by RK4 at 1 ms. Neither the
//! filter nor the loop allocates after setup. Run:
//! `cargo run --release --example observer_loop`.

use rover_estimate::{Estimator, FilterConfig, InitialSigma, SensorSimulator, Truth};
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_scenario::estimate::{EstimateMap, process_system};
use rover_scenario::prepare::Prepared;

/// The speed set-point [m/s] and the P gain [N·m per m/s].
const SPEED: f64 = 0.05;
const KP_SPEED: f64 = 10.0;
/// The heading loop: Δτ = K_ψ·(ψ_ref − ψ̂) − K_r·Ω̂z [N·m per rad, per rad/s].
const K_HEADING: f64 = 2.0;
const K_RATE: f64 = 4.0;
/// How fast the heading set-point turns after settling [rad/s].
const TURN_RATE: f64 = 1.5 * std::f64::consts::PI / 180.0;
const SETTLE: f64 = 6.0;
const DURATION: f64 = 40.0;
const TICK: f64 = 0.01;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/fig13_observer.toml");
    let p = Prepared::from_file(None, &path)?;
    let model = &p.spec.model;
    let sensors = p
        .scenario
        .sensors
        .clone()
        .ok_or("the scenario declares no [sensors]")?;
    let (n, wheels) = (model.dof(), model.wheels.len());

    // The truth and the filter's model: the same rover and map, both open
    // loop (the torques below are the only ones).
    let (mut truth, mut y) = process_system(
        p.plant(false)?,
        model,
        &p.scenario,
        &p.base,
        EstimateMap::True,
    )?;
    let (process, y0) = process_system(
        p.plant(false)?,
        model,
        &p.scenario,
        &p.base,
        EstimateMap::True,
    )?;
    let mut filter = Estimator::new(
        process,
        &sensors,
        FilterConfig::default(),
        0.0,
        &y0,
        &InitialSigma::default(),
    )?;
    let mut readings = SensorSimulator::new(&sensors, wheels, n - 6)?;
    let mut sample = readings.new_sample();
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: 1e-3 })?;

    // Slip steering: the right wheels push harder to turn left (+y is left).
    let left: Vec<bool> = model
        .rest_wheel_centres()
        .iter()
        .map(|u| u[1] > 0.0)
        .collect();
    let (mut torques, steering) = (vec![0.0; wheels], vec![0.0; wheels]);
    let (mut dy, mut rates) = (vec![0.0; y.len()], vec![0.0; wheels]);
    let mut t = 0.0;
    let mut worst = [0.0f64; 2];
    for k in 0..=(DURATION / TICK).round() as usize {
        // What the sensors read now.
        truth.rhs(t, &y, &mut dy)?;
        truth.wheel_spin_rates(&y, &mut rates);
        readings.sample_into(
            &Truth {
                t,
                x: &y[..n],
                w: &y[n..2 * n],
                w_dot: &dy[n..2 * n],
                wheel_rates: &rates,
                torques: &torques,
                steering: &steering,
                gravity: model.gravity,
            },
            &mut sample,
        )?;
        // The filter: predicted with the torques held since the last tick.
        if k > 0 {
            filter.predict(TICK, &torques, &steering)?;
        }
        filter.update(&sample)?;
        let est = filter.state();
        worst[0] = worst[0].max((est[n] - y[n]).abs());
        worst[1] = worst[1].max((est[5] - y[5]).abs());
        // The controllers, on the estimate.
        let (speed, heading) = if t < SETTLE {
            (0.0, 0.0)
        } else {
            (SPEED, TURN_RATE * (t - SETTLE))
        };
        let tau0 = KP_SPEED * (speed - est[n]);
        let turn = if t < SETTLE {
            0.0
        } else {
            K_HEADING * (heading - est[5]) - K_RATE * est[n + 5]
        };
        for (tau, l) in torques.iter_mut().zip(&left) {
            *tau = if *l { tau0 - turn } else { tau0 + turn };
        }
        truth.set_torques(&torques)?;
        rk4.restart();
        let target = t + TICK;
        rk4.advance(&mut truth, &mut t, &mut y, target)?;
    }
    let heading = TURN_RATE * (DURATION - SETTLE);
    println!("after {DURATION} s on the Fig. 13 terrain, the loops closed on the estimate:");
    println!(
        "  heading: truth {:.2}°, set-point {:.2}°",
        y[5].to_degrees(),
        heading.to_degrees()
    );
    println!(
        "  forward speed: truth {:.4} m/s, set-point {SPEED} m/s",
        y[n]
    );
    println!(
        "  the estimate's largest errors: speed {:.2} mm/s, heading {:.3}°",
        1e3 * worst[0],
        worst[1].to_degrees()
    );
    Ok(())
}
