//! Generated == generic: the checked-in generated plants of
//! models/ against the generic plant on the same rover, on 1000 random
//! states each, to 1e-12 relative; the generated exact Jacobian against
//! forward-mode duals through the generic equations.
//!
//! "Relative" is norm-wise: for each output (M, ẋ, ẇ, a wheel's centre,
//! velocity and spin axis, the generalized force of the loads) the largest
//! entry difference over the largest entry magnitude.

use rover_dynamics::Model;
use rover_dynamics::dual::Dual;
use rover_dynamics::eom::derivatives;
use rover_dynamics::forces::Load;
use rover_dynamics::nalgebra::SVector;
use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad, WheelState};
use rover_dynamics::workspace::Workspace;
use rover_runtime::GenericPlant;

use crate::support::rel;
use crate::support::rng::Rng;

const TOL: f64 = 1e-12;
const STATES: usize = 1000;

fn spec(name: &str) -> rover_spec::Spec {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name).unwrap()
}

struct State {
    x: Vec<f64>,
    w: Vec<f64>,
    steer: Vec<f64>,
    loads: Vec<WheelLoad>,
    neutral: Vec<f64>,
}

fn random_state(model: &Model, rng: &mut Rng) -> State {
    let n = model.dof();
    let mut x = vec![
        rng.uniform(-5.0, 5.0),
        rng.uniform(-5.0, 5.0),
        rng.uniform(-1.0, 1.0),
        rng.uniform(-0.6, 0.6),
        rng.uniform(-0.6, 0.6),
        rng.uniform(-3.1, 3.1),
    ];
    for c in &model.coordinates {
        // A little beyond the travel too: the bump stops.
        let pad = 0.05 * (c.max - c.min);
        x.push(rng.uniform(c.min - pad, c.max + pad));
    }
    let w: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
    // Loads of the order of each wheel's share of the weight (on Earth, so
    // that a light rover on the Moon still sees forces that matter).
    let f = model.total_mass() * 9.81 / model.wheels.len() as f64;
    let mut v3 = |s: f64| [0, 1, 2].map(|_| rng.uniform(-s, s));
    let loads = model
        .wheels
        .iter()
        .map(|w| WheelLoad {
            force: v3(f),
            moment: v3(f * w.radius),
            stator_torque: v3(w.max_torque),
        })
        .collect();
    let steer = model
        .wheels
        .iter()
        .map(|_| rng.uniform(-0.5, 0.5))
        .collect();
    let neutral = model
        .coordinates
        .iter()
        .map(|c| rng.uniform(c.min, c.max))
        .collect();
    State {
        x,
        w,
        steer,
        loads,
        neutral,
    }
}

fn flat(states: &[WheelState], k: usize) -> [Vec<f64>; 3] {
    [
        states[k].centre.to_vec(),
        states[k].velocity.to_vec(),
        states[k].spin_axis.to_vec(),
    ]
}

fn compare(name: &str, generated: impl Plant, seed: u64) {
    let generic = GenericPlant::new(spec(name).model).unwrap();
    compare_with(name, generated, generic, seed);
}

