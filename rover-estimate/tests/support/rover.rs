//! A built-in rover on the paper's Fig. 13 terrain (Z_R = 0.2, seed 1, the
//! reproduction's field), in the open loop a filter runs beside it: the
//! tests' truth and model, and the bench's. Shared by `tests/` and
//! `benches/estimate.rs` (`#[path]`).
#![allow(dead_code)]

use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::height_field::Bounds;
use rover_dynamics::plant::Plant;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_runtime::ground::Ground;
use rover_runtime::integrate::{AnyIntegrator, BdfConfig, Integrator, IntegratorConfig, OdeSystem};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::{RandomField, Terrain};
use rover_runtime::wheel_law::WheelLawConfig;

/// The numeric model of a built-in rover.
pub fn model(name: &str) -> Model {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name)
        .unwrap()
        .model
}

/// scenarios/fig13_slip_rough.toml's terrain, from 3 m behind the start
/// to 6.5 m ahead and 3 m to each side.
pub fn fig13_terrain() -> Terrain {
    let field = RandomField {
        z_r: 0.2,
        seed: 1,
        node_amplitude: 0.25,
        node_spacing: 0.7,
        patch_radius: 0.63,
        patch_blend: 0.15,
        extent: Bounds {
            x_min: -3.0,
            x_max: 6.5,
            y_min: -3.0,
            y_max: 3.0,
        },
        ..RandomField::default()
    };
    Terrain::Grid(field.grid().unwrap())
}

/// The rover of `model` on `terrain` with the paper's wheel law and the
/// bounded contact search, no controller loop (the commands are set from
/// outside), at rest with the suspension at its rest angles and G 2 mm
/// into the ground.
pub fn open_loop<P: Plant>(
    model: &Model,
    plant: P,
    terrain: Terrain,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let ground = Ground::new(
        terrain,
        model,
        ContactMethod::Bounded,
        RimSampling::default(),
        WheelLawConfig::default(),
    );
    let sys = RoverSystem::open_loop(plant, Some(ground), model).unwrap();
    let n = model.dof();
    let mut y = vec![0.0; sys.dim()];
    y[6..n].copy_from_slice(&model.rest());
    y[2] = model.touchdown_height() - 2e-3;
    (sys, y)
}

/// BDF at tight tolerances: the truth.
pub fn truth_integrator(dim: usize) -> AnyIntegrator {
    IntegratorConfig::Bdf(BdfConfig {
        rtol: 1e-8,
        atol: Some(1e-10),
        ..BdfConfig::default()
    })
    .build(dim)
    .unwrap()
}

/// The rover settled on its wheels: `seconds` with no torque.
pub fn settled<P: Plant>(sys: &mut RoverSystem<P, Terrain>, y: &mut [f64], seconds: f64) {
    let mut integ = truth_integrator(y.len());
    let mut t = 0.0;
    integ.advance(sys, &mut t, y, seconds).unwrap();
}

/// One recorded filter step: the commands, then the readings at its end.
pub struct Step {
    pub torques: Vec<f64>,
    pub steering: Vec<f64>,
    pub sample: rover_estimate::SensorSample,
}

/// The sensors of the bench and the allocation test: an IMU and wheel
/// encoders read at 100 Hz.
pub fn imu_and_encoders() -> rover_estimate::SensorConfig {
    use rover_estimate::sensors::{EncoderConfig, ImuConfig};
    rover_estimate::SensorConfig {
        seed: 3,
        rate: 100.0,
        imu: Some(ImuConfig {
            gyro_noise_deg_per_sqrt_h: 0.15,
            gyro_bias_deg_per_h: 10.0,
            accel_noise_ug_per_sqrt_hz: 100.0,
            accel_bias_mg: 2.0,
            bias_time: 300.0,
            position: [0.05, 0.0, 0.05],
            orientation_deg: [0.0, 0.0, 0.0],
        }),
        wheel_encoders: Some(EncoderConfig {
            resolution: 2.0 * std::f64::consts::PI / 4096.0,
        }),
        suspension_encoders: None,
        position_fix: None,
        heading_fix: None,
    }
}

/// Each wheel's torque [N·m] of a P speed loop holding 0.1 m/s (10 N·m
/// per m/s a wheel), sampled at 100 Hz.
fn speed_loop(vx: f64, wheels: usize) -> Vec<f64> {
    vec![10.0 * (0.1 - vx); wheels]
}

