//! The linearized parked rover (`rover_scenario::linearize`): its difference
//! quotients against the generated plant's exact Jacobian, its linear
//! response against the nonlinear run it stands for, and its modes against
//! their own eigen-equation.

use rover_dynamics::Model;
use rover_dynamics::nalgebra::{Complex, DMatrix, DVector};
use rover_dynamics::plant::{Plant, WheelLoad};
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_scenario::linearize::{ModeKind, linearize, parked, state_matrix};

use crate::support::rel;

fn model(name: &str) -> Model {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name)
        .unwrap()
        .model
}

fn names(n: usize) -> Vec<String> {
    (0..2 * n).map(|j| format!("z{j}")).collect()
}

/// In free flight the right-hand side is the plant at zero loads, whose
/// exact Jacobian the generator emits: the central differences must agree
/// with it, on a moving, tilted state (so that B(x), the bias and the
/// springs all contribute).
#[test]
fn differences_in_free_flight_are_the_generated_exact_jacobian() {
    let m = model("swing4");
    let n = m.dof();
    let control = Controller::new(ControllerConfig::default(), &m, 0.0).unwrap();
    let mut sys: RoverSystem<_, Terrain> =
        RoverSystem::new(rover_models::Swing4::new(), None, control);
    let mut y = vec![0.0; 2 * n + 1];
    let x = [0.1, -0.2, 0.5, 0.08, -0.12, 0.3, -0.4, -0.25, 0.35, 0.2];
    let w = [0.3, -0.1, 0.2, 0.4, -0.3, 0.25, 0.5, -0.6, 0.3, -0.2];
    y[..n].copy_from_slice(&x);
    y[n..2 * n].copy_from_slice(&w);
    let a = state_matrix(&mut sys, &y, &names(n), &(0..2 * n).collect::<Vec<_>>()).unwrap();
    let exact = rover_models::Swing4::new().jacobian_array(&x, &w, &[WheelLoad::default(); 4]);
    let by_differences: Vec<f64> = a
        .row_iter()
        .flat_map(|r| r.iter().copied().collect::<Vec<_>>())
        .collect();
    let exact: Vec<f64> = exact.iter().flatten().copied().collect();
    let err = rel(&exact, &by_differences);
    assert!(
        err < 1e-7,
        "central differences vs exact Jacobian: {err:.2e}"
    );
}

/// ż = A·z + b (b = B·u for a constant input u, 0 without one) over the
/// time steps of a nonlinear integration both run with the same RK4.
struct Linear(DMatrix<f64>, DVector<f64>);

impl Linear {
    /// ż = A·z.
    fn free(a: &DMatrix<f64>) -> Self {
        Linear(a.clone(), DVector::zeros(a.nrows()))
    }
}

