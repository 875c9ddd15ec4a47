//! Sinusoidal corrugations.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, finite_point};
use super::param::{finite, positive, unit_vector};

/// Shortest wavelength of a corrugation \[m\].
pub const MIN_WAVELENGTH: f64 = 1e-3;
/// Steepest slope of a corrugation, `2π·A/λ` (tan 80°).
pub const MAX_SLOPE: f64 = 5.671_281_819_617_709;

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
        let amplitude = finite("amplitude", amplitude, "m")?;
        let wavelength = positive("wavelength", wavelength, "m")?;
        // Shorter waves are a texture, not ground a wheel rolls over: the
        // contact search and the integrator's steps shrink with them
        // without bound.
        if wavelength < MIN_WAVELENGTH {
            return Err(TerrainError::parameter(
                "wavelength",
                format!("{wavelength} m is shorter than {MIN_WAVELENGTH} m"),
                "corrugations are waves of centimetres to metres; a texture finer than a millimetre is not ground that the rigid wheel model resolves",
            ));
        }
        let slope = 2.0 * core::f64::consts::PI * amplitude.abs() / wavelength;
        if slope > MAX_SLOPE {
            return Err(TerrainError::parameter(
                "amplitude",
                format!(
                    "amplitude {amplitude} m on a wavelength of {wavelength} m gives slopes of {:.1}°, steeper than {:.0}°",
                    slope.atan().to_degrees(),
                    MAX_SLOPE.atan().to_degrees()
                ),
                format!(
                    "keep 2π·amplitude/wavelength ≤ {MAX_SLOPE:.2}: amplitude ≤ {:.4} m at this wavelength",
                    MAX_SLOPE * wavelength / (2.0 * core::f64::consts::PI)
                ),
            ));
        }
        Ok(Sinusoid {
            amplitude,
            wavenumber: 2.0 * core::f64::consts::PI / wavelength,
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
