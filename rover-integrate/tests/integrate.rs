//! Integrators on shared problems with known answers: one harness over every method.
//!
//! Problems: exponential decay and the harmonic oscillator (closed form), a stiff linear 2×2
//! system (closed form) and Robertson's kinetics (stiff, reference from a tight dopri5 run and
//! the literature), the torque-free rigid body in Euler angles (Euler's equations; energy,
//! |L| and the inertial angular momentum conserved), y' = y² (blows up at t = 1) for the errors.

use std::convert::Infallible;
use std::fmt;

use rover_integrate::{
    AdaptiveConfig, BDF_DEFAULT_RTOL, Bdf, BdfConfig, FixedStepConfig, IntegrateError, Integrator,
    IntegratorConfig, OdeSystem, Stats,
};

// ---------------------------------------------------------------------------------------------
// Problems
// ---------------------------------------------------------------------------------------------

/// `y_i' = −r_i·y_i`: `y_i(t) = y_i(0)·exp(−r_i·t)`.
struct Decay {
    rates: Vec<f64>,
}

impl OdeSystem for Decay {
    type Error = Infallible;
    fn dim(&self) -> usize {
        self.rates.len()
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        for ((d, yi), r) in dy.iter_mut().zip(y).zip(&self.rates) {
            *d = -r * yi;
        }
        Ok(())
    }
}

/// `x' = w`, `w' = −ω²·x` with `x(0) = 1`, `w(0) = 0`: `x = cos ωt`, `w = −ω sin ωt`.
/// Counts its position-rate calls when `own_position_rates` is set.
struct Oscillator {
    omega: f64,
    own_position_rates: bool,
    position_rate_calls: u64,
}

impl Oscillator {
    fn new(omega: f64) -> Self {
        Self {
            omega,
            own_position_rates: false,
            position_rate_calls: 0,
        }
    }
    fn exact(&self, t: f64) -> [f64; 2] {
        [(self.omega * t).cos(), -self.omega * (self.omega * t).sin()]
    }
    fn energy(&self, y: &[f64]) -> f64 {
        0.5 * (y[1] * y[1] + self.omega * self.omega * y[0] * y[0])
    }
}

impl OdeSystem for Oscillator {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        dy[0] = y[1];
        dy[1] = -self.omega * self.omega * y[0];
        Ok(())
    }
    fn position_rates(
        &mut self,
        _t: f64,
        y: &[f64],
        dx: &mut [f64],
    ) -> Option<Result<(), Infallible>> {
        if !self.own_position_rates {
            return None;
        }
        self.position_rate_calls += 1;
        dx[0] = y[1];
        Some(Ok(()))
    }
}

/// `y' = A·y`, `A = [[−500.5, 499.5], [499.5, −500.5]]`: eigenvalues −1 (eigenvector (1, 1))
/// and −1000 (eigenvector (1, −1)). From `y(0) = (2, 0)`:
/// `y = e^{−t}·(1, 1) + e^{−1000t}·(1, −1)`.
struct StiffLinear;

impl StiffLinear {
    fn exact(t: f64) -> [f64; 2] {
        let (slow, fast) = ((-t).exp(), (-1000.0 * t).exp());
        [slow + fast, slow - fast]
    }
}

impl OdeSystem for StiffLinear {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        dy[0] = -500.5 * y[0] + 499.5 * y[1];
        dy[1] = 499.5 * y[0] - 500.5 * y[1];
        Ok(())
    }
}

/// [`StiffLinear`] with its exact Jacobian, counting the calls.
struct StiffLinearExact {
    jacobian_calls: u64,
}

impl OdeSystem for StiffLinearExact {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        StiffLinear.rhs(t, y, dy)
    }
    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        jac: &mut [f64],
    ) -> Option<Result<usize, Infallible>> {
        self.jacobian_calls += 1;
        jac.copy_from_slice(&[-500.5, 499.5, 499.5, -500.5]);
        Some(Ok(0))
    }
}

/// Robertson's chemical kinetics (Hairer & Wanner II, §IV.1, eq. 1.4), y(0) = (1, 0, 0);
/// `y1 + y2 + y3 = 1` for all t.
struct Robertson;

impl OdeSystem for Robertson {
    type Error = Infallible;
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        let (a, b, c) = (0.04 * y[0], 1e4 * y[1] * y[2], 3e7 * y[1] * y[1]);
        dy[0] = -a + b;
        dy[1] = a - b - c;
        dy[2] = c;
        Ok(())
    }
}

/// A torque-free rigid body, `y = [φ, θ, ψ, ωx, ωy, ωz]`: ZYX Euler angles (roll, pitch, yaw,
/// `R = Rz(ψ)·Ry(θ)·Rx(φ)`) and body angular velocity, the rover's `[x; w]` structure:
/// ```text
/// φ' = ωx + (ωy sin φ + ωz cos φ) tan θ,  θ' = ωy cos φ − ωz sin φ,
/// ψ' = (ωy sin φ + ωz cos φ) / cos θ,      I·ω' = (I·ω) × ω   (Euler's equations)
/// ```
/// Conserved: `T = ½ Σ I_i ω_i²`, `|I·ω|`, and `R·I·ω` (inertial angular momentum).
struct RigidBody {
    inertia: [f64; 3],
}

impl RigidBody {
    /// The paper's Example 1 body inertia [kg·m²], spinning mainly about its largest axis.
    fn paper_body() -> (Self, [f64; 6]) {
        (
            Self {
                inertia: [0.7, 0.9, 1.5],
            },
            [0.0, 0.0, 0.0, 0.3, -0.2, 2.0],
        )
    }
    fn energy(&self, y: &[f64]) -> f64 {
        0.5 * (0..3)
            .map(|i| self.inertia[i] * y[3 + i] * y[3 + i])
            .sum::<f64>()
    }
    fn body_momentum(&self, y: &[f64]) -> [f64; 3] {
        [0, 1, 2].map(|i| self.inertia[i] * y[3 + i])
    }
    fn inertial_momentum(&self, y: &[f64]) -> [f64; 3] {
        let l = self.body_momentum(y);
        let (sf, cf) = y[0].sin_cos();
        let (st, ct) = y[1].sin_cos();
        let (sp, cp) = y[2].sin_cos();
        let r = [
            [cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf],
            [sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf],
            [-st, ct * sf, ct * cf],
        ];
        [0, 1, 2].map(|i| (0..3).map(|j| r[i][j] * l[j]).sum())
    }
}