impl OdeSystem for Linear {
    type Error = std::convert::Infallible;
    fn dim(&self) -> usize {
        self.0.nrows()
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error> {
        let f = &self.0 * DVector::from_column_slice(y) + &self.1;
        dy.copy_from_slice(f.as_slice());
        Ok(())
    }
}

/// The largest deviation of the nonlinear run from the linear prediction
/// over 0.4 s after a displacement of size `eps` from the equilibrium
/// (heave, roll, pitch and every suspension coordinate at once), relative to
/// the largest predicted displacement.
fn linear_prediction_error<P: Plant>(m: &Model, plant: P, eps: f64) -> f64 {
    let n = m.dof();
    let (mut sys, y_e) = parked(m, plant).unwrap();
    let a = state_matrix(&mut sys, &y_e, &names(n), &(0..2 * n).collect::<Vec<_>>()).unwrap();
    let mut z = vec![0.0; 2 * n];
    z[2] = eps;
    z[3] = 0.5 * eps;
    z[4] = -0.7 * eps;
    for (i, zi) in z[6..n].iter_mut().enumerate() {
        *zi = if i % 2 == 0 { eps } else { -0.6 * eps };
    }
    deviation_from_linear(
        &mut sys,
        &y_e,
        Linear::free(&a),
        z,
        1e-5,
        (0.01, 40),
        (n, 0.0),
    )
}

/// The largest deviation of a nonlinear run of `sys` from the linear model
/// `lin`, both started `z` off `y_e` and integrated by RK4 at `step`, over
/// `samples.1` instants `samples.0` apart, in the first `compared.0` states
/// (X against its steady advance `compared.1·t`), relative to the largest
/// predicted deviation from `y_e` there.
fn deviation_from_linear<S: OdeSystem>(
    sys: &mut S,
    y_e: &[f64],
    mut lin: Linear,
    mut z: Vec<f64>,
    step: f64,
    samples: (f64, usize),
    compared: (usize, f64),
) -> f64
where
    S::Error: std::fmt::Debug,
{
    let (n, drift) = compared;
    let mut y = y_e.to_vec();
    for (yi, zi) in y.iter_mut().zip(&z) {
        *yi += zi;
    }
    let config = FixedStepConfig { step };
    let (mut rk_nl, mut rk_lin) = (
        Rk4::new(y.len(), &config).unwrap(),
        Rk4::new(z.len(), &config).unwrap(),
    );
    let (mut t_nl, mut t_lin) = (0.0, 0.0);
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for k in 1..=samples.1 {
        let t = samples.0 * k as f64;
        rk_nl.advance(sys, &mut t_nl, &mut y, t).unwrap();
        rk_lin.advance(&mut lin, &mut t_lin, &mut z, t).unwrap();
        for i in 0..n {
            let steady = y_e[i] + if i == 0 { drift * t } else { 0.0 };
            worst = worst.max((y[i] - steady - z[i]).abs());
            scale = scale.max(z[i].abs());
        }
    }
    worst / scale
}

/// The linearization is what a nonlinear run does near the equilibrium:
/// small displacements follow it closely, and the deviation shrinks in
/// proportion to the displacement (the signature of a correct first-order
/// model; a wrong column of A would leave a deviation of order one).
#[test]
fn small_motions_follow_the_linearization() {
    for name in ["swing4", "mer"] {
        let m = model(name);
        let coarse = linear_prediction_error(&m, rover_models::plant(name).unwrap(), 1e-4);
        let fine = linear_prediction_error(&m, rover_models::plant(name).unwrap(), 1e-5);
        // Measured: 7.2e-5 and 7.6e-6 (swing4), 9.8e-5 and 8.4e-6 (MER). With
        // the rate columns differenced at 1e-6 instead of 1e-8 the small run
        // stayed at 1.6e-4 (the lateral force's α·|α| term biases central
        // differences in proportion to the step), and this test failed.
        assert!(coarse < 1e-3, "{name}: deviation {coarse:.3e} at 0.1 mm");
        assert!(
            fine < 0.2 * coarse,
            "{name}: {fine:.3e} at 0.01 mm vs {coarse:.3e} at 0.1 mm"
        );
    }
}

/// Every mode satisfies its eigen-equation, the pairs and neutral motions
/// are counted right (X, Y, heading and rolling have no restoring force on
/// flat ground without rolling resistance), and a parked rover is stable.
#[test]
fn modes_are_eigenpairs_of_a_stable_parked_rover() {
    for name in rover_models::NAMES {
        let m = model(name);
        let n = m.dof();
        let lin = linearize(&m, rover_models::plant(name).unwrap()).unwrap();
        assert!(
            lin.residual < 1e-2,
            "{name}: not at rest, |ẇ| = {:.2e}",
            lin.residual
        );
        let count: usize = lin
            .modes
            .iter()
            .map(|md| {
                if md.kind == ModeKind::Oscillatory {
                    2
                } else {
                    1
                }
            })
            .sum();
        assert_eq!(count, 2 * n, "{name}: every eigenvalue once");
        let neutral = lin
            .modes
            .iter()
            .filter(|md| md.kind == ModeKind::Neutral)
            .count();
        assert_eq!(neutral, 4, "{name}: X, Y, ψ and v_x are free");
        // At rest ẋ = B(x)·w = 0 whatever x: the block ∂ẋ/∂x is exactly zero,
        // and A = [[0, B], [K, C]].
        let block = |r: usize, c: usize| {
            DMatrix::from_fn(n, n, |i, j| Complex::new(lin.a[r + i][c + j], 0.0))
        };
        assert!(
            (0..n).all(|i| (0..n).all(|j| lin.a[i][j] == 0.0)),
            "{name}: ∂ẋ/∂x at rest"
        );
        let (b, k, c) = (block(0, n), block(n, 0), block(n, n));
        let b_inv = b
            .try_inverse()
            .expect("B(x) is invertible away from |φ| = 90°");
        for md in lin.modes.iter().filter(|md| md.kind != ModeKind::Neutral) {
            assert!(
                md.eigenvalue[0] < 0.0,
                "{name}: unstable mode {:?}",
                md.eigenvalue
            );
            // With v = [p; q]: λp = B·q, λq = K·p + C·q, so for the shape p,
            // λ²·B⁻¹p = K·p + λ·C·B⁻¹p.
            let lambda = Complex::new(md.eigenvalue[0], md.eigenvalue[1]);
            let p = DVector::from_fn(n, |i, _| Complex::new(md.shape[i][0], md.shape[i][1]));
            let q = &b_inv * &p;
            let lhs = &q * (lambda * lambda);
            let rhs = &k * &p + &c * &q * lambda;
            let size =
                |v: &DVector<Complex<f64>>| v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
            let err = size(&(&lhs - &rhs)) / size(&lhs).max(size(&rhs));
            assert!(
                err < 1e-6,
                "{name}: mode {:?} off its eigen-equation by {err:.2e}",
                md.eigenvalue
            );
            let shares: f64 = md.energy.iter().sum();
            assert!(
                (shares - 1.0).abs() < 1e-12,
                "{name}: energy shares sum to {shares}"
            );
        }
    }
}

/// ExoMars' heave is a closed-form case: its bogies do not move when the
/// body rises (the two real `v_z` modes carry all of the kinetic energy), so
/// it is the whole mass on six tyres, `m·s² + 6c_w·s + 6k_w = 0`: with
/// m = 33.6 kg, c_w = 300 N·s/m, k_w = 4000 N/m the roots are −25 and
/// −200/7 1/s (just past critical damping, ζ = 1.003).
#[test]
fn exomars_heave_is_the_mass_on_its_six_tyres() {
    let m = model("exomars");
    let lin = linearize(&m, rover_models::plant("exomars").unwrap()).unwrap();
    let (k, c) = (m.wheels[0].stiffness, m.wheels[0].damping);
    assert!(m.wheels.iter().all(|w| w.stiffness == k && w.damping == c));
    let (mass, wheels) = (m.total_mass(), m.wheels.len() as f64);
    let disc = ((wheels * c).powi(2) - 4.0 * mass * wheels * k).sqrt();
    let roots = [
        (-wheels * c + disc) / (2.0 * mass),
        (-wheels * c - disc) / (2.0 * mass),
    ];
    assert!((roots[0] + 25.0).abs() < 1e-9 && (roots[1] + 200.0 / 7.0).abs() < 1e-9);
    let heave: Vec<f64> = lin
        .modes
        .iter()
        .filter(|md| {
            md.dominant
                .first()
                .is_some_and(|(name, share)| name == "vz" && *share > 0.99)
        })
        .map(|md| md.eigenvalue[0])
        .collect();
    assert_eq!(heave.len(), 2, "two heave modes, got {heave:?}");
    for (got, want) in heave.iter().zip(roots) {
        assert!(
            (got - want).abs() < 1e-6 * want.abs(),
            "heave λ {got} vs closed form {want}"
        );
    }
}

/// The input matrix of the spring neutrals (what an active suspension
/// moves): a linear spring's neutral enters only its own generalized force,
/// `Q_i = −k_i·(y_i − y0_i)`, so its column is `[0; M⁻¹·k_i·e_i]`.
#[test]
fn spring_neutral_inputs_are_the_springs_through_the_mass_matrix() {
    let mut checked = 0;
    for name in rover_models::NAMES {
        let m = model(name);
        let n = m.dof();
        let mut plant = rover_models::plant(name).unwrap();
        let lin = linearize(&m, plant).unwrap();
        let steerable = m.wheels.iter().filter(|w| w.steerable).count();
        assert_eq!(
            (lin.b.len(), lin.inputs.len()),
            (2 * n, m.m() + m.wheels.len() + steerable)
        );
        let mut mass = vec![0.0; n * n];
        plant.mass_matrix(&lin.equilibrium, &mut mass);
        let lu = DMatrix::from_row_slice(n, n, &mass).lu();
        for (j, c) in m.coordinates.iter().enumerate() {
            let column: Vec<f64> = lin.b.iter().map(|row| row[j]).collect();
            let rover_dynamics::model::Spring::Linear { stiffness } = c.spring else {
                continue;
            };
            let mut q = DVector::zeros(n);
            q[6 + j] = stiffness;
            let want: Vec<f64> = vec![0.0; n]
                .into_iter()
                .chain(lu.solve(&q).unwrap().iter().copied())
                .collect();
            let err = rel(&want, &column);
            assert!(err < 1e-7, "{name}: y0_{} column off by {err:.2e}", j + 1);
            checked += 1;
        }
    }
    assert!(checked >= 8, "linear springs checked: {checked}");
}

/// With rolling resistance (a scenario's `[contact]` table) rolling is no
/// longer free: three neutral motions remain (X, Y, ψ), and v_x moves in
/// stable modes only. (Near standstill the regularized resistance is a
/// damper of `C_rr·F_n/v_ε` per wheel, −162 1/s on ExoMars alone, but it
/// acts at ground level, so it pitches the body and turns the bogies: the
/// modes that carry v_x are pitch–surge mixtures, not that closed form.)
#[test]
fn rolling_resistance_damps_the_rolling_mode() {
    let m = model("exomars");
    let contact = rover_scenario::scenario::ContactConfig {
        rolling_resistance: 0.1,
        ..Default::default()
    };
    let point = rover_scenario::linearize::OperatingPoint {
        contact,
        ..Default::default()
    };
    let lin = rover_scenario::linearize::linearize_at(
        &m,
        rover_models::plant("exomars").unwrap(),
        &point,
    )
    .unwrap();
    let neutral = lin
        .modes
        .iter()
        .filter(|md| md.kind == ModeKind::Neutral)
        .count();
    assert_eq!(neutral, 3, "X, Y, ψ");
    let vx = |md: &rover_scenario::linearize::Mode| md.energy.first().copied().unwrap_or(0.0);
    let surging: Vec<_> = lin
        .modes
        .iter()
        .filter(|md| md.kind != ModeKind::Neutral && vx(md) > 0.2)
        .collect();
    assert!(!surging.is_empty() && surging.iter().all(|md| md.eigenvalue[0] < 0.0));
    // Without it four are neutral (`modes_are_eigenpairs_of_a_stable_parked_rover`).
}

/// A rover that cannot stand: two wheels on one axle, the body's centre
/// 0.3 m above it, is an inverted pendulum on a free-rolling axle. Its
/// equilibrium exists (balanced), and the linearization finds exactly one
/// growing mode, pitch; a nonlinear run started a hair along that mode
/// grows at its rate. (Yaw is neutral too: turning on the spot rolls both
/// wheels without sideslip, and they roll freely.)
#[test]
fn a_rover_balanced_on_one_axle_has_one_growing_pitch_mode() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/support/pendulum.toml"
    ))
    .unwrap();
    let m = rover_spec::load_str(&text, "pendulum.toml").unwrap().model;
    let n = m.dof();
    let plant = || rover_runtime::GenericPlant::new(m.clone()).unwrap();
    let lin = linearize(&m, plant()).unwrap();
    let growing: Vec<_> = lin
        .modes
        .iter()
        .filter(|md| md.kind != ModeKind::Neutral && md.eigenvalue[0] > 0.0)
        .collect();
    assert_eq!(
        growing.len(),
        1,
        "{:?}",
        growing.iter().map(|md| md.eigenvalue).collect::<Vec<_>>()
    );
    let fall = growing[0];
    assert_eq!(fall.kind, ModeKind::Real);
    assert_eq!(fall.dominant[0].0, "Oy", "{:?}", fall.dominant);
    let lambda = fall.eigenvalue[0];
    // Start 1e-6 along the mode (positions; rates λ times as much, through B).
    let (mut sys, y_e) = parked(&m, plant()).unwrap();
    let a = DMatrix::from_fn(2 * n, 2 * n, |i, j| lin.a[i][j]);
    let p = DVector::from_fn(n, |i, _| fall.shape[i][0]);
    let q = a.view((0, n), (n, n)).clone_owned().try_inverse().unwrap() * &p * lambda;
    let mut y = y_e.clone();
    for i in 0..n {
        y[i] += 1e-6 * p[i];
        y[n + i] += 1e-6 * q[i];
    }
    let mut rk = Rk4::new(y.len(), &FixedStepConfig { step: 2.5e-5 }).unwrap();
    let mut t = 0.0;
    let theta = |y: &[f64]| y[4] - y_e[4];
    rk.advance(&mut sys, &mut t, &mut y, 0.5).unwrap();
    let early = theta(&y);
    rk.advance(&mut sys, &mut t, &mut y, 1.0).unwrap();
    let rate = (theta(&y) / early).ln() / 0.5;
    assert!(
        (rate - lambda).abs() < 1e-3 * lambda,
        "nonlinear growth {rate} 1/s vs λ = {lambda}"
    );
}

