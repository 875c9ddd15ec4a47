//! The ruts a run leaves, as grids a user can load as the next run's
//! terrain (docs/TERRAIN.md, "Rut maps"): the rut depth on the rectangle
//! the wheels touched, and the ground there (the terrain's height minus
//! the rut).
//!
//! The rut map is sparse, its rectangle is not: a long diagonal drive
//! touches a few thousand tiles of a rectangle of billions of nodes. A
//! rectangle of more than [`MAX_RUT_NODES`] nodes is written coarser, each
//! coarse node the deepest rut of the fine nodes nearest it (so the grid's
//! deepest rut is the map's), and the grid is built from the tiles
//! directly: the fine rectangle is never held in memory.

use rover_dynamics::height_field::HeightField;
use rover_terrain::png_map::SampleScale;
use rover_terrain::ruts::{RutMap, TILE};
use rover_terrain::{Grid, Terrain, TerrainError};
use serde::Serialize;

/// Most nodes a rut grid holds (2000 × 2000: 40 m × 40 m at 2 cm cells):
/// a CSV of a few tens of megabytes, written at the end of a run, and well
/// within what a terrain file may hold ([`rover_terrain::MAX_FILE_NODES`]).
pub const MAX_RUT_NODES: usize = 4_000_000;

/// Metres per count of `ruts.png` (0.01 mm), up to 0.655 m of rut; a
/// deeper rut coarsens the scale to fit ([`RutGrid::png_scale`]).
pub const RUT_PNG_SCALE: f64 = 1e-5;

/// What `summary.json` says of the ruts.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RutSummary {
    /// The deepest rut \[m\].
    pub deepest_m: f64,
    /// The area the wheels left a rut on \[m²\]: nodes with a rut deeper
    /// than 0, times a cell's area.
    pub touched_area_m2: f64,
    /// Tiles of [`TILE`] × [`TILE`] cells the map holds.
    pub tiles: usize,
    /// Heap the map holds \[bytes\].
    pub heap_bytes: usize,
    /// The map's cell \[m\].
    pub cell_m: f64,
    /// The grid written as `ruts.csv`, `ruts.png` and `ground.csv`.
    pub grid: RutGridInfo,
}

/// Where the written grid lies.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RutGridInfo {
    /// `[nx, ny]`.
    pub nodes: [usize; 2],
    /// `[X, Y]` of the south-west node \[m\].
    pub origin_m: [f64; 2],
    /// Node spacing \[m\] (the cell times `coarsening`).
    pub spacing_m: f64,
    /// Map cells per grid cell: 1, or more where the rectangle exceeds
    /// [`MAX_RUT_NODES`].
    pub coarsening: usize,
    /// Metres per count of `ruts.png` (offset 0).
    pub png_scale_m: f64,
}

/// The ruts at the end of a run, on a regular grid.
#[derive(Clone, PartialEq)]
pub struct RutGrid {
    origin: [f64; 2],
    spacing: f64,
    nx: usize,
    ny: usize,
    /// Rut depth \[m\], south row first.
    depth: Vec<f64>,
    /// The terrain's height minus the rut \[m\].
    ground: Vec<f64>,
    summary: RutSummary,
}

/// Not the nodes: a summary's debug print stays readable.
impl std::fmt::Debug for RutGrid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RutGrid")
            .field("origin", &self.origin)
            .field("spacing", &self.spacing)
            .field("nodes", &[self.nx, self.ny])
            .finish_non_exhaustive()
    }
}

