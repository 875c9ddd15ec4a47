//! rover against MuJoCo on the same rover (docs/ENGINES.md): the paper's
//! Example 2 (swing4) driving 40 s at 0.1 m/s on flat ground, from the
//! same start, in one criterion run:
//!
//! - rover: RK4 with a 1 ms step (160,000 right-hand sides), generated and
//!   generic plant, meridional contact (as `benches/plant.rs`);
//! - MuJoCo: the rover written as MJCF from the same description
//!   ([`mujoco::mjcf`]), 40,000 steps of 1 ms with its `Euler`,
//!   `implicitfast` and `RK4` integrators;
//! - one evaluation of the dynamics with contact at the start state: our
//!   right-hand side against `mj_forward`.
//!
//! Before timing, each run's end state is printed beside the others and
//! checked to be the same motion (see [`check_same_motion`]): a speed
//! figure of a model that drives differently would compare nothing.
//!
//! `MUJOCO_LIB=…/libmujoco.so.3.3.7 cargo bench --features mujoco --bench
//! engines -- --warm-up-time 1 --measurement-time 5`

#[path = "../support/mod.rs"]
mod support;

mod mujoco;

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{BenchmarkId, Criterion};
use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_runtime::GenericPlant;
use rover_runtime::control::SpeedConfig;
use rover_runtime::ground::ContactMethod;
use rover_runtime::integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_spec::Spec;

use mujoco::{Mujoco, Setup};

/// Simulated time of every run [s].
const DURATION: f64 = 40.0;
/// Our step, and MuJoCo's [s].
const STEP: f64 = 1e-3;

/// MuJoCo's integrators, each at [`STEP`], with cylinder wheels; and its
/// cheapest setup, Euler with sphere wheels.
const MUJOCO: [(&str, &str); 4] = [
    ("Euler", "cylinder"),
    ("implicitfast", "cylinder"),
    ("RK4", "cylinder"),
    ("Euler", "sphere"),
];

/// Where a run ends: G's travel and height, the body's attitude, the arm
/// angles and the forward speed.
#[derive(Debug)]
struct End {
    x: f64,
    z: f64,
    roll: f64,
    pitch: f64,
    arms: Vec<f64>,
    vx: f64,
}

fn rover_run<P: Plant>(model: &Model, plant: P) -> End {
    let (mut sys, mut y) = support::system(model, plant, ContactMethod::Meridional);
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: STEP }).unwrap();
    let mut t = 0.0;
    rk4.advance(&mut sys, &mut t, &mut y, DURATION).unwrap();
    let n = model.dof();
    End {
        x: y[0],
        z: y[2],
        roll: y[3],
        pitch: y[4],
        arms: y[6..n].to_vec(),
        vx: y[n],
    }
}

fn mujoco_run(sim: &mut mujoco::Sim<'_>, wheels: usize) -> End {
    sim.reset();
    for _ in 0..steps() {
        sim.step();
    }
    let (q, v) = (sim.qpos(), sim.qvel());
    // Roll and pitch of R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md §1) from the
    // quaternion: R[2][1] = sin φ, R[2][0] = −cos φ·sin θ, R[2][2] = cos φ·cos θ.
    let [w, a, b, c] = [q[3], q[4], q[5], q[6]];
    let r21 = 2.0 * (b * c + w * a);
    let r20 = 2.0 * (a * c - w * b);
    let r22 = 1.0 - 2.0 * (a * a + b * b);
    End {
        x: q[0],
        z: q[2],
        roll: r21.asin(),
        pitch: (-r20).atan2(r22),
        arms: (0..wheels).map(|k| q[7 + 2 * k]).collect(),
        vx: v[0],
    }
}

fn steps() -> usize {
    (DURATION / STEP).round() as usize
}

