//! The Catmull–Rom bicubic interpolant of a grid of heights, cell by cell
//! (MODEL.md §6; `rover_terrain::Grid` is its grid), and one interior
//! cell kept for the queries that follow ([`BicubicCell`]): what the
//! contact search keeps of each wheel's ground between queries, so that a
//! query in the same cell skips locating the cell and reading its 16
//! nodes out of the map.
//!
//! The kernel is Keys' cubic convolution with a = −1/2. On the cell
//! `[p0, p1]` with neighbours `p−1`, `p2` and local coordinate `t ∈ [0, 1]`:
//! ```text
//! p(t) = w−1(t)·p−1 + w0(t)·p0 + w1(t)·p1 + w2(t)·p2
//! w−1 = (−t + 2t² − t³)/2     w0 = (2 − 5t² + 3t³)/2
//! w1  = ( t + 4t² − 3t³)/2    w2 = (−t² + t³)/2
//! ```
//! The grid and a kept cell evaluate it by the same functions
//! ([`catmull_rom`], [`along`], [`across`]), the same operations in the
//! same order, so a kept cell gives the grid's bits.

/// Catmull–Rom weights `[w−1, w0, w1, w2]` at `t` and their `t`-derivatives.
#[inline]
pub fn catmull_rom(t: f64) -> ([f64; 4], [f64; 4]) {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = [
        0.5 * (-t + 2.0 * t2 - t3),
        0.5 * (2.0 - 5.0 * t2 + 3.0 * t3),
        0.5 * (t + 4.0 * t2 - 3.0 * t3),
        0.5 * (-t2 + t3),
    ];
    let dw = [
        0.5 * (-1.0 + 4.0 * t - 3.0 * t2),
        0.5 * (-10.0 * t + 9.0 * t2),
        0.5 * (1.0 + 8.0 * t - 9.0 * t2),
        0.5 * (-2.0 * t + 3.0 * t2),
    ];
    (w, dw)
}

/// One stencil row `p` interpolated along X with the weights `wx` and
/// their derivatives `dwx`: its value and its derivative in `t`.
#[inline(always)]
pub fn along(wx: &[f64; 4], dwx: &[f64; 4], p: &[f64; 4]) -> [f64; 2] {
    [
        wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3],
        dwx[0] * p[0] + dwx[1] * p[1] + dwx[2] * p[2] + dwx[3] * p[3],
    ]
}

/// The four rows' values and `t`-derivatives ([`along`]) combined along
/// Y with the weights `wy` and their derivatives `dwy`: the height and
/// its derivatives in `t` and `s`.
#[inline(always)]
pub fn across(wy: &[f64; 4], dwy: &[f64; 4], rows: &[[f64; 2]; 4]) -> (f64, f64, f64) {
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

/// The height alone on a cell from its rows `block` and the weights along
/// X and Y: the first value of [`across`] over [`along`], bit for bit (the
/// same operations in the same order) without the derivatives.
#[inline(always)]
pub fn height(block: [&[f64; 4]; 4], wx: &[f64; 4], wy: &[f64; 4]) -> f64 {
    let mut z = 0.0;
    for (w, p) in wy.iter().zip(block) {
        z += w * (wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3]);
    }
    z
}

/// One interior cell of a grid's bicubic interpolant (a cell whose 4 × 4
/// stencil holds no ghost node), with what locating a point in it needs.
///
/// The grid has its south-west node at `origin` and its nodes `spacing`
/// apart; the cell's south-west node is node `corner` (integers, stored
/// as floats), and `nodes[b][a]` is node `(corner[0] − 1 + a,
/// corner[1] − 1 + b)`. A point whose local coordinates
/// `u = (x − origin)/spacing` fall in `[corner, corner + 1)` on both axes
/// is in the cell, and [`BicubicCell::height_gradient`] gives there the
/// bits the grid gives: a terrain that hands out cells
/// ([`crate::HeightField::bicubic_cell`]) promises it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BicubicCell {
    /// The grid's south-west node `[X0, Y0]` \[m\].
    pub origin: [f64; 2],
    /// The grid's node spacing `[dx, dy]` \[m\].
    pub spacing: [f64; 2],
    /// The cell's south-west node's indices, as floats.
    pub corner: [f64; 2],
    /// The stencil's nodes \[m\], rows of increasing Y (see above).
    pub nodes: [[f64; 4]; 4],
}

/// Height \[m\] and gradient of a cell's 16 nodes at its local
/// coordinates `(t, s)`, the node spacing `spacing` \[m\]: the grid's
/// operations in the grid's order.
#[inline(always)]
fn cell_height_gradient(
    nodes: &[[f64; 4]; 4],
    t: f64,
    s: f64,
    spacing: [f64; 2],
) -> (f64, [f64; 2]) {
    let (wx, dwx) = catmull_rom(t);
    let (wy, dwy) = catmull_rom(s);
    let [p0, p1, p2, p3] = nodes;
    let rows = [
        along(&wx, &dwx, p0),
        along(&wx, &dwx, p1),
        along(&wx, &dwx, p2),
        along(&wx, &dwx, p3),
    ];
    let (z, dz_dt, dz_ds) = across(&wy, &dwy, &rows);
    (z, [dz_dt / spacing[0], dz_ds / spacing[1]])
}