impl RutGrid {
    /// The grid of `map` over the touched tiles' rectangle, the ground
    /// read from `terrain` (clamped to its map, where the rectangle
    /// overhangs it: only untouched nodes can); `None` on an untouched map.
    pub fn of(map: &RutMap, terrain: &Terrain) -> Option<RutGrid> {
        let bounds = map.bounds()?;
        let cell = map.cell();
        let (i0, j0) = (
            (bounds.x_min / cell).round() as i64,
            (bounds.y_min / cell).round() as i64,
        );
        let fine_nx = ((bounds.x_max - bounds.x_min) / cell).round() as usize + 1;
        let fine_ny = ((bounds.y_max - bounds.y_min) / cell).round() as usize + 1;
        let f = coarsening(fine_nx, fine_ny);
        let (nx, ny) = ((fine_nx - 1).div_ceil(f) + 1, (fine_ny - 1).div_ceil(f) + 1);
        let mut depth = vec![0.0f64; nx * ny];
        let mut touched = 0usize;
        for tile in map.tiles_since(0) {
            let ti = (tile.origin[0] / cell).round() as i64;
            let tj = (tile.origin[1] / cell).round() as i64;
            for lj in 0..tile.nodes {
                for li in 0..tile.nodes {
                    let d = f64::from(tile.depth(li, lj));
                    if d <= 0.0 {
                        continue;
                    }
                    // A node on a tile's north or east border is its
                    // neighbour's own, and that neighbour exists (a press
                    // makes the tile that owns the node).
                    if li < TILE && lj < TILE {
                        touched += 1;
                    }
                    let ri = (ti + li as i64 - i0) as usize;
                    let rj = (tj + lj as i64 - j0) as usize;
                    let (ci, cj) = ((ri + f / 2) / f, (rj + f / 2) / f);
                    let k = cj * nx + ci;
                    depth[k] = depth[k].max(d);
                }
            }
        }
        let spacing = cell * f as f64;
        let origin = [i0 as f64 * cell, j0 as f64 * cell];
        let b = terrain.bounds();
        let ground = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let x = (origin[0] + i as f64 * spacing).clamp(b.x_min, b.x_max);
                let y = (origin[1] + j as f64 * spacing).clamp(b.y_min, b.y_max);
                // The clamped point lies on the map: a grid answers there.
                terrain.height(x, y).unwrap_or(0.0) - depth[j * nx + i]
            })
            .collect();
        let deepest = map.deepest();
        let summary = RutSummary {
            deepest_m: deepest,
            touched_area_m2: touched as f64 * cell * cell,
            tiles: map.tile_count(),
            heap_bytes: map.heap_bytes(),
            cell_m: cell,
            grid: RutGridInfo {
                nodes: [nx, ny],
                origin_m: origin,
                spacing_m: spacing,
                coarsening: f,
                png_scale_m: png_scale(deepest),
            },
        };
        Some(RutGrid {
            origin,
            spacing,
            nx,
            ny,
            depth,
            ground,
            summary,
        })
    }

    /// What `summary.json` says of the ruts.
    pub fn summary(&self) -> &RutSummary {
        &self.summary
    }

    /// The rut depth \[m\] as a terrain grid (`ruts.csv`, `ruts.png`).
    pub fn depth(&self) -> Result<Grid, TerrainError> {
        self.grid(self.depth.clone())
    }

    /// The ground \[m\], the terrain's height minus the rut (`ground.csv`).
    pub fn ground(&self) -> Result<Grid, TerrainError> {
        self.grid(self.ground.clone())
    }

    /// The PNG's vertical mapping: [`RUT_PNG_SCALE`] per count from 0,
    /// coarser when the deepest rut would not fit 65535 counts.
    pub fn png_scale(&self) -> SampleScale {
        SampleScale {
            scale: self.summary.grid.png_scale_m,
            offset: 0.0,
        }
    }

    fn grid(&self, values: Vec<f64>) -> Result<Grid, TerrainError> {
        let s = [self.spacing; 2];
        Grid::new(self.origin, s, self.nx, self.ny, values)
    }

    /// The files a run writes of its ruts, by name, as bytes:
    /// `ruts.csv` and `ruts.png` (the depth) and `ground.csv`.
    pub fn files(&self) -> Result<Vec<(&'static str, Vec<u8>)>, TerrainError> {
        let depth = self.depth()?;
        Ok(vec![
            ("ruts.csv", rut_csv(&depth).into_bytes()),
            (
                "ruts.png",
                rover_terrain::png_map::encode_png(&depth, self.png_scale())?,
            ),
            (
                "ground.csv",
                rover_terrain::csv_grid::format_csv(&self.ground()?).into_bytes(),
            ),
        ])
    }
}

/// The names of the files [`RutGrid::files`] writes.
pub const RUT_FILES: [&str; 3] = ["ruts.csv", "ruts.png", "ground.csv"];

/// The CSV grid of the rut depth: the terrain reader's format, headed by
/// a comment that says its values are depths, not heights.
fn rut_csv(depth: &Grid) -> String {
    let text = rover_terrain::csv_grid::format_csv(depth);
    // The writer's own first line calls the values heights.
    let body = text.strip_prefix('#').map_or(&text[..], |t| {
        t.split_once('\n').map_or("", |(_, rest)| rest)
    });
    format!(
        "# rover rut map: rut depth [m] below the terrain, positive down; row k is \
         Y = y0 + (k-1)*dy (south first), column i is X = x0 + (i-1)*dx; \
         ground.csv is the terrain minus it\n{body}"
    )
}

