//! The ground under a run as a grid of heights: what `rover drive`'s page
//! draws as its terrain mesh and what the MCAP log and the Foxglove
//! channels carry as one (one sampling for both).

use rover_dynamics::HeightField;
use rover_runtime::row::Columns;
use rover_terrain::Terrain;

use super::RowSink;

/// The margin around a run's path that the ground drawn for it covers
/// \[m\].
pub const PATH_MARGIN: f64 = 5.0;

/// Most nodes along the longer side of the ground `rover drive`'s page and
/// `rover view` draw: 256 × 256 nodes.
pub const VIEW_NODES: usize = 256;

/// Heights on a regular grid, row after row (`z[j * nx + i]` at
/// `(x0 + i·dx, y0 + j·dy)`); `None` where the node is off the map or
/// the height is not finite.
#[derive(Clone, Debug, PartialEq)]
pub struct HeightGrid {
    /// The first node's X \[m\].
    pub x0: f64,
    /// The first node's Y \[m\].
    pub y0: f64,
    /// Node spacing along X \[m\].
    pub dx: f64,
    /// Node spacing along Y \[m\].
    pub dy: f64,
    /// Nodes along X (≥ 2).
    pub nx: usize,
    /// Nodes along Y (≥ 2).
    pub ny: usize,
    /// The heights \[m\].
    pub z: Vec<Option<f64>>,
}

impl HeightGrid {
    /// `terrain` over the rectangle `lo`…`hi` (within the terrain's map),
    /// its cells square, at most `max_nodes` nodes (≥ 2) along the longer
    /// side.
    pub fn sample(terrain: &Terrain, lo: [f64; 2], hi: [f64; 2], max_nodes: usize) -> Self {
        let max_nodes = max_nodes.max(2);
        let b = terrain.bounds();
        let x0 = b.x_min.max(lo[0]);
        let x1 = b.x_max.min(hi[0]).max(x0);
        let y0 = b.y_min.max(lo[1]);
        let y1 = b.y_max.min(hi[1]).max(y0);
        let cell = (x1 - x0).max(y1 - y0) / (max_nodes - 1) as f64;
        let nodes = |w: f64| {
            if cell > 0.0 {
                ((w / cell).ceil() as usize + 1).clamp(2, max_nodes)
            } else {
                2
            }
        };
        let (nx, ny) = (nodes(x1 - x0), nodes(y1 - y0));
        let (dx, dy) = ((x1 - x0) / (nx - 1) as f64, (y1 - y0) / (ny - 1) as f64);
        let mut z = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let h = terrain.height(x0 + i as f64 * dx, y0 + j as f64 * dy);
                z.push(h.ok().filter(|h| h.is_finite()));
            }
        }
        HeightGrid {
            x0,
            y0,
            dx,
            dy,
            nx,
            ny,
            z,
        }
    }

    /// The node `(i, j)`'s position, `None` without a height there.
    pub fn node(&self, i: usize, j: usize) -> Option<[f64; 3]> {
        let h = self.z[j * self.nx + i]?;
        Some([
            self.x0 + i as f64 * self.dx,
            self.y0 + j as f64 * self.dy,
            h,
        ])
    }
}

/// The rectangle a run's path covers, gathered row by row from its `X` and
/// `Y` columns.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathBox {
    columns: [usize; 2],
    covered: Option<([f64; 2], [f64; 2])>,
}

impl PathBox {
    /// Where the rows' `X` and `Y` are.
    pub fn start(&mut self, columns: &Columns) {
        self.columns = [
            columns.position("X").unwrap_or(1),
            columns.position("Y").unwrap_or(2),
        ];
    }

    /// Widens the box to the row's `X` and `Y`.
    pub fn add(&mut self, values: &[f64]) {
        let p = [values[self.columns[0]], values[self.columns[1]]];
        self.covered = Some(match self.covered {
            None => (p, p),
            Some((lo, hi)) => (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            ),
        });
    }

    /// The lowest and highest `X` and `Y`; `None` before a row.
    pub fn covered(&self) -> Option<([f64; 2], [f64; 2])> {
        self.covered
    }