fn compare_with(name: &str, mut generated: impl Plant, mut generic: GenericPlant, seed: u64) {
    let model = spec(name).model;
    let (n, k) = (model.dof(), model.wheels.len());
    assert_eq!(generated.dof(), n, "{name}: dof");
    assert_eq!(generated.wheel_count(), k, "{name}: wheel count");
    let mut rng = Rng::new(seed);
    let mut worst = [0.0f64; 5];
    for trial in 0..STATES {
        let s = random_state(&model, &mut rng);
        for (i, &y0) in s.neutral.iter().enumerate() {
            generated.set_spring_neutral(i, y0);
            generic.set_spring_neutral(i, y0);
        }
        // M
        let (mut ma, mut mb) = (vec![0.0; n * n], vec![0.0; n * n]);
        generated.mass_matrix(&s.x, &mut ma);
        generic.mass_matrix(&s.x, &mut mb);
        let e = rel(&ma, &mb);
        worst[0] = worst[0].max(e);
        assert!(e <= TOL, "{name} state {trial}: M differs by {e:e}");
        // Wheel kinematics
        let (mut wa, mut wb) = (
            vec![WheelState::default(); k],
            vec![WheelState::default(); k],
        );
        generated.wheels(&s.x, &s.w, &s.steer, &mut wa);
        generic.wheels(&s.x, &s.w, &s.steer, &mut wb);
        for j in 0..k {
            for (what, (a, b)) in ["centre", "velocity", "spin axis"]
                .iter()
                .zip(flat(&wa, j).iter().zip(flat(&wb, j).iter()))
            {
                let e = rel(a, b);
                worst[1] = worst[1].max(e);
                assert!(
                    e <= TOL,
                    "{name} state {trial}: wheel {j} {what} differs by {e:e}"
                );
            }
        }
        // ẋ, ẇ under the loads
        let mut out = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let [xa, wda, xb, wdb] = &mut out;
        let ra = generated.derivatives(&s.x, &s.w, &s.loads, xa, wda);
        let rb = generic.derivatives(&s.x, &s.w, &s.loads, xb, wdb);
        assert_eq!(ra, rb, "{name} state {trial}: outcome");
        let e = rel(xa, xb);
        worst[2] = worst[2].max(e);
        assert!(e <= TOL, "{name} state {trial}: ẋ differs by {e:e}");
        assert!(wdb.iter().any(|v| *v != 0.0), "{name}: ẇ all zero");
        let e = rel(wda, wdb);
        worst[3] = worst[3].max(e);
        assert!(e <= TOL, "{name} state {trial}: ẇ differs by {e:e}");
        // Generalized force of the loads: M·(ẇ(loads) − ẇ(0)) = Q_loads,
        // compared through Δẇ.
        let zero = vec![WheelLoad::default(); k];
        let mut out0 = [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        let [xa0, wa0, xb0, wb0] = &mut out0;
        generated.derivatives(&s.x, &s.w, &zero, xa0, wa0).unwrap();
        generic.derivatives(&s.x, &s.w, &zero, xb0, wb0).unwrap();
        let da: Vec<f64> = wda.iter().zip(wa0.iter()).map(|(a, b)| a - b).collect();
        let db: Vec<f64> = wdb.iter().zip(wb0.iter()).map(|(a, b)| a - b).collect();
        let e = rel(&da, &db);
        worst[4] = worst[4].max(e);
        assert!(
            e <= TOL,
            "{name} state {trial}: Δẇ of the loads differs by {e:e}"
        );
    }
    eprintln!(
        "{name}: worst relative differences M {:e}, wheels {:e}, ẋ {:e}, ẇ {:e}, Δẇ {:e}",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
}

#[test]
fn generated_exomars_equals_generic() {
    compare("exomars", rover_models::Exomars::new(), 61);
}

#[test]
fn generated_swing4_equals_generic() {
    compare("swing4", rover_models::Swing4::new(), 62);
}

#[test]
fn generated_mer_equals_generic() {
    compare("mer", rover_models::Mer::new(), 63);
}

#[test]
fn generated_lrv_equals_generic() {
    compare("lrv", rover_models::Lrv::new(), 64);
}

#[test]
fn the_run_time_choice_of_a_builtin_is_the_same_plant() {
    compare("mer", rover_models::plant("mer").unwrap(), 66);
}

#[test]
fn every_builtin_has_a_generated_plant() {
    for name in rover_models::NAMES {
        let plant = rover_models::plant(name).unwrap();
        assert_eq!(plant.dof(), spec(name).model.dof(), "{name}");
    }
    assert!(rover_models::plant("nope").is_none());
}

#[test]
fn a_rolled_over_state_is_the_generic_error() {
    let model = spec("swing4").model;
    let n = model.dof();
    let mut x = vec![0.0; n];
    x[6..].copy_from_slice(&model.rest());
    x[3] = std::f64::consts::FRAC_PI_2;
    let w = vec![0.0; n];
    let loads = vec![WheelLoad::default(); 4];
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    let mut generated = rover_models::Swing4::new();
    let err = generated.derivatives(&x, &w, &loads, &mut a, &mut b);
    let mut generic = GenericPlant::new(model).unwrap();
    let expect = generic.derivatives(&x, &w, &loads, &mut a, &mut b);
    assert!(matches!(
        expect,
        Err(rover_dynamics::plant::PlantError::AttitudeSingular { .. })
    ));
    assert_eq!(err, expect);
}

/// A state whose mass matrix has no LDLᵀ factors (a suspension coordinate
/// that is NaN, so pivots are NaN, not > 0) is the generic plant's error
/// for every built-in rover: the same variant with a NaN pivot, not a
/// silent `Ok` (the generated plant tests all pivots in one branch and
/// builds the error out of line). Each reports the first failing pivot of
/// its own elimination order (the generated one eliminates the suspension
/// rows first, docs/CODEGEN.md), so the rows may differ; both are rows of
/// M that the NaN reaches.
#[test]
fn a_mass_matrix_without_factors_is_the_generic_error() {
    use rover_dynamics::plant::PlantError;
    for name in ["exomars", "swing4", "mer", "lrv"] {
        let model = spec(name).model;
        let (n, k) = (model.dof(), model.wheels.len());
        let mut generated = rover_models::plant(name).unwrap();
        let mut generic = GenericPlant::new(model.clone()).unwrap();
        for coordinate in 6..n {
            let mut x = vec![0.0; n];
            x[6..].copy_from_slice(&model.rest());
            x[coordinate] = f64::NAN;
            let (w, loads) = (vec![0.0; n], vec![WheelLoad::default(); k]);
            let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
            let got = generated.derivatives(&x, &w, &loads, &mut a, &mut b);
            let expect = generic.derivatives(&x, &w, &loads, &mut a, &mut b);
            match (got, expect) {
                (
                    Err(PlantError::SingularMass { row, pivot }),
                    Err(PlantError::SingularMass {
                        row: generic_row,
                        pivot: generic_pivot,
                    }),
                ) => {
                    let mut m = vec![0.0; n * n];
                    generic.mass_matrix(&x, &mut m);
                    for r in [row, generic_row] {
                        assert!(
                            m[r * n..(r + 1) * n].iter().any(|v| v.is_nan()),
                            "{name}, coordinate {coordinate} NaN: row {r} of M has no NaN"
                        );
                    }
                    assert!(
                        pivot.is_nan() && generic_pivot.is_nan(),
                        "{name}: {pivot}, {generic_pivot}"
                    );
                }
                other => panic!("{name}, coordinate {coordinate} NaN: {other:?}"),
            }
        }
    }
}

#[test]
fn wrong_slice_lengths_give_nan_not_a_panic() {
    let mut p = rover_models::Swing4::new();
    let (mut xd, mut wd) = (vec![0.0; 10], vec![0.0; 10]);
    let r = p.derivatives(&[0.0; 3], &[0.0; 10], &[], &mut xd, &mut wd);
    assert_eq!(r, Ok(()));
    assert!(xd.iter().chain(&wd).all(|v| v.is_nan()));
    let mut m = vec![0.0; 4];
    p.mass_matrix(&[0.0; 2], &mut m);
    assert!(m.iter().all(|v| v.is_nan()));
}

/// ∂(ẋ, ẇ)/∂(x, w) through the generic equations with duals, column `col`.
/// The nalgebra interface (`FixedPlant`) is the slice interface (`Plant`)
/// bit for bit: same derivatives, the same mass matrix (column storage of a
/// symmetric matrix), the same wheels, and the Jacobian not transposed.
fn check_fixed<P: FixedPlant<N, K>, const N: usize, const K: usize>(
    name: &str,
    mut plant: P,
    jacobian: impl Fn(&P, &SVector<f64, N>, &SVector<f64, N>, &[WheelLoad; K]) -> (f64, f64),
) {
    let model = spec(name).model;
    let mut rng = Rng::new(90 + N as u64);
    for _ in 0..50 {
        let s = random_state(&model, &mut rng);
        let x = SVector::<f64, N>::from_column_slice(&s.x);
        let w = SVector::<f64, N>::from_column_slice(&s.w);
        let steer = SVector::<f64, K>::from_column_slice(&s.steer);
        let loads: [WheelLoad; K] = s.loads.clone().try_into().unwrap();
        let (mut xd, mut wd) = (SVector::zeros(), SVector::zeros());
        let fixed = plant.derivatives_fixed(&x, &w, &loads, &mut xd, &mut wd);
        let (mut xs, mut ws) = (vec![0.0; N], vec![0.0; N]);
        let sliced = plant.derivatives(&s.x, &s.w, &s.loads, &mut xs, &mut ws);
        assert_eq!(fixed, sliced, "{name}: outcome");
        assert_eq!(xd.as_slice(), &xs[..], "{name}: ẋ");
        assert_eq!(wd.as_slice(), &ws[..], "{name}: ẇ");
        let m = plant.mass_matrix_fixed(&x);
        let mut rows = vec![0.0; N * N];
        plant.mass_matrix(&s.x, &mut rows);
        for (i, row) in rows.chunks(N).enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert_eq!(m[(i, j)], *v, "{name}: M[{i}][{j}]");
            }
        }
        let mut states = vec![WheelState::default(); K];
        plant.wheels(&s.x, &s.w, &s.steer, &mut states);
        assert_eq!(
            plant.wheels_fixed(&x, &w, &steer).to_vec(),
            states,
            "{name}: wheels"
        );
        let (by_index, by_row) = jacobian(&plant, &x, &w, &loads);
        assert!(by_row != 0.0, "{name}: gravity makes ∂v̇x/∂θ nonzero");
        assert_eq!(by_index, by_row, "{name}: Jacobian orientation");
    }
}