/// Height \[m\] of a cell's 16 nodes at its local coordinates `(t, s)`.
#[inline(always)]
fn cell_height(nodes: &[[f64; 4]; 4], t: f64, s: f64) -> f64 {
    let [p0, p1, p2, p3] = nodes;
    height([p0, p1, p2, p3], &catmull_rom(t).0, &catmull_rom(s).0)
}

impl BicubicCell {
    /// The local coordinates `(t, s)` of (`x`, `y`) in the cell, if it is
    /// there (false for NaN).
    #[inline(always)]
    fn local(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let u = (x - self.origin[0]) / self.spacing[0];
        let v = (y - self.origin[1]) / self.spacing[1];
        let (t, s) = (u - self.corner[0], v - self.corner[1]);
        ((0.0..1.0).contains(&t) && (0.0..1.0).contains(&s)).then_some((t, s))
    }

    /// Height \[m\] and gradient at (`x`, `y`) if the point is in the
    /// cell, else `None`.
    #[inline]
    pub fn height_gradient(&self, x: f64, y: f64) -> Option<(f64, [f64; 2])> {
        let (t, s) = self.local(x, y)?;
        Some(cell_height_gradient(&self.nodes, t, s, self.spacing))
    }

    /// Height \[m\] at (`x`, `y`) if the point is in the cell, else `None`.
    #[inline]
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        let (t, s) = self.local(x, y)?;
        Some(cell_height(&self.nodes, t, s))
    }
}

/// How many cells a [`KeptCells`] holds: a wheel's rim meets the ground at
/// two crossings, each refined where it was last, and the arcs searched
/// again query a cell or two more.
pub const KEPT_CELLS: usize = 4;

/// The last few interior cells a wheel's queries fell in, all of one grid
/// ([`BicubicCell`]), kept between queries and between evaluations: a
/// query in one of them reads the cell instead of the map, with the same
/// bits. Which cells are kept depends on the queries before, the values
/// never do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeptCells {
    /// The grid's south-west node and node spacing \[m\] (zero spacing while
    /// empty: nothing is found in it).
    origin: [f64; 2],
    spacing: [f64; 2],
    /// Each kept cell's south-west node (as in [`BicubicCell`]); infinite
    /// for an empty slot (no point is in it).
    corners: [[f64; 2]; KEPT_CELLS],
    nodes: [[[f64; 4]; 4]; KEPT_CELLS],
    /// The slot the next cell replaces.
    next: usize,
}

impl KeptCells {
    /// Nothing kept.
    pub const EMPTY: KeptCells = KeptCells {
        origin: [0.0; 2],
        spacing: [0.0; 2],
        corners: [[f64::INFINITY; 2]; KEPT_CELLS],
        nodes: [[[0.0; 4]; 4]; KEPT_CELLS],
        next: 0,
    };

    /// The kept cell that holds (`x`, `y`), with the point's local
    /// coordinates in it.
    #[inline(always)]
    fn find(&self, x: f64, y: f64) -> Option<(usize, f64, f64)> {
        let u = (x - self.origin[0]) / self.spacing[0];
        let v = (y - self.origin[1]) / self.spacing[1];
        for (k, corner) in self.corners.iter().enumerate() {
            let (t, s) = (u - corner[0], v - corner[1]);
            if (0.0..1.0).contains(&t) && (0.0..1.0).contains(&s) {
                return Some((k, t, s));
            }
        }
        None
    }

    /// Height \[m\] and gradient at (`x`, `y`), if a kept cell holds it:
    /// [`BicubicCell::height_gradient`]'s bits.
    #[inline]
    pub fn height_gradient(&self, x: f64, y: f64) -> Option<(f64, [f64; 2])> {
        let (k, t, s) = self.find(x, y)?;
        Some(cell_height_gradient(&self.nodes[k], t, s, self.spacing))
    }

    /// Height \[m\] at (`x`, `y`), if a kept cell holds it:
    /// [`BicubicCell::height`]'s bits.
    #[inline]
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        let (k, t, s) = self.find(x, y)?;
        Some(cell_height(&self.nodes[k], t, s))
    }

    /// Forgets every cell.
    pub fn clear(&mut self) {
        *self = KeptCells::EMPTY;
    }

    /// Keeps `cell`, in place of the oldest kept one; a cell of another grid
    /// (another origin or spacing) first forgets the others.
    #[inline]
    pub fn keep(&mut self, cell: &BicubicCell) {
        if cell.origin != self.origin || cell.spacing != self.spacing {
            *self = KeptCells::EMPTY;
            self.origin = cell.origin;
            self.spacing = cell.spacing;
        }
        let k = self.next % KEPT_CELLS;
        self.corners[k] = cell.corner;
        self.nodes[k] = cell.nodes;
        self.next = (k + 1) % KEPT_CELLS;
    }
}

impl Default for KeptCells {
    fn default() -> KeptCells {
        KeptCells::EMPTY
    }
}