/// Closed loop at speed: swing4 driving at 0.1 m/s under its speed loop and
/// a heading hold with line following. Every motion but X has a restoring
/// force now (the line-following loop is a 0.035 Hz pair), all are stable,
/// and a nonlinear run started off the steady state in Y, ψ, roll, pitch
/// and heave follows the linear model, closer in proportion to the offset.
#[test]
fn closed_loop_at_speed_follows_its_linearization() {
    use rover_scenario::linearize::{OperatingPoint, linearize_at, operating_system};
    let m = model("swing4");
    let n = m.dof();
    let control = toml::from_str(
        "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 5.0\nkd = 0.5\ncross_track = 2.0\n",
    )
    .unwrap();
    let point = OperatingPoint {
        speed: 0.1,
        control,
        ..Default::default()
    };
    let lin = linearize_at(&m, rover_models::Swing4::new(), &point).unwrap();
    let neutral = lin
        .modes
        .iter()
        .filter(|md| md.kind == ModeKind::Neutral)
        .count();
    assert_eq!(neutral, 1, "only X is free");
    assert!(
        lin.modes
            .iter()
            .all(|md| md.kind == ModeKind::Neutral || md.eigenvalue[0] < 0.0)
    );
    let a = DMatrix::from_fn(2 * n, 2 * n, |i, j| lin.a[i][j]);
    let deviation = |eps: f64| {
        let (mut sys, _) = operating_system(&m, rover_models::Swing4::new(), &point).unwrap();
        let y_e = lin.state.clone();
        let mut rate = vec![0.0; y_e.len()];
        sys.rhs(0.0, &y_e, &mut rate).unwrap();
        let mut z = vec![0.0; 2 * n];
        (z[1], z[2], z[3], z[4], z[5]) = (eps, 0.3 * eps, 0.5 * eps, -0.7 * eps, eps);
        // X moves on at the steady rate.
        deviation_from_linear(
            &mut sys,
            &y_e,
            Linear::free(&a),
            z,
            2.5e-5,
            (0.05, 20),
            (n, rate[0]),
        )
    };
    // Measured: 9.3e-4 and 9.3e-5, exactly in proportion: what is left is
    // the second-order term, not an error of A.
    let (coarse, fine) = (deviation(1e-4), deviation(1e-5));
    assert!(coarse < 2e-3, "deviation {coarse:.3e} at 1e-4");
    assert!(
        fine < 0.2 * coarse,
        "{fine:.3e} at 1e-5 vs {coarse:.3e} at 1e-4"
    );
}

