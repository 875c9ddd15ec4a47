//! The ruts as the page draws them (docs/DRIVE.md, "Ruts"): tiles of rut
//! depth, sent as `{"type": "ruts", …}` messages.
//!
//! In `rover drive` the loop copies the tiles the wheels changed into a
//! [`RutFeed`] at most every [`RUT_PERIOD`] (a copy of a few tiles, off
//! the step), and each WebSocket client is sent the tiles changed since it
//! was last sent any: a client that joins late gets every tile, over as
//! many messages as it takes. `rover view` sends the run's `ruts.csv` cut
//! into tiles the same way, in one message.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::time::Duration;

use rover_terrain::Grid;
use rover_terrain::ruts::{RutMap, TILE};

/// How often the loop copies the changed tiles, and how often a client is
/// sent them.
pub const RUT_PERIOD: Duration = Duration::from_millis(200);

/// Metres per count of a message's depths (0.01 mm, as `ruts.png`).
pub const RUT_SCALE: f64 = 1e-5;

/// Most tiles in one message (a tile of 17 × 17 nodes is about a
/// kilobyte of JSON): well within a WebSocket message.
pub const MAX_TILES_PER_MESSAGE: usize = 256;

/// One tile as the loop last copied it.
#[derive(Clone, Debug)]
struct FeedTile {
    origin: [f64; 2],
    nodes: [usize; 2],
    /// Depth \[m\], south row first.
    depth: Vec<f32>,
    /// The feed's revision when it was copied.
    revision: u64,
}

/// The ruts the clients are sent: each tile's last copy, and when it was
/// made.
#[derive(Clone, Debug, Default)]
pub struct RutFeed {
    cell: f64,
    /// The map's revision at the last copy.
    revision: u64,
    index: HashMap<[i64; 2], usize>,
    tiles: Vec<FeedTile>,
}

impl RutFeed {
    /// Copies the tiles of `map` changed since the last copy; whether any
    /// was. Allocates only for a tile not seen before.
    pub fn update(&mut self, map: &RutMap) -> bool {
        let revision = map.revision();
        if revision == self.revision {
            return false;
        }
        self.cell = map.cell();
        let side = TILE as f64 * map.cell();
        for view in map.tiles_since(self.revision) {
            let key = [0, 1].map(|k| (view.origin[k] / side).round() as i64);
            let slot = *self.index.entry(key).or_insert_with(|| {
                self.tiles.push(FeedTile {
                    origin: view.origin,
                    nodes: [view.nodes; 2],
                    depth: vec![0.0; view.nodes * view.nodes],
                    revision: 0,
                });
                self.tiles.len() - 1
            });
            let tile = &mut self.tiles[slot];
            for (d, v) in tile.depth.iter_mut().zip(view.depths()) {
                *d = v;
            }
            tile.revision = revision;
        }
        self.revision = revision;
        true
    }

    /// The feed of a whole grid of depths \[m\] (a run's `ruts.csv`), cut
    /// into tiles of [`TILE`] cells; tiles without a rut are left out.
    pub fn of_grid(grid: &Grid) -> RutFeed {
        let (nx, ny) = (grid.nx(), grid.ny());
        let [x0, y0] = grid.origin();
        let [dx, dy] = grid.spacing();
        let mut feed = RutFeed {
            cell: dx,
            revision: 1,
            ..RutFeed::default()
        };
        for tj in (0..ny - 1).step_by(TILE) {
            for ti in (0..nx - 1).step_by(TILE) {
                let (mx, my) = ((nx - ti).min(TILE + 1), (ny - tj).min(TILE + 1));
                let mut depth = Vec::with_capacity(mx * my);
                for j in tj..tj + my {
                    for i in ti..ti + mx {
                        depth.push(grid.node(i, j).unwrap_or(0.0) as f32);
                    }
                }
                if depth.iter().any(|d| *d > 0.0) {
                    feed.tiles.push(FeedTile {
                        origin: [x0 + ti as f64 * dx, y0 + tj as f64 * dy],
                        nodes: [mx, my],
                        depth,
                        revision: 1,
                    });
                }
            }
        }
        feed
    }

