//! The highest and lowest node over any rectangle of a grid, bounded from
//! a pyramid of tiles, so that the contact search's bound on the ground
//! under a wheel costs a few reads, not every node.
//!
//! Level 0 holds the range of every 2 × 2 block of nodes, level k + 1 that
//! of every 2 × 2 block of level-k tiles (tiles of 2^(k+1) nodes a side),
//! up to one tile over the whole grid: two values per 2 × 2 block and its
//! parents, two thirds of a value per node (the 8 × 8 tiles it replaces
//! kept 1/32; at the 50-million-node limit of a random field, 267 MB next
//! to the heights' 400 MB). A query reads the finest level on which the rectangle
//! touches at most [`MAX_TILES`] tiles, so the bound stays close to the
//! rectangle whatever the grid's resolution and the read count stays
//! bounded. A single tile size could not do both: with the 8 × 8 tiles
//! used before, the bound under a wheel on a 5 cm map reached up to 35 cm
//! beyond it and the search sampled rim it did not need (this pyramid cut
//! the contact search of Fig. 13, swing4, by 19 % and of Fig. 8, ExoMars,
//! by 22 % in instructions, callgrind, with the same results bit for bit),
//! while 2 × 2 tiles alone would cost a wheel on a centimetre map hundreds
//! of reads per query.

/// Most tiles one query reads.
const MAX_TILES: usize = 36;

/// One level: tiles of `2^shift × 2^shift` nodes (a shift, not a size: a
/// query divides node indices by it, and integer division is slow).
#[derive(Debug, Clone, PartialEq)]
struct Level {
    shift: u32,
    columns: usize,
    max: Vec<f64>,
    min: Vec<f64>,
}

/// The pyramid of node ranges of an `nx × ny` grid.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RangePyramid {
    levels: Vec<Level>,
}

impl RangePyramid {
    /// The pyramid of `heights` (`nx` nodes per row, south row first).
    pub(crate) fn new(nx: usize, heights: &[f64]) -> RangePyramid {
        Self::build(nx, heights, Some(heights))
    }

    /// The pyramid of the highest values only: [`RangePyramid::span`] then
    /// bounds nothing from below (−∞). The reference the lazy cell bounds
    /// are held to.
    #[cfg(test)]
    pub(crate) fn upper(nx: usize, values: &[f64]) -> RangePyramid {
        Self::build(nx, values, None)
    }

    fn build(nx: usize, max: &[f64], min: Option<&[f64]>) -> RangePyramid {
        // The nodes are level "−1": tiles of one node, max = min = height.
        Self::above(reduce(max, min, nx, 1))
    }

    /// The pyramid on its finest level.
    fn above(first: Level) -> RangePyramid {
        let mut levels = vec![first];
        loop {
            let top = &levels[levels.len() - 1];
            if top.max.len() <= 1 {
                return RangePyramid { levels };
            }
            let min = (!top.min.is_empty()).then_some(&top.min[..]);
            let up = reduce(&top.max, min, top.columns, top.shift + 1);
            levels.push(up);
        }
    }

    /// Highest and lowest node over nodes `i[0]..=i[1]` × `j[0]..=j[1]` (a
    /// superset: whole tiles of the finest level where they are at most
    /// [`MAX_TILES`]).
    pub(crate) fn span(&self, i: [usize; 2], j: [usize; 2]) -> (f64, f64) {
        // Level k has tiles of 2^(k + 1) nodes a side.
        let shift = chosen_shift(self.levels.len() as u32, i, j);
        let Some(level) = self.levels.get(shift as usize - 1) else {
            return (f64::INFINITY, f64::NEG_INFINITY);
        };
        // Row by row over slices, without a bounds check for every tile (a
        // tile off the level, which no caller asks for, bounds nothing).
        let (first, last) = (i[0] >> level.shift, i[1] >> level.shift);
        let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
        for row in j[0] >> level.shift..=j[1] >> level.shift {
            let start = row * level.columns + first;
            let end = row * level.columns + last;
            match level.max.get(start..=end) {
                Some(tiles) => hi = tiles.iter().fold(hi, |m, &v| larger(m, v)),
                None => hi = f64::INFINITY,
            }
            match level.min.get(start..=end) {
                Some(tiles) => lo = tiles.iter().fold(lo, |m, &v| smaller(m, v)),
                None => lo = f64::NEG_INFINITY,
            }
        }
        (hi, lo)
    }
}

/// The shift of the level (tiles of `2^shift` nodes a side) that a query
/// over nodes `i[0]..=i[1]` × `j[0]..=j[1]` reads in a pyramid whose top
/// level has shift `top`: the finest on which the query touches at most
/// [`MAX_TILES`] tiles, else the top one. Shared with
/// [`LazyCells`](super::lazy_cells::LazyCells), which reads the same cells.
pub(crate) fn chosen_shift(top: u32, i: [usize; 2], j: [usize; 2]) -> u32 {
    let tiles = |s: u32| ((i[1] >> s) - (i[0] >> s) + 1) * ((j[1] >> s) - (j[0] >> s) + 1);
    (1..=top).find(|&s| tiles(s) <= MAX_TILES).unwrap_or(top)
}

