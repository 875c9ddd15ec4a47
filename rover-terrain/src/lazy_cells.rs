//! A grid's cell bounds computed a block of cells at a time, the first time
//! a query reaches the block, with no allocation, and the very maxima that a
//! [`RangePyramid`](super::range_pyramid::RangePyramid) over all of them
//! would give.
//!
//! Bounding the bicubic interpolant's curvature on every cell of the
//! paper's random terrain (640,000 nodes) up front would cost as many
//! instructions as the whole 40 s run of Fig. 8 on it (callgrind), while a run's contact
//! search asks for the cells along its wheels' tracks only. A query here
//! reads the same cells the pyramid's tiles would cover (the level that
//! [`chosen_shift`] picks, its tiles' whole extent), so its maximum is the
//! pyramid's to the bit, and a run's results do not change.

use std::fmt;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicU64, Ordering};

use super::range_pyramid::{chosen_shift, larger, top_shift};

/// Tiles (of 2 × 2 cells, the pyramid's finest) a block has a side: small,
/// so that the first query in a region, in a real-time loop, computes
/// little more than it reads (a wheel's square on a 5 cm grid reads about
/// 32 × 32 cells; filling one block is about 0.1 M instructions).
const BLOCK: usize = 8;

/// The value of cell (i, j) of an `nx × ny` grid, for `i < nx − 1` and
/// `j < ny − 1` (the last row and column start no cell: 0).
type CellFn = Box<dyn Fn(usize, usize) -> f64 + Send + Sync>;

/// The maxima of the cell values of an `nx × ny` grid (cell (i, j) at node
/// (i, j)) over its tiles of 2 × 2 cells, the pyramid's finest level: every
/// query reads whole tiles of a level at least as coarse, so these give
/// its maximum exactly. The tiles' storage is allocated with the grid (a
/// quarter of a value per node, less than the pyramid it replaces), so
/// that filling a block of [`BLOCK`] × [`BLOCK`] tiles, the first time a
/// query reaches it, allocates nothing: the contact search runs in a
/// real-time loop.
pub(crate) struct LazyCells {
    nx: usize,
    ny: usize,
    tiles_x: usize,
    blocks_x: usize,
    top: u32,
    /// Tile maxima, row by row, as `f64` bits (written once per block,
    /// before its `done` completes, which orders them before every read).
    tiles: Box<[AtomicU64]>,
    done: Box<[OnceLock<()>]>,
    cell: CellFn,
}

impl LazyCells {
    /// The cells of an `nx × ny` grid whose values `cell` gives.
    pub(crate) fn new(nx: usize, ny: usize, cell: CellFn) -> LazyCells {
        let (tiles_x, tiles_y) = (nx.div_ceil(2), ny.div_ceil(2));
        let (blocks_x, blocks_y) = (tiles_x.div_ceil(BLOCK), tiles_y.div_ceil(BLOCK));
        LazyCells {
            nx,
            ny,
            tiles_x,
            blocks_x,
            top: top_shift(nx, ny),
            tiles: (0..tiles_x * tiles_y).map(|_| AtomicU64::new(0)).collect(),
            done: (0..blocks_x * blocks_y).map(|_| OnceLock::new()).collect(),
            cell,
        }
    }

    /// Cell (i, j)'s value, 0 on the last row and column.
    fn value(&self, i: usize, j: usize) -> f64 {
        if i + 1 < self.nx && j + 1 < self.ny {
            (self.cell)(i, j)
        } else {
            0.0
        }
    }

    /// Fills block (bi, bj)'s tiles, the first time only.
    fn fill(&self, bi: usize, bj: usize) {
        let Some(done) = self.done.get(bj * self.blocks_x + bi) else {
            return;
        };
        done.get_or_init(|| {
            let tiles_y = self.tiles.len() / self.tiles_x;
            for tj in bj * BLOCK..((bj + 1) * BLOCK).min(tiles_y) {
                for ti in bi * BLOCK..((bi + 1) * BLOCK).min(self.tiles_x) {
                    let mut largest = f64::NEG_INFINITY;
                    for j in 2 * tj..(2 * tj + 2).min(self.ny) {
                        for i in 2 * ti..(2 * ti + 2).min(self.nx) {
                            largest = larger(largest, self.value(i, j));
                        }
                    }
                    if let Some(t) = self.tiles.get(tj * self.tiles_x + ti) {
                        t.store(largest.to_bits(), Ordering::Relaxed);
                    }
                }
            }
        });
    }

