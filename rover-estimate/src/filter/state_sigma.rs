//! One standard deviation per entry of the model's state, for outputs:
//! the error state's, with the attitude's small rotation mapped back to
//! the Euler angles the model keeps.

use super::{ATTITUDE, Estimator, Result, check_len};
use crate::process::ProcessModel;
use crate::rotation::error_map;

impl<M: ProcessModel> Estimator<M> {
    /// One standard deviation per entry of the model state `y` into `out`
    /// (`dim` long): the error state's, except the attitude's, which are
    /// those of φ, θ, ψ, `Σ_e = T⁻¹·Σ_δθ·T⁻ᵀ` with `δθ = T·δe`
    /// (docs/ESTIMATE.md, "The filter").
    pub fn state_sigma(&self, out: &mut [f64]) -> Result<(), M::Error> {
        let (dim, len) = (self.layout.dim, self.layout.len);
        check_len("state_sigma", dim, out.len())?;
        let p = &self.estimate.p;
        for (i, o) in out.iter_mut().enumerate() {
            *o = libm::sqrt(p[i * len + i].max(0.0));
        }
        let (_, t_inv) = error_map(&self.estimate.y[ATTITUDE]);
        let a = ATTITUDE.start;
        for (r, row) in t_inv.iter().enumerate() {
            // (T⁻¹·Σ·T⁻ᵀ)_rr = Σ_ij T⁻¹_ri·Σ_ij·T⁻¹_rj
            let mut var = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    var += row[i] * p[(a + i) * len + a + j] * row[j];
                }
            }
            out[a + r] = libm::sqrt(var.max(0.0));
        }
        Ok(())
    }
}
