//! Flat horizontal ground.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, Plane, finite_point};
use super::param::finite;

/// Horizontal ground at a constant height: `Z_G = z0`. Unbounded
/// (MODEL.md §6, the terrain library).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flat {
    height: f64,
}

impl Flat {
    /// Flat ground at `height` \[m\].
    pub fn new(height: f64) -> Result<Flat, TerrainError> {
        Ok(Flat {
            height: finite("height", height, "m")?,
        })
    }

    /// The ground height \[m\].
    pub fn level(&self) -> f64 {
        self.height
    }
}

impl Default for Flat {
    /// Ground at Z = 0.
    fn default() -> Flat {
        Flat { height: 0.0 }
    }
}

impl HeightField for Flat {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        finite_point(x, y)?;
        Ok(self.height)
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        finite_point(x, y)?;
        Ok((self.height, [0.0, 0.0]))
    }

    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then_some(self.height)
    }

    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then_some(0.0)
    }

    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then_some(0.0)
    }

    fn plane(&self) -> Option<Plane> {
        Some(Plane {
            origin: [0.0, 0.0],
            height: self.height,
            gradient: [0.0, 0.0],
        })
    }
}