/// The shift of the top level of a pyramid over `nx × ny` nodes: the first
/// whose tiles cover the grid with one.
pub(crate) fn top_shift(nx: usize, ny: usize) -> u32 {
    let mut s = 1;
    while nx.div_ceil(1 << s) * ny.div_ceil(1 << s) > 1 {
        s += 1;
    }
    s
}

/// The ranges of every 2 × 2 block of a level of `columns` columns
/// (`max`, `min` row by row, south row first; no `min`, none kept), as the
/// level of tiles of `2^shift` nodes a side.
fn reduce(max: &[f64], min: Option<&[f64]>, columns: usize, shift: u32) -> Level {
    let rows = max.len() / columns;
    let (up_columns, up_rows) = (columns.div_ceil(2), rows.div_ceil(2));
    let mut up = Level {
        shift,
        columns: up_columns,
        max: vec![f64::NEG_INFINITY; up_columns * up_rows],
        min: Vec::new(),
    };
    fn fold(up: &mut [f64], values: &[f64], columns: usize, pick: impl Fn(f64, f64) -> f64 + Copy) {
        let up_columns = columns.div_ceil(2);
        for (row, values) in values.chunks(columns).enumerate() {
            fold_pairs(
                &mut up[(row / 2) * up_columns..][..up_columns],
                values,
                pick,
            );
        }
    }
    fold(&mut up.max, max, columns, larger);
    if let Some(min) = min {
        up.min = vec![f64::INFINITY; up_columns * up_rows];
        fold(&mut up.min, min, columns, smaller);
    }
    up
}

/// The larger of `m` and `v`, and [`smaller`]: one comparison each (a
/// `maxsd`), where `f64::max` and `min` spend several instructions on NaN
/// (a third of a bound query, callgrind; the slope bounds' maxima of
/// magnitudes use it too). They agree with `f64::max` and `min` whenever
/// `m` is not NaN, which a fold from ±∞ never makes it (a NaN `v` is passed
/// over by both), up to the sign of a zero, which no bound's use can tell.
#[inline(always)]
pub(crate) fn larger(m: f64, v: f64) -> f64 {
    if v > m { v } else { m }
}

/// The smaller of `m` and `v` (see [`larger`]).
#[inline(always)]
fn smaller(m: f64, v: f64) -> f64 {
    if v < m { v } else { m }
}

/// Folds one row of `values` into the row of `tiles` above it, each pair of
/// neighbours into one tile by `pick` (the larger or the smaller).
/// Pairs as fixed arrays and `pick` a type of its own: the loop is straight
/// (the slices' `chunks(2)` and a function pointer made it a third of
/// building a random terrain).
#[inline(always)]
fn fold_pairs(tiles: &mut [f64], values: &[f64], pick: impl Fn(f64, f64) -> f64) {
    let (pairs, odd) = values.as_chunks::<2>();
    for (tile, &[a, b]) in tiles.iter_mut().zip(pairs) {
        *tile = pick(pick(*tile, a), b);
    }
    if let (Some(&v), Some(tile)) = (odd.first(), tiles.get_mut(pairs.len())) {
        *tile = pick(*tile, v);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On grids of awkward sizes, every rectangle's bound contains its
    /// nodes' true range, and is the true range for a 2 × 2 block aligned
    /// with the tiles.
    #[test]
    fn a_span_bounds_the_nodes_of_its_rectangle() {
        let mut rng = crate::prng::SplitMix64::new(0x9e37_79b9_7f4a_7c15);
        let mut next = move |n: usize| (rng.next_u64() % n as u64) as usize;
        for (nx, ny) in [(2, 2), (3, 7), (17, 5), (64, 64), (101, 37)] {
            let heights: Vec<f64> = (0..nx * ny)
                .map(|k| ((k * 7919) % 1013) as f64 * 0.001 - 0.5)
                .collect();
            let p = RangePyramid::new(nx, &heights);
            let upper = RangePyramid::upper(nx, &heights);
            assert_eq!(
                p.levels.last().map(|l| l.max.len()),
                Some(1),
                "{nx} × {ny}: one tile on top"
            );
            for _ in 0..500 {
                let (a, b) = (next(nx), next(nx));
                let (c, d) = (next(ny), next(ny));
                let (i, j) = ([a.min(b), a.max(b)], [c.min(d), c.max(d)]);
                let (mut hi, mut lo) = (f64::NEG_INFINITY, f64::INFINITY);
                for y in j[0]..=j[1] {
                    for x in i[0]..=i[1] {
                        hi = hi.max(heights[y * nx + x]);
                        lo = lo.min(heights[y * nx + x]);
                    }
                }
                let (bh, bl) = p.span(i, j);
                assert!(bh >= hi && bl <= lo, "{nx} × {ny}, {i:?} × {j:?}");
                assert_eq!(
                    upper.span(i, j),
                    (bh, f64::NEG_INFINITY),
                    "{nx} × {ny}, {i:?} × {j:?}: the upper pyramid"
                );
                if i[0] % 2 == 0
                    && j[0] % 2 == 0
                    && i[1] == (i[0] + 1).min(nx - 1)
                    && j[1] == (j[0] + 1).min(ny - 1)
                {
                    assert_eq!(
                        (bh, bl),
                        (hi, lo),
                        "{nx} × {ny}, {i:?} × {j:?}: an aligned 2 × 2 block"
                    );
                }
            }
        }
    }
}
