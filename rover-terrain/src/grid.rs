//! A regular grid of heights with a bicubic (default) or bilinear interpolant.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use rover_dynamics::bicubic::{self, BicubicCell};

use serde::{Deserialize, Serialize};

use super::error::TerrainError;
use super::height_field::{Bounds, HeightField, OffMap};
use super::kernel::{Bound, catmull_rom, stencil};
use super::lazy_cells::LazyCells;
use super::range_pyramid::{RangePyramid, larger};

/// Tolerance, in cells, for a query on the map's edge.
const EDGE_SLACK: f64 = 1e-9;

/// Most nodes a terrain file may hold (as many as the random terrain's
/// grid): 50 M nodes take about 2 GB with their range pyramid.
pub const MAX_FILE_NODES: usize = 50_000_000;

/// A file's `nx × ny` grid within [`MAX_FILE_NODES`], checked before
/// anything of that size is allocated.
pub(crate) fn check_file_nodes(
    path: &std::path::Path,
    nx: usize,
    ny: usize,
) -> Result<(), TerrainError> {
    if nx.saturating_mul(ny) > MAX_FILE_NODES {
        return Err(super::error::FileError::at(
            path,
            super::error::Place::Whole,
            format!(
                "the grid is {nx} × {ny} = {} nodes; at most {MAX_FILE_NODES} are loaded",
                nx.saturating_mul(ny)
            ),
            "crop or downsample the map (gdal_translate -outsize, or -srcwin) to the area the rover drives over",
        ));
    }
    Ok(())
}

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
/// Cloning is cheap: the heights are shared. Two grids are equal when
/// their nodes, interpolant and edge policy are.
#[derive(Debug, Clone)]
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
    /// Bounds of the interpolant's gradient magnitude, cell by cell (cell
    /// (i, j) at node (i, j)), computed where [`HeightField::max_slope_in`]
    /// first asks.
    slopes: Arc<LazyCells>,
    /// Bounds of the bicubic interpolant's Hessian norm, cell by cell,
    /// computed where [`HeightField::max_curvature_in`] first asks.
    curvatures: Arc<LazyCells>,
    interpolation: Interpolation,
    edge: EdgePolicy,
    /// This grid's [`HeightField::surface`] token: one per grid built,
    /// interpolant and edge policy chosen; its clones (the same heights)
    /// share it.
    surface: u64,
}

impl PartialEq for Grid {
    /// Everything but the surface token (a grid read twice is one ground).
    fn eq(&self, other: &Grid) -> bool {
        self.origin == other.origin
            && self.spacing == other.spacing
            && self.nx == other.nx
            && self.ny == other.ny
            && self.heights == other.heights
            && self.interpolation == other.interpolation
            && self.edge == other.edge
    }
}

/// The last [`Grid`]'s surface token (0 names no surface).
static SURFACES: AtomicU64 = AtomicU64::new(0);