impl OdeSystem for RigidBody {
    type Error = Infallible;
    fn dim(&self) -> usize {
        6
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        let (sf, cf) = y[0].sin_cos();
        let (wx, wy, wz) = (y[3], y[4], y[5]);
        let yaw_rate = (wy * sf + wz * cf) / y[1].cos();
        dy[0] = wx + (wy * sf + wz * cf) * y[1].tan();
        dy[1] = wy * cf - wz * sf;
        dy[2] = yaw_rate;
        let [i1, i2, i3] = self.inertia;
        dy[3] = (i2 - i3) * wy * wz / i1;
        dy[4] = (i3 - i1) * wz * wx / i2;
        dy[5] = (i1 - i2) * wx * wy / i3;
        Ok(())
    }
}

/// `y_i' = y_i²`: from `y_i(0) = 1` the solution `1/(1 − t)` blows up at t = 1.
struct BlowUp {
    dim: usize,
}

impl OdeSystem for BlowUp {
    type Error = Infallible;
    fn dim(&self) -> usize {
        self.dim
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        for (d, yi) in dy.iter_mut().zip(y) {
            *d = yi * yi;
        }
        Ok(())
    }
}

/// A right-hand side that fails from `t_fail` on, as the plant does when a wheel leaves the map.
struct LeavesTerrain {
    t_fail: f64,
}

#[derive(Debug, PartialEq)]
struct OffMap {
    wheel: usize,
}

impl fmt::Display for OffMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "wheel {} left the terrain map", self.wheel)
    }
}

impl OdeSystem for LeavesTerrain {
    type Error = OffMap;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), OffMap> {
        if t >= self.t_fail {
            return Err(OffMap { wheel: 2 });
        }
        dy[0] = y[1];
        dy[1] = -y[0];
        Ok(())
    }
}

// ---------------------------------------------------------------------------------------------
// The harness
// ---------------------------------------------------------------------------------------------

fn rk4(step: f64) -> IntegratorConfig {
    IntegratorConfig::Rk4(FixedStepConfig { step })
}

fn euler(step: f64) -> IntegratorConfig {
    IntegratorConfig::SemiImplicitEuler(FixedStepConfig { step })
}

fn dopri5(rtol: f64, atol: f64) -> IntegratorConfig {
    IntegratorConfig::Dopri5(AdaptiveConfig {
        rtol,
        atol,
        ..AdaptiveConfig::default()
    })
}

fn bdf(rtol: f64, atol: f64) -> IntegratorConfig {
    IntegratorConfig::Bdf(BdfConfig {
        rtol,
        atol: Some(atol),
        ..BdfConfig::default()
    })
}

/// Every method with the accuracy it is run at, and the global error it is expected to reach
/// per unit time on a smooth problem whose solution and rates are O(1): fixed-step methods
/// from their order (`h^p`), adaptive ones 10× their tolerance (the local error per step is
/// held below the tolerance; a few dozen steps accumulate it).
fn every_method() -> Vec<(IntegratorConfig, f64)> {
    vec![
        (rk4(1e-2), 1e-8),
        (euler(1e-4), 1e-4),
        (dopri5(1e-8, 1e-10), 1e-7),
        (bdf(1e-7, 1e-10), 1e-6),
    ]
}

/// Runs `sys` from `(0, y0)` through the output times `targets`, checking after every call
/// that the time landed exactly on the target; returns the states at the targets and the stats.
fn run<S: OdeSystem>(
    config: &IntegratorConfig,
    sys: &mut S,
    y0: &[f64],
    targets: &[f64],
) -> (Vec<Vec<f64>>, Stats)
where
    S::Error: fmt::Debug,
{
    let mut integrator = config.build(y0.len()).unwrap();
    let (mut t, mut y) = (0.0, y0.to_vec());
    let mut states = Vec::new();
    for &target in targets {
        integrator
            .advance(sys, &mut t, &mut y, target)
            .unwrap_or_else(|e| panic!("{}: {e:?}", config.method()));
        assert_eq!(
            t.to_bits(),
            target.to_bits(),
            "{} missed {target}",
            config.method()
        );
        states.push(y.clone());
    }
    (states, integrator.stats())
}

