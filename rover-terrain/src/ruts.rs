//! The ground's memory of the wheels that passed (docs/MODEL.md, "Ruts and
//! multipass"): at each node of a square lattice, how far the soil's
//! surface lies below the terrain's (the rut's depth d) and how deep the
//! soil was ever pressed below its undisturbed surface (the past sinkage
//! z_u, from which the soil law knows the pressure it already carried).
//!
//! Storage grows with the ground the wheels touched, never with the
//! terrain's extent: the lattice is cut into square tiles of [`TILE`] ×
//! [`TILE`] cells, created when a wheel first presses a node of theirs.
//! A tile holds its own nodes and a ring of its neighbours' around them
//! (a node near a tile's edge is stored in every tile that reads it), so
//! that a query reads one tile. A node is two `f32`s: a 1 km drive of a
//! six-wheel rover at 2 cm cells keeps about twelve thousand tiles, some
//! thirty megabytes.
//!
//! [`RutMap::sample`] is the right-hand side's query (a few a wheel): a
//! hash lookup and a quadratic B-spline over the 3 × 3 nodes nearest the
//! point, no allocation. The B-spline is C1 and reproduces linear ramps
//! exactly: a rut's wall or floor that changes steadily is read as it is,
//! without the ripples at every cell that a C1 blend of the bilinear
//! weights (smoothstep) adds to a ramp, which an implicit integrator's
//! error control would resolve step by step. [`RutMap::press`]
//! writes, between steps of the integrator; it creates tiles, from the
//! pool [`RutMap::reserve`] sized beforehand if any is left (a rig that
//! must not allocate at all in its loop reserves what its drive needs),
//! else from the heap.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use rover_dynamics::height_field::Bounds;

/// Cells along a tile's side.
pub const TILE: usize = 16;

/// Nodes along a tile's side as a view gives them: its own and the
/// first of its east (north) neighbour's.
const NODES: usize = TILE + 1;

/// Nodes stored along a tile's side: local indices −1 ..= [`TILE`], the
/// ring a read near the tile's edge needs.
const STRIDE: usize = TILE + 2;

/// The storage index of the node at local (`li`, `lj`), each in −1 ..= TILE.
#[inline]
fn at(li: i64, lj: i64) -> usize {
    (lj + 1) as usize * STRIDE + (li + 1) as usize
}

/// One tile's nodes, row by row (south first), west to east, from local
/// index −1 to [`TILE`].
#[derive(Clone, Debug)]
struct Tile {
    /// Rut depth d \[m\].
    depth: [f32; STRIDE * STRIDE],
    /// Past sinkage z_u \[m\].
    past: [f32; STRIDE * STRIDE],
    /// The map's revision when the tile last changed.
    revision: u64,
}

impl Tile {
    fn fresh() -> Box<Tile> {
        Box::new(Tile {
            depth: [0.0; STRIDE * STRIDE],
            past: [0.0; STRIDE * STRIDE],
            revision: 0,
        })
    }
}

/// A multiplicative hash of a tile's packed key: the keys are small
/// integers, the map is never exposed to outside input, and std's SipHash
/// costs more than the interpolation it guards.
#[derive(Default, Clone, Copy)]
struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, key: u64) {
        // Fibonacci hashing: the high bits, which hashbrown takes, mix
        // every bit of the key.
        self.0 = (self.0 ^ key).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        self.0 ^= self.0 >> 29;
    }
}

type Index = HashMap<u64, u32, BuildHasherDefault<KeyHasher>>;

fn key(ti: i64, tj: i64) -> u64 {
    ((ti as i32 as u32 as u64) << 32) | (tj as i32 as u32 as u64)
}

/// The memory at one point, interpolated bilinearly from its cell's
/// corners: zero on ground no wheel touched.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RutSample {
    /// Rut depth d \[m\] (≥ 0).
    pub depth: f64,
    /// `[∂d/∂X, ∂d/∂Y]` [m/m].
    pub gradient: [f64; 2],
    /// Past sinkage z_u \[m\] (≥ 0).
    pub past_sinkage: f64,
}

