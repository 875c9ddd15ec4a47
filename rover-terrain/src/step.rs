//! A straight step, smoothed by a short cosine ramp or kept sharp.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, finite_point};
use super::param::{finite, non_negative, unit_vector};

/// A straight step (MODEL.md §6, the terrain library) of `height` across
/// the line through `position`
/// perpendicular to `direction_deg`; the ground is at 0 behind the line and at
/// `height` beyond it (walking along `direction_deg`; a negative height is a
/// step down). With `s = (X − X_p)·cos ψ + (Y − Y_p)·sin ψ` and ramp width `w`:
/// ```text
/// w > 0:  Z_G = 0 for s ≤ −w/2,  h for s ≥ w/2,  h·(1 − cos(π·(s + w/2)/w))/2 between
/// w = 0:  Z_G = 0 for s < 0,     h for s ≥ 0     (kept discontinuous)
/// ```
/// The smoothed step is C1 (the integrator sees continuous contact forces) with
/// steepest slope `atan(π·h/(2w))` at the line. The sharp step has zero gradient
/// on both sides and takes the upper value on the line itself; the meridional
/// contact search still finds the crossing by bisection, but forces jump.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    height: f64,
    position: [f64; 2],
    along: [f64; 2],
    ramp: f64,
}

impl Step {
    /// A step `height` \[m\] at `position` \[m\], rising towards `direction_deg`,
    /// smoothed over `ramp_width` \[m\] (0 keeps it sharp).
    pub fn new(
        height: f64,
        position: [f64; 2],
        direction_deg: f64,
        ramp_width: f64,
    ) -> Result<Step, TerrainError> {
        Ok(Step {
            height: finite("height", height, "m")?,
            position: [
                finite("position[0]", position[0], "m")?,
                finite("position[1]", position[1], "m")?,
            ],
            along: unit_vector("direction_deg", direction_deg)?,
            ramp: non_negative("ramp_width", ramp_width, "m")?,
        })
    }

    #[inline]
    fn evaluate(&self, x: f64, y: f64) -> (f64, [f64; 2]) {
        let s = (x - self.position[0]) * self.along[0] + (y - self.position[1]) * self.along[1];
        let half = 0.5 * self.ramp;
        if s >= half {
            return (self.height, [0.0, 0.0]);
        }
        if s <= -half {
            return (0.0, [0.0, 0.0]);
        }
        // Strictly inside the ramp, so ramp > 0.
        let phase = core::f64::consts::PI * (s + half) / self.ramp;
        let (sin, cos) = phase.sin_cos();
        let z = 0.5 * self.height * (1.0 - cos);
        let dz_ds = 0.5 * self.height * core::f64::consts::PI / self.ramp * sin;
        (z, [dz_ds * self.along[0], dz_ds * self.along[1]])
    }
}

impl HeightField for Step {
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
        area.is_finite().then(|| self.height.max(0.0))
    }

    /// Zero where the area lies wholly on one side of the ramp, else its
    /// steepest slope `|h|·π/(2w)`; `None` across a sharp step, which
    /// jumps.
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        if !area.is_finite() {
            return None;
        }
        // The area's extent along the step's direction, from its corners.
        let s = |x: f64, y: f64| {
            (x - self.position[0]) * self.along[0] + (y - self.position[1]) * self.along[1]
        };
        let corners = [
            s(area.x_min, area.y_min),
            s(area.x_max, area.y_min),
            s(area.x_min, area.y_max),
            s(area.x_max, area.y_max),
        ];
        let lo = corners.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = corners.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let half = 0.5 * self.ramp;
        // A margin for the rounding of s, far below any ramp.
        let margin = 1e-9 * (1.0 + lo.abs().max(hi.abs()));
        if lo - margin > half || hi + margin < -half {
            Some(0.0)
        } else if self.ramp > 0.0 {
            Some(self.height.abs() * core::f64::consts::FRAC_PI_2 / self.ramp)
        } else {
            None
        }
    }
}
