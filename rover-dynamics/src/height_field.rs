//! The height-field interface the contact code queries, and the off-map
//! error (MODEL.md §6). No allocation and no `std`: a rig running a
//! generated plant implements [`HeightField`] for its own map.

use core::fmt;

use crate::bicubic::BicubicCell;

/// A ground surface `Z_G(X, Y)` (MODEL.md §6), queried in the simulation hot loop.
///
/// The contact search calls these a few times per wheel per right-hand-side
/// evaluation (a few dozen for the sampled search), so implementations do no
/// allocation, take no lock and return in a few tens of nanoseconds. Coordinates are inertial `X`, `Y` \[m\]; heights are
/// inertial `Z` \[m\], positive up.
///
/// A query that cannot be answered — a point outside a finite map under the
/// default edge policy, or a non-finite coordinate — returns [`OffMap`]; an
/// implementation never returns a NaN or infinite height.
pub trait HeightField {
    /// Ground height `Z_G` \[m\] at inertial (`x`, `y`) \[m\], or the off-map error.
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap>;

    /// Height `Z_G` \[m\] and gradient `[∂Z_G/∂X, ∂Z_G/∂Y]` [m/m] at (`x`, `y`).
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap>;

    /// An upper bound of `Z_G` \[m\] over the rectangle `area`, given only when
    /// every point of it can be queried (no [`OffMap`]); `None` when either
    /// is unknown. The contact search samples only the part of the rim that
    /// can reach below this bound, so a tight bound saves time and a loose one
    /// costs only time: results are the same either way. The default knows
    /// nothing.
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        let _ = area;
        None
    }

    /// An upper bound of the gradient's magnitude `|∇Z_G|` [m/m] over the
    /// rectangle `area`, given only when every point of it can be queried;
    /// `None` when either is unknown (the default) or the surface has a
    /// jump there. The contact search uses it to skip rim samples that
    /// cannot reach the ground from the last height it queried; like
    /// [`HeightField::max_height_in`], a loose bound costs only time.
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        let _ = area;
        None
    }

    /// An upper bound of the curvature: of the Hessian's spectral norm
    /// `‖∇²Z_G‖₂` [1/m] over the rectangle `area`, given only when every
    /// point of it can be queried and the gradient is Lipschitz there with
    /// that constant (a C1 surface whose second derivatives are bounded,
    /// jumps of them between cells allowed); `None` when either is unknown
    /// (the default) or the surface has a crease or a jump there. The
    /// bounded contact search uses it to prove which stretches of the rim
    /// cannot meet the ground without sampling them; a loose bound costs
    /// only time, a missing one sends it back to the sampled search.
    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        let _ = area;
        None
    }

    /// The plane the whole terrain is, when it is one (flat ground, a
    /// slope): the contact search then cuts the rim with it in closed form
    /// instead of sampling it. `None` (the default) for any other surface;
    /// a terrain that says `Some` must give exactly that plane's heights
    /// at every finite point.
    fn plane(&self) -> Option<Plane> {
        None
    }

    /// A token naming this surface, for the queries that keep a piece of
    /// it between calls ([`HeightField::bicubic_cell`]): two values that
    /// give the same token give the same heights everywhere, and a token
    /// is never handed to another surface. 0 (the default) names none:
    /// nothing is kept.
    fn surface(&self) -> u64 {
        0
    }

    /// The interior bicubic cell that holds (`x`, `y`), for a surface made
    /// of them (a grid under its bicubic interpolant, away from its edges);
    /// `None` (the default) elsewhere. A terrain that gives a cell must give
    /// exactly the cell's heights and gradients
    /// ([`BicubicCell::height_gradient`]) at every point the cell holds, and
    /// a nonzero [`HeightField::surface`]. The contact search keeps each
    /// wheel's last few cells ([`crate::bicubic::KeptCells`]).
    fn bicubic_cell(&self, x: f64, y: f64) -> Option<BicubicCell> {
        let _ = (x, y);
        None
    }
}

/// A plane `Z = height + gradient·((X, Y) − origin)` \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// A point (X0, Y0) of the plane's horizontal projection \[m\].
    pub origin: [f64; 2],
    /// The plane's height at `origin` \[m\].
    pub height: f64,
    /// `[∂Z/∂X, ∂Z/∂Y]` [m/m].
    pub gradient: [f64; 2],
}

impl Plane {
    /// The height at (`x`, `y`) \[m\].
    #[inline]
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        self.height
            + self.gradient[0] * (x - self.origin[0])
            + self.gradient[1] * (y - self.origin[1])
    }
}

impl<H: HeightField + ?Sized> HeightField for &H {
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        (**self).height(x, y)
    }

    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        (**self).height_gradient(x, y)
    }

    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        (**self).max_height_in(area)
    }

    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        (**self).max_slope_in(area)
    }

    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        (**self).max_curvature_in(area)
    }

    fn plane(&self) -> Option<Plane> {
        (**self).plane()
    }

    fn surface(&self) -> u64 {
        (**self).surface()
    }

    fn bicubic_cell(&self, x: f64, y: f64) -> Option<BicubicCell> {
        (**self).bicubic_cell(x, y)
    }
}

/// A rectangle of the horizontal plane, `[x_min, x_max] × [y_min, y_max]` \[m\].
///
/// Unbounded terrains (the analytic library) report infinite bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Smallest `X` \[m\].
    pub x_min: f64,
    /// Largest `X` \[m\].
    pub x_max: f64,
    /// Smallest `Y` \[m\].
    pub y_min: f64,
    /// Largest `Y` \[m\].
    pub y_max: f64,
}

impl Bounds {
    /// The whole plane (every finite point).
    pub const UNBOUNDED: Bounds = Bounds {
        x_min: f64::NEG_INFINITY,
        x_max: f64::INFINITY,
        y_min: f64::NEG_INFINITY,
        y_max: f64::INFINITY,
    };

    /// Whether (`x`, `y`) lies inside, edges included; false for NaN.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        x >= self.x_min && x <= self.x_max && y >= self.y_min && y <= self.y_max
    }

    /// Whether every corner is a finite number (so is every point inside).
    pub fn is_finite(&self) -> bool {
        self.x_min.is_finite()
            && self.x_max.is_finite()
            && self.y_min.is_finite()
            && self.y_max.is_finite()
    }
}

/// A terrain query that fell outside the map (or had a non-finite coordinate).
///
/// Carries the queried point and the map's bounds so the simulator can report
/// which wheel left the map, when and where (MODEL.md §11).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffMap {
    /// Queried `X` \[m\].
    pub x: f64,
    /// Queried `Y` \[m\].
    pub y: f64,
    /// The area the terrain covers.
    pub bounds: Bounds,
}

impl fmt::Display for OffMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = &self.bounds;
        if !(self.x.is_finite() && self.y.is_finite()) {
            return write!(
                f,
                "terrain queried at a non-finite point (X = {} m, Y = {} m); \
                 the state has diverged before the contact search",
                self.x, self.y
            );
        }
        write!(
            f,
            "point (X = {} m, Y = {} m) is off the terrain map, which covers \
             X from {} m to {} m and Y from {} m to {} m; make the terrain larger \
             or set edge = \"clamp\" to hold the edge height beyond it",
            self.x, self.y, b.x_min, b.x_max, b.y_min, b.y_max
        )
    }
}

impl core::error::Error for OffMap {}
