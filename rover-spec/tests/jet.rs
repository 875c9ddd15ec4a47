//! Truncated Taylor series: each operation against a series known in
//! closed form.

use rover_spec::jet::{Jet, MAX_TERMS};
use rover_spec::real::Real;

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

#[test]
fn sin_cos_are_their_taylor_series() {
    let a = 0.3;
    let (s, c) = (Jet::variable(a).sin(), Jet::variable(a).cos());
    let ds = [a.sin(), a.cos(), -a.sin(), -a.cos()];
    for p in 0..MAX_TERMS {
        assert!((s.c[p] - ds[p % 4] / factorial(p)).abs() < 1e-15, "sin {p}");
        assert!(
            (c.c[p] - ds[(p + 1) % 4] / factorial(p)).abs() < 1e-15,
            "cos {p}"
        );
    }
}

#[test]
fn sqrt_and_div_are_binomial_series() {
    // sqrt(1 + ξ) = Σ C(1/2, p) ξ^p;  1/(1 − ξ) = Σ ξ^p.
    let r = Jet::variable(1.0).sqrt();
    let mut binom = 1.0;
    for p in 0..MAX_TERMS {
        assert!((r.c[p] - binom).abs() < 1e-15, "sqrt {p}");
        binom *= (0.5 - p as f64) / (p as f64 + 1.0);
    }
    let q = Jet::cst(1.0) / (Jet::cst(2.0) - Jet::variable(1.0));
    assert!(q.c.iter().all(|&v| (v - 1.0).abs() < 1e-15));
}

#[test]
fn atan2_is_the_arctangent_series() {
    // atan2(ξ, 1) = ξ − ξ³/3 + ξ⁵/5 − …; and atan2(sin t, cos t) = t.
    let x = Jet::variable(0.0);
    let t = x.atan2(Jet::cst(1.0));
    for p in 0..MAX_TERMS {
        let expected = if p % 2 == 1 {
            (if p % 4 == 1 { 1.0 } else { -1.0 }) / p as f64
        } else {
            0.0
        };
        assert!((t.c[p] - expected).abs() < 1e-15, "atan {p}");
    }
    let angle = Jet::variable(2.5);
    let back = angle.sin().atan2(angle.cos());
    assert!((back.c[0] - 2.5).abs() < 1e-15 && (back.c[1] - 1.0).abs() < 1e-14);
    assert!(back.c[2..].iter().all(|v| v.abs() < 1e-13));
}