macro_rules! jacobian_entry {
    ($ty:ty) => {
        |p: &$ty, x: &SVector<f64, _>, w: &SVector<f64, _>, loads: &[WheelLoad; _]| {
            // ∂ẇ_0/∂x_4 (pitch): a row of ẇ, a column of x, far from the diagonal.
            let n = x.len();
            let rows = p.jacobian_array(&x.data.0[0], &w.data.0[0], loads);
            (p.jacobian_fixed(x, w, loads)[(n, 4)], rows[n][4])
        }
    };
}

#[test]
fn the_nalgebra_interface_is_the_slice_interface() {
    use rover_models::{Exomars, Lrv, Mer, Swing4};
    check_fixed("exomars", Exomars::new(), jacobian_entry!(Exomars));
    check_fixed("swing4", Swing4::new(), jacobian_entry!(Swing4));
    check_fixed("mer", Mer::new(), jacobian_entry!(Mer));
    check_fixed("lrv", Lrv::new(), jacobian_entry!(Lrv));
}

/// A generated right-hand side on plain arrays: `derivatives_array` or
/// `derivatives_portable` of one plant.
type ArrayRhs<'a, const N: usize, const K: usize> =
    &'a dyn Fn(
        &[f64; N],
        &[f64; N],
        &[WheelLoad; K],
        &mut [f64; N],
        &mut [f64; N],
    ) -> Result<(), rover_dynamics::plant::PlantError>;