/// Where a wheel presses, at one instant: the line across its rim's
/// lowest point, `half_width` either side along `axle`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// `[X, Y]` of the contact point \[m\].
    pub centre: [f64; 2],
    /// The wheel's axle projected on the ground, a unit vector.
    pub axle: [f64; 2],
    /// Half the wheel's width \[m\].
    pub half_width: f64,
    /// How deep below the undisturbed surface the wheel pressed the soil
    /// there, z \[m\].
    pub past_sinkage: f64,
}

/// A tile's nodes, for drawing or writing them ([`RutMap::tiles_since`]):
/// its own and the first row and column of its east and north
/// neighbours', [`TILE`] + 1 along each side.
#[derive(Clone, Copy, Debug)]
pub struct TileView<'a> {
    /// `[X, Y]` of its south-west node \[m\].
    pub origin: [f64; 2],
    /// Nodes along each side ([`TILE`] + 1).
    pub nodes: usize,
    /// The stored depths (a ring wider than the view).
    stored: &'a [f32],
}

impl TileView<'_> {
    /// The rut depth \[m\] at node (`li`, `lj`), each in 0 ..= [`TILE`].
    pub fn depth(&self, li: usize, lj: usize) -> f32 {
        self.stored[at(li as i64, lj as i64)]
    }

    /// The depths \[m\], south row first, west to east: `nodes²` of them.
    pub fn depths(&self) -> impl Iterator<Item = f32> + '_ {
        (0..self.nodes).flat_map(move |lj| (0..self.nodes).map(move |li| self.depth(li, lj)))
    }
}

/// The rut depth and past sinkage of the ground, in sparse tiles.
///
/// The tiles are boxed: the list of them then holds 8 bytes a tile, so
/// that its growth copies pointers, not 2.3 KB a tile, and its spare
/// capacity (up to as much again as it holds) costs pointers, not tiles.
#[derive(Clone, Debug)]
#[allow(clippy::vec_box)]
pub struct RutMap {
    cell: f64,
    inv_cell: f64,
    index: Index,
    tiles: Vec<Box<Tile>>,
    /// Tiles made ahead of need ([`RutMap::reserve`]).
    pool: Vec<Box<Tile>>,
    /// Bumped by every [`RutMap::press`] that changed a node.
    revision: u64,
    /// The deepest rut \[m\].
    deepest: f64,
    /// The touched tiles' range of indices, `[ti_min, ti_max, tj_min, tj_max]`.
    extent: Option<[i64; 4]>,
}

impl RutMap {
    /// An empty map of square cells of side `cell` \[m\] (> 0 and finite:
    /// the caller checks the user's value), its lattice through the origin.
    pub fn new(cell: f64) -> Self {
        assert!(cell.is_finite() && cell > 0.0, "a rut cell of {cell} m");
        Self {
            cell,
            inv_cell: 1.0 / cell,
            index: Index::default(),
            tiles: Vec::new(),
            pool: Vec::new(),
            revision: 0,
            deepest: 0.0,
            extent: None,
        }
    }

    /// Makes `tiles` tiles ahead of need, and room for them in the index,
    /// so that presses creating up to that many allocate nothing.
    pub fn reserve(&mut self, tiles: usize) {
        self.index.reserve(tiles);
        self.tiles.reserve(tiles);
        self.pool.extend((0..tiles).map(|_| Tile::fresh()));
    }

    /// The cell's side \[m\].
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// How many tiles the wheels have touched.
    pub fn tile_count(&self) -> usize {
        self.tiles.len()
    }