/// Output times `dt, 2·dt, …, n·dt`, computed without accumulating roundoff.
fn outputs(dt: f64, n: usize) -> Vec<f64> {
    (1..=n).map(|i| i as f64 * dt).collect()
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

// ---------------------------------------------------------------------------------------------
// Accuracy against closed forms
// ---------------------------------------------------------------------------------------------

#[test]
fn every_method_solves_exponential_decay_within_its_expected_error() {
    let rates = vec![0.5, 1.0, 2.0];
    let y0 = [1.0, -2.0, 3.0];
    let amplitude = 3.0;
    let targets = outputs(0.1, 30);
    for (config, bound) in every_method() {
        let (states, _) = run(
            &config,
            &mut Decay {
                rates: rates.clone(),
            },
            &y0,
            &targets,
        );
        for (t, y) in targets.iter().zip(&states) {
            let exact: Vec<f64> = (0..3).map(|i| y0[i] * (-rates[i] * t).exp()).collect();
            let err = max_abs_diff(y, &exact) / amplitude;
            let allowed = bound * (1.0 + t);
            assert!(
                err < allowed,
                "{} at t = {t}: error {err:e}",
                config.method()
            );
        }
    }
}

#[test]
fn every_method_follows_the_harmonic_oscillator_closed_form() {
    let targets = outputs(0.25, 20);
    for (config, bound) in every_method() {
        let mut sys = Oscillator::new(2.0);
        let (states, _) = run(&config, &mut sys, &[1.0, 0.0], &targets);
        // Relative to the amplitude (|w| ≤ ω = 2); the phase error grows linearly in time.
        for (t, y) in targets.iter().zip(&states) {
            let err = max_abs_diff(y, &sys.exact(*t)) / 2.0;
            assert!(
                err < bound * (1.0 + t),
                "{} at t = {t}: error {err:e}",
                config.method()
            );
        }
    }
}

/// Global error at t = 5 of a fixed-step method with step h on the oscillator (ω = 2).
fn oscillator_error(config: IntegratorConfig) -> f64 {
    let mut sys = Oscillator::new(2.0);
    let (states, _) = run(&config, &mut sys, &[1.0, 0.0], &[5.0]);
    max_abs_diff(&states[0], &sys.exact(5.0))
}

#[test]
fn rk4_converges_with_order_four_and_semi_implicit_euler_with_order_one() {
    for (make, h, order) in [
        (rk4 as fn(f64) -> IntegratorConfig, 0.02, 4.0),
        (euler as fn(f64) -> IntegratorConfig, 0.002, 1.0),
    ] {
        let errors: Vec<f64> = [h, h / 2.0, h / 4.0]
            .iter()
            .map(|&step| oscillator_error(make(step)))
            .collect();
        for pair in errors.windows(2) {
            let observed = (pair[0] / pair[1]).log2();
            assert!(
                (observed - order).abs() < 0.1,
                "{}: observed order {observed} from errors {errors:?}",
                make(h).method()
            );
        }
    }
}

#[test]
fn semi_implicit_euler_keeps_the_oscillator_energy_bounded_over_long_runs() {
    // h·ω = 0.13: 10 000 steps are about 200 periods.
    let (omega, h) = (1.3, 0.1);
    let mut sys = Oscillator::new(omega);
    let targets = outputs(h, 10_000);
    let (states, _) = run(&euler(h), &mut sys, &[1.0, 0.2], &targets);
    let e0 = sys.energy(&[1.0, 0.2]);
    // Symplectic Euler conserves the modified energy w² + ω²x² − h·ω²·x·w exactly (up to
    // roundoff), so the energy error is bounded by O(h·ω) and does not drift.
    let modified = |y: &[f64]| y[1] * y[1] + omega * omega * y[0] * (y[0] - h * y[1]);
    let m0 = modified(&[1.0, 0.2]);
    let mut first = 0.0f64;
    let mut last = 0.0f64;
    for (i, y) in states.iter().enumerate() {
        assert!(
            (modified(y) - m0).abs() < 1e-12 * m0,
            "step {i}: {}",
            modified(y)
        );
        let rel = (sys.energy(y) - e0).abs() / e0;
        assert!(rel < h * omega, "step {i}: relative energy error {rel}");
        if i < 1000 {
            first = first.max(rel);
        } else if i >= 9000 {
            last = last.max(rel);
        }
    }
    assert!(last < 1.01 * first, "energy error grew: {first} → {last}");
    // RK4 at the same step loses energy steadily instead (its error is tiny but one-signed).
    let (rk, _) = run(&rk4(h), &mut Oscillator::new(omega), &[1.0, 0.2], &targets);
    let rk_end = sys.energy(rk.last().unwrap());
    assert!(rk_end < e0 * (1.0 - 1e-6), "rk4 energy {rk_end} vs {e0}");
}

#[test]
fn semi_implicit_euler_uses_the_systems_position_rates_when_it_has_them() {
    let targets = outputs(0.1, 10);
    let (by_rhs, stats_rhs) = run(
        &euler(0.01),
        &mut Oscillator::new(2.0),
        &[1.0, 0.0],
        &targets,
    );
    let mut sys = Oscillator::new(2.0);
    sys.own_position_rates = true;
    let (by_rates, stats_rates) = run(&euler(0.01), &mut sys, &[1.0, 0.0], &targets);
    assert_eq!(by_rhs, by_rates);
    assert_eq!(sys.position_rate_calls, 100);
    assert_eq!((stats_rhs.steps, stats_rates.rhs_evals), (100, 200));
}

// ---------------------------------------------------------------------------------------------
// Stiff problems
// ---------------------------------------------------------------------------------------------

#[test]
fn bdf_takes_far_fewer_steps_than_dopri5_on_a_stiff_problem() {
    let targets = outputs(1.0, 10);
    let mut stats = Vec::new();
    for config in [dopri5(1e-6, 1e-9), bdf(1e-6, 1e-9)] {
        let (states, s) = run(&config, &mut StiffLinear, &[2.0, 0.0], &targets);
        for (t, y) in targets.iter().zip(&states) {
            let err = max_abs_diff(y, &StiffLinear::exact(*t));
            assert!(err < 1e-5, "{} at t = {t}: error {err:e}", config.method());
        }
        stats.push(s);
    }
    let (explicit, implicit) = (stats[0], stats[1]);
    // dopri5 is held to h ≲ 3.3/1000 by stability: about 3000 steps for 10 s.
    assert!(explicit.steps > 2500, "{explicit:?}");
    assert!(
        10 * implicit.steps < explicit.steps,
        "{implicit:?} vs {explicit:?}"
    );
    // The work, pinned: a change here is a change of algorithm (re-bless deliberately).
    insta::assert_debug_snapshot!((explicit, implicit), @"
    (
        Stats {
            steps: 3057,
            rejected_steps: 10,
            rhs_evals: 18404,
            jacobian_evals: 0,
            lu_decompositions: 0,
        },
        Stats {
            steps: 194,
            rejected_steps: 0,
            rhs_evals: 438,
            jacobian_evals: 1,
            lu_decompositions: 34,
        },
    )
    ");
}

#[test]
fn bdf_uses_the_systems_exact_jacobian_when_it_has_one() {
    let targets = outputs(1.0, 10);
    let mut sys = StiffLinearExact { jacobian_calls: 0 };
    let (states, stats) = run(&bdf(1e-6, 1e-9), &mut sys, &[2.0, 0.0], &targets);
    for (t, y) in targets.iter().zip(&states) {
        assert!(max_abs_diff(y, &StiffLinear::exact(*t)) < 1e-5, "t = {t}");
    }
    assert!(sys.jacobian_calls >= 1);
    assert_eq!(sys.jacobian_calls, stats.jacobian_evals);
    // No finite differences: per step at most one predictor and a few Newton evaluations.
    let (_, by_differences) = run(&bdf(1e-6, 1e-9), &mut StiffLinear, &[2.0, 0.0], &targets);
    assert!(stats.rhs_evals + 2 * stats.jacobian_evals <= by_differences.rhs_evals + 2);
}

#[test]
fn bdf_solves_robertson_like_a_tight_explicit_reference() {
    let targets = [0.4, 4.0, 40.0];
    let y0 = [1.0, 0.0, 0.0];
    let (reference, _) = run(&dopri5(1e-10, 1e-14), &mut Robertson, &y0, &targets);
    // The classical values at t = 40 (Hairer & Wanner II, §IV.1), to the 4–5 digits quoted:
    // y(40) ≈ (0.7158, 9.1855e-6, 0.2842).
    let at_40 = &reference[2];
    assert!((at_40[0] - 0.7158).abs() < 5e-5 && (at_40[2] - 0.2842).abs() < 5e-5);
    assert!((at_40[1] - 9.1855e-6).abs() < 5e-11, "{at_40:?}");
    let (states, stats) = run(&bdf(1e-6, 1e-10), &mut Robertson, &y0, &targets);
    for (y, r) in states.iter().zip(&reference) {
        for i in 0..3 {
            let tol = 1e-5 * r[i].abs() + 1e-9;
            assert!(
                (y[i] - r[i]).abs() < tol,
                "component {i}: {} vs {}",
                y[i],
                r[i]
            );
        }
        assert!((y.iter().sum::<f64>() - 1.0).abs() < 1e-12, "mass {y:?}");
    }
    assert!(stats.steps < 1000, "{stats:?}");
}

/// Keeping the Newton matrix's LU factors while the step changes by less than 30 % (the
/// default `lu_band`) gives Robertson's solution to the same tolerance as factoring at every
/// change (`lu_band = 0`), with fewer factorizations.
#[test]
fn bdf_reuses_its_lu_factors_across_small_step_changes() {
    let targets = [0.4, 4.0, 40.0];
    let y0 = [1.0, 0.0, 0.0];
    let (reference, _) = run(&dopri5(1e-10, 1e-14), &mut Robertson, &y0, &targets);
    let with_band = |lu_band: f64| {
        IntegratorConfig::Bdf(BdfConfig {
            rtol: 1e-6,
            atol: Some(1e-10),
            lu_band,
            ..BdfConfig::default()
        })
    };
    let (fresh, fresh_stats) = run(&with_band(0.0), &mut Robertson, &y0, &targets);
    let (reused, reused_stats) = run(&with_band(0.3), &mut Robertson, &y0, &targets);
    for ((a, b), r) in fresh.iter().zip(&reused).zip(&reference) {
        for i in 0..3 {
            let tol = 1e-5 * r[i].abs() + 1e-9;
            assert!(
                (a[i] - r[i]).abs() < tol,
                "fresh LU, {i}: {} vs {}",
                a[i],
                r[i]
            );
            assert!(
                (b[i] - r[i]).abs() < tol,
                "kept LU, {i}: {} vs {}",
                b[i],
                r[i]
            );
        }
        assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12, "mass {b:?}");
    }
    assert!(
        reused_stats.lu_decompositions < fresh_stats.lu_decompositions,
        "kept {reused_stats:?}, fresh {fresh_stats:?}"
    );
}

/// A position far from the origin moving at a decaying speed, `x' = v`, `v' = −v`:
/// `x = x0 + v0·(1 − e^(−t))`. Its error scale holds the position to its absolute tolerance
/// alone (its size, 1e6 m, means nothing) and the speed relative to its size.
struct FarTraveller {
    /// Whether the system gives its error scale.
    scaled: bool,
}

impl OdeSystem for FarTraveller {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        dy[0] = y[1];
        dy[1] = -y[1];
        Ok(())
    }
    fn error_scale(&self, scale: &mut [f64], relative: &mut [f64]) -> bool {
        if self.scaled {
            scale.copy_from_slice(&[1e-3, 1e-2]);
            relative.copy_from_slice(&[0.0, 1.0]);
        }
        self.scaled
    }
}