/// The two compilations of a generated right-hand side, the crate's
/// target and x86-64-v4 (`rover_dynamics::cpu`), give the same bits: the
/// dispatched call against the portable one on 1000 random states.
fn same_bits_at_every_level<const N: usize, const K: usize>(
    name: &str,
    dispatched: ArrayRhs<N, K>,
    portable: ArrayRhs<N, K>,
) {
    let model = spec(name).model;
    let mut rng = Rng::new(4242 + N as u64);
    let bits = |v: [f64; N]| v.map(f64::to_bits);
    for _ in 0..1000 {
        let s = random_state(&model, &mut rng);
        let x: [f64; N] = s.x.clone().try_into().unwrap();
        let w: [f64; N] = s.w.clone().try_into().unwrap();
        let loads: [WheelLoad; K] = s.loads.clone().try_into().unwrap();
        let (mut xa, mut wa, mut xb, mut wb) = ([0.0; N], [0.0; N], [0.0; N], [0.0; N]);
        let a = dispatched(&x, &w, &loads, &mut xa, &mut wa);
        let b = portable(&x, &w, &loads, &mut xb, &mut wb);
        assert_eq!(a, b, "{name}: outcome at x = {x:?}");
        assert_eq!(bits(xa), bits(xb), "{name}: ẋ at x = {x:?}");
        assert_eq!(bits(wa), bits(wb), "{name}: ẇ at x = {x:?}");
    }
}

