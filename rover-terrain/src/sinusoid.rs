//! Sinusoidal corrugations.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, finite_point};
use super::param::{finite, positive, unit_vector};

/// Straight sinusoidal waves along `direction_deg` (MODEL.md §6, the
/// terrain library):
/// ```text
/// Z_G = A·sin(2π·s/λ + φ),  s = X·cos ψ + Y·sin ψ
/// ```
/// A the amplitude \[m\], λ the wavelength \[m\], φ the phase; crests run
/// perpendicular to ψ. Steepest slope `atan(2π·A/λ)`. Unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sinusoid {
    amplitude: f64,
    wavenumber: f64,
    phase: f64,
    along: [f64; 2],
}

impl Sinusoid {
    /// Waves of `amplitude` \[m\] and `wavelength` \[m\] along `direction_deg`,
    /// phase `phase_deg` at the origin.
    pub fn new(
        amplitude: f64,
        wavelength: f64,
        direction_deg: f64,
        phase_deg: f64,
    ) -> Result<Sinusoid, TerrainError> {
        Ok(Sinusoid {
            amplitude: finite("amplitude", amplitude, "m")?,
            wavenumber: 2.0 * core::f64::consts::PI / positive("wavelength", wavelength, "m")?,
            phase: finite("phase_deg", phase_deg, "degrees")?.to_radians(),
            along: unit_vector("direction_deg", direction_deg)?,
        })
    }

    #[inline]
    fn evaluate(&self, x: f64, y: f64) -> (f64, [f64; 2]) {
        let s = x * self.along[0] + y * self.along[1];
        let (sin, cos) = (self.wavenumber * s + self.phase).sin_cos();
        let dz_ds = self.amplitude * self.wavenumber * cos;
        (
            self.amplitude * sin,
            [dz_ds * self.along[0], dz_ds * self.along[1]],
        )
    }
}

impl HeightField for Sinusoid {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        finite_point(x, y)?;
        Ok(self.evaluate(x, y).0)
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        finite_point(x, y)?;
        Ok(self.evaluate(x, y))
    }

    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then(|| self.amplitude.abs())
    }

    /// The steepest slope anywhere, `|A|·2π/λ`.
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite()
            .then(|| self.amplitude.abs() * self.wavenumber)
    }

    /// The largest curvature anywhere, `|A|·(2π/λ)²`.
    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite()
            .then(|| self.amplitude.abs() * self.wavenumber * self.wavenumber * (1.0 + 1e-12))
    }
}
