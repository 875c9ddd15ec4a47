//! Zero heap allocations over 10,000 steps of a full simulation with a
//! generated plant (issue 6): swing4 driving on flat ground with terrain
//! contact, the speed loop and the fixed-step RK4 integrator. Its own test
//! binary: it installs a counting global allocator.

use rover_dynamics::plant::Plant;
use rover_runtime::contact::RimSampling;
use rover_runtime::control::{Controller, ControllerConfig, Profile, SpeedConfig};
use rover_runtime::ground::{ContactMethod, Ground};
use rover_runtime::integrate::{FixedStepConfig, Integrator, Rk4};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_runtime::wheel_law::WheelLawConfig;

#[test]
fn ten_thousand_rk4_steps_with_a_generated_plant_allocate_nothing() {
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let model = spec.model;
    let plant = rover_models::Swing4::new();
    let n = plant.dof();
    let ground = Ground::new(
        Terrain::default(),
        &model,
        ContactMethod::Meridional,
        RimSampling::default(),
        WheelLawConfig::default(),
    );
    let config = ControllerConfig {
        speed: Some(SpeedConfig {
            speed: Profile::Constant(0.1),
            ..Default::default()
        }),
        ..Default::default()
    };
    let control = Controller::new(config, &model, 0.0).unwrap();
    let mut sys = RoverSystem::new(plant, Some(ground), control);
    let mut y = vec![0.0; 2 * n + 1];
    let rest = model.rest();
    y[6..n].copy_from_slice(&rest);
    // Wheels 1 mm into the ground: contact from the first step.
    let lowest = model
        .wheels
        .iter()
        .map(|w| model.bodies[w.body].position.value(&rest)[2] - w.radius)
        .fold(f64::INFINITY, f64::min);
    y[2] = -lowest - 1e-3;
    let step = 2e-5;
    let mut rk4 = Rk4::new(2 * n + 1, &FixedStepConfig { step }).unwrap();
    let mut t = 0.0;
    // Warm-up step (nothing here should allocate either, but the count
    // starts after it, as the issue says).
    rk4.advance(&mut sys, &mut t, &mut y, step).unwrap();
    // The counter counts: one Vec is one allocation.
    let probe = allocation_counter::measure(|| {
        std::hint::black_box(vec![1u8; 8]);
    });
    assert_eq!(probe.count_total, 1);
    let steps = 10_000;
    let counts = allocation_counter::measure(|| {
        for k in 2..=steps + 1 {
            rk4.advance(&mut sys, &mut t, &mut y, k as f64 * step)
                .unwrap();
        }
    });
    assert_eq!(
        counts.count_total, 0,
        "{} allocations over {steps} steps",
        counts.count_total
    );
    assert!(y.iter().all(|v| v.is_finite()));
    let normal: f64 = sys.reports().iter().map(|r| r.normal).sum();
    assert!(
        normal > 0.0,
        "the wheels touch the ground: ΣF_n = {normal} N"
    );
    assert!((t - (steps + 1) as f64 * step).abs() < 1e-12);
}