#[test]
fn both_compilations_of_the_generated_rhs_give_the_same_bits() {
    use rover_models::{Exomars, Lrv, Mer, Swing4, Swing4Linearized, Swing4Simplified};
    #[cfg(target_arch = "x86_64")]
    assert_eq!(
        rover_dynamics::cpu::x86_64_v4(),
        is_x86_feature_detected!("avx2")
            && is_x86_feature_detected!("fma")
            && is_x86_feature_detected!("avx512f")
            && is_x86_feature_detected!("avx512vl"),
        "the dispatch asks the processor"
    );
    if !rover_dynamics::cpu::x86_64_v4() {
        eprintln!("this processor has no x86-64-v4: both calls run the portable copy");
    }
    macro_rules! check {
        ($name:literal, $plant:expr) => {{
            let p = $plant;
            same_bits_at_every_level(
                $name,
                &|x, w, l, xd, wd| p.derivatives_array(x, w, l, xd, wd),
                &|x, w, l, xd, wd| p.derivatives_portable(x, w, l, xd, wd),
            );
        }};
    }
    check!("exomars", Exomars::new());
    check!("swing4", Swing4::new());
    check!("mer", Mer::new());
    check!("lrv", Lrv::new());
    check!("swing4", Swing4Simplified::new());
    check!("swing4", Swing4Linearized::new());
}

fn dual_column(model: &Model, s: &State, col: usize) -> Vec<f64> {
    let n = model.dof();
    let d = |v: f64, k: usize| {
        if k == col {
            Dual::var(v)
        } else {
            Dual::lift(v)
        }
    };
    let x: Vec<Dual<f64>> = (0..n).map(|k| d(s.x[k], k)).collect();
    let w: Vec<Dual<f64>> = (0..n).map(|k| d(s.w[k], n + k)).collect();
    let lift = |v: [f64; 3]| v.map(Dual::lift);
    let loads: Vec<Load<Dual<f64>>> = s
        .loads
        .iter()
        .map(|l| Load {
            force: lift(l.force),
            moment: lift(l.moment),
            stator_torque: lift(l.stator_torque),
        })
        .collect();
    let neutral: Vec<Dual<f64>> = s.neutral.iter().map(|&v| Dual::lift(v)).collect();
    let mut ws = Workspace::<Dual<f64>>::new(model);
    let (mut xd, mut wd) = (vec![Dual::lift(0.0); n], vec![Dual::lift(0.0); n]);
    derivatives(model, &mut ws, &neutral, &x, &w, &loads, &mut xd, &mut wd);
    xd.iter().chain(&wd).map(|v| v.eps).collect()
}

/// The generated Jacobian of `name` against duals, on 20 random states.
/// `jac(plant_neutrals, x, w, loads)` returns the 2N×2N matrix row-major.
fn check_jacobian(name: &str, seed: u64, jac: impl Fn(&State) -> Vec<f64>) {
    let model = spec(name).model;
    let n = model.dof();
    let mut rng = Rng::new(seed);
    for trial in 0..20 {
        let s = random_state(&model, &mut rng);
        let got = jac(&s);
        for col in 0..2 * n {
            let expect = dual_column(&model, &s, col);
            let column: Vec<f64> = (0..2 * n).map(|row| got[row * 2 * n + col]).collect();
            let e = rel(&column, &expect);
            assert!(
                e <= TOL,
                "{name} state {trial}: Jacobian column {col} differs by {e:e}"
            );
        }
    }
}

