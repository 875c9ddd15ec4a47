//! The wheels' ruts in a run (docs/MODEL.md, "Ruts and multipass"): the
//! ground's memory ([`RutMap`]) and, for each wheel, the trail of where it
//! pressed the soil and how deep, written into the map once the wheel has
//! left that ground.
//!
//! Why a trail: the soil law acts on a wheel at the depth it sinks below
//! the soil's surface where it stands, and the rut under it is read from
//! the map there ([`Ruts::under`]). Written at once, a wheel's own press
//! would be read back by the wheel at its next step, and the wheel would
//! sink into its own rut step after step. Held back until the wheel's
//! contact point is [`CLEARANCE_CELLS`] cells away, further than a read
//! reaches (a cell and a half) and a write spreads (half a cell), a rut
//! is met only by the wheels that come after (or by the same wheel,
//! driven back over it), as on real ground.

use rover_dynamics::plant::WheelState;
use rover_dynamics::soil::Compaction;
use rover_dynamics::wheel_ground::WheelReport;
use rover_dynamics::wheel_soil::SoilUnder;
use rover_terrain::ruts::{Footprint, RutMap};

/// How far \[cells\] a wheel's contact point must move from where it
/// pressed before the press is written: the bilinear read reaches one
/// cell, the rasterized write half a cell more.
pub const CLEARANCE_CELLS: f64 = 3.0;

/// Presses a trail holds before the oldest is written anyway (a wheel
/// that turns on the spot keeps pressing the same ground).
const TRAIL: usize = 32;

/// One wheel's presses not yet written, oldest first, and the last written.
#[derive(Clone, Debug)]
struct Trail {
    ring: [Footprint; TRAIL],
    start: usize,
    len: usize,
    last: Option<Footprint>,
}

impl Trail {
    fn new() -> Self {
        let none = Footprint {
            centre: [0.0; 2],
            axle: [0.0, 1.0],
            half_width: 0.0,
            past_sinkage: 0.0,
        };
        Self {
            ring: [none; TRAIL],
            start: 0,
            len: 0,
            last: None,
        }
    }

    fn newest_mut(&mut self) -> Option<&mut Footprint> {
        (self.len > 0).then(|| &mut self.ring[(self.start + self.len - 1) % TRAIL])
    }

    fn oldest(&self) -> Option<&Footprint> {
        (self.len > 0).then(|| &self.ring[self.start])
    }

    fn pop(&mut self) -> Option<Footprint> {
        let f = *self.oldest()?;
        self.start = (self.start + 1) % TRAIL;
        self.len -= 1;
        Some(f)
    }

    fn push(&mut self, f: Footprint) {
        debug_assert!(self.len < TRAIL);
        self.ring[(self.start + self.len) % TRAIL] = f;
        self.len += 1;
    }
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The ruts of a run: the map, and each wheel's trail.
#[derive(Clone, Debug)]
pub struct Ruts {
    map: RutMap,
    trails: Vec<Trail>,
    /// Half of each wheel's width \[m\].
    half_widths: Vec<f64>,
    /// Each wheel's radius \[m\]: a wheel that lands further than this
    /// from its last press starts a new stretch of rut.
    radii: Vec<f64>,
}

impl Ruts {
    /// Ruts in cells of side `cell` \[m\] under wheels of `widths` and
    /// `radii` \[m\].
    pub fn new(cell: f64, widths: &[f64], radii: &[f64]) -> Self {
        Self {
            map: RutMap::new(cell),
            trails: vec![Trail::new(); widths.len()],
            half_widths: widths.iter().map(|w| 0.5 * w).collect(),
            radii: radii.to_vec(),
        }
    }

    /// The map.
    pub fn map(&self) -> &RutMap {
        &self.map
    }

    /// The map, to reserve tiles ahead ([`RutMap::reserve`]).
    pub fn map_mut(&mut self) -> &mut RutMap {
        &mut self.map
    }

    /// The soil as earlier passes left it at `point` (a wheel's contact
    /// point, inertial \[m\]; Z unused). Allocates nothing.
    pub fn under(&self, point: [f64; 3]) -> SoilUnder {
        let s = self.map.sample(point[0], point[1]);
        SoilUnder {
            rut: s.depth,
            rut_gradient: s.gradient,
            compaction: Compaction {
                past_sinkage: s.past_sinkage,
            },
        }
    }

    /// Records where each wheel presses now (its state and the report of
    /// the last evaluation), and writes into the map the presses each
    /// wheel has left behind; `rut_depth(k, at, z)` is the rut wheel
    /// `k`'s soil at `at` keeps after a press to past sinkage z. Called after each
    /// accepted step. Allocates only when a press reaches ground no tile
    /// holds yet, and not even then from a reserved pool.
    pub fn record(
        &mut self,
        states: &[WheelState],
        reports: &[WheelReport],
        rut_depth: impl Fn(usize, [f64; 2], f64) -> f64,
    ) {
        let cell = self.map.cell();
        for (k, (s, r)) in states.iter().zip(reports).enumerate() {
            let clearance = CLEARANCE_CELLS * cell;
            let here = [r.point[0], r.point[1]];
            let trail = &mut self.trails[k];
            if r.patches > 0 && r.sinkage > 0.0 {
                let axle = [s.spin_axis[0], s.spin_axis[1]];
                let norm = axle[0].hypot(axle[1]);
                let now = Footprint {
                    centre: here,
                    axle: if norm > 1e-9 {
                        axle.map(|a| a / norm)
                    } else {
                        [0.0, 1.0]
                    },
                    half_width: self.half_widths[k],
                    past_sinkage: r.rut + r.sinkage,
                };
                match trail.newest_mut() {
                    // A press every quarter cell, and at most a sixteenth
                    // of the clearance apart, so that the trail holds the
                    // whole stretch behind the wheel.
                    Some(newest)
                        if distance(newest.centre, here) < (0.25 * cell).max(clearance / 16.0) =>
                    {
                        newest.past_sinkage = newest.past_sinkage.max(now.past_sinkage);
                        newest.axle = now.axle;
                    }
                    _ => {
                        if trail.len == TRAIL {
                            let oldest = trail.pop().expect("a full trail");
                            write(&mut self.map, trail, oldest, self.radii[k], |z| {
                                rut_depth(k, oldest.centre, z)
                            });
                        }
                        trail.push(now);
                    }
                }
            }
            while let Some(oldest) = trail.oldest() {
                if distance(oldest.centre, here) <= clearance {
                    break;
                }
                let oldest = trail.pop().expect("an oldest press");
                write(&mut self.map, trail, oldest, self.radii[k], |z| {
                    rut_depth(k, oldest.centre, z)
                });
            }
        }
    }
}

/// Writes `press` into `map`: the band from the trail's last written
/// press to it, or its own footprint when the wheel lifted off between.
fn write(
    map: &mut RutMap,
    trail: &mut Trail,
    press: Footprint,
    radius: f64,
    rut_depth: impl Fn(f64) -> f64,
) {
    let from = match trail.last {
        Some(last) if distance(last.centre, press.centre) <= radius => last,
        _ => press,
    };
    map.press(&from, &press, rut_depth);
    trail.last = Some(press);
}