/// A filter on rover `name` (plant `plant`) on the Fig. 13 terrain, after
/// settling and 8 s of driving at 0.1 m/s (it is then on the rough
/// ground), and `count` filter steps of 10 ms from there (a prediction,
/// an IMU and an encoder update): readings equal to the filter's own
/// predictions, so that a replay from the returned filter takes exactly
/// these steps again.
pub fn recorded<P: Plant + Clone>(
    name: &str,
    plant: P,
    count: usize,
    config: rover_estimate::FilterConfig,
) -> (
    rover_estimate::Estimator<RoverSystem<P, Terrain>>,
    Vec<Step>,
) {
    use rover_estimate::{Estimator, InitialSigma, ProcessModel};
    let model = model(name);
    let (mut sys, mut y) = open_loop(&model, plant, fig13_terrain());
    settled(&mut sys, &mut y, 1.5);
    let wheels = model.wheels.len();
    let n = model.dof();
    let steering = vec![0.0; wheels];
    let mut integ = truth_integrator(y.len());
    let mut t = 1.5;
    for k in 1..=800 {
        sys.set_torques(&speed_loop(y[n], wheels)).unwrap();
        integ.restart();
        integ
            .advance(&mut sys, &mut t, &mut y, 1.5 + 0.01 * k as f64)
            .unwrap();
    }
    let mut filter = Estimator::new(
        sys,
        &imu_and_encoders(),
        config,
        t,
        &y,
        &InitialSigma::default(),
    )
    .unwrap();
    let mut angles = vec![0.0; wheels];
    filter.update_wheel_angles(&angles).unwrap();
    let start = filter.clone();
    let dim = y.len();
    let (mut rates, mut gradient) = (vec![0.0; wheels], vec![0.0; wheels * dim]);
    let dt = 0.01;
    let steps = (0..count)
        .map(|_| {
            let torques = speed_loop(filter.state()[n], wheels);
            filter.predict(dt, &torques, &steering).unwrap();
            let h = filter.predicted_imu(None).unwrap();
            let (t, state) = (filter.time(), filter.state().to_vec());
            filter
                .model_mut()
                .wheel_rates(t, &state, &mut rates, &mut gradient)
                .unwrap();
            for (a, r) in angles.iter_mut().zip(&rates) {
                *a += r * dt;
            }
            let step = Step {
                torques,
                steering: steering.clone(),
                sample: rover_estimate::SensorSample {
                    t,
                    gyro: Some([h[0], h[1], h[2]]),
                    accel: Some([h[3], h[4], h[5]]),
                    wheel_angles: angles.clone(),
                    ..Default::default()
                },
            };
            filter.update(&step.sample).unwrap();
            step
        })
        .collect();
    (start, steps)
}

/// One filter step of a replay: the prediction, then the sample's
/// updates (the IMU's, the encoders').
pub fn replay<M: rover_estimate::ProcessModel>(
    filter: &mut rover_estimate::Estimator<M>,
    step: &Step,
) -> Result<(), rover_estimate::EstimateError<M::Error>> {
    filter.predict(0.01, &step.torques, &step.steering)?;
    filter.update(&step.sample)
}

/// [`open_loop`] on ground covered with the built-in soil `soil`: the
/// state gains each wheel's spin, rolling at the start.
pub fn open_loop_on_soil<P: Plant>(
    model: &Model,
    plant: P,
    terrain: Terrain,
    soil: &str,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let soil = rover_runtime::soil::SoilConfig::builtin(soil)
        .unwrap()
        .soil()
        .unwrap();
    let ground = Ground::new(
        terrain,
        model,
        ContactMethod::Bounded,
        RimSampling::default(),
        WheelLawConfig::default(),
    )
    .with_soil(&soil, model)
    .unwrap();
    let mut sys = RoverSystem::open_loop(plant, Some(ground), model).unwrap();
    let n = model.dof();
    let mut y = vec![0.0; sys.dim()];
    y[6..n].copy_from_slice(&model.rest());
    y[2] = model.touchdown_height() - 2e-3;
    sys.roll_spins(0.0, &mut y);
    (sys, y)
}
