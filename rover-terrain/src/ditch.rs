//! A trench with a flat bottom and raised-cosine walls.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, finite_point};
use super::profile::{Footprint, Profile};

/// A ditch `depth` deep in flat ground at Z = 0 (MODEL.md §6, the terrain
/// library): the negative of a bump,
/// i.e. a trapezoidal trench whose walls are raised-cosine ramps (so the
/// surface stays C1, with no corner at the rim or the floor):
/// ```text
/// Z_G = −d·p(s),  p = 1 on the floor (|s| ≤ bottom_width/2), the cosine wall
///                 (1 + cos(π·(|s| − bottom_width/2)/r))/2 with r = (width − bottom_width)/2,
///                 0 beyond |s| = width/2
/// ```
/// `width` is the opening at ground level, `bottom_width` the flat floor
/// (0: a pure cosine trough). Steepest wall `atan(π·d/(2r))` at mid-wall.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ditch {
    profile: Profile,
}

impl Ditch {
    /// A ditch `depth` \[m\] deep (> 0), `width` \[m\] wide at the top,
    /// `bottom_width` \[m\] of flat floor, centred on `center` \[m\].
    pub fn new(
        depth: f64,
        width: f64,
        bottom_width: f64,
        center: [f64; 2],
        direction_deg: f64,
        footprint: Footprint,
    ) -> Result<Ditch, TerrainError> {
        if !(depth.is_finite() && depth > 0.0) {
            return Err(TerrainError::parameter(
                "depth",
                format!("must be > 0 m, got {depth}"),
                "give the depth below the surrounding ground as a positive number of metres",
            ));
        }
        Ok(Ditch {
            profile: Profile::new(
                ["depth", "width", "bottom_width"],
                -depth,
                width,
                bottom_width,
                center,
                direction_deg,
                footprint,
            )?,
        })
    }
}

impl HeightField for Ditch {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        finite_point(x, y)?;
        Ok(self.profile.evaluate(x, y).0)
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        finite_point(x, y)?;
        Ok(self.profile.evaluate(x, y))
    }

    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then(|| self.profile.max_height())
    }

    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then(|| self.profile.steepest())
    }

    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        area.is_finite().then(|| self.profile.curvature())
    }
}