    /// `terrain` under the box, [`PATH_MARGIN`] wider on every side, at
    /// most `max_nodes` nodes along the longer side; `None` before a row.
    pub fn ground(&self, terrain: &Terrain, max_nodes: usize) -> Option<HeightGrid> {
        let (lo, hi) = self.covered?;
        Some(HeightGrid::sample(
            terrain,
            [lo[0] - PATH_MARGIN, lo[1] - PATH_MARGIN],
            [hi[0] + PATH_MARGIN, hi[1] + PATH_MARGIN],
            max_nodes,
        ))
    }
}

/// The ground under a run's path, kept as the run goes: a [`RowSink`]
/// that widens a [`PathBox`] with each row and, at the end, samples the
/// terrain the run drove on over it. What `rover view` draws (the output
/// folder's `terrain.json`), taken from the run's own terrain rather than
/// from a second build of it.
#[derive(Clone, Debug, PartialEq)]
pub struct PathGround {
    path: PathBox,
    max_nodes: usize,
    grid: Option<HeightGrid>,
}

impl PathGround {
    /// A sink that samples at most `max_nodes` nodes along the longer side.
    pub fn new(max_nodes: usize) -> Self {
        Self {
            path: PathBox::default(),
            max_nodes,
            grid: None,
        }
    }

    /// The rectangle the rows covered; `None` before a row.
    pub fn path(&self) -> &PathBox {
        &self.path
    }

    /// The ground under the path, once the run has finished on a terrain
    /// with at least one row.
    pub fn grid(&self) -> Option<&HeightGrid> {
        self.grid.as_ref()
    }
}

impl RowSink for PathGround {
    fn start(&mut self, columns: &Columns) -> std::io::Result<()> {
        self.path.start(columns);
        Ok(())
    }

    fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        self.path.add(values);
        Ok(())
    }

    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()> {
        self.grid = terrain.and_then(|t| self.path.ground(t, self.max_nodes));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rover_terrain::{Flat, Slope};

    /// A [`PathGround`] beside another sink: both see every row; at the end
    /// the ground is the terrain sampled over the rows' box, widened by
    /// the margin, as [`HeightGrid::sample`] gives it.
    #[test]
    fn the_path_ground_samples_the_terrain_over_the_rows_box() {
        let columns = Columns::new(4, 4);
        let (ix, iy) = (
            columns.position("X").unwrap(),
            columns.position("Y").unwrap(),
        );
        let mut view = PathGround::new(64);
        let mut other = PathGround::new(16);
        let mut both = (&mut view, Some(&mut other));
        both.start(&columns).unwrap();
        let mut row = vec![0.0; columns.len()];
        for (x, y) in [(0.5, -1.0), (3.0, 0.25), (1.0, 2.0)] {
            row[ix] = x;
            row[iy] = y;
            both.row(&row).unwrap();
        }
        let terrain = Terrain::Slope(Slope::new(10.0, 30.0, [0.0; 2], 0.1).unwrap());
        both.finish(Some(&terrain)).unwrap();
        assert_eq!(view.path().covered(), Some(([0.5, -1.0], [3.0, 2.0])));
        let want = HeightGrid::sample(
            &terrain,
            [0.5 - PATH_MARGIN, -1.0 - PATH_MARGIN],
            [3.0 + PATH_MARGIN, 2.0 + PATH_MARGIN],
            64,
        );
        assert_eq!(view.grid(), Some(&want));
        assert_eq!(other.grid().map(|g| g.nx.max(g.ny)), Some(16));
        // No row: no ground; no terrain (free flight): none either.
        let mut empty = PathGround::new(64);
        empty.start(&columns).unwrap();
        empty.finish(Some(&Terrain::Flat(Flat::default()))).unwrap();
        assert_eq!(empty.grid(), None);
        let mut flying = PathGround::new(64);
        flying.start(&columns).unwrap();
        flying.row(&row).unwrap();
        flying.finish(None).unwrap();
        assert_eq!(
            (flying.grid(), flying.path().covered().is_some()),
            (None, true)
        );
    }
}
