//! rover against MuJoCo on the same rover (docs/ENGINES.md): the paper's
//! Example 2 (swing4) driving 40 s at 0.1 m/s from the same start, on
//! flat ground and on rough ground (the paper's random terrain, Z_R = 0.2,
//! given to both engines as the same grid of heights), in one criterion
//! run:
//!
//! - rover: RK4 with a 1 ms step (generated and generic plant), the
//!   semi-implicit Euler at 1 ms (one evaluation a step, like MuJoCo's
//!   Euler) and the scenarios' default BDF at its default tolerance and at
//!   1e-4 (generated plant), meridional contact;
//! - MuJoCo: the rover written as MJCF from the same description
//!   ([`mujoco::mjcf`]), 1 ms steps of its `Euler`, `implicitfast` and
//!   `RK4` integrators with cylinder wheels and of `Euler` with sphere
//!   wheels (one contact each), its default 2 ms step, and `implicitfast`
//!   at the longest steps whose runs still pass the check below (5–20 ms);
//! - one evaluation of the dynamics with contact, driving at t = 10 s: our
//!   right-hand side against `mj_forward`.
//!
//! Before timing, each run's end state is printed beside the others and
//! checked to be the same motion ([`Tolerance`]): a speed figure of a
//! model that drives differently would compare nothing.
//!
//! `MUJOCO_LIB=…/libmujoco.so.3.3.7 cargo bench --features mujoco --bench
//! engines -- --warm-up-time 1 --measurement-time 10`

#[path = "../support/mod.rs"]
mod support;

mod mujoco;

use std::hint::black_box;
use std::path::{Path, PathBuf};

use criterion::{BenchmarkId, Criterion};
use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{
    FixedStepConfig, Integrator, IntegratorConfig, OdeSystem, Rk4, Ros2, Ros2Config,
    SemiImplicitEuler,
};
use rover_runtime::GenericPlant;
use rover_runtime::control::SpeedConfig;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::{Grid, Terrain};
use rover_spec::Spec;

use mujoco::{Mujoco, Setup};

/// Simulated time of every run [s].
const DURATION: f64 = 40.0;
/// Our fixed step, and the step at which the single evaluations are sampled [s].
const STEP: f64 = 1e-3;
/// Our BDF runs: the scenarios' default integrator as it is (`None`), and
/// at uniform tolerances `rtol`, `atol = rtol/100` (docs/ENGINES.md).
const BDF_RTOL: [Option<f64>; 3] = [None, Some(1e-6), Some(1e-4)];
/// The fine RK4 step the BDF runs' end states are measured against [s].
const FINE_STEP: f64 = 1e-4;

/// Steps of the fixed-step linearly implicit method (ROS2) \[s\].
const ROS2_STEPS: [f64; 2] = [5e-3, 1e-2];
/// When the single evaluations of the dynamics are timed: driving, past
/// the settling [s].
const SAMPLE_TIME: f64 = 10.0;

/// Where a run ends: G's travel and height, the body's attitude, the arm
/// angles and the forward speed.
#[derive(Debug)]
struct End {
    x: f64,
    y: f64,
    z: f64,
    roll: f64,
    pitch: f64,
    arms: Vec<f64>,
    vx: f64,
}

/// How a ground is given to each engine, what MuJoCo runs on it, and how
/// closely the runs must agree.
struct Ground {
    name: &'static str,
    terrain: Terrain,
    map: Option<Grid>,
    /// MuJoCo's integrator, wheel shape and step [s].
    setups: &'static [(&'static str, &'static str, f64)],
    tolerance: Tolerance,
}

/// Largest differences between the end of our run and MuJoCo's.
struct Tolerance {
    /// Every arm angle [°].
    arm_deg: f64,
    /// G's height [m].
    z: f64,
    /// Roll and pitch [°].
    attitude_deg: f64,
    /// Forward speed [m/s].
    vx: f64,
    /// Travel along X, relative.
    x_rel: f64,
    /// Sideways drift [m].
    y: f64,
}

