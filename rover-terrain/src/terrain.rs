//! The terrain the simulator drives on: any kind of the library, or a grid.

use super::bump::Bump;
use super::ditch::Ditch;
use super::flat::Flat;
use super::grid::Grid;
use super::height_field::{Bounds, HeightField, OffMap, Plane};
use super::sinusoid::Sinusoid;
use super::slope::Slope;
use super::step::Step;
use rover_dynamics::bicubic::BicubicCell;

/// Any terrain: the analytic library (exact heights and gradients, unbounded)
/// or a grid (loaded from a file, or the random field of MODEL.md §11).
///
/// `Send + Sync + Clone` (a grid's heights are shared, not copied); queries
/// dispatch with one `match`, no allocation. The default is flat ground at Z = 0.
#[derive(Debug, Clone, PartialEq)]
pub enum Terrain {
    /// Horizontal ground.
    Flat(Flat),
    /// An inclined plane.
    Slope(Slope),
    /// A raised-cosine bump.
    Bump(Bump),
    /// A trench.
    Ditch(Ditch),
    /// A step, sharp or smoothed.
    Step(Step),
    /// Sinusoidal corrugations.
    Sinusoid(Sinusoid),
    /// A grid of heights with its interpolant and edge policy.
    Grid(Grid),
}

impl Default for Terrain {
    fn default() -> Terrain {
        Terrain::Flat(Flat::default())
    }
}

impl Terrain {
    /// The area where queries succeed (infinite for the analytic kinds and
    /// for a grid whose edge policy is `clamp`).
    pub fn bounds(&self) -> Bounds {
        match self {
            Terrain::Grid(grid) => match grid.edge_policy() {
                super::grid::EdgePolicy::Error => grid.bounds(),
                super::grid::EdgePolicy::Clamp => Bounds::UNBOUNDED,
            },
            _ => Bounds::UNBOUNDED,
        }
    }
}

impl HeightField for Terrain {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        match self {
            Terrain::Flat(t) => t.height(x, y),
            Terrain::Slope(t) => t.height(x, y),
            Terrain::Bump(t) => t.height(x, y),
            Terrain::Ditch(t) => t.height(x, y),
            Terrain::Step(t) => t.height(x, y),
            Terrain::Sinusoid(t) => t.height(x, y),
            Terrain::Grid(t) => t.height(x, y),
        }
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        match self {
            Terrain::Flat(t) => t.height_gradient(x, y),
            Terrain::Slope(t) => t.height_gradient(x, y),
            Terrain::Bump(t) => t.height_gradient(x, y),
            Terrain::Ditch(t) => t.height_gradient(x, y),
            Terrain::Step(t) => t.height_gradient(x, y),
            Terrain::Sinusoid(t) => t.height_gradient(x, y),
            Terrain::Grid(t) => t.height_gradient(x, y),
        }
    }

    #[inline]
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        match self {
            Terrain::Flat(t) => t.max_height_in(area),
            Terrain::Slope(t) => t.max_height_in(area),
            Terrain::Bump(t) => t.max_height_in(area),
            Terrain::Ditch(t) => t.max_height_in(area),
            Terrain::Step(t) => t.max_height_in(area),
            Terrain::Sinusoid(t) => t.max_height_in(area),
            Terrain::Grid(t) => t.max_height_in(area),
        }
    }

    #[inline]
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        match self {
            Terrain::Flat(t) => t.max_slope_in(area),
            Terrain::Slope(t) => t.max_slope_in(area),
            Terrain::Bump(t) => t.max_slope_in(area),
            Terrain::Ditch(t) => t.max_slope_in(area),
            Terrain::Step(t) => t.max_slope_in(area),
            Terrain::Sinusoid(t) => t.max_slope_in(area),
            Terrain::Grid(t) => t.max_slope_in(area),
        }
    }

    #[inline]
    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        match self {
            Terrain::Flat(t) => t.max_curvature_in(area),
            Terrain::Slope(t) => t.max_curvature_in(area),
            Terrain::Bump(t) => t.max_curvature_in(area),
            Terrain::Ditch(t) => t.max_curvature_in(area),
            Terrain::Step(t) => t.max_curvature_in(area),
            Terrain::Sinusoid(t) => t.max_curvature_in(area),
            Terrain::Grid(t) => t.max_curvature_in(area),
        }
    }

    #[inline]
    fn plane(&self) -> Option<Plane> {
        match self {
            Terrain::Flat(t) => t.plane(),
            Terrain::Slope(t) => t.plane(),
            _ => None,
        }
    }

    #[inline]
    fn surface(&self) -> u64 {
        match self {
            Terrain::Grid(t) => t.surface(),
            _ => 0,
        }
    }

    #[inline]
    fn bicubic_cell(&self, x: f64, y: f64) -> Option<BicubicCell> {
        match self {
            Terrain::Grid(t) => t.bicubic_cell(x, y),
            _ => None,
        }
    }
}

impl From<Grid> for Terrain {
    fn from(grid: Grid) -> Terrain {
        Terrain::Grid(grid)
    }
}
