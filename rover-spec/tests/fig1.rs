//! The paper's Fig. 1: a trailing arm about 45°, Taylor k = 5, over 20°–70°.
//!
//! Nondimensional error, per component, as the paper defines it:
//! `e_x = ((u_j)_x − x_j + l·sin y)/l` and `e_z = ((u_j)_z − z_j + l·cos y)/l`,
//! i.e. (polynomial − exact)/l. Both components give the same band (x and z
//! are mirror images about 45°): −9.953e-5 … +8.602e-5, inside the paper's
//! printed −9.96e-5 … 8.61e-5 (which rounds outwards); the opposite sign
//! convention (exact − polynomial) would give −8.60e-5 … +9.95e-5.

use rover_spec::linkage::{CoordRange, FitMethod, FitOptions, Linkage};
use rover_spec::point_fit::fit_point;
use rover_spec::suspension::SwingArm;

const L: f64 = 1.0;

fn arm() -> SwingArm {
    SwingArm {
        pivot: [0.0; 3],
        length: L,
        axis: 1,
        rest: 45f64.to_radians(),
        camber_rest: 0.0,
    }
}

fn range() -> CoordRange {
    CoordRange {
        rest: 45f64.to_radians(),
        min: 20f64.to_radians(),
        max: 70f64.to_radians(),
    }
}

/// Signed nondimensional errors (min, max) of x and z over 20°–70°, and the
/// reported maximum position error.
fn errors(method: FitMethod) -> ([f64; 2], [f64; 2], f64) {
    let arm = arm();
    let rest = arm.points()[0].rest;
    let options = FitOptions {
        method,
        terms: 5,
        tolerance: 1.0,
        angle_tolerance: 1.0,
    };
    let fit = fit_point(&arm, 0, rest, &[range()], &[0], &options).expect("fit");
    let (mut ex, mut ez) = ([f64::MAX, f64::MIN], [f64::MAX, f64::MIN]);
    for i in 0..=5000 {
        let y = (20.0 + 50.0 * i as f64 / 5000.0).to_radians();
        let u = fit.position.value(&[y]);
        let x = (u[0] + L * y.sin()) / L;
        let z = (u[2] + L * y.cos()) / L;
        ex = [ex[0].min(x), ex[1].max(x)];
        ez = [ez[0].min(z), ez[1].max(z)];
    }
    (ex, ez, fit.max_position_error)
}

#[test]
fn taylor_k5_error_is_the_papers_band() {
    let (ex, ez, reported) = errors(FitMethod::Taylor);
    for e in [ex, ez] {
        // Within the paper's band, and reaching it (not merely inside).
        assert!(e[0] >= -9.96e-5 && e[0] < -9.94e-5, "min {e:?}");
        assert!(e[1] <= 8.61e-5 && e[1] > 8.59e-5, "max {e:?}");
    }
    // The extreme x error is at 70°, the extreme z error at 20°: mirror images.
    assert!((ex[0] - ez[0]).abs() < 1e-12 && (ex[1] - ez[1]).abs() < 1e-12);
    // The reported error (Euclidean, both components) bounds both.
    assert!(reported >= ex[0].abs().max(ex[1]) * L);
    assert!(reported < 1.5e-4 * L, "{reported}");
}

#[test]
fn least_squares_is_better_over_the_same_range() {
    let (tx, tz, taylor) = errors(FitMethod::Taylor);
    let (lx, lz, lsq) = errors(FitMethod::LeastSquares);
    assert!(lsq < taylor / 5.0, "least squares {lsq} vs Taylor {taylor}");
    for (l, t) in [(lx, tx), (lz, tz)] {
        assert!(l[0].abs().max(l[1].abs()) < t[0].abs().max(t[1].abs()) / 5.0);
    }
}

#[test]
fn taylor_coefficients_are_eq_33() {
    // Z_ij of the paper (expanded about y0 = 45° in ξ = y − y0):
    // x: −l·[s, c, −s/2, −c/6, s/24], z: −l·[c, −s, −c/2, s/6, c/24].
    let arm = arm();
    let rest = arm.points()[0].rest;
    let options = FitOptions {
        method: FitMethod::Taylor,
        terms: 5,
        tolerance: 1.0,
        angle_tolerance: 1.0,
    };
    let fit = fit_point(&arm, 0, rest, &[range()], &[0], &options).unwrap();
    let (s, c) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
    let x = [s, c, -s / 2.0, -c / 6.0, s / 24.0];
    let z = [c, -s, -c / 2.0, s / 6.0, c / 24.0];
    let t = &fit.position.terms[0];
    assert_eq!(t.center, 45f64.to_radians());
    assert!((fit.position.constant[0] + L * x[0]).abs() < 1e-15);
    assert!((fit.position.constant[2] + L * z[0]).abs() < 1e-15);
    for p in 1..5 {
        assert!((t.coeffs[p][0] + L * x[p]).abs() < 1e-14, "x{p}");
        assert_eq!(t.coeffs[p][1], 0.0);
        assert!((t.coeffs[p][2] + L * z[p]).abs() < 1e-14, "z{p}");
    }
}