/// A token no grid has had.
fn new_surface() -> u64 {
    SURFACES.fetch_add(1, Ordering::Relaxed) + 1
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
        let heights: Arc<[f64]> = heights.into();
        let of_cell = Arc::clone(&heights);
        let curvature = move |i, j| cell_curvature(nx, ny, spacing, &of_cell, i, j);
        let of_cell = Arc::clone(&heights);
        let slope = move |i, j| cell_slope(nx, ny, spacing, &of_cell, i, j);
        Ok(Grid {
            origin,
            spacing,
            nx,
            ny,
            last: [(nx - 1) as f64, (ny - 1) as f64],
            tiles: Arc::new(RangePyramid::new(nx, &heights)),
            slopes: Arc::new(LazyCells::new(nx, ny, Box::new(slope))),
            curvatures: Arc::new(LazyCells::new(nx, ny, Box::new(curvature))),
            heights,
            interpolation: Interpolation::default(),
            edge: EdgePolicy::default(),
            surface: new_surface(),
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
        self.surface = new_surface();
        self
    }

    /// The same grid with another edge policy.
    pub fn with_edge_policy(mut self, edge: EdgePolicy) -> Grid {
        self.edge = edge;
        self.surface = new_surface();
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

    /// The index ranges `[[i0, i1], [j0, j1]]` of the nodes whose cells
    /// `area` touches, widened by `widen[0]` indices before and `widen[1]`
    /// after, clamped into `[0, n − 1 − shrink]` (`shrink` = 1 for cell
    /// indices); `None` for a non-finite area or, under the `error` edge
    /// policy, one that reaches off the map.
    fn index_ranges(&self, area: &Bounds, widen: [f64; 2], shrink: f64) -> Option<[[usize; 2]; 2]> {
        if !area.is_finite() {
            return None;
        }
        let map = self.bounds();
        if self.edge == EdgePolicy::Error
            && !(map.contains(area.x_min, area.y_min) && map.contains(area.x_max, area.y_max))
        {
            return None;
        }
        // ⌊u⌋ through i64 (exact below 2⁶³, where it saturates, and the
        // clamp below makes that the same): the baseline x86-64 target has
        // no instruction for `floor`, which is a call there.
        let floor = |u: f64| {
            let t = u as i64 as f64;
            if t > u { t - 1.0 } else { t }
        };
        let range = |lo: f64, hi: f64, axis: usize| {
            let (origin, spacing) = (self.origin[axis], self.spacing[axis]);
            let top = self.last[axis] - shrink;
            let first = floor((lo - origin) / spacing) - widen[0];
            let end = floor((hi - origin) / spacing) + widen[1];
            // Clamped into [0, top]: the casts are exact.
            [first.clamp(0.0, top) as usize, end.clamp(0.0, top) as usize]
        };
        Some([
            range(area.x_min, area.x_max, 0),
            range(area.y_min, area.y_max, 1),
        ])
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
                Some(block) => interior_height(block, catmull_rom(t).0, catmull_rom(s).0),
                None => self.bicubic(i, t, j, s).0,
            },
            Interpolation::Bilinear => self.bilinear(i, t, j, s).0,
        })
    }

    /// The interpolant at every point (`xs[i]`, `ys[j]`), row by row (`j`
    /// outer), each given to `emit(i, j, z)`: bit for bit what
    /// [`HeightField::height`] gives there (the same operations in the same
    /// order), with the cell and the kernel weights of each column and each
    /// row found once instead of at every point. What resampling a field
    /// onto a finer grid needs (the random terrain's 640,000 nodes cost a
    /// third of a whole Fig. 13 run when queried one by one, callgrind).
    pub(crate) fn sample_lattice(
        &self,
        xs: &[f64],
        ys: &[f64],
        mut emit: impl FnMut(usize, usize, f64),
    ) -> Result<(), OffMap> {
        let off = |x: f64, y: f64| OffMap {
            x,
            y,
            bounds: self.bounds(),
        };
        // The other coordinate of a point off the map, for the error.
        let (x0, y0) = (xs.first().copied(), ys.first().copied());
        let bicubic = self.interpolation == Interpolation::Bicubic;
        let mut columns = Vec::with_capacity(xs.len());
        for &x in xs {
            let (i, t, _) = self
                .locate(x, 0)
                .ok_or_else(|| off(x, y0.unwrap_or(f64::NAN)))?;
            columns.push((i, catmull_rom(t).0));
        }
        // An interior cell's height is `Σ_r wy_r·(wx·row_r)` over its four
        // node rows (`bicubic::height`). The products `wx·row_r` of a column
        // depend on the node row and the column only: every output row whose
        // stencil takes node row `r` shares them, so each is computed once
        // per node row and the sum over the rows is the same operations in
        // the same order. `dots[r % 4]` holds node row `r`'s, `held[r % 4]`
        // says which node row it holds.
        let mut dots = [(); 4].map(|_| vec![0.0; xs.len()]);
        let mut held = [usize::MAX; 4];
        for (j_out, &y) in ys.iter().enumerate() {
            let (j, s, _) = self
                .locate(y, 1)
                .ok_or_else(|| off(x0.unwrap_or(f64::NAN), y))?;
            let (wy, _) = catmull_rom(s);
            let interior_row = bicubic && j > 0 && j + 2 < self.ny;
            if interior_row {
                for r in j - 1..j + 3 {
                    if held[r % 4] != r {
                        self.row_dots(r, &columns, &mut dots[r % 4]);
                        held[r % 4] = r;
                    }
                }
            }
            for (i_out, (&x, &(i, _))) in xs.iter().zip(&columns).enumerate() {
                let z = if interior_row && i > 0 && i + 2 < self.nx {
                    let mut z = 0.0;
                    for (k, w) in wy.iter().enumerate() {
                        z += w * dots[(j - 1 + k) % 4][i_out];
                    }
                    z
                } else {
                    self.height_only(x, y)?
                };
                emit(i_out, j_out, z);
            }
        }
        Ok(())
    }

    /// `wx·row` for node row `r` under each column `(i, wx)` whose stencil
    /// is interior (`bicubic::height`'s inner products, in its order); 0
    /// under the others, which are not read.
    fn row_dots(&self, r: usize, columns: &[(usize, [f64; 4])], out: &mut [f64]) {
        let row = &self.heights[r * self.nx..(r + 1) * self.nx];
        for (d, &(i, wx)) in out.iter_mut().zip(columns) {
            *d = if i > 0 && i + 2 < self.nx {
                let p = &row[i - 1..i + 3];
                wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3]
            } else {
                0.0
            };
        }
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
    /// Inside the map the stencil rows are read as slices
    /// ([`Grid::interior_block`]); on its edge they take the ghost nodes.
    /// Both give the same bits (the same operations in the same order):
    /// the slices only spare the node-by-node reads, which were half of a
    /// query with its gradient (callgrind).
    #[inline]
    fn bicubic(&self, i: usize, t: f64, j: usize, s: f64) -> (f64, f64, f64) {
        self.bicubic_rows(i, t, j, s, self.interior_block(i, j))
    }

    /// [`Grid::bicubic`] from the interior block if given, else from the
    /// stencils.
    #[inline(always)]
    fn bicubic_rows(
        &self,
        i: usize,
        t: f64,
        j: usize,
        s: f64,
        block: Option<[&[f64; 4]; 4]>,
    ) -> (f64, f64, f64) {
        let (wx, dwx) = catmull_rom(t);
        let (wy, dwy) = catmull_rom(s);
        // Interpolate each stencil row along X (value and X-derivative); ghost
        // rows extrapolate from real rows, which is the same as extrapolating
        // their nodes because both steps are linear.
        let along = |p: [f64; 4]| bicubic::along(&wx, &dwx, &p);
        let rows = match block {
            // Written out: `block.map(…)` was an out-of-line
            // `array::try_map` call on every query with a gradient
            // (callgrind).
            Some([p0, p1, p2, p3]) => [along(*p0), along(*p1), along(*p2), along(*p3)],
            None => stencil(self.ny, j, |r| {
                along(stencil(self.nx, i, |c| self.at(c, r)))
            }),
        };
        bicubic::across(&wy, &dwy, &rows)
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

    fn surface(&self) -> u64 {
        self.surface
    }

    /// The interior cell of (`x`, `y`) under the bicubic interpolant:
    /// `None` on the bilinear one, in the cells along the map's edges
    /// (their stencils take ghost nodes) and off the map.
    #[inline]
    fn bicubic_cell(&self, x: f64, y: f64) -> Option<BicubicCell> {
        if self.interpolation != Interpolation::Bicubic {
            return None;
        }
        let [(i, _, clamp_x), (j, _, clamp_y)] = self.cell(x, y).ok()?;
        if clamp_x || clamp_y {
            return None;
        }
        let [p0, p1, p2, p3] = self.interior_block(i, j)?;
        Some(BicubicCell {
            origin: self.origin,
            spacing: self.spacing,
            corner: [i as f64, j as f64],
            nodes: [*p0, *p1, *p2, *p3],
        })
    }

    /// The highest node whose cell's stencil reaches into `area` (plus the
    /// bicubic overshoot), read from the range pyramid; `None` if part of the area is
    /// off the map under the `error` edge policy.
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        // Cells touched, widened by the stencil (one node before, two
        // after); clamping also covers queries held at the edge.
        let [i, j] = self.index_ranges(area, [1.0, 2.0], 0.0)?;
        let (hi, lo) = self.tiles.span(i, j);
        Some(match self.interpolation {
            Interpolation::Bilinear => hi,
            Interpolation::Bicubic => hi + BICUBIC_OVERSHOOT * (hi - lo),
        })
    }

    /// The largest cell bound (`cell_slope` in the source) over the cells that
    /// `area` touches; `None` if part of it is off the map under the
    /// `error` edge policy. Beyond a clamped edge the ground is the edge's
    /// height held: its gradient is the edge cell's along the edge, zero
    /// across it.
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        let [i, j] = self.index_ranges(area, [0.0, 0.0], 1.0)?;
        Some(self.slopes.max(i, j))
    }

    /// The largest cell bound (`cell_curvature` in the source) over the
    /// cells that `area` touches, for the bicubic interpolant; `None` for the
    /// bilinear one (its gradient jumps across cell edges) and for an area
    /// that reaches off the map (under the `clamp` policy the gradient jumps
    /// at the edge).
    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        if self.interpolation != Interpolation::Bicubic {
            return None;
        }
        let map = self.bounds();
        if !(map.contains(area.x_min, area.y_min) && map.contains(area.x_max, area.y_max)) {
            return None;
        }
        let [i, j] = self.index_ranges(area, [0.0, 0.0], 1.0)?;
        Some(self.curvatures.max(i, j))
    }
}

