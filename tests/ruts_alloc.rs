//! The force path on ground that keeps ruts allocates nothing: MER on
//! random ground covered with dry sand, driven until its middle and rear
//! wheels run in the front ones' ruts, then the right-hand side and the
//! assembled Jacobian read the map without one allocation, and fixed steps
//! that record new presses (and make new tiles) allocate nothing once the
//! map's pool holds the tiles they make. Its own test binary: it installs
//! a counting global allocator.

use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, SemiImplicitEuler};
use rover_models::Mer;
use rover_runtime::control::{Controller, ControllerConfig, Profile, SpeedConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::soil::SoilConfig;
use rover_runtime::terrain::{Terrain, TerrainConfig};
use rover_runtime::wheel_law::WheelLawConfig;

/// The fixed step \[s\].
const STEP: f64 = 1e-3;

/// The drive's speed \[m/s\]: the rear wheels, 1.35 m behind the front
/// ones, reach their ruts after about 7 s.
const SPEED: f64 = 0.2;

fn mer() -> Model {
    rover_spec::load_str(rover_models::builtin("mer").unwrap(), "mer")
        .unwrap()
        .model
}

/// MER at rest on random ground under dry sand keeping ruts in 2 cm cells,
/// the wheels 2 mm into the soil and rolling, its speed loop holding
/// [`SPEED`] (the default proportional gain, which a 1 ms explicit step
/// holds, and an integral one for the torque the sand asks).
fn soft_system(model: &Model) -> (RoverSystem<Mer, Terrain>, Vec<f64>) {
    let terrain: TerrainConfig =
        toml::from_str("kind = \"random\"\nz_r = 0.1\nextent = [-3.0, 6.0, -3.0, 3.0]").unwrap();
    let terrain = terrain.build(std::path::Path::new(".")).unwrap();
    let sand = SoilConfig::builtin("dry_sand").unwrap().soil().unwrap();
    let ground = Ground::new(
        terrain,
        model,
        ContactMethod::default(),
        RimSampling::default(),
        WheelLawConfig::default(),
    )
    .with_soil(&sand, model)
    .unwrap()
    .with_ruts(0.02);
    let config = ControllerConfig {
        speed: Some(SpeedConfig {
            speed: Profile::Constant(SPEED),
            kp: 10.0,
            ki: 1000.0,
            ..Default::default()
        }),
        ..Default::default()
    };
    let control = Controller::new(config, model, 0.0).unwrap();
    let mut sys = RoverSystem::new(Mer::new(), Some(ground), control);
    let mut y = vec![0.0; sys.dim()];
    let n = model.dof();
    y[6..n].copy_from_slice(&model.rest());
    y[2] = model.touchdown_height() - 2e-3;
    sys.roll_spins(0.0, &mut y);
    (sys, y)
}

fn tiles(sys: &RoverSystem<Mer, Terrain>) -> usize {
    sys.ground
        .as_ref()
        .unwrap()
        .ruts()
        .unwrap()
        .map()
        .tile_count()
}

#[test]
fn rhs_jacobian_and_steps_on_ruts_allocate_nothing() {
    let model = mer();
    let (mut sys, mut y) = soft_system(&model);
    let mut euler = SemiImplicitEuler::new(y.len(), &FixedStepConfig { step: STEP }).unwrap();
    let mut t = 0.0;
    euler.advance(&mut sys, &mut t, &mut y, 9.0).unwrap();
    let mut dy = vec![0.0; y.len()];
    sys.rhs(t, &y, &mut dy).unwrap();
    let ruts: Vec<f64> = sys.reports().iter().map(|r| r.rut).collect();
    // Wheels 3..6 are the middle and rear ones.
    assert!(
        tiles(&sys) > 0 && ruts[2..].iter().all(|&r| r > 1e-4),
        "x = {} m, {} tiles, ruts under the wheels {ruts:?} m",
        y[0],
        tiles(&sys)
    );

    // (a) The right-hand side and the assembled Jacobian along 200 states
    // 1 ms apart, the rear wheels in ruts all along.
    let mut path = Vec::new();
    let (mut ahead, mut ya, mut ta) = (sys.clone(), y.clone(), t);
    for _ in 0..200 {
        let to = ta + STEP;
        euler.advance(&mut ahead, &mut ta, &mut ya, to).unwrap();
        path.push((ta, ya.clone()));
    }
    let dim = y.len();
    let mut jac = vec![0.0; dim * dim];
    let mut deepest_rear = f64::INFINITY;
    let counts = allocation_counter::measure(|| {
        for (k, (t, y)) in path.iter().enumerate() {
            sys.rhs(*t, y, &mut dy).unwrap();
            let rear = sys.reports()[4].rut.min(sys.reports()[5].rut);
            deepest_rear = deepest_rear.min(rear);
            if k % 10 == 0 {
                sys.jacobian(*t, y, &mut jac).unwrap().unwrap();
            }
        }
    });
    assert_eq!(
        counts.count_total, 0,
        "{} allocations over 200 right-hand sides and 20 Jacobians",
        counts.count_total
    );
    assert!(deepest_rear > 1e-4, "rear wheels' ruts {deepest_rear} m");
    assert!(jac.iter().all(|v| v.is_finite()) && jac.iter().any(|&v| v != 0.0));

    // (b) 4000 steps (0.8 m: every track enters new tiles) with the
    // recording of `step_accepted`, from a pool of 64 tiles.
    const POOL: usize = 64;
    let ground = sys.ground.as_mut().unwrap();
    ground.ruts_mut().unwrap().map_mut().reserve(POOL);
    let before = tiles(&sys);
    let counts = allocation_counter::measure(|| {
        for _ in 0..4000 {
            let to = t + STEP;
            euler.advance(&mut sys, &mut t, &mut y, to).unwrap();
        }
    });
    let made = tiles(&sys) - before;
    assert!(
        made > 0 && made <= POOL,
        "{made} tiles made from a pool of {POOL}"
    );
    assert_eq!(
        counts.count_total, 0,
        "{} allocations over 4000 steps that made {made} tiles",
        counts.count_total
    );
    assert!(y.iter().all(|v| v.is_finite()));
}
