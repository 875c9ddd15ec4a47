//! Where a grid without its own georeference (a PNG, a bare CSV matrix) lies.

use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::param::{finite, positive};

/// The position of a grid's south-west node and the node spacing, for files
/// that do not carry them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Georeference {
    /// `[X, Y]` \[m\] of the south-west node (for an image, the centre of the
    /// bottom-left pixel).
    pub origin: [f64; 2],
    /// `[dx, dy]` \[m\] between neighbouring nodes (pixel centres).
    pub spacing: [f64; 2],
}

impl Georeference {
    /// Checks the numbers (finite origin, positive spacing).
    pub fn check(&self) -> Result<Georeference, TerrainError> {
        finite("origin[0]", self.origin[0], "m")?;
        finite("origin[1]", self.origin[1], "m")?;
        positive("spacing[0]", self.spacing[0], "m")?;
        positive("spacing[1]", self.spacing[1], "m")?;
        Ok(*self)
    }
}