/// The bicubic height on an interior cell from its 4 × 4 nodes and the
/// kernel weights along X (`wx`) and Y (`wy`): one expression
/// (`rover_dynamics::bicubic::height`) for [`Grid::height_only`],
/// [`Grid::sample_lattice`] and a kept cell, so all give the same bits.
#[inline(always)]
fn interior_height(block: [&[f64; 4]; 4], wx: [f64; 4], wy: [f64; 4]) -> f64 {
    bicubic::height(block, &wx, &wy)
}

/// The bound of the interpolant's gradient magnitude on cell (i, j), at
/// its south-west node (`i < nx − 1`, `j < ny − 1`), for both
/// interpolants; the grid asks for them lazily ([`LazyCells`]).
///
/// On a cell, ∂Z/∂t = Σ_k w_k(s)·r_k'(t), where r_k is the Catmull–Rom
/// cubic along X of stencil row k = −1 … 2. Each r_k' is a quadratic in t,
/// whose largest magnitude b_k on [0, 1] is at an end or at its vertex
/// ([`steepest`]). The inner weights w0, w1 are positive and sum to
/// `1 + s(1 − s)/2 ≤ 9/8`, the outer ones negative and sum to
/// `−s(1 − s)/2 ≥ −1/8`, so `|∂Z/∂t| ≤ 9/8·max(b0, b1) + 1/8·max(b−1, b2)`,
/// and likewise along Y. A ghost row beyond the map's edge is a
/// combination of real rows (`3r0 − 3r1 + r2`, or `2r0 − r1` on a grid of
/// two rows), so its b is at most the same combination of their b with
/// every sign made positive. The bilinear interpolant's derivative along
/// X lies between the cell's two node differences p1 − p0, each of which
/// is some r_k'(t) (mean value theorem): the same bound holds for it.
fn cell_slope(nx: usize, ny: usize, spacing: [f64; 2], heights: &[f64], i: usize, j: usize) -> f64 {
    let at = |i: usize, j: usize| heights.get(j * nx + i).copied().unwrap_or(0.0);
    let combine = |b: [f64; 4]| 1.125 * larger(b[1], b[2]) + 0.125 * larger(b[0], b[3]);
    let (per_dx, per_dy) = (1.0 / spacing[0], 1.0 / spacing[1]);
    // b along X of stencil row r, and along Y of stencil column c.
    let along_x = |r: usize| steepest(stencil(nx, i, |c| at(c, r)));
    let along_y = |c: usize| steepest(stencil(ny, j, |r| at(c, r)));
    let gx = combine(ghost_bounds(ny, j, along_x)) * per_dx;
    let gy = combine(ghost_bounds(nx, i, along_y)) * per_dy;
    // Rounded up past the interpolant's own rounding (and the reciprocals').
    (gx * gx + gy * gy).sqrt() * (1.0 + 1e-9)
}

