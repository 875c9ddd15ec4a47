//! A regular grid of heights with a bicubic (default) or bilinear interpolant.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap};
use super::kernel::{catmull_rom, stencil};
use super::range_pyramid::RangePyramid;

/// Tolerance, in cells, for a query on the map's edge.
const EDGE_SLACK: f64 = 1e-9;

/// How far the bicubic interpolant can rise above its nodes, as a share of
/// their range: the Catmull–Rom weights' negative lobes sum to at most
/// 1/8 in one dimension (Σ|w| ≤ 1.25, ghost nodes included), so the tensor
/// product's to (1.25² − 1)/2 = 0.28125; rounded up.
const BICUBIC_OVERSHOOT: f64 = 0.3;

/// How heights between grid nodes are computed (MODEL.md §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Interpolation {
    /// Catmull–Rom bicubic (tensor product, see the `kernel` docs): passes
    /// through the nodes, C1 everywhere on the map (continuous height and
    /// gradient, so contact forces are continuous for the integrator),
    /// exact for quadratics `a + bX + cY + dX² + eXY + fY²`
    /// (and their tensor products up to degree 2 in each of X, Y). The default.
    #[default]
    Bicubic,
    /// Bilinear: C0, exact for planes; the gradient jumps across cell edges.
    Bilinear,
}

/// What a query outside the grid's nodes gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgePolicy {
    /// Leaving the map is an [`OffMap`] error (the default): a simulation that
    /// drives off its terrain stops and says where, rather than inventing ground.
    #[default]
    Error,
    /// The coordinate is clamped to the map: beyond an edge the ground holds
    /// the edge height (a horizontal extension), and the gradient component
    /// across that edge is zero there. Non-finite queries are still errors.
    Clamp,
}

/// A regular grid of heights `Z_G` \[m\] at nodes `(X0 + i·dx, Y0 + j·dy)`,
/// `i = 0 … nx−1` eastward, `j = 0 … ny−1` northward.
///
/// Heights are stored row by row from the south row (`j = 0`), west to east:
/// `heights[j·nx + i]`. The map covers `[X0, X0 + (nx−1)·dx] × [Y0, Y0 + (ny−1)·dy]`
/// (node to node; a file's cells are read as nodes at their centres).
/// Cloning is cheap: the heights are shared.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    origin: [f64; 2],
    spacing: [f64; 2],
    nx: usize,
    ny: usize,
    /// `[nx − 1, ny − 1]` as floats, the last node's local coordinate:
    /// converted once (an unsigned conversion is a dozen instructions at
    /// the baseline x86-64 target, and every height query needs both).
    last: [f64; 2],
    heights: Arc<[f64]>,
    tiles: Arc<RangePyramid>,
    interpolation: Interpolation,
    edge: EdgePolicy,
}

impl Grid {
    /// A grid from its south-west node `origin` \[m\], node `spacing` `[dx, dy]` \[m\],
    /// node counts and `heights` (south row first, see [`Grid`]).
    ///
    /// Needs at least 2 × 2 nodes, finite origin, finite positive spacing, and
    /// `nx·ny` finite heights. Bicubic, edge policy [`EdgePolicy::Error`].
    pub fn new(
        origin: [f64; 2],
        spacing: [f64; 2],
        nx: usize,
        ny: usize,
        heights: Vec<f64>,
    ) -> Result<Grid, TerrainError> {
        for (name, value) in [("origin[0]", origin[0]), ("origin[1]", origin[1])] {
            if !value.is_finite() {
                return Err(TerrainError::parameter(
                    name,
                    format!("the grid origin must be a finite coordinate, got {value}"),
                    "give the south-west node's X, Y in metres",
                ));
            }
        }
        for (name, value) in [("spacing[0]", spacing[0]), ("spacing[1]", spacing[1])] {
            if !(value.is_finite() && value > 0.0) {
                return Err(TerrainError::parameter(
                    name,
                    format!("the grid spacing must be > 0 m, got {value}"),
                    "give the distance between neighbouring nodes in metres",
                ));
            }
        }
        if nx < 2 || ny < 2 {
            return Err(TerrainError::parameter(
                "grid",
                format!("a grid needs at least 2 × 2 nodes, got {nx} × {ny}"),
                "interpolation needs a node on each side of every cell",
            ));
        }
        let count = nx.checked_mul(ny);
        if count != Some(heights.len()) {
            return Err(TerrainError::parameter(
                "grid",
                format!(
                    "{nx} × {ny} nodes need {} heights, got {}",
                    nx.saturating_mul(ny),
                    heights.len()
                ),
                "give one height per node, south row first, west to east",
            ));
        }
        if let Some(k) = heights.iter().position(|z| !z.is_finite()) {
            return Err(TerrainError::parameter(
                "grid",
                format!(
                    "the height at node (i = {}, j = {}) is {}, not a finite number",
                    k % nx,
                    k / nx,
                    heights[k]
                ),
                "every node needs a finite height in metres",
            ));
        }
        Ok(Grid {
            origin,
            spacing,
            nx,
            ny,
            last: [(nx - 1) as f64, (ny - 1) as f64],
            tiles: Arc::new(RangePyramid::new(nx, &heights)),
            heights: heights.into(),
            interpolation: Interpolation::default(),
            edge: EdgePolicy::default(),
        })
    }