    /// The heap the map holds \[bytes\]: its tiles (the pool's included)
    /// and the index's table, by their capacities.
    pub fn heap_bytes(&self) -> usize {
        let tile = std::mem::size_of::<Tile>();
        let boxes = std::mem::size_of::<Box<Tile>>();
        let slot = std::mem::size_of::<(u64, u32)>() + 1;
        (self.tiles.len() + self.pool.len()) * tile
            + (self.tiles.capacity() + self.pool.capacity()) * boxes
            + self.index.capacity() * slot
    }

    /// The deepest rut \[m\] (0 on an untouched map).
    pub fn deepest(&self) -> f64 {
        self.deepest
    }

    /// The revision: it changes whenever a press changes a node.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The memory at (`x`, `y`) \[m\]; zero where no wheel pressed, and at
    /// a non-finite point: the quadratic B-spline of the 3 × 3 nodes
    /// nearest it (module doc). Allocates nothing.
    #[inline]
    pub fn sample(&self, x: f64, y: f64) -> RutSample {
        let (gx, gy) = (x * self.inv_cell, y * self.inv_cell);
        if !(gx.is_finite() && gy.is_finite()) || gx.abs() > 1e15 || gy.abs() > 1e15 {
            return RutSample::default();
        }
        let (mx, my) = (gx.round(), gy.round());
        let (i, j) = (mx as i64, my as i64);
        let t = TILE as i64;
        let Some(&slot) = self.index.get(&key(i.div_euclid(t), j.div_euclid(t))) else {
            return RutSample::default();
        };
        let tile = &self.tiles[slot as usize];
        let (li, lj) = (i.rem_euclid(t), j.rem_euclid(t));
        // The weights of the nodes m − 1, m, m + 1 at u = g − m in
        // [−½, ½], and their derivatives in u.
        let spline = |u: f64| {
            let (a, c) = (0.5 - u, 0.5 + u);
            ([0.5 * a * a, 0.75 - u * u, 0.5 * c * c], [-a, -2.0 * u, c])
        };
        let (wx, dx) = spline(gx - mx);
        let (wy, dy) = spline(gy - my);
        let mut out = RutSample::default();
        for (b, (&wyb, &dyb)) in wy.iter().zip(&dy).enumerate() {
            let row = at(li - 1, lj - 1 + b as i64);
            let (mut d, mut d_x, mut p) = (0.0, 0.0, 0.0);
            for (a, (&wxa, &dxa)) in wx.iter().zip(&dx).enumerate() {
                let depth = f64::from(tile.depth[row + a]);
                d += wxa * depth;
                d_x += dxa * depth;
                p += wxa * f64::from(tile.past[row + a]);
            }
            out.depth += wyb * d;
            out.gradient[0] += wyb * d_x;
            out.gradient[1] += dyb * d;
            out.past_sinkage += wyb * p;
        }
        out.gradient = out.gradient.map(|g| g * self.inv_cell);
        out
    }

    /// Presses the soil along a wheel's path from `from` to `to` (two
    /// consecutive footprints of one wheel): every node the swept band
    /// covers is pressed to the past sinkage interpolated along the path,
    /// where that is deeper than it was, and its rut is then
    /// `rut_depth(z_u)` (the soil law's depth left once the wheel is gone)
    /// where that is deeper than the rut already there. The band is
    /// rasterized by nearest node at half a cell's spacing both ways, so
    /// that no node within it is skipped, and a wheel that stood still
    /// presses the line of its footprint. Returns whether any node changed.
    pub fn press(
        &mut self,
        from: &Footprint,
        to: &Footprint,
        rut_depth: impl Fn(f64) -> f64,
    ) -> bool {
        let h = self.cell;
        let along = (to.centre[0] - from.centre[0]).hypot(to.centre[1] - from.centre[1]);
        let width = from.half_width.max(to.half_width);
        if !(along.is_finite() && width.is_finite()) {
            return false;
        }
        let steps_along = (along / (0.5 * h)).ceil().max(1.0) as usize;
        let steps_across = ((2.0 * width) / (0.5 * h)).ceil().max(1.0) as usize;
        let mut changed = false;
        self.revision += 1;
        for a in 0..=steps_along {
            let s = a as f64 / steps_along as f64;
            let lerp = |p: f64, q: f64| p + s * (q - p);
            let c = [0, 1].map(|k| lerp(from.centre[k], to.centre[k]));
            let axle = [0, 1].map(|k| lerp(from.axle[k], to.axle[k]));
            let norm = axle[0].hypot(axle[1]);
            if norm.is_nan() || norm <= 0.0 {
                continue;
            }
            let axle = axle.map(|v| v / norm);
            let w = lerp(from.half_width, to.half_width);
            let z = lerp(from.past_sinkage, to.past_sinkage);
            if !(z > 0.0 && z.is_finite()) {
                continue;
            }
            let rut = rut_depth(z).clamp(0.0, z);
            for b in 0..=steps_across {
                let u = -w + 2.0 * w * b as f64 / steps_across as f64;
                let (x, y) = (c[0] + u * axle[0], c[1] + u * axle[1]);
                let (i, j) = ((x / h).round() as i64, (y / h).round() as i64);
                changed |= self.press_node(i, j, z as f32, rut as f32);
            }
        }
        if !changed {
            self.revision -= 1;
        }
        changed
    }