    /// The largest value over cells `i[0]..=i[1]` × `j[0]..=j[1]` (indices
    /// below `nx`, `ny`), widened as `RangePyramid::span` widens it: to the
    /// whole tiles of the level it reads.
    pub(crate) fn max(&self, i: [usize; 2], j: [usize; 2]) -> f64 {
        let s = chosen_shift(self.top, i, j);
        // The widened range of cells, as tiles of 2 × 2 cells (s ≥ 1, so
        // it starts on a tile's first cell and ends on a tile's last or
        // the map's).
        let widen = |k: [usize; 2], n: usize| {
            let first = (k[0] >> s) << s;
            let last = (((k[1] >> s) + 1) << s).min(n) - 1;
            [first / 2, last / 2]
        };
        let ([t0, t1], [u0, u1]) = (widen(i, self.nx), widen(j, self.ny));
        for bj in u0 / BLOCK..=u1 / BLOCK {
            for bi in t0 / BLOCK..=t1 / BLOCK {
                self.fill(bi, bj);
            }
        }
        let mut largest = f64::NEG_INFINITY;
        for u in u0..=u1 {
            match self
                .tiles
                .get(u * self.tiles_x + t0..=u * self.tiles_x + t1)
            {
                Some(row) => {
                    largest = row.iter().fold(largest, |m, t| {
                        larger(m, f64::from_bits(t.load(Ordering::Relaxed)))
                    })
                }
                None => largest = f64::INFINITY,
            }
        }
        largest
    }

    /// Blocks filled so far, of all.
    pub(crate) fn computed(&self) -> (usize, usize) {
        let filled = self.done.iter().filter(|b| b.get().is_some()).count();
        (filled, self.done.len())
    }
}

impl fmt::Debug for LazyCells {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (filled, all) = self.computed();
        write!(
            f,
            "LazyCells({} × {} cells, {filled} of {all} blocks computed)",
            self.nx, self.ny
        )
    }
}

/// Equal for grids of the same shape: the values are a function of the
/// heights and spacing, which the grid compares itself.
impl PartialEq for LazyCells {
    fn eq(&self, other: &Self) -> bool {
        self.nx == other.nx && self.ny == other.ny
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prng::SplitMix64;
    use crate::range_pyramid::RangePyramid;

    /// On grids of many shapes (powers of two and not, thinner than a
    /// block and wider than several) and random rectangles, small and
    /// whole-map, the maximum is the pyramid's over all the cells, bit for bit.
    #[test]
    fn the_maximum_is_the_pyramids() {
        let mut rng = SplitMix64::new(0x1a2b_c311);
        for (nx, ny) in [
            (2, 2),
            (3, 2),
            (2, 5),
            (7, 9),
            (64, 64),
            (65, 63),
            (130, 77),
            (300, 20),
        ] {
            let value = |i: usize, j: usize| ((i * 7919 + j * 104_729) % 1013) as f64 * 1e-3;
            let all: Vec<f64> = (0..nx * ny)
                .map(|k| {
                    let (i, j) = (k % nx, k / nx);
                    if i + 1 < nx && j + 1 < ny {
                        value(i, j)
                    } else {
                        0.0
                    }
                })
                .collect();
            let pyramid = RangePyramid::upper(nx, &all);
            let lazy = LazyCells::new(nx, ny, Box::new(value));
            let pick = |rng: &mut SplitMix64, n: usize| {
                let a = (rng.next_u64() % n as u64) as usize;
                let b = (rng.next_u64() % n as u64) as usize;
                [a.min(b), a.max(b)]
            };
            for trial in 0..400 {
                let (i, j) = if trial == 0 {
                    ([0, nx - 1], [0, ny - 1])
                } else {
                    (pick(&mut rng, nx), pick(&mut rng, ny))
                };
                let (want, _) = pyramid.span(i, j);
                let got = lazy.max(i, j);
                assert_eq!(got.to_bits(), want.to_bits(), "{nx} × {ny}, {i:?} × {j:?}");
            }
        }
    }

    /// A query computes the blocks it reaches, not the others.
    #[test]
    fn a_small_query_computes_few_blocks() {
        let lazy = LazyCells::new(1000, 800, Box::new(|i, j| (i + j) as f64));
        assert_eq!(lazy.computed(), (0, 63 * 50));
        // Read as the pyramid reads it: tiles of 4 × 4 cells, so up to
        // cell (523, 423).
        assert_eq!(lazy.max([500, 520], [400, 420]), (523 + 423) as f64);
        let (done, _) = lazy.computed();
        assert!(done <= 4, "{done} blocks for a 21 × 21 query");
    }
}
