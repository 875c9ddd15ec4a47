//! A raised-cosine bump.

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap, finite_point};
use super::profile::{Footprint, Profile};

/// A bump of `height` on flat ground at Z = 0 (MODEL.md §6, the terrain
/// library): a flat top of `top_width`
/// (0 for a pointed cosine bump) and raised-cosine flanks, full base `width`:
/// ```text
/// Z_G = h·p(s),  p as in the profile: 1 on the top, (1 + cos(π·(|s| − top/2)/r))/2
///                on the flanks (r = (width − top_width)/2), 0 beyond
/// ```
/// `s` is the distance from `center` along `direction_deg` (ridge footprint)
/// or from the centre point (round footprint). C1; steepest slope
/// `atan(π·h/(2r))` at mid-flank. With `top_width = 0` it is the classic
/// `h·(1 + cos(2π·s/width))/2`, |s| < width/2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bump {
    profile: Profile,
}

impl Bump {
    /// A bump `height` \[m\] high (negative digs a dip), `width` \[m\] at the base,
    /// `top_width` \[m\] flat on top, centred on `center` \[m\].
    pub fn new(
        height: f64,
        width: f64,
        top_width: f64,
        center: [f64; 2],
        direction_deg: f64,
        footprint: Footprint,
    ) -> Result<Bump, TerrainError> {
        Ok(Bump {
            profile: Profile::new(
                ["height", "width", "top_width"],
                height,
                width,
                top_width,
                center,
                direction_deg,
                footprint,
            )?,
        })
    }
}

impl HeightField for Bump {
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
