//! Generated vs generic plant: per built-in rover, the plant's
//! right-hand side alone, plant + contact through `RoverSystem::rhs` on flat
//! ground (meridional and tracked contact; the meridional search cuts the
//! rim with the ground plane in closed form), on the same flat ground given
//! as a grid (the meridional search samples the rim, as on any rough map),
//! and on the paper's rough terrain (the sampled and the bounded search, at
//! one state and along a path of states), and the mass matrix alone; whole
//! 40 s runs of swing4 on flat ground with RK4; and where swing4's
//! right-hand side on rough ground spends its time; one wheel's soil
//! forces; and MER's whole right-hand side and assembled Jacobian on the
//! rough terrain, rigid and under a soil (`rhs_soil`). Same seeded states
//! for both back ends, setup outside the timing.
//! `cargo bench --bench plant -- --warm-up-time 1 --measurement-time 3`.

mod support;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rover_dynamics::Model;
use rover_dynamics::nalgebra::SVector;
use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad};
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::GenericPlant;
use rover_runtime::terrain::Terrain;
use support::{driven, model, path_from, system, system_on};

/// A small deterministic generator (xorshift64*), so the states are seeded.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let u = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
}

struct Sample {
    x: Vec<f64>,
    w: Vec<f64>,
    loads: Vec<WheelLoad>,
}

fn samples(model: &Model, count: usize) -> Vec<Sample> {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let n = model.dof();
    (0..count)
        .map(|_| {
            let mut x: Vec<f64> = (0..6).map(|_| rng.uniform(-0.3, 0.3)).collect();
            for c in &model.coordinates {
                x.push(rng.uniform(c.min, c.max));
            }
            let w = (0..n).map(|_| rng.uniform(-0.5, 0.5)).collect();
            let loads = model
                .wheels
                .iter()
                .map(|_| WheelLoad {
                    force: [
                        rng.uniform(-5.0, 5.0),
                        rng.uniform(-5.0, 5.0),
                        rng.uniform(0.0, 20.0),
                    ],
                    moment: [rng.uniform(-0.5, 0.5), 0.0, rng.uniform(-0.5, 0.5)],
                    stator_torque: [0.0, rng.uniform(-1.0, 1.0), 0.0],
                })
                .collect();
            Sample { x, w, loads }
        })
        .collect()
}

/// Flat ground at Z = 0 as a 4 m × 4 m bicubic grid (5 cm spacing): the
/// geometry of [`system`], but the contact search samples the rim as on
/// any rough map instead of cutting it with a plane in closed form.
fn flat_grid() -> Terrain {
    Terrain::Grid(
        rover_runtime::terrain::Grid::from_fn([-2.0, -2.0], [0.05, 0.05], 81, 81, |_, _| 0.0)
            .unwrap(),
    )
}

fn bench_plant<P: Plant>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    plant: &mut P,
    samples: &[Sample],
) {
    let n = plant.dof();
    let (mut xd, mut wd) = (vec![0.0; n], vec![0.0; n]);
    let mut k = 0;
    group.bench_function(BenchmarkId::new("rhs_plant", id), |b| {
        b.iter(|| {
            let s = &samples[k % samples.len()];
            k += 1;
            let r = plant.derivatives(black_box(&s.x), black_box(&s.w), &s.loads, &mut xd, &mut wd);
            black_box(&r);
            black_box(&wd);
        })
    });
    let mut m = vec![0.0; n * n];
    group.bench_function(BenchmarkId::new("mass_matrix", id), |b| {
        b.iter(|| {
            let s = &samples[k % samples.len()];
            k += 1;
            plant.mass_matrix(black_box(&s.x), &mut m);
            black_box(&m);
        })
    });
}

fn bench_contact<P: Plant>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: &str,
    model: &Model,
    plant: P,
    method: ContactMethod,
) {
    let what = match method {
        ContactMethod::Meridional => "rhs_contact",
        ContactMethod::Tracked => "rhs_contact_tracked",
        ContactMethod::Bounded => "rhs_contact_bounded",
    };
    bench_contact_on(
        group,
        what,
        id,
        Terrain::default(),
        model,
        plant,
        method,
        None,
    );
}