/// The grounds. On flat ground the engines can only differ by their
/// wheel–ground laws: the same sag of every arm (2°; our wheels deflect
/// 3 mm under their load, MuJoCo's barely), height and attitude (1 cm,
/// 0.5°), speed (2 mm/s) and travel (5 %). On rough ground the two
/// surfaces between the same nodes differ (bicubic against MuJoCo's
/// triangles) and so do the laws, so each wheel meets its bumps a little
/// differently: the runs must still cover the same ground, on the same
/// line, at the same speed (10 % of the travel, 5 cm sideways, 5 mm/s) and
/// end on the same spot of the map (5 cm of height, 5° of attitude and of
/// arm angle).
fn grounds() -> Vec<Ground> {
    let rough = support::rough_field();
    vec![
        Ground {
            name: "flat",
            terrain: Terrain::default(),
            map: None,
            setups: &[
                ("Euler", "cylinder", 1e-3),
                ("implicitfast", "cylinder", 1e-3),
                ("RK4", "cylinder", 1e-3),
                ("Euler", "sphere", 1e-3),
                ("Euler", "cylinder", 2e-3),
                ("implicitfast", "cylinder", 10e-3),
                ("implicitfast", "cylinder", 20e-3),
            ],
            tolerance: Tolerance {
                arm_deg: 2.0,
                z: 0.01,
                attitude_deg: 0.5,
                vx: 2e-3,
                x_rel: 0.05,
                y: 0.01,
            },
        },
        Ground {
            name: "rough",
            terrain: Terrain::Grid(rough.clone()),
            map: Some(rough),
            setups: &[
                ("Euler", "cylinder", 1e-3),
                ("Euler", "sphere", 1e-3),
                ("Euler", "cylinder", 2e-3),
                ("implicitfast", "cylinder", 5e-3),
                ("implicitfast", "cylinder", 10e-3),
            ],
            tolerance: Tolerance {
                arm_deg: 5.0,
                z: 0.05,
                attitude_deg: 5.0,
                vx: 5e-3,
                x_rel: 0.1,
                y: 0.05,
            },
        },
    ]
}

fn end_of(model: &Model, y: &[f64]) -> End {
    let n = model.dof();
    End {
        x: y[0],
        y: y[1],
        z: y[2],
        roll: y[3],
        pitch: y[4],
        arms: y[6..n].to_vec(),
        vx: y[n],
    }
}

fn rover_rk4<P: Plant>(model: &Model, plant: P, terrain: &Terrain) -> End {
    rover_fixed(model, plant, terrain, Rk4::new)
}

/// The rover driving on `terrain` from the start to `until` with the
/// integrator `make` builds for the state's dimension: the system, the
/// state and the integrator there.
fn drive<P: Plant, I: Integrator>(
    model: &Model,
    plant: P,
    terrain: &Terrain,
    make: impl FnOnce(usize) -> I,
    until: f64,
) -> (RoverSystem<P, Terrain>, Vec<f64>, I) {
    let (mut sys, mut y) =
        support::system_on(terrain.clone(), model, plant, ContactMethod::default());
    let mut integrator = make(y.len());
    let mut t = 0.0;
    integrator.advance(&mut sys, &mut t, &mut y, until).unwrap();
    (sys, y, integrator)
}

/// Our fixed-step run with `method` (RK4, or the semi-implicit Euler that
/// evaluates the dynamics once a step, as MuJoCo's Euler does).
fn rover_fixed<P: Plant, I: Integrator, E: std::fmt::Debug>(
    model: &Model,
    plant: P,
    terrain: &Terrain,
    method: impl Fn(usize, &FixedStepConfig) -> Result<I, E>,
) -> End {
    rover_fixed_at(model, plant, terrain, method, STEP)
}

/// [`rover_fixed`] at the step `step`.
fn rover_fixed_at<P: Plant, I: Integrator, E: std::fmt::Debug>(
    model: &Model,
    plant: P,
    terrain: &Terrain,
    method: impl Fn(usize, &FixedStepConfig) -> Result<I, E>,
    step: f64,
) -> End {
    let make = |dim| method(dim, &FixedStepConfig { step }).unwrap();
    let (_, y, _) = drive(model, plant, terrain, make, DURATION);
    end_of(model, &y)
}