/// Operating points that are not steady are refused with the reason: a
/// turn commanded by a time table, and coasting at speed against rolling
/// resistance (no speed loop holds v_x, and it decays).
#[test]
fn unsteady_operating_points_are_refused() {
    use rover_scenario::linearize::{LinearizeError, OperatingPoint, linearize_at};
    let m = model("swing4");
    let timed = OperatingPoint {
        speed: 0.1,
        control: toml::from_str(
            "[speed]\nspeed = 0.1\n[steering]\nkind = \"slip\"\n\
             delta_tau = { points = [[0.0, 0.0], [5.0, 0.2]] }\n",
        )
        .unwrap(),
        ..Default::default()
    };
    let coasting = OperatingPoint {
        speed: 0.1,
        contact: rover_scenario::scenario::ContactConfig {
            rolling_resistance: 0.1,
            ..Default::default()
        },
        ..Default::default()
    };
    for (point, why) in [(timed, "constant"), (coasting, "dvx/dt")] {
        match linearize_at(&m, rover_models::Swing4::new(), &point) {
            Err(LinearizeError::NotSteady(message)) => assert!(message.contains(why), "{message}"),
            other => panic!("expected NotSteady, got {:?}", other.map(|l| l.speed)),
        }
    }
}

/// A heading hold's integrals are states of the closed loop, after the
/// speed loop's, and their rows are the integrands' derivatives in closed
/// form: ζ̇ = V − v_x, ζ̇_heading = e = ψ_ref − atan(k_e·e_y + k_y·ζ_line) − ψ,
/// ζ̇_line = e_y = Y on the line Y = 0 (ψ_ref = 0). Without a speed-loop
/// gain its integral is left out and the others keep their places.
#[test]
fn heading_hold_integrals_are_states_of_the_closed_loop() {
    use rover_scenario::linearize::{OperatingPoint, linearize_at};
    let m = model("swing4");
    let n = m.dof();
    let (k_e, k_y) = (2.0, 0.2);
    for speed_ki in [2.0, 0.0] {
        let control = toml::from_str(&format!(
            "[speed]\nspeed = 0.1\nki = {speed_ki}\n[steering]\nkind = \"heading\"\nkp = 5.0\n\
             kd = 0.5\nki = 1.0\ncross_track = {k_e}\ncross_track_integral = {k_y}\n"
        ))
        .unwrap();
        let point = OperatingPoint {
            speed: 0.1,
            control,
            ..Default::default()
        };
        let lin = linearize_at(&m, rover_models::Swing4::new(), &point).unwrap();
        let extra: Vec<&str> = lin.states[2 * n..].iter().map(|s| s.as_str()).collect();
        let want: &[&str] = if speed_ki > 0.0 {
            &["zeta", "zeta_heading", "zeta_line"]
        } else {
            &["zeta_heading", "zeta_line"]
        };
        assert_eq!(extra, want);
        let dim = lin.states.len();
        assert_eq!((lin.a.len(), lin.a[0].len()), (dim, dim));
        let col = |name: &str| lin.states.iter().position(|s| s == name).unwrap();
        let row_is = |row: &str, entries: &[(&str, f64)]| {
            let r = &lin.a[col(row)];
            for (j, v) in r.iter().enumerate() {
                let want = entries
                    .iter()
                    .find(|(name, _)| col(name) == j)
                    .map_or(0.0, |e| e.1);
                assert!(
                    (v - want).abs() < 1e-6,
                    "∂{row}/∂{}: {v} vs {want}",
                    lin.states[j]
                );
            }
        };
        row_is("zeta_line", &[("Y", 1.0)]);
        row_is(
            "zeta_heading",
            &[("psi", -1.0), ("Y", -k_e), ("zeta_line", -k_y)],
        );
        if speed_ki > 0.0 {
            row_is("zeta", &[("vx", -1.0)]);
        }
        assert!(
            lin.modes
                .iter()
                .all(|md| md.kind == ModeKind::Neutral || md.eigenvalue[0] < 0.0),
            "the tuned loop is stable"
        );
    }
}