/// The right-hand side with contact on `terrain`, as benchmark `what`/`id`,
/// at the state `at` (default: the start, wheels just touching).
#[allow(clippy::too_many_arguments)]
fn bench_contact_on<P: Plant>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    what: &str,
    id: &str,
    terrain: Terrain,
    model: &Model,
    plant: P,
    method: ContactMethod,
    at: Option<&[f64]>,
) {
    let (mut sys, mut y) = system_on(terrain, model, plant, method);
    if let Some(at) = at {
        y.copy_from_slice(at);
    }
    let mut dy = vec![0.0; y.len()];
    sys.rhs(0.0, &y, &mut dy).unwrap();
    group.bench_function(BenchmarkId::new(what, id), |b| {
        b.iter(|| {
            sys.rhs(0.0, black_box(&y), &mut dy).unwrap();
            black_box(&dy);
        })
    });
}

fn one_model<P: Plant + Clone>(c: &mut Criterion, name: &str, generated: P) {
    let model = model(name);
    let samples = samples(&model, 64);
    let mut group = c.benchmark_group(name);
    let mut generic = GenericPlant::new(model.clone()).unwrap();
    bench_plant(&mut group, "generated", &mut generated.clone(), &samples);
    bench_plant(&mut group, "generic", &mut generic, &samples);
    for method in [ContactMethod::Meridional, ContactMethod::Tracked] {
        bench_contact(&mut group, "generated", &model, generated.clone(), method);
        bench_contact(&mut group, "generic", &model, generic.clone(), method);
    }
    let method = ContactMethod::Meridional;
    let what = "rhs_contact_grid";
    let (plant, grid) = (generated.clone(), flat_grid());
    bench_contact_on(
        &mut group,
        what,
        "generated",
        grid,
        &model,
        plant,
        method,
        None,
    );
    let (plant, grid) = (generic.clone(), flat_grid());
    bench_contact_on(
        &mut group, what, "generic", grid, &model, plant, method, None,
    );
    // The paper's rough terrain, at the state the rover reaches after
    // driving 5 s on it (the same state for both back ends).
    let rough = Terrain::Grid(support::rough_field());
    let state = driven(&rough, &model, generic.clone(), 5.0);
    let at = Some(&state[..]);
    // The states 1 ms apart over the next 0.2 s, evaluated in turn: a
    // search that remembers a wheel between calls (the bounded one) meets
    // the small moves an integrator makes, not one state over and over.
    let path = path_from(&rough, &model, generic.clone(), &state, 200);
    for method in [ContactMethod::Meridional, ContactMethod::Bounded] {
        let what = match method {
            ContactMethod::Bounded => "rhs_contact_rough_path_bounded",
            _ => "rhs_contact_rough_path",
        };
        bench_path(
            &mut group,
            what,
            "generated",
            rough.clone(),
            &model,
            generated.clone(),
            method,
            &path,
        );
        bench_path(
            &mut group,
            what,
            "generic",
            rough.clone(),
            &model,
            generic.clone(),
            method,
            &path,
        );
    }
    for (what, method) in [
        ("rhs_contact_rough", ContactMethod::Meridional),
        ("rhs_contact_rough_bounded", ContactMethod::Bounded),
    ] {
        let (plant, ground) = (generated.clone(), rough.clone());
        bench_contact_on(
            &mut group,
            what,
            "generated",
            ground,
            &model,
            plant,
            method,
            at,
        );
        let (plant, ground) = (generic.clone(), rough.clone());
        bench_contact_on(
            &mut group, what, "generic", ground, &model, plant, method, at,
        );
    }
    group.finish();
}

