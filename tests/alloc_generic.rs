//! Zero heap allocations per step on the real-time path with the generic
//! plant: GenericPlant + terrain contact + controller + RK4 / semi-implicit
//! Euler (issue 5). Its own test binary: it installs a counting allocator.

use rover_runtime::GenericPlant;
use rover_runtime::contact::RimSampling;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::{ContactMethod, Ground};
use rover_runtime::integrate::{FixedStepConfig, Integrator, IntegratorConfig};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::TerrainConfig;
use rover_runtime::wheel_law::WheelLawConfig;

#[test]
fn real_time_path_allocates_nothing_per_step() {
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let model = spec.model;
    let terrain: TerrainConfig =
        toml::from_str("kind = \"random\"\nz_r = 0.1\nextent = [-3.0, 3.0, -3.0, 3.0]").unwrap();
    let terrain = terrain.build(std::path::Path::new(".")).unwrap();
    let control: ControllerConfig = toml::from_str(
        "[speed]\nspeed = 0.1\nki = 5.0\ndistribution = \"measured_load\"\n[steering]\nkind = \"slip\"\ndelta_tau = 0.1",
    )
    .unwrap();
    for method in ["rk4", "semi_implicit_euler"] {
        let ground = Ground::new(
            terrain.clone(),
            &model,
            ContactMethod::Meridional,
            RimSampling::default(),
            WheelLawConfig::default(),
        );
        let controller = Controller::new(control.clone(), &model, 0.0).unwrap();
        let mut sys = RoverSystem::new(
            GenericPlant::new(model.clone()).unwrap(),
            Some(ground),
            controller,
        );
        let n = model.dof();
        let mut y = vec![0.0; 2 * n + 1];
        y[2] = 0.27;
        y[6..n].copy_from_slice(&model.rest());
        y[n] = 0.1;
        let config = match method {
            "rk4" => IntegratorConfig::Rk4(FixedStepConfig { step: 1e-4 }),
            _ => IntegratorConfig::SemiImplicitEuler(FixedStepConfig { step: 1e-4 }),
        };
        let mut integ = config.build(2 * n + 1).unwrap();
        let mut t = 0.0;
        integ.advance(&mut sys, &mut t, &mut y, 1e-4).unwrap();
        let counted = allocation_counter::measure(|| {
            for k in 2..=10_001 {
                integ
                    .advance(&mut sys, &mut t, &mut y, k as f64 * 1e-4)
                    .unwrap();
            }
        });
        assert_eq!(
            counted.count_total, 0,
            "{method}: {} allocations over 10 000 steps",
            counted.count_total
        );
        assert!((t - 1.0001).abs() < 1e-12 && y.iter().all(|v| v.is_finite()));
        assert!(
            sys.reports().iter().any(|r| r.normal > 0.0),
            "{method}: the wheels touch the ground"
        );
    }
}