/// The torque and steering columns of B are what the open-loop commands do
/// to the nonlinear rover: held constant from the equilibrium, a small
/// torque difference (left wheels back, right forward: a turn on the spot)
/// and, on the LRV at 0.5 m/s, a small steering angle of every steerable
/// wheel move the run as `ż = A·z + B·u` predicts, and half the input
/// gives half the deviation's share (first order: what is left is the
/// second-order term).
#[test]
fn torque_and_steering_inputs_are_what_the_commands_do() {
    use rover_scenario::linearize::{OperatingPoint, linearize_at, operating_system};
    let cases: [(&str, f64, &str); 2] = [("swing4", 0.0, "tau"), ("lrv", 0.5, "delta")];
    for (name, speed, kind) in cases {
        let m = model(name);
        let n = m.dof();
        let control = if speed > 0.0 {
            toml::from_str(&format!("[speed]\nspeed = {speed}\n")).unwrap()
        } else {
            Default::default()
        };
        let point = OperatingPoint {
            speed,
            control,
            ..Default::default()
        };
        let plant = || rover_models::plant(name).unwrap();
        let lin = linearize_at(&m, plant(), &point).unwrap();
        let dim = lin.states.len();
        let a = DMatrix::from_fn(dim, dim, |i, j| lin.a[i][j]);
        let deviation = |size: f64| {
            // The input: ±size on the torques, size on every steering angle.
            let mut torques = vec![0.0; m.wheels.len()];
            let mut angles = vec![0.0; m.wheels.len()];
            let mut u = DVector::zeros(lin.inputs.len());
            for (c, input) in lin.inputs.iter().enumerate() {
                let Some((what, wheel)) = input.split_once('_') else {
                    continue;
                };
                let j: usize = wheel.parse::<usize>().unwrap() - 1;
                if what == kind && kind == "tau" {
                    let body = &m.bodies[m.wheels[j].body];
                    let left = body.position.value(&m.rest())[1] > 0.0;
                    torques[j] = if left { -size } else { size };
                    u[c] = torques[j];
                } else if what == kind {
                    angles[j] = size;
                    u[c] = size;
                }
            }
            assert!(u.norm() > 0.0, "{name}: no {kind} input");
            let bu = DMatrix::from_fn(dim, lin.inputs.len(), |i, j| lin.b[i][j]) * &u;
            let (mut sys, _) = operating_system(&m, plant(), &point).unwrap();
            sys.set_torques(&torques).unwrap();
            sys.set_steering(&angles).unwrap();
            let mut rate = vec![0.0; lin.state.len()];
            sys.rhs(0.0, &lin.state, &mut rate).unwrap();
            let drift = rate[0] - bu[0]; // X's steady advance, without the input's
            deviation_from_linear(
                &mut sys,
                &lin.state,
                Linear(a.clone(), bu),
                vec![0.0; dim],
                2.5e-5,
                (0.05, 20),
                (2 * n, drift),
            )
        };
        let (coarse, fine) = (deviation(2e-3), deviation(1e-3));
        // Measured: swing4 5.5e-4 → 2.8e-4, LRV 2.8e-3 → 1.4e-3.
        assert!(coarse < 5e-3, "{name}: {kind} deviation {coarse:.3e}");
        assert!(
            fine < 0.7 * coarse,
            "{name}: {fine:.3e} at half the input vs {coarse:.3e}"
        );
    }
}

