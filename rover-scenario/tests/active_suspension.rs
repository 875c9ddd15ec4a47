//! The leveling law of the active suspension (MODEL.md §8) on Example 2:
//! it levels a constant slope with its arms off their stops, its sampled
//! closed loop about the static equilibrium is stable (the linearization's
//! A and B with the law's update), and it is refused where it cannot run.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rover_scenario::prepare::Prepared;

/// Attitude and arm angles at the end of a run: (roll, pitch) in degrees,
/// y1..y4 in radians.
fn run(toml: &str) -> ((f64, f64), Vec<f64>) {
    let prepared = Prepared::from_text(Some("swing4"), toml, Path::new("t.toml"), Path::new("."))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut csv = Vec::new();
    let summary = prepared
        .run(true, &mut csv, &AtomicBool::new(false), |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(summary.complete, "{:?}", summary.error);
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let last: Vec<f64> = lines
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let col = |n: &str| last[header.iter().position(|h| *h == n).unwrap()];
    (
        (col("phi").to_degrees(), col("theta").to_degrees()),
        (1..=4).map(|i| col(&format!("y{i}"))).collect(),
    )
}

/// On a 6° slope climbing towards 30° from the heading (pitch and roll
/// both), held still by a PI speed loop, the leveling law brings the body
/// level to < 0.1° within 30 s with every arm off its stops; passive, the
/// body takes most of the slope.
#[test]
fn leveling_law_levels_a_constant_slope_with_arms_off_their_stops() {
    let base = "duration = 32.0\nsettle = 2.0\noutput_rate = 10.0\n\
                [terrain]\nkind = \"slope\"\nangle_deg = 6.0\ndirection_deg = 30.0\n\
                [control.speed]\nspeed = 0.0\nkp = 10.0\nki = 20.0\n\
                [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n";
    let ((roll_p, pitch_p), _) = run(base);
    assert!(
        roll_p.abs() > 2.0 && pitch_p.abs() > 2.0,
        "passive: roll {roll_p}°, pitch {pitch_p}°"
    );
    let ((roll, pitch), y) = run(&format!(
        "{base}[control.active_suspension]\nlaw = \"leveling\"\n"
    ));
    assert!(
        roll.abs() < 0.1 && pitch.abs() < 0.1,
        "leveling: roll {roll}°, pitch {pitch}° (passive {roll_p}°, {pitch_p}°)"
    );
    let travel = [(-60.0, -2.0), (-60.0, -2.0), (2.0, 60.0), (2.0, 60.0)];
    for (i, (v, (lo, hi))) in y.iter().zip(travel).enumerate() {
        let d = v.to_degrees();
        assert!(
            d > lo + 1.0 && d < hi - 1.0,
            "arm y{} at {d}° is on (or within 1° of) a stop [{lo}, {hi}]°",
            i + 1
        );
    }
}

/// The sampled closed loop of the leveling law about Example 2's static
/// equilibrium. With A, B from the linearization (B's columns for the spring
/// neutrals), Φ = e^{AT}, Γ = ∫₀ᵀ e^{As} ds·B over one update T, and the
/// law's update `u_k = u_{k−1} + L·x_k + M·u_{k−1}` (probed from the law
/// itself, which is affine), the state [x_k; u_{k−1}] evolves by
/// `[[Φ + ΓL, Γ(I + M)], [L, I + M]]`. Returns the largest |λ| of that
/// matrix over the eigenvalues the law moves (those of Φ at |λ| ≈ 1, the
/// free rolling and the horizontal position and heading, stay), and the
/// number of eigenvalues left at |λ| ≥ 1 that Φ does not have.
fn closed_loop(extra: &str) -> (f64, usize) {
    use nalgebra::DMatrix;
    use rover_runtime::control::{ActiveSuspension, ActiveSuspensionConfig};
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let model = spec.model;
    let lin = rover_scenario::linearize::linearize(&model, rover_models::plant("swing4").unwrap())
        .unwrap();
    let m = model.m();
    let n = lin.a.len();
    assert_eq!(n, 2 * (6 + m), "states {:?}", lin.states);
    let config: ActiveSuspensionConfig =
        toml::from_str(&format!("law = \"leveling\"\n{extra}")).unwrap();
    let t = config.sample_time;
    let y_eq = rover_runtime::quasi_static::flat_ground_equilibrium(&model).unwrap();
    let mut law = ActiveSuspension::leveling(config, &model, &y_eq).unwrap();
    // The law's increment for a state x (deviations: the affine part
    // cancels in the difference with the equilibrium's).
    let neutral: Vec<f64> = model.coordinates.iter().map(|c| c.neutral).collect();
    let mut step = |x: &[f64], u: &[f64]| -> Vec<f64> {
        let xs: Vec<f64> = lin.state.iter().zip(x).map(|(a, b)| a + b).collect();
        let att = rover_dynamics::attitude::Attitude::new(xs[3], xs[4], xs[5]);
        let r = att.rates([xs[9 + m], xs[10 + m], xs[11 + m]]);
        let y0: Vec<f64> = neutral.iter().zip(u).map(|(a, b)| a + b).collect();
        let mut out = y0.clone();
        law.update(xs[4], r[1], xs[3], r[0], &xs[6..6 + m], &mut out);
        out.iter().zip(&y0).map(|(a, b)| a - b).collect()
    };
    let base = step(&vec![0.0; n], &vec![0.0; m]);
    let h = 1e-7;
    let mut l = DMatrix::zeros(m, n);
    for j in 0..n {
        let mut x = vec![0.0; n];
        x[j] = h;
        for (i, v) in step(&x, &vec![0.0; m]).iter().enumerate() {
            l[(i, j)] = (v - base[i]) / h;
        }
    }
    let mut mm = DMatrix::zeros(m, m);
    for j in 0..m {
        let mut u = vec![0.0; m];
        u[j] = h;
        for (i, v) in step(&vec![0.0; n], &u).iter().enumerate() {
            mm[(i, j)] = (v - base[i]) / h;
        }
    }
    // Φ and Γ from the exponential of [[A, B], [0, 0]]·T.
    let mut aug = DMatrix::zeros(n + m, n + m);
    for i in 0..n {
        for j in 0..n {
            aug[(i, j)] = lin.a[i][j] * t;
        }
        for j in 0..m {
            let col = lin
                .inputs
                .iter()
                .position(|s| *s == format!("y0_{}", j + 1))
                .unwrap();
            aug[(i, n + j)] = lin.b[i][col] * t;
        }
    }
    let e = expm(&aug);
    let phi = e.view((0, 0), (n, n)).into_owned();
    let gamma = e.view((0, n), (n, m)).into_owned();
    let im = DMatrix::identity(m, m) + &mm;
    let mut cl = DMatrix::zeros(n + m, n + m);
    cl.view_mut((0, 0), (n, n)).copy_from(&(&phi + &gamma * &l));
    cl.view_mut((0, n), (n, m)).copy_from(&(&gamma * &im));
    cl.view_mut((n, 0), (m, n)).copy_from(&l);
    cl.view_mut((n, n), (m, m)).copy_from(&im);
    // Φ's eigenvalues at |λ| ≈ 1 stay (the law cannot move them): take
    // each one's nearest out of the closed loop's, then look at the rest.
    let open: Vec<_> = phi
        .complex_eigenvalues()
        .iter()
        .copied()
        .filter(|z| z.re.hypot(z.im) > 1.0 - 1e-4)
        .collect();
    let mut closed: Vec<_> = cl.complex_eigenvalues().iter().copied().collect();
    for z in &open {
        let k = (0..closed.len())
            .min_by(|&a, &b| {
                let da = (closed[a] - z).re.hypot((closed[a] - z).im);
                let db = (closed[b] - z).re.hypot((closed[b] - z).im);
                da.partial_cmp(&db).unwrap()
            })
            .unwrap();
        closed.swap_remove(k);
    }
    let radii: Vec<f64> = closed.iter().map(|z| z.re.hypot(z.im)).collect();
    let moved = radii.iter().cloned().fold(0.0, f64::max);
    let unstable = radii.iter().filter(|r| **r >= 1.0).count();
    (moved, unstable)
}

/// The defaults give a stable sampled loop with margin (every moved
/// eigenvalue well inside the unit circle); a gain far past the design
/// (the whole attitude error and a rate term ten times the arm's lag per
/// update) is found unstable by the same analysis.
#[test]
fn leveling_closed_loop_is_stable_about_the_static_equilibrium() {
    let (radius, unstable) = closed_loop("");
    assert!(
        unstable == 0 && radius < 0.98,
        "defaults: largest moved |λ| = {radius}, {unstable} at |λ| ≥ 1"
    );
    let (radius, unstable) = closed_loop("attitude_gain = 1.0\nrate_gain = 7.0\n");
    assert!(
        unstable > 0,
        "an excessive rate gain should destabilize: largest moved |λ| = {radius}"
    );
}

/// e^M by scaling and squaring: M/2^s with norm below 1/2, a Taylor series
/// of 16 terms, squared s times.
fn expm(m: &nalgebra::DMatrix<f64>) -> nalgebra::DMatrix<f64> {
    let norm = m.iter().map(|v| v.abs()).sum::<f64>();
    let s = (norm / 0.5).log2().ceil().max(0.0) as i32;
    let a = m / 2f64.powi(s);
    let n = m.nrows();
    let mut sum = nalgebra::DMatrix::identity(n, n);
    let mut term = nalgebra::DMatrix::identity(n, n);
    for k in 1..=16 {
        term = &term * &a / k as f64;
        sum += &term;
    }
    for _ in 0..s {
        sum = &sum * &sum;
    }
    sum
}
