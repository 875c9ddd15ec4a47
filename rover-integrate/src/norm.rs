//! Weighted root-mean-square norms for error control (Hairer, Nørsett & Wanner I, §II.4, eq. 4.11).

/// The absolute tolerance of each component, in the component's own units.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Atol<'a> {
    /// One value for every component.
    Uniform(f64),
    /// One value per component (the system's [`error_scale`](crate::OdeSystem::error_scale)
    /// times `rtol`), each with the weight of its relative part (1, or 0 for a component
    /// whose size means nothing, such as a position).
    PerComponent {
        /// Absolute tolerances.
        atol: &'a [f64],
        /// Weights of `rtol·|y_i|`.
        relative: &'a [f64],
    },
}

impl Atol<'_> {
    /// The error weight of component `i` of size `y`: `atol_i + rtol·relative_i·y`.
    #[inline]
    fn weight(&self, i: usize, rtol: f64, y: f64) -> f64 {
        match self {
            Self::Uniform(a) => a + rtol * y,
            Self::PerComponent { atol, relative } => atol[i] + rtol * relative[i] * y,
        }
    }
}

/// `sqrt(1/n · Σ (v_i / (atol_i + rtol·r_i·max(|a_i|, |b_i|)))²)` (`r_i` the relative part's
/// weight, 1 for a uniform `atol`): the norm of an error estimate `v` for a step from `a` to
/// `b`. Zero for an empty vector.
pub(crate) fn error_norm(v: &[f64], a: &[f64], b: &[f64], rtol: f64, atol: Atol<'_>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let sum: f64 = v
        .iter()
        .zip(a.iter().zip(b))
        .enumerate()
        .map(|(i, (vi, (ai, bi)))| {
            let scaled = vi / atol.weight(i, rtol, ai.abs().max(bi.abs()));
            scaled * scaled
        })
        .sum();
    (sum / v.len() as f64).sqrt()
}

/// `sqrt(1/n · Σ (v_i / (atol_i + rtol·r_i·|y_i|))²)`.
pub(crate) fn scaled_norm(v: &[f64], y: &[f64], rtol: f64, atol: Atol<'_>) -> f64 {
    error_norm(v, y, y, rtol, atol)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed form: each component divided by its own weight, then the RMS.
    #[test]
    fn per_component_weights_divide_each_component() {
        let v = [1e-3, 2e-5, -3e-2];
        let y = [2.0, -0.5, 0.0];
        let atol = [1e-3, 1e-5, 1e-2];
        let rtol = 1e-2;
        // Weights 1e-3 + 0.02, 1e-5 + 0.005, 1e-2 + 0.
        let want =
            ((1e-3f64 / 0.021).powi(2) + (2e-5f64 / 0.00501).powi(2) + (3e-2f64 / 0.01).powi(2))
                / 3.0;
        let ones = [1.0; 3];
        let per = |atol| Atol::PerComponent {
            atol,
            relative: &ones,
        };
        let got = scaled_norm(&v, &y, rtol, per(&atol));
        assert!((got - want.sqrt()).abs() < 1e-15 * want.sqrt(), "{got}");
        // A uniform tolerance is the per-component one with equal entries.
        let uniform = scaled_norm(&v, &y, rtol, Atol::Uniform(1e-3));
        let equal = scaled_norm(&v, &y, rtol, per(&[1e-3; 3]));
        assert_eq!(uniform.to_bits(), equal.to_bits());
        // Without its relative part, a component is held to its absolute tolerance alone.
        let absolute = [1.0, 0.0, 1.0];
        let got = scaled_norm(
            &v,
            &y,
            rtol,
            Atol::PerComponent {
                atol: &atol,
                relative: &absolute,
            },
        );
        let want = ((1e-3f64 / 0.021).powi(2) + (2e-5f64 / 1e-5).powi(2) + 3.0f64.powi(2)) / 3.0;
        assert!((got - want.sqrt()).abs() < 1e-15 * want.sqrt(), "{got}");
    }

    /// The larger of the two states sets the relative part of a step's weight.
    #[test]
    fn error_norm_takes_the_larger_end_of_the_step() {
        let atol = Atol::PerComponent {
            atol: &[0.5],
            relative: &[1.0],
        };
        let got = error_norm(&[1.0], &[-3.0], &[1.0], 0.5, atol);
        assert_eq!(got, 0.5);
    }
}