/// The run with a scenario's default integrator, as it is (`rtol` None:
/// its tolerances per component, docs/PERFORMANCE.md) or at the uniform
/// relative tolerance `rtol` with `atol` 100 times less; also its
/// right-hand sides.
fn rover_bdf<P: Plant>(
    model: &Model,
    plant: P,
    terrain: &Terrain,
    rtol: Option<f64>,
) -> (End, u64) {
    let mut config = rover_scenario::scenario::default_integrator();
    if let (IntegratorConfig::Bdf(bdf), Some(rtol)) = (&mut config, rtol) {
        bdf.rtol = rtol;
        bdf.atol = Some(rtol / 100.0);
    }
    let make = |dim| config.build(dim).unwrap();
    let (_, y, bdf) = drive(model, plant, terrain, make, DURATION);
    (end_of(model, &y), bdf.stats().rhs_evals)
}

/// The run with ROS2 at a fixed `step`; also its right-hand sides.
fn rover_ros2<P: Plant>(model: &Model, plant: P, terrain: &Terrain, step: f64) -> (End, u64) {
    let config = Ros2Config {
        step,
        jacobian_every: 1,
        jacobian: Default::default(),
    };
    let make = |dim| Ros2::new(dim, &config).unwrap();
    let (_, y, ros2) = drive(model, plant, terrain, make, DURATION);
    (end_of(model, &y), ros2.stats().rhs_evals)
}

fn mujoco_run(sim: &mut mujoco::Sim<'_>, wheels: usize) -> End {
    sim.run(DURATION);
    let (q, v) = (sim.qpos(), sim.qvel());
    // Roll and pitch of R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md §1) from the
    // quaternion: R[2][1] = sin φ, R[2][0] = −cos φ·sin θ, R[2][2] = cos φ·cos θ.
    let [w, a, b, c] = [q[3], q[4], q[5], q[6]];
    let r21 = 2.0 * (b * c + w * a);
    let r20 = 2.0 * (a * c - w * b);
    let r22 = 1.0 - 2.0 * (a * a + b * b);
    End {
        x: q[0],
        y: q[1],
        z: q[2],
        roll: r21.asin(),
        pitch: (-r20).atan2(r22),
        arms: (0..wheels).map(|k| q[7 + 2 * k]).collect(),
        vx: v[0],
    }
}

fn check_same_motion(reference: &End, other: &End, tol: &Tolerance, label: &str) {
    let deg = 180.0 / std::f64::consts::PI;
    let mut bad = Vec::new();
    for (k, (a, b)) in reference.arms.iter().zip(&other.arms).enumerate() {
        if ((a - b) * deg).abs() > tol.arm_deg {
            bad.push(format!("arm {}: {:.2}° vs {:.2}°", k + 1, a * deg, b * deg));
        }
    }
    for (what, a, b, limit) in [
        ("Z [m]", reference.z, other.z, tol.z),
        ("Y [m]", reference.y, other.y, tol.y),
        ("v_x [m/s]", reference.vx, other.vx, tol.vx),
        ("X [m]", reference.x, other.x, tol.x_rel * reference.x.abs()),
        (
            "roll [°]",
            reference.roll * deg,
            other.roll * deg,
            tol.attitude_deg,
        ),
        (
            "pitch [°]",
            reference.pitch * deg,
            other.pitch * deg,
            tol.attitude_deg,
        ),
    ] {
        if (a - b).abs() > limit {
            bad.push(format!("{what}: {a:.4} vs {b:.4}"));
        }
    }
    assert!(
        bad.is_empty(),
        "{label} does not drive as rover does, nothing to compare: {}",
        bad.join("; ")
    );
}

/// A BDF run's name: its default tolerances, or `rtol`.
fn bdf_label(rtol: Option<f64>) -> String {
    rtol.map_or_else(|| "default".to_owned(), |r| format!("rtol_{r:e}"))
}