/// The right-hand side with contact on `terrain` at the states of `path`
/// in turn, as benchmark `what`/`id` (the time of one evaluation).
#[allow(clippy::too_many_arguments)]
fn bench_path<P: Plant>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    what: &str,
    id: &str,
    terrain: Terrain,
    model: &Model,
    plant: P,
    method: ContactMethod,
    path: &[Vec<f64>],
) {
    let (mut sys, _) = system_on(terrain, model, plant, method);
    let mut dy = vec![0.0; path[0].len()];
    let mut k = 0;
    group.bench_function(BenchmarkId::new(what, id), |b| {
        b.iter(|| {
            sys.rhs(0.0, black_box(&path[k % path.len()]), &mut dy)
                .unwrap();
            k += 1;
            black_box(&dy);
        })
    });
}

/// The generated plant through its typed API (`FixedPlant`, nalgebra
/// vectors, no slice checks or load copies), same states.
fn fixed_api<P: FixedPlant<N, W>, const N: usize, const W: usize>(
    c: &mut Criterion,
    name: &str,
    plant: P,
) {
    let samples: Vec<_> = samples(&model(name), 64)
        .into_iter()
        .map(|s| {
            let loads: [WheelLoad; W] = core::array::from_fn(|j| s.loads[j]);
            (
                SVector::<f64, N>::from_column_slice(&s.x),
                SVector::<f64, N>::from_column_slice(&s.w),
                loads,
            )
        })
        .collect();
    let (mut xd, mut wd) = (SVector::<f64, N>::zeros(), SVector::<f64, N>::zeros());
    let mut k = 0;
    c.benchmark_group(name)
        .bench_function(BenchmarkId::new("rhs_plant", "generated_fixed"), |b| {
            b.iter(|| {
                let (x, w, loads) = &samples[k % samples.len()];
                k += 1;
                let r =
                    plant.derivatives_fixed(black_box(x), black_box(w), loads, &mut xd, &mut wd);
                black_box(&r);
                black_box(&wd);
            })
        });
}

/// swing4's generated right-hand side compiled for the build's target
/// only (`derivatives_portable`), next to `generated`, which picks the
/// x86-64-v4 copy when the processor has it (`rover_dynamics::cpu`).
fn portable_swing4(c: &mut Criterion) {
    let plant = rover_models::Swing4::new();
    let samples: Vec<_> = samples(&model("swing4"), 64)
        .into_iter()
        .map(|s| {
            let x: [f64; 10] = core::array::from_fn(|i| s.x[i]);
            let w: [f64; 10] = core::array::from_fn(|i| s.w[i]);
            let loads: [WheelLoad; 4] = core::array::from_fn(|j| s.loads[j]);
            (x, w, loads)
        })
        .collect();
    let (mut xd, mut wd) = ([0.0; 10], [0.0; 10]);
    let mut k = 0;
    c.benchmark_group("swing4").bench_function(
        BenchmarkId::new("rhs_plant", "generated_portable"),
        |b| {
            b.iter(|| {
                let (x, w, loads) = &samples[k % samples.len()];
                k += 1;
                let r =
                    plant.derivatives_portable(black_box(x), black_box(w), loads, &mut xd, &mut wd);
                black_box(&r);
                black_box(&wd);
            })
        },
    );
}

fn per_model(c: &mut Criterion) {
    one_model(c, "exomars", rover_models::Exomars::new());
    one_model(c, "swing4", rover_models::Swing4::new());
    fixed_api(c, "swing4", rover_models::Swing4::new());
    portable_swing4(c);
    one_model(c, "mer", rover_models::Mer::new());
    one_model(c, "lrv", rover_models::Lrv::new());
}

/// 40 s of swing4 on flat ground at 0.1 m/s, RK4 with a 1 ms step
/// (160,000 right-hand sides).
fn whole_runs(c: &mut Criterion) {
    let model = model("swing4");
    let mut group = c.benchmark_group("swing4_run_40s");
    group.sample_size(10);
    fn run<P: Plant + Clone>(model: &Model, plant: P) -> f64 {
        let (mut sys, mut y) = system(model, plant, ContactMethod::Meridional);
        let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: 1e-3 }).unwrap();
        let mut t = 0.0;
        rk4.advance(&mut sys, &mut t, &mut y, 40.0).unwrap();
        y[0]
    }
    group.bench_function(BenchmarkId::new("rk4", "generated"), |b| {
        b.iter(|| black_box(run(&model, rover_models::Swing4::new())))
    });
    let generic = GenericPlant::new(model.clone()).unwrap();
    group.bench_function(BenchmarkId::new("rk4", "generic"), |b| {
        b.iter(|| black_box(run(&model, generic.clone())))
    });
    group.finish();
}