/// A steady turn is where a run settles: ExoMars under Ackermann steering
/// (R = 2 m) and a PI speed loop at 0.1 m/s, swing4 slip-steered by
/// Δτ = 0.2 N·m. The steady state found by Newton on the right-hand side
/// (yaw rate, sideslip, roll, pitch, suspension, heave) is the end of a
/// 60 s run of the same scenario (BDF, rtol 1e-9), to 3e-13.
#[test]
fn a_steady_turn_is_where_a_run_settles() {
    use rover_scenario::linearize::{OperatingPoint, linearize_at};
    let cases = [
        (
            "exomars",
            "[steering]\nkind = \"ackermann\"\nradius = 2.0\n",
        ),
        ("swing4", "[steering]\nkind = \"slip\"\ndelta_tau = 0.2\n"),
    ];
    for (name, steering) in cases {
        let m = model(name);
        let n = m.dof();
        let control = format!("[speed]\nspeed = 0.1\nki = 5.0\n{steering}");
        let point = OperatingPoint {
            speed: 0.1,
            control: toml::from_str(&control).unwrap(),
            ..Default::default()
        };
        let lin = linearize_at(&m, rover_models::plant(name).unwrap(), &point).unwrap();
        let yaw_rate = lin.state[n + 5];
        assert!(yaw_rate > 0.01, "{name}: it turns left, Ω_z = {yaw_rate}");
        let run = crate::support::run::run(
            name,
            &format!(
                "duration = 60.0\nsettle = 1.0\noutput_rate = 1.0\n\
                 [integrator.bdf]\nrtol = 1e-9\natol = 1e-11\n\
                 {}",
                control
                    .replace("[speed]", "[control.speed]")
                    .replace("[steering]", "[control.steering]")
            ),
        );
        for (i, state) in lin.states.iter().enumerate().take(2 * n) {
            if matches!(i, 0 | 1 | 5) {
                continue; // X, Y, ψ go round the circle
            }
            let end = *run.col(state).last().unwrap();
            assert!(
                // Measured: 3e-13 at most.
                (end - lin.state[i]).abs() < 1e-10 * (1.0 + lin.state[i].abs()),
                "{name}: {state} settles at {end}, the steady state has {}",
                lin.state[i]
            );
        }
        assert!(
            lin.modes
                .iter()
                .all(|md| md.kind == rover_scenario::linearize::ModeKind::Neutral
                    || md.eigenvalue[0] < 0.0),
            "{name}: the turn is stable"
        );
    }
}

