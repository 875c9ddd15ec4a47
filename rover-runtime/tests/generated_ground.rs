//! The generated force path against the runtime's: each built-in rover's
//! `derivatives_on_ground` (its generated plant, its tyres and radii as
//! constants, the no_std contact search and wheel law of
//! `rover_dynamics::wheel_ground`) against `RoverSystem` with the generic
//! plant, on the paper's rough terrain, under open-loop torques and
//! steering: the same ẋ and ẇ to 1e-12 (norm-wise relative, as the
//! plants alone are held to) and the same patches — on rigid ground and on
//! a soil, where the wheels' spin rates must agree too — at seeded random poses
//! and along a path 1 ms a step, where the bounded search reuses what it
//! proved.

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::height_field::Bounds;
use rover_dynamics::soil::{Soil, SoilWheel};
use rover_dynamics::wheel_ground::{ContactMethod, FixedGround, Search};
use rover_dynamics::wheel_law::Tyre;
use rover_dynamics::wheel_soil::SoilTyre;
use rover_integrate::OdeSystem;
use rover_runtime::GenericPlant;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::{Ground, touchdown_heights};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::{Grid, RandomField};
use rover_runtime::wheel_law::WheelLawConfig;
use rover_test_support::rel;
use rover_test_support::rng::Rng;

const TOL: f64 = 1e-12;

/// The paper's rough terrain (Z_R = 0.2), over the ground the poses stand on.
fn rough() -> Grid {
    RandomField {
        z_r: 0.2,
        node_amplitude: 0.25,
        patch_radius: 0.6,
        extent: Bounds {
            x_min: -3.5,
            x_max: 3.5,
            y_min: -3.0,
            y_max: 3.0,
        },
        ..RandomField::default()
    }
    .grid()
    .unwrap()
}

/// A pose over the rough ground with the lowest wheel `depth` into it, the
/// suspension near rest, and a random twist.
fn pose(model: &Model, terrain: &Grid, rng: &mut Rng, depth: f64) -> (Vec<f64>, Vec<f64>) {
    let n = model.dof();
    let mut x = vec![0.0; n];
    x[0] = rng.uniform(-0.5, 0.5);
    x[1] = rng.uniform(-0.5, 0.5);
    x[3] = rng.uniform(-0.1, 0.1);
    x[4] = rng.uniform(-0.1, 0.1);
    x[5] = rng.uniform(-3.1, 3.1);
    for (i, c) in model.coordinates.iter().enumerate() {
        let rest = model.rest()[i];
        x[6 + i] = rest + rng.uniform(-0.05, 0.05) * (c.max - c.min);
    }
    let attitude = Attitude::new(x[3], x[4], x[5]);
    let heights = touchdown_heights(model, [x[0], x[1]], attitude, &x[6..], terrain).unwrap();
    x[2] = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max) - depth;
    let w = (0..n).map(|_| rng.uniform(-0.3, 0.3)).collect();
    (x, w)
}