/// [`cell_slope`] row by row, south row first, each row given to `emit`
/// (0 on the last row and column): the b of the four stencil rows kept in
/// a ring, so that every b is computed once. The reference the tests hold
/// [`cell_slope`] to, bit for bit.
#[cfg(test)]
fn cell_slope_rows(
    nx: usize,
    ny: usize,
    spacing: [f64; 2],
    heights: &[f64],
    mut emit: impl FnMut(&[f64]),
) {
    let at = |i: usize, j: usize| heights.get(j * nx + i).copied().unwrap_or(0.0);
    // b along X of node row r, cell by cell: inside the map the stencils
    // are windows of real nodes; the edge cells take the ghosts.
    let along_x_of = |r: usize, b: &mut [f64]| {
        let row = &heights[r * nx..(r + 1) * nx];
        for (b, window) in b[1..].iter_mut().zip(row.windows(4)) {
            *b = steepest([window[0], window[1], window[2], window[3]]);
        }
        for i in [0, nx - 2] {
            b[i] = steepest(stencil(nx, i, |c| at(c, r)));
        }
    };
    // The rows j − 1 … j + 2 that cell row j reads, at [r % 4].
    let mut ring = [(); 4].map(|_| vec![0.0; nx]);
    let mut next = 0;
    let mut along_y = vec![0.0; nx];
    let mut slopes = vec![0.0; nx];
    let combine = |b: [f64; 4]| 1.125 * larger(b[1], b[2]) + 0.125 * larger(b[0], b[3]);
    let (per_dx, per_dy) = (1.0 / spacing[0], 1.0 / spacing[1]);
    // Rounded up past the interpolant's own rounding (and the reciprocals').
    let magnitude = |bx: [f64; 4], by: [f64; 4]| {
        let (gx, gy) = (combine(bx) * per_dx, combine(by) * per_dy);
        (gx * gx + gy * gy).sqrt() * (1.0 + 1e-9)
    };
    for j in 0..ny - 1 {
        while next <= (j + 2).min(ny - 1) {
            along_x_of(next, &mut ring[next % 4]);
            next += 1;
        }
        let interior = j >= 1 && j + 2 < ny;
        // b along Y of every node column c at cell row j.
        if interior {
            let rows = [j - 1, j, j + 1, j + 2].map(|r| &heights[r * nx..(r + 1) * nx]);
            for (c, b) in along_y.iter_mut().enumerate() {
                *b = steepest(rows.map(|row| row[c]));
            }
        } else {
            for (c, b) in along_y.iter_mut().enumerate() {
                *b = steepest(stencil(ny, j, |r| at(c, r)));
            }
        }
        if interior {
            let rows = [j - 1, j, j + 1, j + 2].map(|r| &ring[r % 4][..]);
            let cells = slopes[1..nx.saturating_sub(2)].iter_mut().enumerate();
            for ((k, slope), by) in cells.zip(along_y.windows(4)) {
                let i = k + 1;
                *slope = magnitude(rows.map(|row| row[i]), [by[0], by[1], by[2], by[3]]);
            }
        }
        for i in 0..nx - 1 {
            if !interior || i == 0 || i + 2 >= nx {
                slopes[i] = magnitude(
                    ghost_bounds(ny, j, |r| ring[r % 4][i]),
                    ghost_bounds(nx, i, |c| along_y[c]),
                );
            }
        }
        emit(&slopes);
    }
    // The last row starts no cell.
    slopes.fill(0.0);
    emit(&slopes);
}