/// Map cells per grid cell so that the grid holds at most
/// [`MAX_RUT_NODES`] nodes.
fn coarsening(nx: usize, ny: usize) -> usize {
    let mut f = 1;
    while ((nx - 1).div_ceil(f) + 1).saturating_mul((ny - 1).div_ceil(f) + 1) > MAX_RUT_NODES {
        f += 1;
    }
    f
}

/// [`RUT_PNG_SCALE`], or the scale at which `deepest` is the last count.
fn png_scale(deepest: f64) -> f64 {
    if deepest <= RUT_PNG_SCALE * 65535.0 {
        RUT_PNG_SCALE
    } else {
        // Just above deepest/65535, so that rounding stays within range.
        deepest / 65534.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rover_terrain::ruts::Footprint;

    fn pressed(from: [f64; 2], to: [f64; 2], z: f64) -> RutMap {
        let mut map = RutMap::new(0.02);
        let at = |c: [f64; 2]| Footprint {
            centre: c,
            axle: [0.0, 1.0],
            half_width: 0.08,
            past_sinkage: z,
        };
        map.press(&at(from), &at(to), |z| 0.75 * z);
        map
    }

    fn slope() -> Terrain {
        Terrain::Grid(
            Grid::from_fn([-5.0, -5.0], [0.1, 0.1], 101, 101, |x, y| {
                0.1 * x - 0.05 * y
            })
            .unwrap(),
        )
    }

    /// At full resolution the grid is the map's own depth grid, node for
    /// node, and the ground is the terrain minus it.
    #[test]
    fn the_grid_holds_the_maps_nodes() {
        let map = pressed([-0.7, 0.3], [1.3, 0.3], 0.02);
        let terrain = slope();
        let grid = RutGrid::of(&map, &terrain).unwrap();
        let (origin, [nx, ny], depths) = map.depth_grid().unwrap();
        let depth = grid.depth().unwrap();
        assert_eq!(depth.origin(), origin);
        assert_eq!([depth.nx(), depth.ny()], [nx, ny]);
        assert_eq!(depth.heights(), &depths[..]);
        let ground = grid.ground().unwrap();
        for (k, (&g, &d)) in ground.heights().iter().zip(&depths).enumerate() {
            let (x, y) = (
                origin[0] + (k % nx) as f64 * 0.02,
                origin[1] + (k / nx) as f64 * 0.02,
            );
            assert!((g - (terrain.height(x, y).unwrap() - d)).abs() < 1e-12);
        }
        let s = grid.summary();
        let max = depths.iter().copied().fold(0.0, f64::max);
        assert_eq!(s.deepest_m, max);
        let touched = depths.iter().filter(|&&d| d > 0.0).count();
        assert!((s.touched_area_m2 - touched as f64 * 0.02 * 0.02).abs() < 1e-12);
        assert_eq!(s.grid.coarsening, 1);
        assert_eq!(s.grid.png_scale_m, RUT_PNG_SCALE);
    }

    /// A rectangle beyond the limit is coarsened, keeping the deepest rut
    /// of each coarse node's neighbourhood; storage follows the limit.
    #[test]
    fn a_long_diagonal_is_written_coarser() {
        let map = pressed([0.0, 0.0], [45.0, 45.0], 0.03);
        let grid = RutGrid::of(&map, &Terrain::default()).unwrap();
        let [nx, ny] = grid.summary().grid.nodes;
        assert!(nx * ny <= MAX_RUT_NODES, "{nx} × {ny}");
        assert!(grid.summary().grid.coarsening > 1);
        let depth = grid.depth().unwrap();
        let max = depth.heights().iter().copied().fold(0.0, f64::max);
        assert_eq!(max, map.deepest());
        // A coarse node on the path holds the rut.
        let s = grid.summary().grid.spacing_m;
        let (i, j) = ((20.0 / s).round() as usize, (20.0 / s).round() as usize);
        assert_eq!(depth.node(i, j), Some(f64::from(0.0225f32)));
    }

    /// The scale resolves 0.01 mm, and a rut too deep for it fits a
    /// coarser one.
    #[test]
    fn the_png_scale_fits_the_deepest_rut() {
        assert_eq!(png_scale(0.3), 1e-5);
        let deep = png_scale(0.9);
        assert!((0.9 / deep).round() <= 65535.0);
    }
}