/// Without `atol`, BDF holds each component to `rtol·(scale_i + relative_i·|y_i|)`: the
/// position 1e6 m from the origin to its scale in metres, not to 1e-4 of a million metres.
#[test]
fn bdf_holds_each_component_to_the_systems_error_scale() {
    let (x0, v0, t_end) = (1e6, 1.0, 5.0_f64);
    let config = BdfConfig {
        rtol: 1e-4,
        ..BdfConfig::default()
    };
    let exact = x0 + v0 * (1.0 - (-t_end).exp());
    let mut errors = Vec::new();
    for scaled in [true, false] {
        let mut bdf = Bdf::new(2, &config).unwrap();
        let (mut t, mut y) = (0.0, [x0, v0]);
        bdf.advance(&mut FarTraveller { scaled }, &mut t, &mut y, t_end)
            .unwrap();
        let atol = bdf.absolute_tolerances();
        if scaled {
            assert_eq!(atol, [1e-4 * 1e-3, 1e-4 * 1e-2]);
        } else {
            assert_eq!(atol, [1e-4 * 1e-5; 2]);
        }
        errors.push((y[0] - exact).abs());
    }
    // Held to 1e-7 m a step over a few dozen steps; with the relative tolerance alone (1e-4
    // of 1e6 m) only the speed's error control holds the position.
    assert!(errors[0] < 1e-6, "{errors:?}");
    assert!(errors[1] > 10.0 * errors[0], "{errors:?}");
    // An explicit atol means what it says, for every component.
    let mut bdf = Bdf::new(
        2,
        &BdfConfig {
            atol: Some(1e-7),
            ..config
        },
    )
    .unwrap();
    let (mut t, mut y) = (0.0, [x0, v0]);
    bdf.advance(&mut FarTraveller { scaled: true }, &mut t, &mut y, 1.0)
        .unwrap();
    assert_eq!(bdf.absolute_tolerances(), [1e-7; 2]);
}