/// The right-hand side of swing4 at the three dynamic fidelity levels
/// (MODEL.md §9), generic plant, the reduced levels frozen at the loaded
/// static equilibrium: plant alone, and with the tracked contact.
fn fidelity_levels(c: &mut Criterion) {
    use rover_dynamics::fidelity::Fidelity;
    let model = model("swing4");
    let samples = samples(&model, 64);
    let y_ref = rover_runtime::quasi_static::flat_ground_equilibrium(&model).unwrap();
    let mut group = c.benchmark_group("swing4_fidelity");
    for (label, level) in [
        ("full", Fidelity::Full),
        ("simplified", Fidelity::Simplified),
        ("linearized", Fidelity::Linearized),
    ] {
        let mut plant = GenericPlant::with_fidelity_at(model.clone(), level, &y_ref).unwrap();
        let n = plant.dof();
        let (mut xd, mut wd) = (vec![0.0; n], vec![0.0; n]);
        let mut k = 0;
        group.bench_function(BenchmarkId::new("rhs_plant", label), |b| {
            b.iter(|| {
                let s = &samples[k % samples.len()];
                k += 1;
                let r =
                    plant.derivatives(black_box(&s.x), black_box(&s.w), &s.loads, &mut xd, &mut wd);
                black_box(&r);
                black_box(&wd);
            })
        });
        bench_contact(&mut group, label, &model, plant, ContactMethod::Tracked);
    }
    group.finish();
}

/// Where swing4's right-hand side on rough ground spends its time (generated
/// plant, the states 1 ms apart of `rhs_contact_rough_path` in turn), as
/// cumulative stages, so that each part is the difference of two medians:
/// the wheels' kinematics; and the contact search (bounded, and the
/// sampled one for comparison); and the wheel law reduced to loads; and
/// the rest of the right-hand side (controller, plant).
fn rhs_parts(c: &mut Criterion) {
    use rover_dynamics::plant::WheelState;
    let model = model("swing4");
    let rough = Terrain::Grid(support::rough_field());
    let generic = GenericPlant::new(model.clone()).unwrap();
    let state = driven(&rough, &model, generic.clone(), 5.0);
    let path = path_from(&rough, &model, generic, &state, 200);
    let n = model.dof();
    let k = model.wheels.len();
    let mut group = c.benchmark_group("swing4_rhs_parts");
    for method in [ContactMethod::Bounded, ContactMethod::Meridional] {
        let label = format!("{method:?}").to_lowercase();
        let (mut sys, _) = system_on(rough.clone(), &model, rover_models::Swing4::new(), method);
        let (steer, torques) = (vec![0.0; k], vec![0.1; k]);
        let mut wheels = vec![WheelState::default(); k];
        let (mut normals, mut loads) = (vec![0.0; k], vec![WheelLoad::default(); k]);
        let mut reports = vec![Default::default(); k];
        let mut at = 0;
        let mut next = || {
            at += 1;
            &path[at % path.len()]
        };
        if method == ContactMethod::Bounded {
            group.bench_function(BenchmarkId::new("wheels", "generated"), |b| {
                b.iter(|| {
                    let y = next();
                    sys.plant
                        .wheels(black_box(&y[..n]), &y[n..2 * n], &steer, &mut wheels);
                    black_box(&wheels);
                })
            });
        }
        group.bench_function(BenchmarkId::new("wheels_contact", &label), |b| {
            b.iter(|| {
                let y = next();
                sys.plant
                    .wheels(black_box(&y[..n]), &y[n..2 * n], &steer, &mut wheels);
                let ground = sys.ground.as_mut().unwrap();
                ground.find_contacts(&wheels, &mut normals).unwrap();
                black_box(&normals);
            })
        });
        group.bench_function(BenchmarkId::new("wheels_contact_law", &label), |b| {
            b.iter(|| {
                let y = next();
                sys.plant
                    .wheels(black_box(&y[..n]), &y[n..2 * n], &steer, &mut wheels);
                let ground = sys.ground.as_mut().unwrap();
                ground.find_contacts(&wheels, &mut normals).unwrap();
                ground.loads(&wheels, &torques, &[], &mut loads, &mut reports);
                black_box(&loads);
            })
        });
    }
    group.finish();
}