    /// The feed's revision: a client sent everything up to it is up to date.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The message of the tiles changed after revision `since` (every
    /// tile for 0), at most [`MAX_TILES_PER_MESSAGE`] of them unless one
    /// copy changed more, with the revision the client is then up to;
    /// `None` when none changed.
    pub fn message(&self, since: u64) -> Option<(String, u64)> {
        let mut changed: Vec<&FeedTile> =
            self.tiles.iter().filter(|t| t.revision > since).collect();
        if changed.is_empty() {
            return None;
        }
        changed.sort_by_key(|t| t.revision);
        let mut upto = changed.len();
        if upto > MAX_TILES_PER_MESSAGE {
            // Whole copies only: the client's revision must cover every
            // tile of the copies it was sent.
            let last = changed[MAX_TILES_PER_MESSAGE].revision;
            upto = changed.partition_point(|t| t.revision < last);
            if upto == 0 {
                upto = changed.partition_point(|t| t.revision <= last);
            }
        }
        let sent = &changed[..upto];
        let revision = sent[sent.len() - 1].revision;
        let mut out = String::with_capacity(64 + 1200 * sent.len());
        let _ = write!(
            out,
            "{{\"type\":\"ruts\",\"cell\":{},\"scale\":{RUT_SCALE},\"revision\":{revision},\"tiles\":[",
            self.cell
        );
        for (k, t) in sent.iter().enumerate() {
            let sep = if k == 0 { "" } else { "," };
            let _ = write!(
                out,
                "{sep}{{\"origin\":[{},{}],\"nodes\":[{},{}],\"depth\":[",
                t.origin[0], t.origin[1], t.nodes[0], t.nodes[1]
            );
            for (i, d) in t.depth.iter().enumerate() {
                let sep = if i == 0 { "" } else { "," };
                let count = (f64::from(*d) / RUT_SCALE).round().max(0.0) as u64;
                let _ = write!(out, "{sep}{count}");
            }
            out.push_str("]}");
        }
        out.push_str("]}");
        Some((out, revision))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rover_terrain::ruts::Footprint;

    fn press(map: &mut RutMap, x0: f64, x1: f64, y: f64) {
        let at = |x| Footprint {
            centre: [x, y],
            axle: [0.0, 1.0],
            half_width: 0.08,
            past_sinkage: 0.02,
        };
        map.press(&at(x0), &at(x1), |z| 0.5 * z);
    }

    fn tiles(message: &str) -> Vec<serde_json::Value> {
        let v: serde_json::Value = serde_json::from_str(message).unwrap();
        assert_eq!(v["type"], "ruts");
        v["tiles"].as_array().unwrap().clone()
    }

    /// A client is sent every tile once, then only the tiles a later press
    /// changed; the depths come back to the scale's resolution.
    #[test]
    fn a_client_is_sent_each_change_once() {
        let mut map = RutMap::new(0.02);
        let mut feed = RutFeed::default();
        press(&mut map, 0.0, 3.0, 0.0);
        assert!(feed.update(&map));
        assert!(!feed.update(&map));
        let (first, rev) = feed.message(0).unwrap();
        let sent = tiles(&first);
        assert_eq!(sent.len(), map.tile_count());
        let deepest = sent
            .iter()
            .flat_map(|t| t["depth"].as_array().unwrap().clone())
            .map(|k| k.as_f64().unwrap() * RUT_SCALE)
            .fold(0.0, f64::max);
        assert!((deepest - map.deepest()).abs() <= 0.5 * RUT_SCALE);
        assert!(feed.message(rev).is_none());
        // A press far away: only its tiles.
        let before = map.tile_count();
        press(&mut map, 10.0, 10.5, 5.0);
        feed.update(&map);
        let (second, _) = feed.message(rev).unwrap();
        let changed = tiles(&second);
        assert_eq!(changed.len(), map.tile_count() - before);
        assert!(
            changed
                .iter()
                .all(|t| t["origin"][0].as_f64().unwrap() > 9.0)
        );
    }

    /// A client that joins late is sent everything over several messages,
    /// each within the limit, none twice.
    #[test]
    fn a_late_client_is_sent_everything_in_parts() {
        let mut map = RutMap::new(0.02);
        let mut feed = RutFeed::default();
        for k in 0..40 {
            press(&mut map, 0.0, 8.0, k as f64 * 0.4);
            feed.update(&map);
        }
        assert!(map.tile_count() > MAX_TILES_PER_MESSAGE);
        let (mut since, mut total, mut messages) = (0, 0, 0);
        while let Some((m, rev)) = feed.message(since) {
            let n = tiles(&m).len();
            assert!(n <= MAX_TILES_PER_MESSAGE, "{n}");
            total += n;
            messages += 1;
            since = rev;
        }
        assert_eq!(total, map.tile_count());
        assert!(messages > 1);
    }

    /// A grid cut into tiles holds its depths at their places.
    #[test]
    fn a_grid_is_cut_into_tiles() {
        let (nx, ny) = (40, 20);
        let grid = Grid::from_fn([1.0, 2.0], [0.02, 0.02], nx, ny, |x, y| {
            if (x - 1.5).abs() < 0.05 && y > 2.2 {
                0.01
            } else {
                0.0
            }
        })
        .unwrap();
        let feed = RutFeed::of_grid(&grid);
        let (m, _) = feed.message(0).unwrap();
        for t in tiles(&m) {
            let [ox, oy] = [0, 1].map(|k| t["origin"][k].as_f64().unwrap());
            let [mx, _] = [0, 1].map(|k| t["nodes"][k].as_u64().unwrap() as usize);
            for (n, k) in t["depth"].as_array().unwrap().iter().enumerate() {
                let (i, j) = (
                    ((ox - 1.0) / 0.02).round() as usize + n % mx,
                    ((oy - 2.0) / 0.02).round() as usize + n / mx,
                );
                let d = k.as_f64().unwrap() * RUT_SCALE;
                assert!((d - grid.node(i, j).unwrap()).abs() <= 0.5 * RUT_SCALE);
            }
        }
    }
}
