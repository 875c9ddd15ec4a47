//! Method coefficients, as data: the Dormand–Prince 5(4) Butcher tableau and the NDF/BDF
//! coefficients.

/// An explicit embedded Runge–Kutta pair with `S` stages and the FSAL property: `c`, the
/// strictly lower triangular `a` whose last row holds the weights `b` of the propagated solution
/// (so the last stage is evaluated at the new point), and `e = b − b̂`, the difference to the
/// embedded solution's weights (the local error estimate is `h·Σ e_i·k_i`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ButcherTableau<const S: usize> {
    pub c: [f64; S],
    pub a: [[f64; S]; S],
    pub e: [f64; S],
}

/// Dormand & Prince (1980), "A family of embedded Runge–Kutta formulae", J. Comput. Appl.
/// Math. 6; Hairer, Nørsett & Wanner I, §II.5, Table 5.2, p. 178. Order 5 propagated
/// (local extrapolation), order 4 embedded; 7 stages, the last evaluated at the new point
/// (FSAL: `b = a[6]`, `b_7 = 0`), so 6 evaluations per accepted step.
pub(crate) const DOPRI5: ButcherTableau<7> = ButcherTableau {
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    a: [
        [0.0; 7],
        [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0],
        [
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
            0.0,
            0.0,
            0.0,
        ],
        [
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
            0.0,
            0.0,
        ],
        [
            35.0 / 384.0,
            0.0,
            500.0 / 1113.0,
            125.0 / 192.0,
            -2187.0 / 6784.0,
            11.0 / 84.0,
            0.0,
        ],
    ],
    // b − b̂ with b̂ = (5179/57600, 0, 7571/16695, 393/640, −92097/339200, 187/2100, 1/40).
    e: [
        71.0 / 57600.0,
        0.0,
        -71.0 / 16695.0,
        71.0 / 1920.0,
        -17253.0 / 339200.0,
        22.0 / 525.0,
        -1.0 / 40.0,
    ],
};

/// Highest order of the NDF/BDF family used.
pub(crate) const BDF_MAX_ORDER: usize = 5;

/// The NDF coefficients κ_k, k = 0..=5 (Shampine & Reichelt 1997, "The MATLAB ODE Suite",
/// SIAM J. Sci. Comput. 18, Table 2.1): order k of the NDF is BDF_k with a term
/// `−κ_k·γ_k·(y_{n+1} − y^(0)_{n+1})` added, trading a little stability angle for a smaller
/// error constant (order 5 is left as BDF). Index 0 is unused.
pub(crate) const NDF_KAPPA: [f64; BDF_MAX_ORDER + 1] =
    [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];

/// `γ_k = Σ_{j=1..k} 1/j`, k = 0..=6.
pub(crate) const BDF_GAMMA: [f64; BDF_MAX_ORDER + 2] = [
    0.0,
    1.0,
    1.0 + 1.0 / 2.0,
    1.0 + 1.0 / 2.0 + 1.0 / 3.0,
    1.0 + 1.0 / 2.0 + 1.0 / 3.0 + 1.0 / 4.0,
    1.0 + 1.0 / 2.0 + 1.0 / 3.0 + 1.0 / 4.0 + 1.0 / 5.0,
    1.0 + 1.0 / 2.0 + 1.0 / 3.0 + 1.0 / 4.0 + 1.0 / 5.0 + 1.0 / 6.0,
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Row sums of `a` equal `c`, and the order conditions hold: up to order 5 for `b`
    /// (the 17 conditions are implied by the ones checked here together with the simplifying
    /// assumptions, which we check too), order 4 for `b̂ = b − e`.
    #[test]
    fn dopri5_tableau_satisfies_its_order_conditions() {
        let t = DOPRI5;
        let b = t.a[6];
        for i in 0..7 {
            let row: f64 = t.a[i].iter().sum();
            assert!((row - t.c[i]).abs() < 1e-15, "row {i}: {row} vs {}", t.c[i]);
        }
        let bh: Vec<f64> = (0..7).map(|i| b[i] - t.e[i]).collect();
        let moment = |w: &[f64], q: i32| -> f64 { (0..7).map(|i| w[i] * t.c[i].powi(q)).sum() };
        for q in 0..5 {
            let expected = 1.0 / f64::from(q + 1);
            assert!((moment(&b, q) - expected).abs() < 1e-14, "b, c^{q}");
            if q < 4 {
                assert!((moment(&bh, q) - expected).abs() < 1e-14, "b̂, c^{q}");
            }
        }
        // Simplifying assumption C(2) for stages 3..7: Σ_j a_ij c_j = c_i²/2 (stage 2 excepted,
        // as in all explicit methods), and D(1): Σ_i b_i a_ij = b_j (1 − c_j).
        for i in 2..7 {
            let s: f64 = (0..i).map(|j| t.a[i][j] * t.c[j]).sum();
            assert!((s - t.c[i] * t.c[i] / 2.0).abs() < 1e-14, "C(2) stage {i}");
        }
        for j in 0..7 {
            let s: f64 = (0..7).map(|i| b[i] * t.a[i][j]).sum();
            assert!((s - b[j] * (1.0 - t.c[j])).abs() < 1e-14, "D(1) column {j}");
        }
        // FSAL: the last stage, at c = 1, is the propagated solution (b_7 = 0).
        assert_eq!((t.c[6], b[6]), (1.0, 0.0));
    }
}