/// The Jacobian an implicit integrator takes on swing4 driving on the
/// paper's rough terrain (the generated plant, the states of
/// `rhs_contact_rough_path` in turn): assembled from the plant's exact one
/// and the wheels' load derivatives, and by forward differences of the
/// whole right-hand side (what the integrators do without it); and the
/// plant's exact Jacobian at fixed loads alone.
fn jacobians(c: &mut Criterion) {
    let model = model("swing4");
    let rough = Terrain::Grid(support::rough_field());
    let generic = GenericPlant::new(model.clone()).unwrap();
    let state = driven(&rough, &model, generic.clone(), 5.0);
    let path = path_from(&rough, &model, generic, &state, 200);
    let n = model.dof();
    let (mut sys, _) = system_on(
        rough,
        &model,
        rover_models::Swing4::new(),
        ContactMethod::Bounded,
    );
    let dim = path[0].len();
    let mut jac = vec![0.0; dim * dim];
    let mut group = c.benchmark_group("swing4_jacobian");
    let mut at = 0;
    group.bench_function(BenchmarkId::new("assembled", "generated"), |b| {
        b.iter(|| {
            at += 1;
            let y = &path[at % path.len()];
            sys.jacobian(0.0, black_box(y), &mut jac).unwrap().unwrap();
            black_box(&jac);
        })
    });
    let (mut f0, mut f, mut yp) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
    group.bench_function(BenchmarkId::new("differences", "generated"), |b| {
        b.iter(|| {
            at += 1;
            let y = &path[at % path.len()];
            sys.rhs(0.0, black_box(y), &mut f0).unwrap();
            yp.copy_from_slice(y);
            for j in 0..dim {
                let h = 1e-8 * y[j].abs().max(1.0);
                yp[j] = y[j] + h;
                sys.rhs(0.0, &yp, &mut f).unwrap();
                yp[j] = y[j];
                for i in 0..dim {
                    jac[i * dim + j] = (f[i] - f0[i]) / h;
                }
            }
            black_box(&jac);
        })
    });
    let loads = vec![WheelLoad::default(); model.wheels.len()];
    let mut fixed = vec![0.0; 4 * n * n];
    group.bench_function(BenchmarkId::new("plant_at_fixed_loads", "generated"), |b| {
        b.iter(|| {
            at += 1;
            let y = &path[at % path.len()];
            sys.plant
                .jacobian(black_box(&y[..n]), &y[n..2 * n], &loads, &mut fixed)
                .unwrap();
            black_box(&fixed);
        })
    });
    group.finish();
}

