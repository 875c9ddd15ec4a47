//! A plane inclined in any direction.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, Plane, finite_point};
use super::param::{finite, unit_vector};

/// A plane rising at `angle_deg` towards the azimuth `direction_deg`
/// (MODEL.md §6, the terrain library):
/// ```text
/// Z_G = z0 + tan(α)·((X − X0)·cos ψ + (Y − Y0)·sin ψ)
/// ```
/// α the slope angle (negative: descending towards ψ), ψ the direction of
/// ascent from +X towards +Y, (X0, Y0) a point at height z0. Unbounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slope {
    origin: [f64; 2],
    height: f64,
    gradient: [f64; 2],
}

impl Slope {
    /// A plane through `origin` at `height` \[m\], inclined `angle_deg` (|α| < 90°)
    /// with ascent towards `direction_deg`.
    pub fn new(
        angle_deg: f64,
        direction_deg: f64,
        origin: [f64; 2],
        height: f64,
    ) -> Result<Slope, TerrainError> {
        if !(angle_deg.is_finite() && angle_deg.abs() < 90.0) {
            return Err(TerrainError::parameter(
                "angle_deg",
                format!("the slope angle must be between -90° and 90°, got {angle_deg}"),
                "give the inclination in degrees; use direction_deg to say which way it rises",
            ));
        }
        let e = unit_vector("direction_deg", direction_deg)?;
        let tan = angle_deg.to_radians().tan();
        Ok(Slope {
            origin: [
                finite("origin[0]", origin[0], "m")?,
                finite("origin[1]", origin[1], "m")?,
            ],
            height: finite("height", height, "m")?,
            gradient: [tan * e[0], tan * e[1]],
        })
    }

    /// The slope as a [`Plane`] (its heights are that plane's, bit for bit).
    #[inline]
    pub fn as_plane(&self) -> Plane {
        Plane {
            origin: self.origin,
            height: self.height,
            gradient: self.gradient,
        }
    }

    /// The gradient `[∂Z/∂X, ∂Z/∂Y]`, the same everywhere.
    pub fn gradient(&self) -> [f64; 2] {
        self.gradient
    }
}

impl HeightField for Slope {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        self.height_gradient(x, y).map(|(z, _)| z)
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        finite_point(x, y)?;
        let z = self.as_plane().height_at(x, y);
        if !z.is_finite() {
            // Only for points ~1e300 m away on a steep slope.
            return Err(OffMap {
                x,
                y,
                bounds: super::height_field::Bounds::UNBOUNDED,
            });
        }
        Ok((z, self.gradient))
    }

    /// The plane's largest value is at a corner of the area.
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        if !area.is_finite() {
            return None;
        }
        let x = if self.gradient[0] > 0.0 {
            area.x_max
        } else {
            area.x_min
        };
        let y = if self.gradient[1] > 0.0 {
            area.y_max
        } else {
            area.y_min
        };
        self.height(x, y).ok()
    }

    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite()
            .then(|| self.gradient[0].hypot(self.gradient[1]))
    }

    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then_some(0.0)
    }

    fn plane(&self) -> Option<Plane> {
        Some(self.as_plane())
    }
}