macro_rules! jacobian_of {
    ($ty:ty, $n:expr, $k:expr) => {
        |s: &State| {
            let mut plant = <$ty>::new();
            for (i, &y0) in s.neutral.iter().enumerate() {
                plant.set_spring_neutral(i, y0);
            }
            let x: [f64; $n] = s.x.clone().try_into().unwrap();
            let w: [f64; $n] = s.w.clone().try_into().unwrap();
            let loads: [WheelLoad; $k] = s.loads.clone().try_into().unwrap();
            plant
                .jacobian_array(&x, &w, &loads)
                .iter()
                .flatten()
                .copied()
                .collect()
        }
    };
}

#[test]
fn generated_jacobians_are_the_exact_derivatives() {
    check_jacobian("exomars", 71, jacobian_of!(rover_models::Exomars, 9, 6));
    check_jacobian("swing4", 72, jacobian_of!(rover_models::Swing4, 10, 4));
    check_jacobian("mer", 73, jacobian_of!(rover_models::Mer, 9, 6));
    check_jacobian("lrv", 74, jacobian_of!(rover_models::Lrv, 10, 4));
}

#[test]
fn generated_reduced_fidelity_levels_equal_generic() {
    // MODEL.md §9 levels 2 and 3, both back ends frozen at the same loaded
    // static equilibrium (docs/FIDELITY.md).
    use rover_dynamics::fidelity::Fidelity;
    let model = spec("swing4").model;
    let y_ref = rover_runtime::quasi_static::flat_ground_equilibrium(&model).unwrap();
    let generic = |level| GenericPlant::with_fidelity_at(model.clone(), level, &y_ref).unwrap();
    compare_with(
        "swing4",
        rover_models::Swing4Simplified::new(),
        generic(Fidelity::Simplified),
        67,
    );
    compare_with(
        "swing4",
        rover_models::Swing4Linearized::new(),
        generic(Fidelity::Linearized),
        68,
    );
}

/// A reduced level from the derive: frozen at the description's rest y_c
/// by default, or at an explicit `y_ref`.
mod derived_levels {
    use rover_derive::Rover;

    #[derive(Rover)]
    #[rover(file = "models/exomars.toml", fidelity = "simplified")]
    pub struct ExomarsSimplified;

    #[derive(Rover)]
    #[rover(
        file = "models/swing4.toml",
        fidelity = "linearized",
        y_ref = [-0.55, -0.57, 0.56, 0.58],
        jacobian = false
    )]
    pub struct Swing4Linearized;

    #[derive(Rover)]
    #[rover(
        file = "models/swing4.toml",
        fidelity = "linearized_exact_rotation",
        y_ref = [-0.55, -0.57, 0.56, 0.58],
        jacobian = false
    )]
    pub struct Swing4LinearizedExactRotation;
}

#[test]
fn derived_reduced_levels_equal_generic() {
    use rover_dynamics::fidelity::Fidelity;
    let exomars = spec("exomars").model;
    compare_with(
        "exomars",
        derived_levels::ExomarsSimplified::plant(),
        GenericPlant::with_fidelity(exomars, Fidelity::Simplified).unwrap(),
        81,
    );
    let swing4 = spec("swing4").model;
    compare_with(
        "swing4",
        derived_levels::Swing4Linearized::plant(),
        GenericPlant::with_fidelity_at(
            swing4.clone(),
            Fidelity::Linearized,
            &[-0.55, -0.57, 0.56, 0.58],
        )
        .unwrap(),
        82,
    );
    compare_with(
        "swing4",
        derived_levels::Swing4LinearizedExactRotation::plant(),
        GenericPlant::with_fidelity_at(
            swing4,
            Fidelity::LinearizedExactRotation,
            &[-0.55, -0.57, 0.56, 0.58],
        )
        .unwrap(),
        83,
    );
}
