//! The filter on MER (its generated plant, six wheels) on the Fig. 13
//! terrain covered with dry sand: the wheels' spins are states, which the
//! wheel encoders read directly; the truth integrated by BDF, noise-free
//! readings made here (motor-side encoders: 2^16 counts a wheel turn),
//! the rover's P speed loop (100 N·m per m/s a wheel, on the truth's
//! speed, so that the test is about the filter).
//!
//! A wheel's spin settles in milliseconds against the sand's shear, and
//! the assembled Jacobian of the soil law is approximate: one or two
//! linearly implicit steps of 10 ms lose the rolling rover (G's speed
//! 0.34 m/s against 0.065 after 0.3 s), four leave it 6 mm/s slow, eight
//! track it (measured here; `FilterConfig::substeps`).

use rover_dynamics::plant::Plant;
use rover_estimate::sensors::{EncoderConfig, ImuConfig, SensorConfig, SensorSample};
use rover_estimate::{Estimator, FilterConfig, InitialSigma, ProcessModel};
use rover_models::Mer;
use rover_runtime::integrate::Integrator;

use crate::support::rover;

fn sensors() -> SensorConfig {
    SensorConfig {
        seed: 5,
        rate: 100.0,
        imu: Some(ImuConfig {
            gyro_noise_deg_per_sqrt_h: 0.15,
            gyro_bias_deg_per_h: 10.0,
            accel_noise_ug_per_sqrt_hz: 100.0,
            accel_bias_mg: 2.0,
            bias_time: 300.0,
            position: [0.0; 3],
            orientation_deg: [0.0; 3],
        }),
        wheel_encoders: Some(EncoderConfig {
            resolution: 2.0 * std::f64::consts::PI / 65536.0,
        }),
        suspension_encoders: None,
        position_fix: None,
        heading_fix: None,
    }
}

/// Two seconds of driving after settling, eight substeps: once the wheels
/// have spun up (0.2 s), the filter, started at the truth, keeps G's
/// velocity within 2 mm/s and every spin within 0.03 rad/s; its normal
/// loads and slips are the model's.
#[test]
fn tracks_mer_on_sand_with_the_spins_as_states() {
    let model = rover::model("mer");
    let terrain = rover::fig13_terrain();
    let (mut truth, mut y) =
        rover::open_loop_on_soil(&model, Mer::new(), terrain.clone(), "dry_sand");
    let n = model.dof();
    let spins = truth.spin_range();
    assert_eq!(spins.len(), 6);
    rover::settled(&mut truth, &mut y, 1.0);
    let (process, _) = rover::open_loop_on_soil(&model, Mer::new(), terrain, "dry_sand");
    // A soil law only approximates real sand: the preset for such a model.
    let config = FilterConfig {
        substeps: 8,
        ..FilterConfig::approximate_model()
    };
    let mut filter = Estimator::new(
        process,
        &sensors(),
        config,
        1.0,
        &y,
        &InitialSigma::approximate_model(),
    )
    .unwrap();
    let wheels = truth.plant.wheel_count();
    let mut integ = rover::truth_integrator(y.len());
    let mut dy = vec![0.0; y.len()];
    let mut angles = vec![0.0; wheels];
    let res = sensors().wheel_encoders.unwrap().resolution;
    let quantized = |a: &[f64]| {
        a.iter()
            .map(|v| (v / res).round() * res)
            .collect::<Vec<_>>()
    };
    filter.update_wheel_angles(&quantized(&angles)).unwrap();
    let mut t = 1.0;
    let (mut worst_v, mut worst_spin) = (0.0f64, 0.0f64);
    for k in 1..=200 {
        let torques = vec![100.0 * (0.1 - y[n]); wheels];
        truth.set_torques(&torques).unwrap();
        integ.restart();
        let t_end = 1.0 + 0.01 * k as f64;
        // The angles: the spins' integral, by the trapezoid rule on 1 ms.
        let t_start = t;
        for j in 1..=10 {
            let before: Vec<f64> = y[spins.clone()].to_vec();
            let tj = if j == 10 {
                t_end
            } else {
                t_start + 0.001 * j as f64
            };
            let h = tj - t;
            integ.advance(&mut truth, &mut t, &mut y, tj).unwrap();
            for (w, a) in angles.iter_mut().enumerate() {
                *a += 0.5 * h * (before[w] + y[spins.start + w]);
            }
        }
        truth.evaluate_at(t, &y, &mut dy).unwrap();
        filter.predict(0.01, &torques, &vec![0.0; wheels]).unwrap();
        let up = rover_dynamics::attitude::Attitude::new(y[3], y[4], y[5]).up_in_body();
        let (v, w) = ([y[n], y[n + 1], y[n + 2]], [y[n + 3], y[n + 4], y[n + 5]]);
        let transport = [
            w[1] * v[2] - w[2] * v[1],
            w[2] * v[0] - w[0] * v[2],
            w[0] * v[1] - w[1] * v[0],
        ];
        let accel = [0, 1, 2].map(|i| dy[n + i] + transport[i] + model.gravity * up[i]);
        let sample = SensorSample {
            t,
            gyro: Some(w),
            accel: Some(accel),
            wheel_angles: quantized(&angles),
            ..SensorSample::default()
        };
        filter.update(&sample).unwrap();
        let e = filter.state();
        let dv: f64 = (0..3)
            .map(|i| (e[n + i] - y[n + i]).powi(2))
            .sum::<f64>()
            .sqrt();
        if t < 1.2 {
            continue;
        }
        worst_v = worst_v.max(dv);
        for s in spins.clone() {
            worst_spin = worst_spin.max((e[s] - y[s]).abs());
        }
    }
    assert!(worst_v < 2e-3, "velocity error {worst_v}");
    assert!(worst_spin < 0.03, "spin error {worst_spin}");
    let (mut normal, mut slip) = (vec![0.0; wheels], vec![0.0; wheels]);
    filter.wheel_outputs(&mut normal, &mut slip).unwrap();
    assert!(normal.iter().all(|n| *n > 0.0), "{normal:?}");
    assert!(
        slip.iter().all(|s| *s > 0.0 && *s < 0.5),
        "driving slips: {slip:?}"
    );
    assert_eq!(ProcessModel::dim(filter.model()), 2 * n + 6);
}