    /// A grid sampled from `f(X, Y)` at its nodes (see [`Grid::new`]).
    pub fn from_fn(
        origin: [f64; 2],
        spacing: [f64; 2],
        nx: usize,
        ny: usize,
        mut f: impl FnMut(f64, f64) -> f64,
    ) -> Result<Grid, TerrainError> {
        let count = nx.checked_mul(ny).ok_or_else(|| {
            TerrainError::parameter(
                "grid",
                format!("{nx} × {ny} nodes is too many"),
                "use a coarser spacing or a smaller extent",
            )
        })?;
        let mut heights = Vec::with_capacity(count);
        for j in 0..ny {
            for i in 0..nx {
                heights.push(f(
                    origin[0] + i as f64 * spacing[0],
                    origin[1] + j as f64 * spacing[1],
                ));
            }
        }
        Grid::new(origin, spacing, nx, ny, heights)
    }

    /// The same grid with another interpolant.
    pub fn with_interpolation(mut self, interpolation: Interpolation) -> Grid {
        self.interpolation = interpolation;
        self
    }

    /// The same grid with another edge policy.
    pub fn with_edge_policy(mut self, edge: EdgePolicy) -> Grid {
        self.edge = edge;
        self
    }

    /// The south-west node `[X0, Y0]` \[m\].
    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    /// The node spacing `[dx, dy]` \[m\].
    pub fn spacing(&self) -> [f64; 2] {
        self.spacing
    }

    /// Nodes along X.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Nodes along Y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// All heights, south row first, west to east.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The height at node (`i`, `j`), if it exists.
    pub fn node(&self, i: usize, j: usize) -> Option<f64> {
        if i < self.nx && j < self.ny {
            self.heights.get(j * self.nx + i).copied()
        } else {
            None
        }
    }

    /// The interpolant in use.
    pub fn interpolation(&self) -> Interpolation {
        self.interpolation
    }

    /// The edge policy in use.
    pub fn edge_policy(&self) -> EdgePolicy {
        self.edge
    }