/// A generated plant's own force path (`derivatives_on_ground`: the
/// contact search, the wheel law with the tyres as constants, the plant)
/// on the paper's rough terrain, at the states 1 ms apart of
/// `rhs_contact_rough_path` in turn, open-loop torques; in the same run,
/// the runtime's right-hand side with the generic plant on the same path
/// (the bounded search, the speed loop), and the generated plant alone.
fn force_path(c: &mut Criterion) {
    use rover_dynamics::wheel_ground::Search;
    use rover_runtime::wheel_law::WheelLawConfig;
    macro_rules! one {
        ($name:literal, $plant:ty) => {{
            type P = $plant;
            const N: usize = P::DOF;
            const W: usize = P::WHEELS;
            let model = model($name);
            let grid = support::rough_field();
            let rough = Terrain::Grid(grid.clone());
            let generic = GenericPlant::new(model.clone()).unwrap();
            let state = driven(&rough, &model, generic.clone(), 5.0);
            let path = path_from(&rough, &model, generic.clone(), &state, 200);
            let states: Vec<([f64; N], [f64; N])> = path
                .iter()
                .map(|y| (y[..N].try_into().unwrap(), y[N..2 * N].try_into().unwrap()))
                .collect();
            let mut group = c.benchmark_group(concat!("force_path_", $name));
            let plant = P::new();
            let law = WheelLawConfig::default();
            let mut ground = P::ground(Search::default());
            let torques = [0.1 * model.wheels[0].max_torque; W];
            let mut k = 0;
            group.bench_function("generated_on_ground", |b| {
                b.iter(|| {
                    let (x, w) = &states[k % states.len()];
                    k += 1;
                    let (mut xd, mut wd) = ([0.0; N], [0.0; N]);
                    plant
                        .derivatives_on_ground(
                            &mut ground,
                            &grid,
                            &law,
                            &P::TYRES,
                            black_box(x),
                            w,
                            &[0.0; W],
                            |_| torques,
                            &mut xd,
                            &mut wd,
                        )
                        .unwrap();
                    black_box((&xd, &wd));
                })
            });
            let loads = [WheelLoad::default(); W];
            group.bench_function("generated_plant_only", |b| {
                b.iter(|| {
                    let (x, w) = &states[k % states.len()];
                    k += 1;
                    let (mut xd, mut wd) = ([0.0; N], [0.0; N]);
                    plant
                        .derivatives_array(black_box(x), w, &loads, &mut xd, &mut wd)
                        .unwrap();
                    black_box((&xd, &wd));
                })
            });
            bench_path(
                &mut group,
                "runtime",
                "generic",
                rough.clone(),
                &model,
                generic,
                ContactMethod::Bounded,
                &path,
            );
            group.finish();
        }};
    }
    one!("swing4", rover_models::Swing4);
    one!("exomars", rover_models::Exomars);
    one!("mer", rover_models::Mer);
    one!("lrv", rover_models::Lrv);
}

/// One wheel's soil forces at a typical state (lunar nominal soil, a
/// 0.4 m wheel 0.23 m wide sunk at θ1 = 0.3 rad, 20 % slip, 3° slip angle),
/// by quadratures of 4 to 64 points a piece (4 hold 1e-4, the testbed
/// takes 16), with the rigid
/// ground's patch law beside them for scale; and the testbed's steady
/// state (a bisection on the entry angle).
fn soil(c: &mut Criterion) {
    use rover_dynamics::soil::{
        GaussLegendre, Soil, SoilContact, SoilWheel, soil_forces, steady_state,
    };
    use rover_dynamics::wheel_law::{Lateral, PatchMotion, Tyre, patch_forces};
    let soil = Soil {
        n: 1.0,
        k_c: 1400.0,
        k_phi: 820e3,
        cohesion: 170.0,
        friction_angle: 35f64.to_radians(),
        shear_modulus: 0.018,
        lateral_shear_modulus: 0.018,
        a0: 0.4,
        a1: 0.15,
        rear_ratio: 0.0,
        unit_weight: 0.0,
        reload_k0: 0.0,
        reload_au: 5.03e8,
    };
    let contact = SoilContact {
        entry_angle: 0.3,
        slip: 0.2,
        slip_angle: 3f64.to_radians(),
    };
    let wheel = SoilWheel::new(&soil, 0.4, 0.23);
    let mut group = c.benchmark_group("soil_one_wheel");
    macro_rules! rule {
        ($q:literal) => {
            let rule = GaussLegendre::<$q>::new();
            group.bench_function(concat!("forces_q", $q), |b| {
                b.iter(|| soil_forces(&wheel, std::hint::black_box(contact), &rule))
            });
        };
    }
    rule!(4);
    rule!(8);
    rule!(16);
    rule!(64);
    let tyre = Tyre {
        stiffness: 4000.0,
        damping: 300.0,
        mu_x: 0.5,
        mu_y: 0.5,
        cornering_stiffness: 50.0,
        rolling_resistance: 0.0,
    };
    let motion = PatchMotion {
        deflection: 0.01,
        deflection_rate: 0.001,
        v_t: 0.1,
        v_c: 0.005,
        lever: 0.39,
        torque: 1.0,
    };
    group.bench_function("rigid_patch_law", |b| {
        b.iter(|| {
            patch_forces(
                &Lateral::Exponential { v_eps: 1e-3 },
                &tyre,
                &std::hint::black_box(motion),
            )
        })
    });
    let rule = GaussLegendre::<16>::new();
    group.bench_function("testbed_steady_state_q16", |b| {
        b.iter(|| steady_state(&wheel, std::hint::black_box(250.0), 0.2, 0.0, &rule))
    });
    group.finish();
}