    /// Presses node (`i`, `j`) to past sinkage `z`, its rut then `rut`,
    /// in every tile that holds it.
    fn press_node(&mut self, i: i64, j: i64, z: f32, rut: f32) -> bool {
        let t = TILE as i64;
        // Along each axis: the tile that owns the node, and the neighbour
        // whose ring holds it when it lies on the owner's edge.
        let holders = |g: i64| {
            let (tile, local) = (g.div_euclid(t), g.rem_euclid(t));
            let other = if local == 0 {
                Some((tile - 1, t))
            } else if local == t - 1 {
                Some((tile + 1, -1))
            } else {
                None
            };
            ((tile, local), other)
        };
        let (own_x, other_x) = holders(i);
        let (own_y, other_y) = holders(j);
        // The owner's copy says whether it is pressed deeper; every copy
        // holds the same values.
        let slot = self.tile_slot(own_x.0, own_y.0);
        if z <= self.tiles[slot].past[at(own_x.1, own_y.1)] {
            return false;
        }
        let revision = self.revision;
        for (tx, lx) in [Some(own_x), other_x].into_iter().flatten() {
            for (ty, ly) in [Some(own_y), other_y].into_iter().flatten() {
                let slot = self.tile_slot(tx, ty);
                let tile = &mut self.tiles[slot];
                let n = at(lx, ly);
                tile.past[n] = z;
                tile.depth[n] = tile.depth[n].max(rut);
                tile.revision = revision;
                self.deepest = self.deepest.max(f64::from(tile.depth[n]));
            }
        }
        true
    }

    /// The slot of tile (`ti`, `tj`), made if it is not there yet.
    fn tile_slot(&mut self, ti: i64, tj: i64) -> usize {
        let k = key(ti, tj);
        if let Some(&slot) = self.index.get(&k) {
            return slot as usize;
        }
        let tile = self.pool.pop().unwrap_or_else(Tile::fresh);
        let slot = self.tiles.len();
        self.tiles.push(tile);
        self.index.insert(k, slot as u32);
        self.extent = Some(match self.extent {
            None => [ti, ti, tj, tj],
            Some([a, b, c, d]) => [a.min(ti), b.max(ti), c.min(tj), d.max(tj)],
        });
        slot
    }

    /// The rectangle the touched tiles cover \[m\], or `None` on an
    /// untouched map.
    pub fn bounds(&self) -> Option<Bounds> {
        let [a, b, c, d] = self.extent?;
        let side = TILE as f64 * self.cell;
        Some(Bounds {
            x_min: a as f64 * side,
            x_max: (b + 1) as f64 * side,
            y_min: c as f64 * side,
            y_max: (d + 1) as f64 * side,
        })
    }