    /// The area covered by the nodes.
    pub fn bounds(&self) -> Bounds {
        Bounds {
            x_min: self.origin[0],
            x_max: self.origin[0] + (self.nx - 1) as f64 * self.spacing[0],
            y_min: self.origin[1],
            y_max: self.origin[1] + (self.ny - 1) as f64 * self.spacing[1],
        }
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> f64 {
        // i < nx and j < ny by construction of every caller; `get` keeps this
        // panic-free even so.
        self.heights.get(j * self.nx + i).copied().unwrap_or(0.0)
    }

    /// Locates `x` along one axis: the cell index, the local coordinate in
    /// `[0, 1]`, and whether the coordinate was clamped (then the derivative
    /// along this axis is zero). `None` when off the map.
    #[inline]
    fn locate(&self, value: f64, axis: usize) -> Option<(usize, f64, bool)> {
        let (origin, spacing, last, n) = (
            self.origin[axis],
            self.spacing[axis],
            self.last[axis],
            if axis == 0 { self.nx } else { self.ny },
        );
        let mut u = (value - origin) / spacing;
        let mut clamped = false;
        // A point on the edge, as `bounds()` computes it, may land a rounding
        // error outside: accept 1e-9 of a cell and snap it in.
        if (-EDGE_SLACK..0.0).contains(&u) {
            u = 0.0;
        } else if u > last && u <= last + EDGE_SLACK {
            u = last;
        }
        if !(u >= 0.0 && u <= last) {
            match self.edge {
                EdgePolicy::Error => return None,
                EdgePolicy::Clamp => {
                    if u.is_nan() || !value.is_finite() {
                        return None;
                    }
                    u = u.clamp(0.0, last);
                    clamped = true;
                }
            }
        }
        // u ∈ [0, n−1] (n < 2⁵³), so truncation is the floor and every
        // conversion is exact. Through i64, not `floor` and usize: the
        // baseline x86-64 target has no instruction for either (a software
        // floor and unsigned fix-ups were a fifth of the grid's share of the
        // contact search, callgrind).
        let k = (u as i64 as usize).min(n - 2);
        Some((k, u - k as i64 as f64, clamped))
    }

    /// The cell of (`x`, `y`) along both axes ([`Grid::locate`] each), or
    /// the off-map error. Always inlined: as a call it cost the contact
    /// search on a grid 6 % more instructions (callgrind).
    #[inline(always)]
    fn cell(&self, x: f64, y: f64) -> Result<[(usize, f64, bool); 2], OffMap> {
        let off = || OffMap {
            x,
            y,
            bounds: self.bounds(),
        };
        let along_x = self.locate(x, 0).ok_or_else(off)?;
        let along_y = self.locate(y, 1).ok_or_else(off)?;
        Ok([along_x, along_y])
    }

    #[inline]
    fn evaluate(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        let [(i, t, clamp_x), (j, s, clamp_y)] = self.cell(x, y)?;
        let (z, mut dz_dt, mut dz_ds) = match self.interpolation {
            Interpolation::Bicubic => self.bicubic(i, t, j, s),
            Interpolation::Bilinear => self.bilinear(i, t, j, s),
        };
        if clamp_x {
            dz_dt = 0.0;
        }
        if clamp_y {
            dz_ds = 0.0;
        }
        Ok((z, [dz_dt / self.spacing[0], dz_ds / self.spacing[1]]))
    }

    /// The height alone: what [`Grid::evaluate`] gives as its first value,
    /// bit for bit (the same operations in the same order), without the
    /// gradient's and, inside the map, the ghost nodes' work. The contact
    /// search asks this for every rim sample.
    #[inline]
    fn height_only(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        let [(i, t, _), (j, s, _)] = self.cell(x, y)?;
        Ok(match self.interpolation {
            Interpolation::Bicubic => match self.interior_block(i, j) {
                Some(block) => {
                    let (wx, _) = catmull_rom(t);
                    let (wy, _) = catmull_rom(s);
                    let mut z = 0.0;
                    for k in 0..4 {
                        let p = block[k];
                        z += wy[k] * (wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3]);
                    }
                    z
                }
                None => self.bicubic(i, t, j, s).0,
            },
            Interpolation::Bilinear => self.bilinear(i, t, j, s).0,
        })
    }

    /// The 4 × 4 nodes around cell (i, j), rows of increasing Y, when none is
    /// a ghost (the cell is not on the map's edge).
    #[inline]
    fn interior_block(&self, i: usize, j: usize) -> Option<[&[f64; 4]; 4]> {
        if i == 0 || i + 2 >= self.nx || j == 0 || j + 2 >= self.ny {
            return None;
        }
        let row = |r: usize| -> Option<&[f64; 4]> {
            let start = r * self.nx + i - 1;
            self.heights.get(start..start + 4)?.try_into().ok()
        };
        Some([row(j - 1)?, row(j)?, row(j + 1)?, row(j + 2)?])
    }