/// The runs drive the same way: the same sag of every arm (2°: the two
/// wheel–ground laws sink the wheels differently), the same height and
/// attitude (1 cm, 0.5°), the same speed (2 mm/s) and travel (5 %). What
/// differs by design is listed in docs/ENGINES.md.
fn check_same_motion(reference: &End, other: &End, label: &str) {
    let deg = 180.0 / std::f64::consts::PI;
    let mut bad = Vec::new();
    for (k, (a, b)) in reference.arms.iter().zip(&other.arms).enumerate() {
        if ((a - b) * deg).abs() > 2.0 {
            bad.push(format!("arm {}: {:.2}° vs {:.2}°", k + 1, a * deg, b * deg));
        }
    }
    if (reference.z - other.z).abs() > 0.01 {
        bad.push(format!("Z: {:.4} vs {:.4} m", reference.z, other.z));
    }
    for (what, a, b) in [
        ("roll", reference.roll, other.roll),
        ("pitch", reference.pitch, other.pitch),
    ] {
        if ((a - b) * deg).abs() > 0.5 {
            bad.push(format!("{what}: {:.2}° vs {:.2}°", a * deg, b * deg));
        }
    }
    if (reference.vx - other.vx).abs() > 2e-3 {
        bad.push(format!("v_x: {:.4} vs {:.4} m/s", reference.vx, other.vx));
    }
    if (reference.x - other.x).abs() > 0.05 * reference.x.abs() {
        bad.push(format!("X: {:.3} vs {:.3} m", reference.x, other.x));
    }
    assert!(
        bad.is_empty(),
        "{label} does not drive as rover does, nothing to compare: {}",
        bad.join("; ")
    );
}

fn print_end(label: &str, e: &End) {
    let deg = 180.0 / std::f64::consts::PI;
    let arms: Vec<String> = e.arms.iter().map(|a| format!("{:7.2}", a * deg)).collect();
    println!(
        "{label:<24} X {:7.4} m  Z {:7.4} m  roll {:6.3}°  pitch {:6.3}°  v_x {:7.4} m/s  arms {}°",
        e.x,
        e.z,
        e.roll * deg,
        e.pitch * deg,
        e.vx,
        arms.join(" ")
    );
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
    let kp = SpeedConfig::default().kp;
    let dir = std::env::temp_dir().join(format!("rover-engines-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut sims = Vec::new();
    for (integrator, wheel) in MUJOCO {
        let xml = mujoco::mjcf(
            &spec,
            Setup {
                integrator,
                timestep: STEP,
                wheel,
            },
            kp,
            support::SPEED,
            support::start_height(&model),
        )
        .unwrap();
        let label = format!("{integrator}_{wheel}");
        let file = dir.join(format!("swing4_{label}.xml"));
        std::fs::write(&file, xml).unwrap();
        sims.push((label, mj.model(&file).unwrap_or_else(|e| panic!("{e}"))));
    }

    println!(
        "MuJoCo {} ({}), swing4, {DURATION} s at {} m/s:",
        mj.version(),
        lib.display(),
        support::SPEED
    );
    let reference = rover_run(&model, rover_models::Swing4::new());
    print_end("rover RK4 (generated)", &reference);
    let wheels = model.wheels.len();
    for (setup, sim) in &mut sims {
        let end = mujoco_run(sim, wheels);
        let label = format!("MuJoCo {setup}");
        print_end(&label, &end);
        check_same_motion(&reference, &end, &label);
    }

    let mut c = Criterion::default().configure_from_args();
    {
        let mut group = c.benchmark_group("swing4_engines_40s");
        group.sample_size(10);
        group.bench_function(BenchmarkId::new("rover_rk4_1ms", "generated"), |b| {
            b.iter(|| black_box(rover_run(&model, rover_models::Swing4::new()).x))
        });
        let generic = GenericPlant::new(model.clone()).unwrap();
        group.bench_function(BenchmarkId::new("rover_rk4_1ms", "generic"), |b| {
            b.iter(|| black_box(rover_run(&model, generic.clone()).x))
        });
        for (setup, sim) in &mut sims {
            let id = BenchmarkId::new("mujoco_1ms", setup.as_str());
            group.bench_function(id, |b| {
                b.iter(|| {
                    sim.reset();
                    for _ in 0..steps() {
                        sim.step();
                    }
                })
            });
        }
        group.finish();
    }
    {
        // One evaluation of the dynamics with contact, at the start.
        let mut group = c.benchmark_group("swing4_engines_dynamics");
        let (mut sys, y) = support::system(
            &model,
            rover_models::Swing4::new(),
            ContactMethod::Meridional,
        );
        let mut dy = vec![0.0; y.len()];
        group.bench_function(BenchmarkId::new("rover_rhs", "generated"), |b| {
            b.iter(|| sys.rhs(0.0, black_box(&y), &mut dy).unwrap())
        });
        for (setup, sim) in sims.iter_mut().filter(|(s, _)| s.starts_with("Euler")) {
            sim.reset();
            let id = BenchmarkId::new("mujoco_forward", setup.as_str());
            group.bench_function(id, |b| b.iter(|| sim.forward()));
        }
        group.finish();
    }
    c.final_summary();
    let _ = std::fs::remove_dir_all(&dir);
}