/// A six-wheel rover's (MER's, generated plant) whole right-hand side on
/// the paper's rough terrain, rigid and under a soil (dry sand), at the
/// same state: the rover after driving 5 s on the rigid ground (settled on
/// its wheels at its speed), its wheels' spins (the soil's extra states)
/// rolling without slip; and along the states 1 ms apart of
/// `rhs_contact_rough_path`. The contact search is the default (bounded)
/// one, the same patches both ways; on the soil the soil law replaces the
/// tyre law on each of them. And the assembled Jacobian
/// (`OdeSystem::jacobian`) at the same state, both ways.
fn rhs_soil(c: &mut Criterion) {
    use rover_runtime::soil::SoilConfig;
    let model = model("mer");
    let soil = SoilConfig::builtin("dry_sand").unwrap().soil().unwrap();
    let rough = Terrain::Grid(support::rough_field());
    let generic = GenericPlant::new(model.clone()).unwrap();
    let state = driven(&rough, &model, generic.clone(), 5.0);
    let path = path_from(&rough, &model, generic, &state, 200);
    let method = ContactMethod::Bounded;
    let plant = rover_models::Mer::new();
    let (mut rigid, _) = system_on(rough.clone(), &model, plant, method);
    let (mut soft, _) = support::soil_system_on(rough, &model, plant, method, &soil);
    // The soft system's state: the rigid one, then the spins.
    let with_spins = |sys: &mut rover_runtime::sim::RoverSystem<_, _>, y: &[f64]| {
        let mut z = vec![0.0; sys.dim()];
        z[..y.len()].copy_from_slice(y);
        sys.roll_spins(0.0, &mut z);
        z
    };
    let y_rigid = state.clone();
    let y_soft = with_spins(&mut soft, &state);
    assert_eq!(soft.spin_range().len(), model.wheels.len());
    assert_eq!(soft.spin_range().end, y_soft.len());
    let path_soft: Vec<Vec<f64>> = path.iter().map(|y| with_spins(&mut soft, y)).collect();
    let mut group = c.benchmark_group("rhs_soil");
    for (id, sys, y, path) in [
        ("rigid", &mut rigid, &y_rigid, &path),
        ("soil", &mut soft, &y_soft, &path_soft),
    ] {
        let dim = y.len();
        let mut dy = vec![0.0; dim];
        sys.rhs(0.0, y, &mut dy).unwrap();
        let patches: usize = sys.reports().iter().map(|r| r.patches).sum();
        assert!(patches >= model.wheels.len(), "{id}: {patches} patches");
        group.bench_function(BenchmarkId::new("rhs", id), |b| {
            b.iter(|| {
                sys.rhs(0.0, black_box(y), &mut dy).unwrap();
                black_box(&dy);
            })
        });
        let mut k = 0;
        group.bench_function(BenchmarkId::new("rhs_path", id), |b| {
            b.iter(|| {
                sys.rhs(0.0, black_box(&path[k % path.len()]), &mut dy)
                    .unwrap();
                k += 1;
                black_box(&dy);
            })
        });
        let mut jac = vec![0.0; dim * dim];
        sys.jacobian(0.0, y, &mut jac).unwrap().unwrap();
        group.bench_function(BenchmarkId::new("jacobian", id), |b| {
            b.iter(|| {
                sys.jacobian(0.0, black_box(y), &mut jac).unwrap().unwrap();
                black_box(&jac);
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    soil,
    force_path,
    per_model,
    whole_runs,
    fidelity_levels,
    rhs_parts,
    jacobians,
    rhs_soil
);
criterion_main!(benches);