    /// Height and derivatives with respect to the local cell coordinates.
    #[inline]
    fn bicubic(&self, i: usize, t: f64, j: usize, s: f64) -> (f64, f64, f64) {
        let (wx, dwx) = catmull_rom(t);
        let (wy, dwy) = catmull_rom(s);
        // Interpolate each stencil row along X (value and X-derivative); ghost
        // rows extrapolate from real rows, which is the same as extrapolating
        // their nodes because both steps are linear.
        let row = |r: usize| -> [f64; 2] {
            let p = stencil(self.nx, i, |c| self.at(c, r));
            [
                wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3],
                dwx[0] * p[0] + dwx[1] * p[1] + dwx[2] * p[2] + dwx[3] * p[3],
            ]
        };
        let rows = stencil(self.ny, j, row);
        let mut z = 0.0;
        let mut dz_dt = 0.0;
        let mut dz_ds = 0.0;
        for k in 0..4 {
            z += wy[k] * rows[k][0];
            dz_dt += wy[k] * rows[k][1];
            dz_ds += dwy[k] * rows[k][0];
        }
        (z, dz_dt, dz_ds)
    }

    #[inline]
    fn bilinear(&self, i: usize, t: f64, j: usize, s: f64) -> (f64, f64, f64) {
        let z00 = self.at(i, j);
        let z10 = self.at(i + 1, j);
        let z01 = self.at(i, j + 1);
        let z11 = self.at(i + 1, j + 1);
        let south = z00 + t * (z10 - z00);
        let north = z01 + t * (z11 - z01);
        let z = south + s * (north - south);
        let dz_dt = (1.0 - s) * (z10 - z00) + s * (z11 - z01);
        let dz_ds = north - south;
        (z, dz_dt, dz_ds)
    }
}

impl HeightField for Grid {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        self.height_only(x, y)
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        self.evaluate(x, y)
    }

    /// The highest node whose cell's stencil reaches into `area` (plus the
    /// bicubic overshoot), read from the range pyramid; `None` if part of the area is
    /// off the map under the `error` edge policy.
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        if !area.is_finite() {
            return None;
        }
        let map = self.bounds();
        if self.edge == EdgePolicy::Error
            && !(map.contains(area.x_min, area.y_min) && map.contains(area.x_max, area.y_max))
        {
            return None;
        }
        // Cells touched, widened by the stencil (one node before, two after);
        // clamping also covers queries held at the edge.
        let nodes = |lo: f64, hi: f64, axis: usize| {
            let (origin, spacing, last) = (self.origin[axis], self.spacing[axis], self.last[axis]);
            let first = ((lo - origin) / spacing).floor() - 1.0;
            let end = ((hi - origin) / spacing).floor() + 2.0;
            // Clamped into [0, n − 1]: the casts are exact.
            [
                first.clamp(0.0, last) as usize,
                end.clamp(0.0, last) as usize,
            ]
        };
        let i = nodes(area.x_min, area.x_max, 0);
        let j = nodes(area.y_min, area.y_max, 1);
        let (hi, lo) = self.tiles.span(i, j);
        Some(match self.interpolation {
            Interpolation::Bilinear => hi,
            Interpolation::Bicubic => hi + BICUBIC_OVERSHOOT * (hi - lo),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The height-only query is the full query's height, bit for bit, inside
    /// the map, in its edge cells (ghost nodes) and beyond a clamped edge.
    #[test]
    fn height_alone_is_the_height_of_the_full_query() {
        let f = |x: f64, y: f64| 0.03 * (7.0 * x).sin() * (5.0 * y).cos() + 0.01 * (23.0 * y).sin();
        let mut rng = crate::terrain::prng::SplitMix64::new(0x2545_f491_4f6c_dd1d);
        let mut uniform = |lo: f64, hi: f64| lo + (hi - lo) * rng.next_f64();
        for interpolation in [Interpolation::Bicubic, Interpolation::Bilinear] {
            for edge in [EdgePolicy::Error, EdgePolicy::Clamp] {
                let grid = Grid::from_fn([-1.0, -0.5], [0.1, 0.05], 21, 23, f)
                    .unwrap()
                    .with_interpolation(interpolation)
                    .with_edge_policy(edge);
                let mut interior = 0;
                for _ in 0..5000 {
                    let (x, y) = (uniform(-1.2, 1.2), uniform(-0.7, 0.8));
                    let full = grid.evaluate(x, y).map(|(z, _)| z.to_bits());
                    let alone = grid.height(x, y).map(f64::to_bits);
                    assert_eq!(full, alone, "{interpolation:?} {edge:?} at ({x}, {y})");
                    interior += usize::from(x.abs() < 0.85 && (y - 0.05).abs() < 0.45);
                }
                assert!(interior > 2000);
            }
        }
    }
}
