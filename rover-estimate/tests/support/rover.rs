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
        atol: 1e-10,
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