/// The bound of the bicubic interpolant's curvature on cell (i, j) (at
/// node (i, j); the grid asks for them lazily, [`LazyCells`]).
///
/// On a cell with local coordinates t, s ∈ [0, 1] the interpolant is
/// `Σ_b w_b(s)·r_b(t)`, r_b the Catmull–Rom cubic along X of stencil row
/// b. Its second derivatives are bounded cell by cell:
/// - `∂²/∂t² = Σ_b w_b(s)·r_b''(t)`, with r_b'' linear in t (largest at an
///   end), combined over b as the slopes are (inner weights ≤ 9/8, outer
///   ≥ −1/8 in sum): `|Z_tt| ≤ 9/8·max(B_0, B_1) + 1/8·max(B_−1, B_2)`;
///   likewise `Z_ss` from the columns;
/// - `∂²/∂t∂s = Σ_b w_b'(s)·r_b'(t)`, with `Σ_b |w_b'(s)| ≤ 3` (at s = ½;
///   a test holds it) and `|r_b'| ≤` [`steepest`]: `|Z_ts| ≤ 3·max_b steepest(r_b)`.
///
/// The spectral norm of the Hessian is at most its Frobenius norm
/// `sqrt(Z_xx² + 2·Z_xy² + Z_yy²)`, with `Z_xx = Z_tt/dx²` and so on. The
/// stencils take the ghost nodes beyond the map's edges, as the interpolant
/// does. The second derivatives jump between cells (the interpolant is C1),
/// which a Lipschitz bound of the gradient allows.
fn cell_curvature(
    nx: usize,
    ny: usize,
    [dx, dy]: [f64; 2],
    heights: &[f64],
    i: usize,
    j: usize,
) -> f64 {
    let at = |i: usize, j: usize| heights.get(j * nx + i).copied().unwrap_or(0.0);
    let combine = |b: [f64; 4]| 1.125 * larger(b[1], b[2]) + 0.125 * larger(b[0], b[3]);
    // The largest |r''| of a stencil line's cubic: r'' is linear, largest at an end.
    let second = |[pm, p0, p1, p2]: [f64; 4]| {
        let start = 2.0 * pm - 5.0 * p0 + 4.0 * p1 - p2;
        let end = -pm + 4.0 * p0 - 5.0 * p1 + 2.0 * p2;
        larger(start.abs(), end.abs())
    };
    // block[b][a]: stencil row b (along Y), column a (along X).
    let block: [[f64; 4]; 4] = stencil(ny, j, |r| stencil(nx, i, |c| at(c, r)));
    // Written out, not with `array::map`, whose out-of-line calls were a
    // third of this function (callgrind; building a map's bounds is mostly
    // this function): the same operations in the same order otherwise.
    let [b0, b1, b2, b3] = block;
    let column = |a: usize| [b0[a], b1[a], b2[a], b3[a]];
    let zxx = combine([second(b0), second(b1), second(b2), second(b3)]) / (dx * dx);
    let zyy = combine([
        second(column(0)),
        second(column(1)),
        second(column(2)),
        second(column(3)),
    ]) / (dy * dy);
    let twist = larger(
        larger(
            larger(larger(0.0, steepest(b0)), steepest(b1)),
            steepest(b2),
        ),
        steepest(b3),
    );
    let zxy = 3.0 * twist / (dx * dy);
    // Rounded up past the arithmetic's own rounding.
    (zxx * zxx + 2.0 * zxy * zxy + zyy * zyy).sqrt() * (1.0 + 1e-9)
}

