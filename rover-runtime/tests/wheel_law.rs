//! The wheel force laws (MODEL.md §7) on closed-form cases.

use rover_dynamics::wheel_law::{PatchMotion, Tyre, WheelLaw};
use rover_runtime::wheel_law::{ChenGenta, MagicFormula};

const TYRE: Tyre = Tyre {
    stiffness: 4000.0,
    damping: 300.0,
    mu_x: 0.5,
    mu_y: 0.5,
    cornering_stiffness: 50.0,
    rolling_resistance: 0.0,
};

fn motion(deflection: f64, rate: f64, v_t: f64, v_c: f64, torque: f64) -> PatchMotion {
    PatchMotion {
        deflection,
        deflection_rate: rate,
        v_t,
        v_c,
        lever: 0.088,
        torque,
    }
}

#[test]
fn normal_force_is_a_spring_damper_that_never_pulls() {
    let law = ChenGenta::default();
    let f = law.forces(&TYRE, &motion(0.002, 0.01, 0.1, 0.0, 0.0));
    assert!((f.normal - (4000.0 * 0.002 + 300.0 * 0.01)).abs() < 1e-12);
    // Leaving the ground fast: k·Δ + c·Δ̇ < 0 → no force at all.
    let f = law.forces(&TYRE, &motion(0.001, -0.1, 0.1, 0.05, 1.0));
    assert_eq!((f.normal, f.drawbar, f.lateral), (0.0, 0.0, 0.0));
}

#[test]
fn drawbar_pull_is_torque_over_lever_saturated_by_friction() {
    let law = ChenGenta::default();
    let f = law.forces(&TYRE, &motion(0.002, 0.0, 0.1, 0.0, 0.2));
    assert!((f.drawbar - 0.2 / 0.088).abs() < 1e-12);
    let f = law.forces(&TYRE, &motion(0.002, 0.0, 0.1, 0.0, -5.0));
    assert!(
        (f.drawbar + 0.5 * 8.0).abs() < 1e-12,
        "saturated at −μx·F_n: {}",
        f.drawbar
    );
}

#[test]
fn cornering_force_opposes_sideslip_with_the_paper_law_and_slope_c() {
    let law = ChenGenta::default();
    let fnorm = 8.0;
    for alpha in [0.01f64, 0.1, 0.5] {
        let f = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, alpha.tan(), 0.0));
        let expected = -0.5 * fnorm * (1.0 - (-50.0 * alpha / (0.5 * fnorm)).exp());
        assert!(
            (f.lateral - expected).abs() < 1e-12,
            "α = {alpha}: {} vs {expected}",
            f.lateral
        );
        let g = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, -alpha.tan(), 0.0));
        assert_eq!(g.lateral, -f.lateral, "odd in α");
    }
    // Standstill: α = atan2(V_c, v_ε), finite — for small V_c a stiff damper C/v_ε.
    let f = law.forces(&TYRE, &motion(0.002, 0.0, 0.0, 1e-6, 0.0));
    let alpha = 1e-6f64.atan2(1e-3);
    let expected = -0.5 * fnorm * (1.0 - (-50.0 * alpha / (0.5 * fnorm)).exp());
    assert!((f.lateral - expected).abs() < 1e-15);
    assert!(
        (f.lateral + 50.0 * 1e-6 / 1e-3).abs() < 0.01 * 0.05,
        "≈ −C·V_c/v_ε"
    );
}

#[test]
fn combined_slip_shrinks_the_lateral_force_on_the_friction_ellipse() {
    let law = ChenGenta::default();
    let free = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, 0.1, 0.0));
    let driven = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, 0.1, 0.3 * 4.0 * 0.088));
    let ratio: f64 = 0.3 * 4.0 / (0.5 * 8.0);
    assert!((driven.lateral - free.lateral * (1.0 - ratio * ratio).sqrt()).abs() < 1e-12);
}

#[test]
fn magic_formula_has_slope_c_at_zero_and_saturates_at_mu_fn() {
    let law = MagicFormula::default();
    let fnorm = 8.0;
    let small = 1e-6;
    let f = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, small, 0.0));
    assert!(
        (f.lateral / small + 50.0).abs() < 1e-3,
        "slope {}",
        f.lateral / small
    );
    let big = law.forces(&TYRE, &motion(0.002, 0.0, 1.0, 1.0, 0.0));
    assert!(big.lateral < 0.0 && big.lateral.abs() <= 0.5 * fnorm + 1e-12);
    // The peak of sin(C·atan(·)) is D = μy·F_n.
    let peak = (1..2000)
        .map(|i| {
            law.forces(
                &TYRE,
                &motion(0.002, 0.0, 1.0, (i as f64 * 1e-3).tan(), 0.0),
            )
            .lateral
            .abs()
        })
        .fold(0.0, f64::max);
    assert!((peak - 0.5 * fnorm).abs() < 1e-3, "peak {peak}");
}

#[test]
fn normal_force_is_continuous_at_touchdown_and_exact_beyond_the_ramp() {
    let law = ChenGenta::default();
    let landing = 0.2; // Δ̇ [m/s]
    // At the first touch the force starts from zero, not from c_w·Δ̇ = 60 N.
    let first = law
        .forces(&TYRE, &motion(1e-9, landing, 0.1, 0.0, 0.0))
        .normal;
    assert!(first < 1e-3, "F_n at Δ = 1 nm is {first} N");
    // Beyond the 0.1 mm ramp, eq. 37 exactly.
    let d = 2e-4;
    let f = law.forces(&TYRE, &motion(d, landing, 0.1, 0.0, 0.0)).normal;
    assert!((f - (4000.0 * d + 300.0 * landing)).abs() < 1e-12);
    // Continuous through the ramp.
    let mut prev = 0.0;
    for i in 1..=200 {
        let d = i as f64 * 1e-6;
        let f = law.forces(&TYRE, &motion(d, landing, 0.1, 0.0, 0.0)).normal;
        assert!(f - prev < 1.0, "jump of {} N at Δ = {d}", f - prev);
        prev = f;
    }
}
