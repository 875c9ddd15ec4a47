//! A grid's cell bounds computed a block of cells at a time, the first time
//! a query reaches the block, with the very maxima that a
//! [`RangePyramid`](super::range_pyramid::RangePyramid) over all of them
//! would give.
//!
//! Bounding the bicubic interpolant's curvature on every cell of the
//! paper's random terrain (640,000 nodes) cost as many instructions as
//! the whole 40 s run of Fig. 8 on it (callgrind), while a run's contact
//! search asks for the cells along its wheels' tracks only. A query here
//! reads the same cells the pyramid's tiles would cover (the level that
//! [`chosen_shift`] picks, its tiles' whole extent), so its maximum is the
//! pyramid's to the bit, and a run's results do not change.

use std::fmt;
use std::sync::OnceLock;

use super::range_pyramid::{chosen_shift, larger, top_shift};

/// Cells a block has a side.
const BLOCK: usize = 64;

/// The value of cell (i, j) of an `nx × ny` grid, for `i < nx − 1` and
/// `j < ny − 1` (the last row and column start no cell: 0).
type CellFn = Box<dyn Fn(usize, usize) -> f64 + Send + Sync>;

/// Cell values of an `nx × ny` grid (cell (i, j) at node (i, j)), each
/// block of [`BLOCK`] × [`BLOCK`] cells computed once, when first read.
pub(crate) struct LazyCells {
    nx: usize,
    ny: usize,
    blocks_x: usize,
    top: u32,
    blocks: Box<[OnceLock<Box<[f64]>>]>,
    cell: CellFn,
}

impl LazyCells {
    /// The cells of an `nx × ny` grid whose values `cell` gives.
    pub(crate) fn new(nx: usize, ny: usize, cell: CellFn) -> LazyCells {
        let (blocks_x, blocks_y) = (nx.div_ceil(BLOCK), ny.div_ceil(BLOCK));
        LazyCells {
            nx,
            ny,
            blocks_x,
            top: top_shift(nx, ny),
            blocks: (0..blocks_x * blocks_y).map(|_| OnceLock::new()).collect(),
            cell,
        }
    }

    /// Block (bi, bj), row by row, computed on first use.
    fn block(&self, bi: usize, bj: usize) -> &[f64] {
        let Some(slot) = self.blocks.get(bj * self.blocks_x + bi) else {
            return &[];
        };
        slot.get_or_init(|| {
            let mut values = vec![0.0; BLOCK * BLOCK];
            for (r, row) in values.chunks_mut(BLOCK).enumerate() {
                let j = bj * BLOCK + r;
                for (c, v) in row.iter_mut().enumerate() {
                    let i = bi * BLOCK + c;
                    if i + 1 < self.nx && j + 1 < self.ny {
                        *v = (self.cell)(i, j);
                    }
                }
            }
            values.into_boxed_slice()
        })
    }

    /// The largest value over cells `i[0]..=i[1]` × `j[0]..=j[1]` (indices
    /// below `nx`, `ny`), widened as `RangePyramid::span` widens it: to the
    /// whole tiles of the level it reads.
    pub(crate) fn max(&self, i: [usize; 2], j: [usize; 2]) -> f64 {
        let s = chosen_shift(self.top, i, j);
        let widen = |k: [usize; 2], n: usize| {
            let first = (k[0] >> s) << s;
            let last = (((k[1] >> s) + 1) << s).min(n) - 1;
            [first, last]
        };
        let ([i0, i1], [j0, j1]) = (widen(i, self.nx), widen(j, self.ny));
        let mut largest = f64::NEG_INFINITY;
        for bj in j0 / BLOCK..=j1 / BLOCK {
            for bi in i0 / BLOCK..=i1 / BLOCK {
                let block = self.block(bi, bj);
                let (c0, c1) = (
                    i0.max(bi * BLOCK) - bi * BLOCK,
                    i1.min(bi * BLOCK + BLOCK - 1) - bi * BLOCK,
                );
                let (r0, r1) = (
                    j0.max(bj * BLOCK) - bj * BLOCK,
                    j1.min(bj * BLOCK + BLOCK - 1) - bj * BLOCK,
                );
                for r in r0..=r1 {
                    match block.get(r * BLOCK + c0..=r * BLOCK + c1) {
                        Some(row) => largest = row.iter().fold(largest, |m, &v| larger(m, v)),
                        None => largest = f64::INFINITY,
                    }
                }
            }
        }
        largest
    }

    /// Blocks computed so far, of all.
    pub(crate) fn computed(&self) -> (usize, usize) {
        let done = self.blocks.iter().filter(|b| b.get().is_some()).count();
        (done, self.blocks.len())
    }
}

impl fmt::Debug for LazyCells {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (done, all) = self.computed();
        write!(
            f,
            "LazyCells({} × {} cells, {done} of {all} blocks computed)",
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
        assert_eq!(lazy.computed(), (0, 16 * 13));
        // Read as the pyramid reads it: tiles of 4 × 4 cells, so up to
        // cell (523, 423).
        assert_eq!(lazy.max([500, 520], [400, 420]), (523 + 423) as f64);
        let (done, _) = lazy.computed();
        assert!(done <= 4, "{done} blocks for a 21 × 21 query");
    }
}