/// The largest magnitude over t ∈ [0, 1] of the derivative of the
/// Catmull–Rom cubic through `p`: `r'(t) = c + b·t + a·t²` (the weights'
/// derivatives of `kernel::catmull_rom` collected by power of t), largest
/// at an end or at the vertex.
fn steepest([pm, p0, p1, p2]: [f64; 4]) -> f64 {
    let c = 0.5 * (p1 - pm);
    let b = 2.0 * pm - 5.0 * p0 + 4.0 * p1 - p2;
    let a = 1.5 * (3.0 * (p0 - p1) + p2 - pm);
    let at_end = larger(c.abs(), (c + b + a).abs());
    let vertex = -b / (2.0 * a);
    if vertex > 0.0 && vertex < 1.0 {
        larger(at_end, (c + vertex * (b + vertex * a)).abs())
    } else {
        at_end
    }
}

/// The stencil of bounds `b ≥ 0` around cell `k` of a line of `n` nodes
/// ([`stencil`] over [`Bound`]: ghosts bounded by the triangle inequality).
fn ghost_bounds(n: usize, k: usize, fetch: impl Fn(usize) -> f64) -> [f64; 4] {
    stencil(n, k, |i| Bound(fetch(i))).map(|b| b.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interior block gives the stencils' bits.
    #[test]
    fn interior_blocks_are_the_stencils_bit_for_bit() {
        let f = |x: f64, y: f64| 0.03 * (7.0 * x).sin() * (5.0 * y).cos() + 0.01 * (23.0 * y).sin();
        let grid = Grid::from_fn([-1.0, -0.5], [0.1, 0.05], 21, 23, f).unwrap();
        let mut rng = crate::prng::SplitMix64::new(0x0dd_b1a5);
        let mut interior = 0;
        for _ in 0..5000 {
            let (i, j) = (
                (rng.next_u64() % 20) as usize,
                (rng.next_u64() % 22) as usize,
            );
            let (t, s) = (rng.next_f64(), rng.next_f64());
            let Some(block) = grid.interior_block(i, j) else {
                continue;
            };
            interior += 1;
            let bits = |(z, a, b): (f64, f64, f64)| [z.to_bits(), a.to_bits(), b.to_bits()];
            assert_eq!(
                bits(grid.bicubic_rows(i, t, j, s, Some(block))),
                bits(grid.bicubic_rows(i, t, j, s, None)),
                "cell ({i}, {j}) at ({t}, {s})"
            );
        }
        assert!(interior > 3000);
    }

    /// `Σ_b |w_b'(s)| ≤ 3` on [0, 1], the constant `cell_curvature` takes
    /// for the mixed derivative (reached at s = ½).
    #[test]
    fn the_kernel_slopes_sum_to_at_most_three() {
        let largest = (0..=1000)
            .map(|k| {
                let (_, dw) = catmull_rom(f64::from(k) / 1000.0);
                dw.iter().map(|w| w.abs()).sum::<f64>()
            })
            .fold(0.0, f64::max);
        assert!((largest - 3.0).abs() < 1e-12, "{largest}");
    }

    /// Every cell's curvature bound holds: the Hessian's spectral norm,
    /// from central differences of the exact gradient at points spread over
    /// the cell, stays below it, on grids of random nodes (the worst case),
    /// edge cells included; and the bound is not vacuous.
    #[test]
    fn cell_curvatures_bound_the_hessian() {
        let mut rng = crate::prng::SplitMix64::new(0x0c0f_fee5_eed5_0001);
        for (nx, ny) in [(2, 2), (3, 2), (5, 4), (9, 7)] {
            let heights: Vec<f64> = (0..nx * ny).map(|_| rng.next_f64() - 0.5).collect();
            let spacing = [0.3, 0.2];
            let grid = Grid::new([0.0, 0.0], spacing, nx, ny, heights).unwrap();
            for j in 0..ny - 1 {
                for i in 0..nx - 1 {
                    let x0 = i as f64 * spacing[0];
                    let y0 = j as f64 * spacing[1];
                    let inside = Bounds {
                        x_min: x0 + 0.4 * spacing[0],
                        x_max: x0 + 0.6 * spacing[0],
                        y_min: y0 + 0.4 * spacing[1],
                        y_max: y0 + 0.6 * spacing[1],
                    };
                    let bound = grid.max_curvature_in(&inside).unwrap();
                    let mut largest: f64 = 0.0;
                    let e = 1e-6;
                    for a in 0..11 {
                        for b in 0..11 {
                            let x = x0 + (f64::from(a) + 0.5) / 11.0 * spacing[0];
                            let y = y0 + (f64::from(b) + 0.5) / 11.0 * spacing[1];
                            let g = |x: f64, y: f64| grid.height_gradient(x, y).unwrap().1;
                            let (gxp, gxm) = (g(x + e, y), g(x - e, y));
                            let (gyp, gym) = (g(x, y + e), g(x, y - e));
                            let hxx = (gxp[0] - gxm[0]) / (2.0 * e);
                            let hxy = 0.5 * ((gxp[1] - gxm[1]) + (gyp[0] - gym[0])) / (2.0 * e);
                            let hyy = (gyp[1] - gym[1]) / (2.0 * e);
                            // Spectral norm of the symmetric 2 × 2 matrix.
                            let mean = 0.5 * (hxx + hyy);
                            let radius = (0.5 * (hxx - hyy)).hypot(hxy);
                            largest = largest.max(mean.abs() + radius);
                        }
                    }
                    let own = cell_curvature(nx, ny, spacing, grid.heights(), i, j);
                    assert!(
                        largest <= own && own <= bound,
                        "{nx} × {ny}, cell ({i}, {j}): {largest}, {own}, {bound}"
                    );
                    // Not vacuous: the cell's own bound, away from the ghosts,
                    // within a small factor of what the samples show (up to
                    // 3.5 on these uncorrelated nodes: the Frobenius norm and
                    // the per-term maxima each give away a little; on a
                    // wheel the terrain's curvature enters times R², next to
                    // the rim's own R, so this costs little).
                    let interior = i > 0 && j > 0 && i + 2 < nx && j + 2 < ny;
                    assert!(
                        !interior || own < 4.0 * largest,
                        "{nx} × {ny}, cell ({i}, {j}): {own} for {largest}"
                    );
                }
            }
            let bilinear = grid.clone().with_interpolation(Interpolation::Bilinear);
            assert_eq!(bilinear.max_curvature_in(&grid.bounds()), None);
        }
    }

    /// Every cell's slope bound holds at points spread over the cell, on
    /// grids of random nodes (steep, uncorrelated: the worst case for the
    /// bound) of sizes down to 2 × 2 (linear ghosts), edge cells included,
    /// for both interpolants; on a plane, interior cells are bounded by
    /// 1.25 times its slope.
    #[test]
    fn cell_slopes_bound_the_gradient() {
        let mut rng = crate::prng::SplitMix64::new(0x5eed_51a0_be5e_c0de);
        for (nx, ny) in [(2, 2), (3, 2), (2, 3), (3, 3), (5, 4), (9, 7), (16, 11)] {
            let heights: Vec<f64> = (0..nx * ny).map(|_| rng.next_f64() - 0.5).collect();
            let spacing = [0.3, 0.2];
            let mut slopes = Vec::new();
            cell_slope_rows(nx, ny, spacing, &heights, |row| {
                slopes.extend_from_slice(row)
            });
            // One cell at a time, as the grid computes them: the rows' bits.
            for j in 0..ny - 1 {
                for i in 0..nx - 1 {
                    let one = cell_slope(nx, ny, spacing, &heights, i, j);
                    assert_eq!(
                        one.to_bits(),
                        slopes[j * nx + i].to_bits(),
                        "{nx} × {ny} ({i}, {j})"
                    );
                }
            }
            for interpolation in [Interpolation::Bicubic, Interpolation::Bilinear] {
                let grid = Grid::new([0.0, 0.0], spacing, nx, ny, heights.clone())
                    .unwrap()
                    .with_interpolation(interpolation);
                for j in 0..ny - 1 {
                    for i in 0..nx - 1 {
                        let bound = slopes[j * nx + i];
                        let mut steepest: f64 = 0.0;
                        // Inside the cell: the bilinear gradient jumps at its edges.
                        for a in 0..21 {
                            for b in 0..21 {
                                let (t, s) =
                                    ((f64::from(a) + 0.5) / 21.0, (f64::from(b) + 0.5) / 21.0);
                                let x = (i as f64 + t) * spacing[0];
                                let y = (j as f64 + s) * spacing[1];
                                let (_, [gx, gy]) = grid.height_gradient(x, y).unwrap();
                                steepest = steepest.max(gx.hypot(gy));
                            }
                        }
                        assert!(
                            steepest <= bound,
                            "{nx} × {ny} {interpolation:?}, cell ({i}, {j}): {steepest} > {bound}"
                        );
                        // Not vacuous: within a factor of 4 of the bicubic's
                        // steepest slope away from the ghosts.
                        let interior = i > 0 && j > 0 && i + 2 < nx && j + 2 < ny;
                        assert!(
                            interpolation == Interpolation::Bilinear
                                || !interior
                                || bound < 4.0 * steepest,
                            "{nx} × {ny} {interpolation:?}, cell ({i}, {j}): {bound} for {steepest}"
                        );
                    }
                }
            }
        }
        let (a, b) = (0.3, -0.4);
        let plane = Grid::from_fn([0.0, 0.0], [0.1, 0.1], 8, 8, |x, y| a * x + b * y).unwrap();
        let mut slopes = Vec::new();
        cell_slope_rows(8, 8, [0.1, 0.1], plane.heights(), |row| {
            slopes.extend_from_slice(row)
        });
        let bound = slopes[3 * 8 + 3];
        assert!(
            (bound - 1.25 * 0.5).abs() < 1e-9,
            "an interior cell of a plane of slope 0.5: {bound}"
        );
    }

    /// A kept cell (`rover_dynamics::bicubic::KeptCells`) answers with the
    /// grid's bits: along walks that cross cell edges (and stop exactly on
    /// them, and on nodes), in the map's edge cells (which give no cell:
    /// the grid answers), beyond a clamped edge, and off the map; the
    /// bilinear interpolant gives no cells.
    #[test]
    fn kept_cells_give_the_grid_bits() {
        use rover_dynamics::bicubic::KeptCells;
        let f = |x: f64, y: f64| 0.03 * (7.0 * x).sin() * (5.0 * y).cos() + 0.01 * (23.0 * y).sin();
        let mut rng = crate::prng::SplitMix64::new(0x6e11_ce11_0b17_5eed);
        for edge in [EdgePolicy::Error, EdgePolicy::Clamp] {
            let grid = Grid::from_fn([-1.0, -0.5], [0.1, 0.05], 21, 23, f)
                .unwrap()
                .with_edge_policy(edge);
            let mut kept = KeptCells::default();
            let (mut hits, mut new, mut edges, mut on_lines) = (0, 0, 0, 0);
            let (mut x, mut y) = (0.0, 0.0);
            for step in 0..40_000 {
                if step % 100 == 0 {
                    // Anywhere, up to a cell beyond the map.
                    x = -1.1 + 2.2 * rng.next_f64();
                    y = -0.55 + 1.1 * rng.next_f64();
                } else {
                    x += 0.02 * (rng.next_f64() - 0.5);
                    y += 0.01 * (rng.next_f64() - 0.5);
                }
                let (mut qx, mut qy) = (x, y);
                // Now and then exactly on a node line, as the grid places it.
                if step % 7 == 0 {
                    qx = -1.0 + ((x + 1.0) / 0.1).round() * 0.1;
                    on_lines += 1;
                }
                if step % 11 == 0 {
                    qy = -0.5 + ((y + 0.5) / 0.05).round() * 0.05;
                }
                let grid_value = grid.height_gradient(qx, qy);
                let value = match kept.height_gradient(qx, qy) {
                    Some(v) => {
                        hits += 1;
                        Ok(v)
                    }
                    None => match grid.bicubic_cell(qx, qy) {
                        Some(cell) => {
                            new += 1;
                            kept.keep(&cell);
                            let v = cell.height_gradient(qx, qy);
                            assert_eq!(v, kept.height_gradient(qx, qy));
                            Ok(v.expect("a cell holds the point it was given for"))
                        }
                        None => {
                            edges += 1;
                            grid_value
                        }
                    },
                };
                let bits = |r: Result<(f64, [f64; 2]), OffMap>| {
                    r.map(|(z, [a, b])| [z.to_bits(), a.to_bits(), b.to_bits()])
                };
                assert_eq!(bits(value), bits(grid_value), "{edge:?} at ({qx}, {qy})");
                let height = kept.height(qx, qy).map(f64::to_bits);
                if let Some(h) = height {
                    assert_eq!(Ok(h), grid.height(qx, qy).map(f64::to_bits), "({qx}, {qy})");
                }
            }
            assert!(
                hits > 20_000 && new > 1000 && edges > 1000 && on_lines > 5000,
                "{edge:?}: {hits} hits, {new} cells, {edges} at the edges"
            );
        }
        let bilinear = Grid::from_fn([0.0, 0.0], [0.1, 0.1], 8, 8, f)
            .unwrap()
            .with_interpolation(Interpolation::Bilinear);
        assert_eq!(bilinear.bicubic_cell(0.35, 0.35), None);
        // Another interpolant or edge policy is another surface.
        let grid = Grid::from_fn([0.0, 0.0], [0.1, 0.1], 8, 8, f).unwrap();
        let other = grid.clone().with_edge_policy(EdgePolicy::Clamp);
        assert_eq!(grid.surface(), grid.clone().surface());
        assert_ne!(grid.surface(), other.surface());
        assert_ne!(grid.surface(), 0);
    }

    /// The height-only query is the full query's height, bit for bit, inside
    /// the map, in its edge cells (ghost nodes) and beyond a clamped edge.
    #[test]
    fn height_alone_is_the_height_of_the_full_query() {
        let f = |x: f64, y: f64| 0.03 * (7.0 * x).sin() * (5.0 * y).cos() + 0.01 * (23.0 * y).sin();
        let mut rng = crate::prng::SplitMix64::new(0x2545_f491_4f6c_dd1d);
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