/// Output instants passed by interpolation give the solution to the same tolerance as
/// landing on each, with fewer steps, and every call still ends on its target.
#[test]
fn bdf_interpolates_output_instants_it_steps_past() {
    let targets = outputs(0.05, 200);
    let config = IntegratorConfig::Bdf(BdfConfig {
        rtol: 1e-6,
        atol: Some(1e-9),
        ..BdfConfig::default()
    });
    let mut landed = config.build(2).unwrap();
    let mut passed = config.build(2).unwrap();
    let (mut t1, mut y1) = (0.0, vec![2.0, 0.0]);
    let (mut t2, mut y2) = (0.0, vec![2.0, 0.0]);
    for &target in &targets {
        landed
            .advance(&mut StiffLinear, &mut t1, &mut y1, target)
            .unwrap();
        passed
            .advance_output(&mut StiffLinear, &mut t2, &mut y2, target, f64::INFINITY)
            .unwrap();
        assert_eq!(t2.to_bits(), target.to_bits());
        let exact = StiffLinear::exact(target);
        assert!(max_abs_diff(&y1, &exact) < 1e-5, "landed at {target}");
        assert!(
            max_abs_diff(&y2, &exact) < 1e-5,
            "passed at {target}: {y2:?}"
        );
    }
    let (a, b) = (landed.stats(), passed.stats());
    assert!(
        b.steps < a.steps && 2 * b.lu_decompositions < a.lu_decompositions,
        "passed {b:?}, landed {a:?}"
    );
    // A limit before the next step's end makes it land, as `advance` does.
    let mut limited = config.build(2).unwrap();
    let (mut t, mut y) = (0.0, vec![2.0, 0.0]);
    for &target in &targets {
        limited
            .advance_output(&mut StiffLinear, &mut t, &mut y, target, target)
            .unwrap();
    }
    assert_eq!(limited.stats(), a);
    assert_eq!(y, y1);
}

/// Van der Pol's oscillator at μ = 1000 (Hairer & Wanner II, §IV.1), a stiff limit cycle
/// whose steps change all the time: the same end state with and without reusing the LU.
#[test]
fn bdf_keeps_van_der_pol_with_kept_lu_factors() {
    struct VanDerPol;
    impl OdeSystem for VanDerPol {
        type Error = Infallible;
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
            dy[0] = y[1];
            dy[1] = 1000.0 * ((1.0 - y[0] * y[0]) * y[1]) - y[0];
            Ok(())
        }
    }
    let targets = outputs(300.0, 10);
    let y0 = [2.0, 0.0];
    let config = |lu_band: f64| {
        IntegratorConfig::Bdf(BdfConfig {
            rtol: 1e-8,
            atol: Some(1e-10),
            lu_band,
            ..BdfConfig::default()
        })
    };
    let (fresh, fresh_stats) = run(&config(0.0), &mut VanDerPol, &y0, &targets);
    let (reused, reused_stats) = run(&config(0.3), &mut VanDerPol, &y0, &targets);
    for (a, b) in fresh.iter().zip(&reused) {
        // x stays within [−2, 2]; 1e-4 is ~1000 times the tolerance, far below the cycle's scale.
        assert!((a[0] - b[0]).abs() < 1e-4, "{a:?} vs {b:?}");
    }
    assert!(
        reused_stats.lu_decompositions < fresh_stats.lu_decompositions,
        "kept {reused_stats:?}, fresh {fresh_stats:?}"
    );
}

// ---------------------------------------------------------------------------------------------
// Rigid body: conservation and agreement between methods
// ---------------------------------------------------------------------------------------------

#[test]
fn every_method_conserves_the_torque_free_rigid_body_invariants() {
    let targets = outputs(0.5, 20);
    for (config, bound) in every_method() {
        let (mut body, y0) = RigidBody::paper_body();
        let (states, _) = run(&config, &mut body, &y0, &targets);
        let (e0, l0) = (body.energy(&y0), body.inertial_momentum(&y0));
        let norm0 = l0.iter().map(|v| v * v).sum::<f64>().sqrt();
        for (t, y) in targets.iter().zip(&states) {
            let de = (body.energy(y) - e0).abs() / e0;
            let l = body.inertial_momentum(y);
            let dl = max_abs_diff(&l, &l0) / norm0;
            let norm = body
                .body_momentum(y)
                .iter()
                .map(|v| v * v)
                .sum::<f64>()
                .sqrt();
            let dnorm = (norm - norm0).abs() / norm0;
            // Errors grow with the turns made, like the oscillator's phase.
            let allowed = bound * (1.0 + t);
            assert!(
                de < allowed && dl < allowed && dnorm < allowed,
                "{} at t = {t}: ΔT/T {de:e}, ΔL/|L| {dl:e}, Δ|L|/|L| {dnorm:e}",
                config.method()
            );
        }
    }
}