/// G's distance [m] and the larger difference of roll and pitch [°]
/// between two ends.
fn distance(a: &End, b: &End) -> (f64, f64) {
    let position = ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.z - b.z).powi(2)).sqrt();
    let attitude = (a.roll - b.roll)
        .abs()
        .max((a.pitch - b.pitch).abs())
        .to_degrees();
    (position, attitude)
}

fn print_end(label: &str, e: &End) {
    let deg = 180.0 / std::f64::consts::PI;
    let arms: Vec<String> = e.arms.iter().map(|a| format!("{:7.2}", a * deg)).collect();
    println!(
        "  {label:<30} X {:7.4}  Y {:7.4}  Z {:7.4} m  roll {:6.2}°  pitch {:6.2}°  v_x {:7.4} m/s  arms {}°",
        e.x,
        e.y,
        e.z,
        e.roll * deg,
        e.pitch * deg,
        e.vx,
        arms.join(" ")
    );
}

/// MuJoCo's models of swing4 on `ground`, each written to `dir` and compiled.
fn mujoco_models<'a>(
    mj: &'a Mujoco,
    spec: &Spec,
    ground: &Ground,
    dir: &Path,
) -> Vec<(String, mujoco::Sim<'a>)> {
    let kp = SpeedConfig::default().kp;
    let start = support::start_height(&spec.model);
    ground
        .setups
        .iter()
        .map(|&(integrator, wheel, timestep)| {
            let setup = Setup {
                integrator,
                timestep,
                wheel,
            };
            let xml = mujoco::mjcf(spec, setup, ground.map.as_ref(), kp, support::SPEED, start)
                .unwrap_or_else(|e| panic!("{e}"));
            let label = format!("{integrator}_{wheel}_{}ms", timestep * 1e3);
            let file = dir.join(format!("swing4_{}_{label}.xml", ground.name));
            std::fs::write(&file, xml).unwrap();
            (
                label,
                mj.model(&file, timestep).unwrap_or_else(|e| panic!("{e}")),
            )
        })
        .collect()
}