/// Driving against rolling resistance: with a P speed loop the steady
/// speed is below its set-point by what the torque must make up. At the
/// steady state every wheel's torque is the loop's `kp·(V − v_x)`, and the
/// pulls they drive balance the resistance `C_rr·ΣF_n` (the net
/// longitudinal ground force vanishes).
#[test]
fn a_speed_loop_against_rolling_resistance_settles_below_its_set_point() {
    use rover_scenario::linearize::{OperatingPoint, linearize_at, operating_system};
    let m = model("exomars");
    let n = m.dof();
    let (speed, kp, c_rr) = (0.1, 10.0, 0.05);
    let point = OperatingPoint {
        speed,
        contact: rover_scenario::scenario::ContactConfig {
            rolling_resistance: c_rr,
            ..Default::default()
        },
        control: toml::from_str(&format!("[speed]\nspeed = {speed}\nkp = {kp}\n")).unwrap(),
    };
    let lin = linearize_at(&m, rover_models::Exomars::new(), &point).unwrap();
    let v_x = lin.state[n];
    assert!(v_x < speed && v_x > 0.5 * speed, "v_x = {v_x}");
    let (mut sys, _) = operating_system(&m, rover_models::Exomars::new(), &point).unwrap();
    let mut f = vec![0.0; lin.state.len()];
    sys.rhs(0.0, &lin.state, &mut f).unwrap();
    for tau in sys.torques() {
        assert!((tau - kp * (speed - v_x)).abs() < 1e-12, "τ = {tau}");
    }
    let normal: f64 = sys.reports().iter().map(|r| r.normal).sum();
    let net: f64 = sys.reports().iter().map(|r| r.drawbar).sum();
    assert!(
        net.abs() < 1e-9 * c_rr * normal,
        "net pull {net} N against a resistance of {} N",
        c_rr * normal
    );
    assert!(lin.modes.iter().all(
        |md| md.eigenvalue[0] < 0.0 || md.kind == rover_scenario::linearize::ModeKind::Neutral
    ));
}
