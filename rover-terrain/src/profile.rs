//! The raised-cosine profile shared by bumps and ditches, and their footprints.

use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::param::{finite, non_negative, positive, unit_vector};

/// How a one-dimensional profile is laid on the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Footprint {
    /// A straight ridge (or trench) of infinite length: the profile runs along
    /// `direction_deg` through the centre and is constant across it, so a
    /// rover driving along `direction_deg` meets it with both sides at once.
    /// The default.
    #[default]
    Ridge,
    /// Round: the profile is a function of the distance from the centre.
    Round,
}

/// A flat top of width `top` with raised-cosine flanks, full base width `base`:
/// ```text
/// p(s) = 1                                   |s| ≤ top/2
/// p(s) = (1 + cos(π·(|s| − top/2)/r))/2      top/2 < |s| < top/2 + r,  r = (base − top)/2
/// p(s) = 0                                   beyond
/// ```
/// C1 (value and slope continuous; the slope is zero at both ends of a flank),
/// steepest slope `π/(2r)` at mid-flank. Placed by a [`Footprint`] around `centre`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Profile {
    amplitude: f64,
    half_top: f64,
    ramp: f64,
    centre: [f64; 2],
    along: [f64; 2],
    footprint: Footprint,
}

impl Profile {
    /// Checks and builds the profile. `names` are the parameter names for
    /// (amplitude, base width, top width) in error messages.
    pub(crate) fn new(
        names: [&str; 3],
        amplitude: f64,
        base: f64,
        top: f64,
        centre: [f64; 2],
        direction_deg: f64,
        footprint: Footprint,
    ) -> Result<Profile, TerrainError> {
        let amplitude = finite(names[0], amplitude, "m")?;
        let base = positive(names[1], base, "m")?;
        let top = non_negative(names[2], top, "m")?;
        if top >= base {
            return Err(TerrainError::parameter(
                names[2],
                format!("must be smaller than {} ({base} m), got {top} m", names[1]),
                format!(
                    "{} is the full width at the base, {} the flat part; the flanks take the rest",
                    names[1], names[2]
                ),
            ));
        }
        Ok(Profile {
            amplitude,
            half_top: 0.5 * top,
            ramp: 0.5 * (base - top),
            centre: [
                finite("center[0]", centre[0], "m")?,
                finite("center[1]", centre[1], "m")?,
            ],
            along: unit_vector("direction_deg", direction_deg)?,
            footprint,
        })
    }

    /// Height and gradient at (x, y); the point must be finite.
    /// The largest height anywhere: the top, or the surrounding ground at 0.
    pub(crate) fn max_height(&self) -> f64 {
        self.amplitude.max(0.0)
    }

    /// The largest curvature anywhere, at the flanks' ends: `|A|·π²/(2r²)`,
    /// the profile's `|p''|`. On a round footprint the Hessian's other
    /// eigenvalue is `p'(s)/s`, no larger: `p'` is zero on the top (or at
    /// its centre) and grows from there at most as fast as `|p''|` allows.
    pub(crate) fn curvature(&self) -> f64 {
        let k = core::f64::consts::PI / self.ramp;
        0.5 * self.amplitude.abs() * k * k * (1.0 + 1e-12)
    }

    /// The steepest slope anywhere, at mid-flank: `|A|·π/(2r)`.
    pub(crate) fn steepest(&self) -> f64 {
        self.amplitude.abs() * core::f64::consts::FRAC_PI_2 / self.ramp
    }

    #[inline]
    pub(crate) fn evaluate(&self, x: f64, y: f64) -> (f64, [f64; 2]) {
        let dx = x - self.centre[0];
        let dy = y - self.centre[1];
        // s ≥ 0 the profile coordinate, e its gradient (a unit vector or zero).
        let (s, e) = match self.footprint {
            Footprint::Ridge => {
                let s = dx * self.along[0] + dy * self.along[1];
                let sign = if s < 0.0 { -1.0 } else { 1.0 };
                (s.abs(), [sign * self.along[0], sign * self.along[1]])
            }
            Footprint::Round => {
                let r = dx.hypot(dy);
                if r > 0.0 {
                    (r, [dx / r, dy / r])
                } else {
                    (0.0, [0.0, 0.0])
                }
            }
        };
        let flank = s - self.half_top;
        if flank <= 0.0 {
            return (self.amplitude, [0.0, 0.0]);
        }
        if flank >= self.ramp {
            return (0.0, [0.0, 0.0]);
        }
        let phase = core::f64::consts::PI * flank / self.ramp;
        let (sin, cos) = phase.sin_cos();
        let z = 0.5 * self.amplitude * (1.0 + cos);
        let dz_ds = -0.5 * self.amplitude * core::f64::consts::PI / self.ramp * sin;
        (z, [dz_ds * e[0], dz_ds * e[1]])
    }
}