fn main() {
    let Some(lib) = std::env::var_os("MUJOCO_LIB").map(PathBuf::from) else {
        eprintln!(
            "set MUJOCO_LIB to MuJoCo's shared library, e.g. after `pip install mujoco==3.3.7`:\n  \
             MUJOCO_LIB=$(python3 -c 'import mujoco, os; print(os.path.dirname(mujoco.__file__))')/libmujoco.so.3.3.7"
        );
        std::process::exit(2);
    };
    let mj = Mujoco::load(&lib).unwrap_or_else(|e| panic!("{e}"));
    let source = rover_models::builtin_path("swing4").unwrap();
    let spec: Spec =
        rover_spec::load_str(rover_models::builtin("swing4").unwrap(), source).unwrap();
    let model = spec.model.clone();
    let wheels = model.wheels.len();
    let dir = std::env::temp_dir().join(format!("rover-engines-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut c = Criterion::default().configure_from_args();
    println!(
        "MuJoCo {} ({}): swing4, {DURATION} s at {} m/s",
        mj.version(),
        lib.display(),
        support::SPEED
    );
    for ground in grounds() {
        let mut sims = mujoco_models(&mj, &spec, &ground, &dir);
        let terrain = &ground.terrain;
        println!("{} ground, where each run ends:", ground.name);
        let reference = rover_rk4(&model, rover_models::Swing4::new(), terrain);
        print_end("rover RK4 1 ms", &reference);
        let euler = rover_fixed(
            &model,
            rover_models::Swing4::new(),
            terrain,
            SemiImplicitEuler::new,
        );
        print_end("rover semi-implicit Euler 1 ms", &euler);
        check_same_motion(
            &reference,
            &euler,
            &ground.tolerance,
            "rover's semi-implicit Euler",
        );
        let fine = rover_fixed_at(
            &model,
            rover_models::Swing4::new(),
            terrain,
            Rk4::new,
            FINE_STEP,
        );
        print_end("rover RK4 0.1 ms", &fine);
        for rtol in BDF_RTOL {
            let (bdf, rhs) = rover_bdf(&model, rover_models::Swing4::new(), terrain, rtol);
            let label = format!("rover BDF {} ({rhs} RHS)", bdf_label(rtol));
            print_end(&label, &bdf);
            check_same_motion(&reference, &bdf, &ground.tolerance, &label);
            let (position, attitude) = distance(&fine, &bdf);
            println!("    from RK4 0.1 ms: {position:.1e} m, {attitude:.1e}° (roll, pitch)");
        }
        for step in ROS2_STEPS {
            let (ros2, rhs) = rover_ros2(&model, rover_models::Swing4::new(), terrain, step);
            let label = format!("rover ROS2 {} ms ({rhs} RHS)", step * 1e3);
            print_end(&label, &ros2);
            check_same_motion(&reference, &ros2, &ground.tolerance, &label);
        }
        for (setup, sim) in &mut sims {
            let end = mujoco_run(sim, wheels);
            let label = format!("MuJoCo {setup}");
            print_end(&label, &end);
            check_same_motion(&reference, &end, &ground.tolerance, &label);
        }

        let mut group = c.benchmark_group(format!("swing4_{}_40s", ground.name));
        group.sample_size(10);
        group.bench_function(BenchmarkId::new("rover_rk4_1ms", "generated"), |b| {
            b.iter(|| black_box(rover_rk4(&model, rover_models::Swing4::new(), terrain).x))
        });
        let generic = GenericPlant::new(model.clone()).unwrap();
        group.bench_function(BenchmarkId::new("rover_rk4_1ms", "generic"), |b| {
            b.iter(|| black_box(rover_rk4(&model, generic.clone(), terrain).x))
        });
        group.bench_function(
            BenchmarkId::new("rover_semi_implicit_euler_1ms", "generated"),
            |b| {
                b.iter(|| {
                    let plant = rover_models::Swing4::new();
                    black_box(rover_fixed(&model, plant, terrain, SemiImplicitEuler::new).x)
                })
            },
        );
        for rtol in BDF_RTOL {
            let id = BenchmarkId::new("rover_bdf", format!("generated_{}", bdf_label(rtol)));
            group.bench_function(id, |b| {
                b.iter(|| {
                    black_box(
                        rover_bdf(&model, rover_models::Swing4::new(), terrain, rtol)
                            .0
                            .x,
                    )
                })
            });
        }
        for step in ROS2_STEPS {
            let id = BenchmarkId::new("rover_ros2", format!("generated_{}ms", step * 1e3));
            group.bench_function(id, |b| {
                b.iter(|| {
                    black_box(
                        rover_ros2(&model, rover_models::Swing4::new(), terrain, step)
                            .0
                            .x,
                    )
                })
            });
        }
        for (setup, sim) in &mut sims {
            group.bench_function(BenchmarkId::new("mujoco", setup.as_str()), |b| {
                b.iter(|| sim.run(DURATION))
            });
        }
        group.finish();

        // One evaluation of the dynamics with contact, driving, at t = 10 s.
        let mut group = c.benchmark_group(format!("swing4_{}_dynamics", ground.name));
        let rk4 = |dim| Rk4::new(dim, &FixedStepConfig { step: STEP }).unwrap();
        let plant = rover_models::Swing4::new();
        let (mut sys, y, _) = drive(&model, plant, terrain, rk4, SAMPLE_TIME);
        let mut dy = vec![0.0; y.len()];
        group.bench_function(BenchmarkId::new("rover_rhs", "generated"), |b| {
            b.iter(|| sys.rhs(SAMPLE_TIME, black_box(&y), &mut dy).unwrap())
        });
        for (setup, sim) in sims
            .iter_mut()
            .filter(|(s, _)| s.starts_with("Euler") && s.ends_with("_1ms"))
        {
            sim.run(SAMPLE_TIME);
            group.bench_function(BenchmarkId::new("mujoco_forward", setup.as_str()), |b| {
                b.iter(|| sim.forward())
            });
        }
        group.finish();
    }
    c.final_summary();
    let _ = std::fs::remove_dir_all(&dir);
}