#[test]
fn the_integrators_agree_with_each_other_on_a_smooth_run() {
    let targets = outputs(0.5, 20);
    let (mut body, y0) = RigidBody::paper_body();
    let (reference, _) = run(&dopri5(1e-12, 1e-14), &mut body, &y0, &targets);
    for (config, bound) in every_method() {
        let (states, _) = run(&config, &mut body, &y0, &targets);
        for ((t, y), r) in targets.iter().zip(&states).zip(&reference) {
            let err = max_abs_diff(y, r);
            assert!(
                err < bound * (1.0 + t),
                "{} at t = {t}: differs from the reference by {err:e}",
                config.method()
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Landing on targets, step-size memory, restarts
// ---------------------------------------------------------------------------------------------

#[test]
fn every_method_lands_exactly_on_irregular_targets() {
    let targets = [1e-9, 0.013, 0.1, 0.1000001, 0.37, 0.37, 1.0, 2.71];
    for (config, _) in every_method() {
        // `run` asserts bit-exact landing after each call; here also check the state.
        let (states, _) = run(&config, &mut Oscillator::new(2.0), &[1.0, 0.0], &targets);
        let last = states.last().unwrap();
        let exact = Oscillator::new(2.0).exact(2.71);
        assert!(max_abs_diff(last, &exact) < 1e-2, "{}", config.method());
    }
}

#[test]
fn fixed_step_methods_take_no_sliver_steps_between_regular_outputs() {
    // 0.1 is not a multiple of 0.01 in binary; 100 steps, not 100 + slivers.
    for config in [rk4(0.01), euler(0.01)] {
        let (_, stats) = run(
            &config,
            &mut Oscillator::new(2.0),
            &[1.0, 0.0],
            &outputs(0.1, 10),
        );
        assert_eq!(stats.steps, 100, "{}", config.method());
    }
}

#[test]
fn adaptive_methods_keep_their_step_size_across_calls() {
    for config in [dopri5(1e-8, 1e-10), bdf(1e-7, 1e-10)] {
        let (_, one_call) = run(&config, &mut Oscillator::new(2.0), &[1.0, 0.0], &[10.0]);
        let (_, many_calls) = run(
            &config,
            &mut Oscillator::new(2.0),
            &[1.0, 0.0],
            &outputs(0.1, 100),
        );
        // Landing on 100 targets shortens up to 100 steps; restarting from scratch at each
        // target would cost far more (dopri5: a new starting step; bdf: order 1 again).
        assert!(
            many_calls.steps < one_call.steps + 110,
            "{}: {one_call:?} vs {many_calls:?}",
            config.method()
        );
        // Continuing a run reuses f(t, y): the evaluations of dopri5 are 6 per attempt plus
        // the initial evaluation and the starting-step one.
        if config.method() == "dopri5" {
            let attempts = many_calls.steps + many_calls.rejected_steps;
            assert_eq!(many_calls.rhs_evals, 6 * attempts + 2, "{many_calls:?}");
        }
    }
}

#[test]
fn a_state_changed_between_calls_or_a_restart_is_not_integrated_with_stale_history() {
    for (config, bound) in every_method() {
        let mut sys = Decay {
            rates: vec![1.0, 3.0],
        };
        let mut integrator = config.build(2).unwrap();
        let (mut t, mut y) = (0.0, vec![1.0, 1.0]);
        integrator.advance(&mut sys, &mut t, &mut y, 1.0).unwrap();
        // An impulse: the state jumps; the integrator must notice.
        y[0] += 1.0;
        let jumped = y.clone();
        integrator.advance(&mut sys, &mut t, &mut y, 2.0).unwrap();
        let exact = [jumped[0] * (-1.0f64).exp(), jumped[1] * (-3.0f64).exp()];
        assert!(
            max_abs_diff(&y, &exact) < bound,
            "{}: {y:?}",
            config.method()
        );
        // A new control value: the right-hand side changes; the caller says so.
        sys.rates = vec![2.0, 0.5];
        integrator.restart();
        let before = y.clone();
        integrator.advance(&mut sys, &mut t, &mut y, 3.0).unwrap();
        let exact = [before[0] * (-2.0f64).exp(), before[1] * (-0.5f64).exp()];
        assert!(
            max_abs_diff(&y, &exact) < bound,
            "{}: {y:?}",
            config.method()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------------

#[test]
fn a_failing_right_hand_side_stops_the_run_with_its_time() {
    for (config, _) in every_method() {
        let mut sys = LeavesTerrain { t_fail: 0.52 };
        let mut integrator = config.build(2).unwrap();
        let (mut t, mut y) = (0.0, vec![1.0, 0.0]);
        let err = integrator
            .advance(&mut sys, &mut t, &mut y, 1.0)
            .unwrap_err();
        let IntegrateError::Rhs { t: t_err, source } = &err else {
            panic!("{}: {err:?}", config.method());
        };
        assert_eq!(*source, OffMap { wheel: 2 });
        assert!(
            *t_err >= 0.52 && *t_err < 0.6,
            "{}: t = {t_err}",
            config.method()
        );
        // The caller keeps the last accepted step, which ends before the failing evaluation.
        assert!(t <= *t_err && t > 0.4, "{}: t = {t}", config.method());
        assert!(y.iter().all(|v| v.is_finite()));
    }
    let mut integrator = rk4(0.1).build(2).unwrap();
    let (mut t, mut y) = (0.0, vec![1.0, 0.0]);
    let err = integrator
        .advance(&mut LeavesTerrain { t_fail: 0.52 }, &mut t, &mut y, 1.0)
        .unwrap_err();
    assert_eq!(t, 0.5);
    assert_eq!(
        err.to_string(),
        "right-hand side failed at t = 0.55 s: wheel 2 left the terrain map"
    );
    assert_eq!(err.time(), Some(0.55));
}

#[test]
fn a_collapsing_step_size_stops_the_run_naming_time_and_step() {
    let min_step = 1e-7;
    let adaptive = [
        IntegratorConfig::Dopri5(AdaptiveConfig {
            min_step,
            ..AdaptiveConfig::default()
        }),
        IntegratorConfig::Bdf(BdfConfig {
            rtol: 1e-6,
            atol: Some(1e-9),
            min_step,
            ..BdfConfig::default()
        }),
    ];
    for config in adaptive {
        let mut integrator = config.build(1).unwrap();
        let (mut t, mut y) = (0.0, vec![1.0]);
        let err = integrator
            .advance(&mut BlowUp { dim: 1 }, &mut t, &mut y, 2.0)
            .unwrap_err();
        let IntegrateError::StepTooSmall {
            t: t_err,
            h,
            min_step: m,
        } = err
        else {
            panic!("{}: {err:?}", config.method());
        };
        assert!(
            (t_err - 1.0).abs() < 1e-3 && h < m && m == min_step,
            "{err:?}"
        );
        assert_eq!(t, t_err);
        let message = err.to_string();
        assert!(
            message.starts_with(&format!(
                "step size {h:e} s at t = {t_err} s is below the minimum step 1e-7 s"
            )),
            "{message}"
        );
    }
}

#[test]
fn too_many_steps_stops_the_run_where_it_got_to() {
    let config = IntegratorConfig::Dopri5(AdaptiveConfig {
        max_steps: 5,
        ..AdaptiveConfig::default()
    });
    let mut integrator = config.build(2).unwrap();
    let (mut t, mut y) = (0.0, vec![1.0, 0.0]);
    let err = integrator
        .advance(&mut Oscillator::new(2.0), &mut t, &mut y, 100.0)
        .unwrap_err();
    assert!(matches!(
        err,
        IntegrateError::TooManySteps {
            max_steps: 5,
            t_target: 100.0,
            ..
        }
    ));
    assert!(t > 0.0 && t < 100.0);
    assert_eq!(
        err.to_string(),
        format!(
            "5 step attempts reached only t = {t} s on the way to 100 s: raise `max_steps`, \
             raise `max_step` if it is set (no step is longer), or loosen the tolerances; with \
             an explicit method, `[integrator.bdf]` takes stiff contact in larger steps"
        )
    );
}

#[test]
fn a_diverging_state_names_the_component_and_time() {
    // RK4 with a far too long step on y' = y² (second component only; the first stays 0).
    let mut integrator = rk4(0.5).build(2).unwrap();
    let (mut t, mut y) = (0.0, vec![0.0, 1.0]);
    let err = integrator
        .advance(&mut BlowUp { dim: 2 }, &mut t, &mut y, 100.0)
        .unwrap_err();
    let IntegrateError::NonFinite {
        t: t_err,
        component,
        value,
    } = err
    else {
        panic!("{err:?}");
    };
    assert_eq!(component, 1);
    assert!(!value.is_finite());
    assert!(t_err > 0.5 && t_err < 100.0);
    assert_eq!(
        err.to_string(),
        format!("state component 1 is {value} at t = {t_err} s: the run diverged")
    );
    // A non-finite initial state is caught before any step.
    let err = integrator
        .advance(&mut BlowUp { dim: 2 }, &mut 0.0, &mut [f64::NAN, 0.0], 1.0)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "state component 0 is NaN at t = 0 s: the run diverged"
    );
}

#[test]
fn bad_calls_are_reported_not_panicked_on() {
    let mut integrator = dopri5(1e-6, 1e-9).build(2).unwrap();
    let err = integrator
        .advance(&mut Oscillator::new(1.0), &mut 1.0, &mut [1.0, 0.0], 0.5)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "target time 0.5 s is not a finite time at or after the current time 1 s \
         (integration runs forward only)"
    );
    let err = integrator
        .advance(&mut BlowUp { dim: 3 }, &mut 0.0, &mut [1.0, 0.0, 0.0], 1.0)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "the integrator was built for dimension 2, but the system has dimension 3 and the \
         state vector length 3"
    );
    /// Declares more positions than it has entries.
    struct BadSplit;
    impl OdeSystem for BadSplit {
        type Error = Infallible;
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, _y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
            dy.fill(0.0);
            Ok(())
        }
        fn split(&self) -> usize {
            3
        }
    }
    let err = euler(0.1)
        .build(2)
        .unwrap()
        .advance(&mut BadSplit, &mut 0.0, &mut [0.0, 0.0], 1.0)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "the system declares 3 position entries but has dimension 2: `split` must be at \
         most `dim`"
    );
    // t_target == t: nothing to do, no evaluation.
    let mut y = [1.0, 0.0];
    integrator
        .advance(&mut Oscillator::new(1.0), &mut 0.25, &mut y, 0.25)
        .unwrap();
    assert_eq!((y, integrator.stats().rhs_evals), ([1.0, 0.0], 0));
}

// ---------------------------------------------------------------------------------------------
// Configuration from a scenario file
// ---------------------------------------------------------------------------------------------

fn parse(toml_text: &str) -> Result<IntegratorConfig, String> {
    toml::from_str(toml_text).map_err(|e| e.to_string())
}

#[test]
fn configs_parse_from_toml_with_defaults() {
    assert_eq!(parse("[rk4]\nstep = 1e-3"), Ok(rk4(1e-3)));
    assert_eq!(parse("[semi_implicit_euler]\nstep = 5e-4"), Ok(euler(5e-4)));
    assert_eq!(
        parse("[dopri5]\nrtol = 1e-8\nmax_step = 0.01"),
        Ok(IntegratorConfig::Dopri5(AdaptiveConfig {
            rtol: 1e-8,
            max_step: 0.01,
            ..AdaptiveConfig::default()
        }))
    );
    assert_eq!(
        parse("[dopri5]"),
        Ok(IntegratorConfig::Dopri5(AdaptiveConfig::default()))
    );
    let IntegratorConfig::Bdf(b) = parse("[bdf]\nmax_order = 2\nndf = false").unwrap() else {
        panic!()
    };
    assert_eq!(
        (b.max_order, b.ndf, b.rtol, b.atol, b.max_step, b.lu_band),
        (2, false, BDF_DEFAULT_RTOL, None, f64::INFINITY, 0.3)
    );
}

#[test]
fn unknown_keys_and_methods_are_rejected() {
    let err = parse("[dopri5]\nrtl = 1e-6").unwrap_err();
    assert!(
        err.contains("unknown field `rtl`, expected one of `rtol`"),
        "{err}"
    );
    let err = parse("[rk4]\nstep = 1e-3\nsteps = 2").unwrap_err();
    assert!(err.contains("unknown field `steps`"), "{err}");
    let err = parse("[rk45]\nstep = 1e-3").unwrap_err();
    assert!(err.contains("unknown variant `rk45`"), "{err}");
}

#[test]
fn out_of_range_settings_get_a_message_naming_method_field_value_and_fix() {
    let bad = |text: &str| parse(text).unwrap().build(4).unwrap_err().to_string();
    assert_eq!(
        bad("[rk4]\nstep = 0"),
        "integrator `rk4`: `step` must be a positive, finite time step in seconds, got 0; \
         the real-time path typically uses 1e-4 to 1e-3 s"
    );
    assert_eq!(
        bad("[dopri5]\nrtol = -1e-6"),
        "integrator `dopri5`: `rtol` must be in [1e-14, 1), got -1e-6; relative tolerances \
         are typically 1e-3 (quick look) to 1e-8 (reference runs)"
    );
    assert_eq!(
        bad("[bdf]\nmax_order = 6"),
        "integrator `bdf`: `max_order` must be 1, 2, 3, 4 or 5, got 6; 5 is the default \
         (as ode15s); 2 is the highest A-stable order"
    );
    assert_eq!(
        bad("[bdf]\natol = 0.0"),
        "integrator `bdf`: `atol` must be a positive, finite number, got 0; it is in the \
         state's SI units (m, rad, m/s, rad/s); 1e-9 suits a rover"
    );
    assert_eq!(
        bad("[dopri5]\nmin_step = 0.1\nmax_step = 0.01"),
        "integrator `dopri5`: `min_step` must be a finite number of seconds, ≥ 0 and below \
         `max_step`, got 0.1; the default 1e-10 s stops a run whose steps collapse"
    );
    assert_eq!(
        bad("[semi_implicit_euler]\nstep = nan"),
        "integrator `semi_implicit_euler`: `step` must be a positive, finite time step in \
         seconds, got NaN; the real-time path typically uses 1e-4 to 1e-3 s"
    );
}

/// `y' = −k·y + ε·u(y)`, with `u ∈ [−1, 1]` a deterministic hash of y's bits: a stiff
/// system at rest whose right-hand side carries rounding-level noise that does not shrink
/// from one Newton iteration to the next (like a contact search's located crossings).
struct NoisyRest {
    k: f64,
    eps: f64,
}

impl OdeSystem for NoisyRest {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        let mut h = 0x9e37_79b9_7f4a_7c15_u64;
        for v in y {
            h = (h ^ v.to_bits()).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            h ^= h >> 31;
        }
        let u = (h >> 11) as f64 / (1u64 << 52) as f64 - 1.0;
        for (d, v) in dy.iter_mut().zip(y) {
            *d = -self.k * v + self.eps * u;
        }
        Ok(())
    }
}

#[test]
fn bdf_rests_on_a_noisy_equilibrium_without_collapsing_its_step() {
    // Noise 1e-6 against atol 1e-8: Newton corrections near the rest point are the noise
    // itself, whose "rate" of decrease is about 1 at every step size. They are below the
    // Newton tolerance once the step is small enough, and must be accepted there.
    let mut sys = NoisyRest { k: 1e3, eps: 1e-6 };
    let config = bdf(1e-6, 1e-8);
    let (states, stats) = run(&config, &mut sys, &[0.0, 0.0], &outputs(1.0, 200));
    let last = states.last().unwrap();
    // The equilibrium is |y| ≤ ε/k, give or take the integration error.
    assert!(
        last.iter().all(|v| v.abs() < 1e-8),
        "{last:?} after {} steps",
        stats.steps
    );
}

/// Decay that logs, in order, every time it is evaluated at (`false`) and
/// every step its integrator says it accepted and builds on (`true`).
struct Recording {
    decay: Decay,
    log: Vec<(f64, bool)>,
}

impl OdeSystem for Recording {
    type Error = Infallible;
    fn dim(&self) -> usize {
        self.decay.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        self.log.push((t, false));
        self.decay.rhs(t, y, dy)
    }
    fn step_accepted(&mut self, t: f64, _y: &[f64]) {
        self.log.push((t, true));
    }
}

/// Every method reports the steps it builds on in increasing time, and
/// never evaluates the system before the last one it reported: a system
/// with memory (the ground's ruts) may change what lies behind it. The
/// fixed-step methods and dopri5 report every step; BDF every step but
/// its landings on an output instant, from which the next step does not
/// start.
#[test]
fn every_method_reports_the_steps_it_builds_on_in_time_order() {
    let ros2 = IntegratorConfig::Ros2(rover_integrate::Ros2Config {
        step: 1e-3,
        jacobian_every: 1,
        jacobian: Default::default(),
    });
    for config in every_method().into_iter().map(|(c, _)| c).chain([ros2]) {
        let mut sys = Recording {
            decay: Decay {
                rates: vec![1.0, 30.0],
            },
            log: Vec::new(),
        };
        // Output instants a step rarely divides, so that BDF lands on them.
        let (_, stats) = run(&config, &mut sys, &[1.0, 1.0], &outputs(0.0137, 60));
        let name = config.method();
        let accepted: Vec<f64> = sys.log.iter().filter(|e| e.1).map(|e| e.0).collect();
        assert!(!accepted.is_empty(), "{name}");
        assert!(
            accepted.windows(2).all(|w| w[0] < w[1]),
            "{name}: steps reported out of order"
        );
        if name == "bdf" {
            assert!(
                (accepted.len() as u64) < stats.steps,
                "{name}: no landing left out"
            );
        } else {
            assert_eq!(accepted.len() as u64, stats.steps, "{name}");
        }
        let mut reported = f64::NEG_INFINITY;
        for &(t, step) in &sys.log {
            if step {
                reported = t;
            } else {
                assert!(
                    t >= reported,
                    "{name}: evaluated at {t} after reporting {reported}"
                );
            }
        }
    }
}