/// Compares the generated force path of rover `name` with the runtime's.
#[allow(clippy::too_many_arguments)]
fn compare<const N: usize, const W: usize>(
    name: &str,
    seed: u64,
    soil: Option<&Soil>,
    tyres: &[Tyre; W],
    rhs: impl Fn(
        &mut FixedGround<W>,
        &Grid,
        &WheelLawConfig,
        &[f64; N],
        &[f64; N],
        &[f64; W],
        [f64; W],
        &mut [f64; N],
        &mut [f64; N],
    ),
) {
    let spec = rover_spec::load_str(rover_models::builtin(name).unwrap(), name).unwrap();
    let model = spec.model;
    let terrain = rough();
    let law = WheelLawConfig::default();
    let ground = Ground::new(
        terrain.clone(),
        &model,
        ContactMethod::Bounded,
        RimSampling::default(),
        law,
    );
    assert_eq!(ground.tyres(), tyres, "{name}: the generated tyres");
    let ground = match soil {
        Some(soil) => ground.with_soil(soil, &model).unwrap(),
        None => ground,
    };
    let control = Controller::new(ControllerConfig::default(), &model, 0.0).unwrap();
    let mut sys = RoverSystem::new(
        GenericPlant::new(model.clone()).unwrap(),
        Some(ground),
        control,
    );
    let search = Search::new(ContactMethod::Bounded, RimSampling::default());
    let mut fixed = match soil {
        Some(soil) => FixedGround::<W>::on_soil(
            search,
            core::array::from_fn(|k| {
                let w = &model.wheels[k];
                SoilTyre {
                    wheel: SoilWheel::new(soil, w.radius, w.width.unwrap()),
                    damping: w.damping,
                }
            }),
        ),
        None => FixedGround::<W>::new(search),
    };
    let inertias: [f64; W] = core::array::from_fn(|k| model.wheels[k].spin_inertia);
    let mut rng = Rng::new(seed);
    let (mut worst, mut patches) = (0.0f64, 0);
    for trial in 0..40 {
        let depth = rng.uniform(0.02, 0.05);
        let (mut x, w) = pose(&model, &terrain, &mut rng, depth);
        let torques: [f64; W] =
            core::array::from_fn(|k| rng.uniform(-0.5, 0.5) * model.wheels[k].max_torque);
        let steer: [f64; W] = core::array::from_fn(|k| {
            if model.wheels[k].steerable {
                rng.uniform(-0.4, 0.4)
            } else {
                0.0
            }
        });
        sys.set_torques(&torques).unwrap();
        sys.set_steering(&steer).unwrap();
        // On a soil, each wheel spins near rolling, some skidding, some spinning.
        let spins: [f64; W] = core::array::from_fn(|k| {
            rng.uniform(-0.5, 0.5) / model.wheels[k].radius * if soil.is_some() { 1.0 } else { 0.0 }
        });
        // Along a path from the pose: 30 states 1 ms apart.
        for step in 0..30 {
            for i in 0..N {
                x[i] += 1e-3 * w[i].min(0.3);
            }
            let mut y = x.clone();
            y.extend_from_slice(&w);
            if soil.is_some() {
                y.extend_from_slice(&spins);
            }
            let mut dy = vec![0.0; y.len()];
            sys.rhs(0.0, &y, &mut dy).unwrap();
            fixed.set_spins(&spins);
            let (xs, ws): (&[f64; N], &[f64; N]) = (
                x.as_slice().try_into().unwrap(),
                w.as_slice().try_into().unwrap(),
            );
            let (mut xd, mut wd) = ([0.0; N], [0.0; N]);
            rhs(
                &mut fixed, &terrain, &law, xs, ws, &steer, torques, &mut xd, &mut wd,
            );
            for k in 0..W {
                let (a, b) = (fixed.reports()[k], sys.reports()[k]);
                assert_eq!(
                    a.patches, b.patches,
                    "{name} trial {trial} step {step}: wheel {k}'s patches"
                );
                patches += a.patches;
            }
            let mut e = rel(&xd, &dy[..N]).max(rel(&wd, &dy[N..2 * N]));
            if soil.is_some() {
                let rates = fixed.spin_rates(&torques, &inertias);
                e = e.max(rel(&rates, &dy[2 * N..]));
            }
            worst = worst.max(e);
            assert!(
                e <= TOL,
                "{name} trial {trial} step {step}: ẋ, ẇ differ by {e:e}"
            );
        }
    }
    // The poses press the lowest wheel into the ground; on ground this rough
    // a large rover's other wheels often hang: at least a quarter touch.
    assert!(
        patches > 40 * 30 * W / 4,
        "{name}: only {patches} patches in {} wheel states",
        40 * 30 * W
    );
    eprintln!("{name}: worst relative difference of ẋ, ẇ {worst:e}, {patches} patches");
}

macro_rules! generated_on_ground {
    ($test:ident, $name:literal, $plant:ty, $seed:literal) => {
        generated_on_ground!($test, $name, $plant, $seed, None);
    };
    ($test:ident, $name:literal, $plant:ty, $seed:literal, $soil:expr) => {
        #[test]
        fn $test() {
            let plant = <$plant>::new();
            let soil: Option<Soil> = $soil;
            compare(
                $name,
                $seed,
                soil.as_ref(),
                &<$plant>::TYRES,
                |g, t, l, x, w, s, tau, xd, wd| {
                    plant
                        .derivatives_on_ground(g, t, l, &<$plant>::TYRES, x, w, s, |_| tau, xd, wd)
                        .unwrap()
                },
            );
        }
    };
}

generated_on_ground!(
    generated_swing4_on_rough_ground_equals_generic,
    "swing4",
    rover_models::Swing4,
    71
);
generated_on_ground!(
    generated_exomars_on_rough_ground_equals_generic,
    "exomars",
    rover_models::Exomars,
    72
);
generated_on_ground!(
    generated_mer_on_rough_ground_equals_generic,
    "mer",
    rover_models::Mer,
    73
);
generated_on_ground!(
    generated_lrv_on_rough_ground_equals_generic,
    "lrv",
    rover_models::Lrv,
    74
);

/// The soil of the soft cases.
fn dry_sand() -> Option<Soil> {
    Some(
        rover_runtime::soil::SoilConfig::builtin("dry_sand")
            .unwrap()
            .soil()
            .unwrap(),
    )
}

generated_on_ground!(
    generated_exomars_on_rough_soil_equals_generic,
    "exomars",
    rover_models::Exomars,
    81,
    dry_sand()
);
generated_on_ground!(
    generated_mer_on_rough_soil_equals_generic,
    "mer",
    rover_models::Mer,
    82,
    dry_sand()
);
