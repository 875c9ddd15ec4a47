//! What the benches share: a built-in rover's model, and that rover on
//! flat ground, wheels just touching, driving at 0.1 m/s under the paper's
//! P speed loop (the default `kp`). Each bench uses part of it.
#![allow(dead_code)]

use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::height_field::Bounds;
use rover_dynamics::plant::Plant;
use rover_dynamics::soil::Soil;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::control::{Controller, ControllerConfig, Profile, SpeedConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::{Grid, RandomField, Terrain};
use rover_runtime::wheel_law::WheelLawConfig;

/// The speed every bench drives at [m/s].
pub const SPEED: f64 = 0.1;

/// The numeric model of a built-in rover.
pub fn model(name: &str) -> Model {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name)
        .unwrap()
        .model
}

/// The rover on flat ground, wheels just touching, driving at [`SPEED`].
pub fn system<P: Plant>(
    model: &Model,
    plant: P,
    method: ContactMethod,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    system_on(Terrain::default(), model, plant, method)
}

/// [`system`] on `terrain`: the state starts at rest with the suspension
/// at its rest angles and G at [`start_height`].
pub fn system_on<P: Plant>(
    terrain: Terrain,
    model: &Model,
    plant: P,
    method: ContactMethod,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    system_with(ground(terrain, model, method), model, plant)
}

/// The ground of `terrain` for `model`'s wheels, searched by `method`,
/// under the paper's wheel law.
fn ground(terrain: Terrain, model: &Model, method: ContactMethod) -> Ground<Terrain> {
    Ground::new(
        terrain,
        model,
        method,
        RimSampling::default(),
        WheelLawConfig::default(),
    )
}

/// [`system_on`] with `terrain` covered by `soil`: the state gains each
/// wheel's spin at its end (`RoverSystem::spin_range`), zero here (a
/// bench sets them, e.g. by `RoverSystem::roll_spins`).
pub fn soil_system_on<P: Plant>(
    terrain: Terrain,
    model: &Model,
    plant: P,
    method: ContactMethod,
    soil: &Soil,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let ground = ground(terrain, model, method)
        .with_soil(soil, model)
        .unwrap();
    system_with(ground, model, plant)
}

/// The rover on `ground`, driving at [`SPEED`], at rest with the
/// suspension at its rest angles and G at [`start_height`].
fn system_with<P: Plant>(
    ground: Ground<Terrain>,
    model: &Model,
    plant: P,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let n = model.dof();
    let config = ControllerConfig {
        speed: Some(SpeedConfig {
            speed: Profile::Constant(SPEED),
            ..Default::default()
        }),
        ..Default::default()
    };
    let control = Controller::new(config, model, 0.0).unwrap();
    let sys = RoverSystem::new(plant, Some(ground), control);
    let mut y = vec![0.0; sys.dim()];
    let rest = model.rest();
    y[6..n].copy_from_slice(&rest);
    y[2] = start_height(model);
    (sys, y)
}

/// G's starting height: 2 mm into the ground, so that every wheel is in
/// contact from the first step.
pub fn start_height(model: &Model) -> f64 {
    model.touchdown_height() - 2e-3
}

/// The paper's rough terrain as the reproduction of Figs. 13–16 builds it
/// (Z_R = 0.2, seed 1, docs/REPRODUCTION.md), over the ground the benches
/// drive on: from 3 m behind the start (the LRV's rear wheels start 1.5 m
/// behind it) to 6.5 m ahead, 2 m to each side. The grid's nodes keep
/// their places, to rounding, whatever the extent (multiples of its 5 cm
/// spacing), so the ground is the same where the maps overlap.
pub fn rough_field() -> Grid {
    RandomField {
        z_r: 0.2,
        node_amplitude: 0.25,
        patch_radius: 0.6,
        extent: Bounds {
            x_min: -3.0,
            x_max: 6.5,
            y_min: -2.0,
            y_max: 2.0,
        },
        ..RandomField::default()
    }
    .grid()
    .unwrap()
}

/// The state after driving `seconds` on `terrain` from the start (RK4,
/// 1 ms, the sampled search).
pub fn driven<P: Plant>(terrain: &Terrain, model: &Model, plant: P, seconds: f64) -> Vec<f64> {
    let (mut sys, mut y) = system_on(terrain.clone(), model, plant, ContactMethod::Meridional);
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: 1e-3 }).unwrap();
    let mut t = 0.0;
    rk4.advance(&mut sys, &mut t, &mut y, seconds).unwrap();
    y
}

/// `count` states 1 ms apart from `start` on `terrain` (RK4, 1 ms, the
/// sampled search).
pub fn path_from<P: Plant>(
    terrain: &Terrain,
    model: &Model,
    plant: P,
    start: &[f64],
    count: usize,
) -> Vec<Vec<f64>> {
    let (mut sys, mut y) = system_on(terrain.clone(), model, plant, ContactMethod::Meridional);
    y.copy_from_slice(start);
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: 1e-3 }).unwrap();
    let mut t = 0.0;
    (0..count)
        .map(|k| {
            rk4.advance(&mut sys, &mut t, &mut y, (k + 1) as f64 * 1e-3)
                .unwrap();
            y.clone()
        })
        .collect()
}
