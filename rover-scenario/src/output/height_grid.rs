//! The ground under a run as a grid of heights: what `rover drive`'s page
//! draws as its terrain mesh and what the MCAP log and the Foxglove
//! channels carry as one (one sampling for both).

use rover_dynamics::HeightField;
use rover_terrain::Terrain;

/// The margin around a run's path that the ground drawn for it covers
/// \[m\].
pub const PATH_MARGIN: f64 = 5.0;

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