    /// The tiles changed after revision `since` (every tile for 0), in the
    /// order they were made.
    pub fn tiles_since(&self, since: u64) -> impl Iterator<Item = TileView<'_>> + '_ {
        let side = TILE as f64 * self.cell;
        self.index.iter().filter_map(move |(&k, &slot)| {
            let tile = &self.tiles[slot as usize];
            (tile.revision > since).then(|| {
                let (ti, tj) = ((k >> 32) as u32 as i32, k as u32 as i32);
                TileView {
                    origin: [f64::from(ti) * side, f64::from(tj) * side],
                    nodes: NODES,
                    stored: &tile.depth[..],
                }
            })
        })
    }

    /// The rut depths at the nodes of the touched tiles' rectangle, with
    /// the lattice's origin there: `(origin [m], [nx, ny], depths [m],
    /// south row first)`; `None` on an untouched map. Untouched nodes are 0.
    pub fn depth_grid(&self) -> Option<([f64; 2], [usize; 2], Vec<f64>)> {
        let [a, b, c, d] = self.extent?;
        let t = TILE as i64;
        let (i0, j0) = (a * t, c * t);
        let nx = ((b - a + 1) * t + 1) as usize;
        let ny = ((d - c + 1) * t + 1) as usize;
        let mut depths = vec![0.0; nx * ny];
        for (&k, &slot) in &self.index {
            let (ti, tj) = (
                i64::from((k >> 32) as u32 as i32),
                i64::from(k as u32 as i32),
            );
            let tile = &self.tiles[slot as usize];
            for lj in 0..NODES {
                for li in 0..NODES {
                    let gi = (ti * t + li as i64 - i0) as usize;
                    let gj = (tj * t + lj as i64 - j0) as usize;
                    depths[gj * nx + gi] = f64::from(tile.depth[at(li as i64, lj as i64)]);
                }
            }
        }
        Some((
            [i0 as f64 * self.cell, j0 as f64 * self.cell],
            [nx, ny],
            depths,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn footprint(x: f64, y: f64, z: f64) -> Footprint {
        Footprint {
            centre: [x, y],
            axle: [0.0, 1.0],
            half_width: 0.08,
            past_sinkage: z,
        }
    }

    /// A straight pass presses a band as wide as the wheel and as long as
    /// its path, to the depth the law gives, and nothing beyond it.
    #[test]
    fn a_pass_presses_a_band_of_the_wheels_width() {
        let mut map = RutMap::new(0.02);
        let rut = |z: f64| 0.8 * z;
        assert!(map.press(&footprint(-0.3, 0.5, 0.02), &footprint(0.7, 0.5, 0.02), rut));
        let inside = map.sample(0.2, 0.5);
        // Depths are stored as f32: to 2e-9 m at 2 cm.
        let stored = 0.02 * f64::from(f32::EPSILON);
        assert!((inside.depth - 0.016).abs() < stored, "{inside:?}");
        assert!((inside.past_sinkage - 0.02).abs() < stored);
        assert!(
            inside.gradient.iter().all(|g| g.abs() < 1e-12),
            "{inside:?}"
        );
        for (x, y) in [
            (0.2, 0.65),
            (0.2, 0.35),
            (0.8, 0.5),
            (-0.4, 0.5),
            (50.0, -3.0),
        ] {
            assert_eq!(map.sample(x, y), RutSample::default(), "({x}, {y})");
        }
        // Across the band's edge the depth falls over a cell and a half.
        let edge = map.sample(0.2, 0.59);
        assert!(edge.depth > 0.0 && edge.depth < 0.016 && edge.gradient[1] < 0.0);
        assert!(map.deepest() > 0.0159 && map.deepest() < 0.0161);
    }

    /// Pressing is a maximum: a shallower pass changes nothing, a deeper
    /// one deepens; the same press twice changes nothing the second time.
    #[test]
    fn the_soil_remembers_its_deepest_press() {
        let mut map = RutMap::new(0.02);
        let rut = |z: f64| z - 0.002;
        let (a, b) = (footprint(0.0, 0.0, 0.02), footprint(0.5, 0.0, 0.02));
        assert!(map.press(&a, &b, rut));
        let rev = map.revision();
        assert!(!map.press(&a, &b, rut));
        let shallow = |x| footprint(x, 0.0, 0.01);
        assert!(!map.press(&shallow(0.0), &shallow(0.5), rut));
        assert_eq!(map.revision(), rev);
        let stored = 0.03 * f64::from(f32::EPSILON);
        assert!((map.sample(0.25, 0.0).past_sinkage - 0.02).abs() < stored);
        let deep = |x| footprint(x, 0.0, 0.03);
        assert!(map.press(&deep(0.0), &deep(0.5), rut));
        assert!((map.sample(0.25, 0.0).depth - 0.028).abs() < stored);
        assert!(map.tiles_since(rev).count() > 0);
        assert_eq!(map.tiles_since(map.revision()).count(), 0);
    }

    /// Tiles are shared at their borders: a band across tile corners and
    /// into negative coordinates reads the same depth on either side of
    /// every border, and the grid of the touched tiles holds it.
    #[test]
    fn tile_borders_and_negative_coordinates_read_alike() {
        let mut map = RutMap::new(0.02);
        let side = TILE as f64 * 0.02;
        let diagonal = |s: f64| Footprint {
            centre: [s, s],
            axle: [-0.5f64.sqrt(), 0.5f64.sqrt()],
            half_width: 0.1,
            past_sinkage: 0.02,
        };
        map.press(&diagonal(-2.0 * side), &diagonal(2.0 * side), |z| z);
        // Depths are stored as f32: to 2e-9 m at 2 cm.
        let stored = 0.02 * f64::from(f32::EPSILON);
        for k in -1..=1 {
            let at = k as f64 * side;
            for e in [-1e-9, 0.0, 1e-9] {
                let s = map.sample(at + e, at + e);
                assert!((s.depth - 0.02).abs() < stored, "{at} {e}: {s:?}");
            }
        }
        let (origin, [nx, ny], depths) = map.depth_grid().unwrap();
        let b = map.bounds().unwrap();
        assert_eq!([origin[0], origin[1]], [b.x_min, b.y_min]);
        assert_eq!((nx - 1) as f64 * 0.02, b.x_max - b.x_min);
        let (i, j) = (
            ((0.0 - origin[0]) / 0.02).round() as usize,
            ((0.0 - origin[1]) / 0.02).round() as usize,
        );
        assert_eq!(depths[j * nx + i], f64::from(0.02f32));
        assert_eq!(depths.len(), nx * ny);
    }

    /// Storage grows with the path, not with how far it goes from the
    /// origin; a reserved pool is used before the heap.
    #[test]
    fn storage_follows_the_touched_ground() {
        let drive = |x0: f64| {
            let mut map = RutMap::new(0.02);
            let mut last = footprint(x0, 0.0, 0.02);
            for k in 1..=100 {
                let next = footprint(x0 + 0.1 * k as f64, 0.0, 0.02);
                map.press(&last, &next, |z| z);
                last = next;
            }
            map
        };
        let near = drive(0.0);
        // 50 km east, on the same tile boundaries.
        let far = drive(156_250.0 * TILE as f64 * 0.02);
        assert_eq!(near.tile_count(), far.tile_count());
        // 10 m of a 16 cm band: 32 tiles along, 1 or 2 across.
        assert!(
            near.tile_count() >= 32 && near.tile_count() <= 70,
            "{}",
            near.tile_count()
        );
        let mut pooled = RutMap::new(0.02);
        pooled.reserve(80);
        let before = pooled.heap_bytes();
        pooled.press(
            &footprint(0.0, 0.0, 0.02),
            &footprint(10.0, 0.0, 0.02),
            |z| z,
        );
        assert_eq!(pooled.heap_bytes(), before);
    }
}
