//! Contact by a bounded search of the rim: the patches of MODEL.md §6, found
//! without sampling the rim and with a proof that none is missed (ours).
//!
//! Along the rim, `P(β) = G_j + R·(cos β·d + sin β·f)`, the clearance
//! `h(β) = Z_P − Z_G(X_P, Y_P)` has a second derivative
//! ```text
//! h'' = P''_z − ∇Z_G·P''_xy − P'_xyᵀ·∇²Z_G·P'_xy,   |P'| = |P''| = R
//! |h''| ≤ K = R·sqrt(1 + G²) + C·R²
//! ```
//! with `G` and `C` the terrain's bounds of slope and curvature under the
//! wheel ([`HeightField::max_slope_in`], [`HeightField::max_curvature_in`]).
//! Knowing `h` and `h'` at the ends of an arc, Taylor's bounds
//! `h_a + h'_a·u ∓ K·u²/2` (and the same from the other end) enclose `h` on
//! the whole arc, and `h'_a ∓ K·u` enclose `h'`. An arc is then settled
//! without looking inside it when its enclosure is
//! - above the ground: no crossing, no patch, no dip;
//! - below the ground: no crossing, no ridge;
//! - monotone: one crossing if its ends are on opposite sides (refined by
//!   the meridional search's Newton/Illinois steps), none otherwise;
//!
//! and halved otherwise. The search starts from the arc of the rim that can
//! reach below the terrain's highest point under the wheel, so every
//! crossing of the rim with the ground is found, whatever its width: a
//! feature narrower than the sampled search's 1° spacing is not missed.
//! Only features that rise or dip less than [`NEGLIGIBLE`] through the rim
//! are left unresolved (they would carry less than a nanonewton).
//!
//! The patches are then made exactly as the sampled search makes them
//! (MODEL.md §6 chords, blends where a patch splits: the meridional
//! module's `Runs`), so the two searches differ only by how precisely they
//! locate the crossings and by what the sampled one misses between samples.
//!
//! A terrain that gives no curvature bound (a step, a bilinear grid, a
//! point off a clamped map) and a plane (cut in closed form) take the
//! meridional search.

use crate::terrain::{HeightField, OffMap, Plane};

use super::meridional::{MeridionalContact, Runs, clearance_slope, crossing_from, cut_by_plane};
use super::patch::{Contact, RimAngle, RimFrame};

/// Height \[m\] below which a feature's excursion through the rim is not
/// resolved: an arc whose ends are on the same side of the ground and whose
/// enclosure reaches less than this across it is taken as on that side.
pub const NEGLIGIBLE: f64 = 1e-10;

/// Most halvings of the half rim (2⁻⁴⁰ of π: far below what [`NEGLIGIBLE`]
/// needs; a guard against a non-finite bound).
const MAX_LEVEL: u32 = 40;

/// The bounded search, with the meridional search for the terrains it cannot
/// bound. Stateless.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoundedContact {
    /// The search for planes and for terrains without bounds; its crossing
    /// tolerance is this search's too.
    pub fallback: MeridionalContact,
}

/// A rim point: its angle, clearance and clearance slope.
#[derive(Clone, Copy, Debug)]
struct Node {
    at: RimAngle,
    h: f64,
    slope: f64,
}

/// What the search needs to settle an arc: the terrain, the rim, the bound
/// `K` of `|h''|`, the rounding of `h` and the crossing tolerance.
struct Bounds<'a, H: ?Sized> {
    terrain: &'a H,
    frame: RimFrame,
    k: f64,
    rounding: f64,
    tolerance: f64,
}

impl<H: HeightField + ?Sized> Bounds<'_, H> {
    fn node(&self, beta: f64) -> Result<Node, OffMap> {
        let at = RimAngle::new(beta);
        let (h, slope) = clearance_slope(self.terrain, &self.frame, at)?;
        Ok(Node { at, h, slope })
    }

    /// Settles the arc from `a` to `b` (`a` already reported to `scan`),
    /// reporting its crossings and then `b`, in rim order.
    fn settle(&self, a: Node, b: Node, level: u32, scan: &mut Scan) -> Result<(), OffMap> {
        let length = b.at.beta - a.at.beta;
        let (below_a, below_b) = (a.h < 0.0, b.h < 0.0);
        let settled = if length.is_nan() || length <= 0.0 {
            true
        } else {
            let (low, high) = enclosure(&a, &b, length, self.k);
            let (low, high) = (low - self.rounding, high + self.rounding);
            if low > 0.0 || high < 0.0 {
                true
            } else if monotone(&a, &b, length, self.k) {
                if below_a != below_b {
                    scan.cross(self.crossing(&a, &b)?);
                }
                true
            } else if below_a == below_b
                && (if below_a { high < NEGLIGIBLE } else { low > -NEGLIGIBLE })
            {
                true
            } else if level >= MAX_LEVEL {
                if below_a != below_b {
                    scan.cross(self.crossing(&a, &b)?);
                }
                true
            } else {
                false
            }
        };
        if settled {
            scan.node(&b);
            return Ok(());
        }
        let mid = self.node(a.at.beta + 0.5 * length)?;
        self.settle(a, mid, level + 1, scan)?;
        self.settle(mid, b, level + 1, scan)
    }

    /// The crossing between `a` and `b` (on opposite sides), starting with a
    /// Newton step from the end nearer the ground.
    fn crossing(&self, a: &Node, b: &Node) -> Result<RimAngle, OffMap> {
        let near = if a.h.abs() <= b.h.abs() { a } else { b };
        let guess = (near.slope != 0.0).then(|| near.at.beta - near.h / near.slope);
        crossing_from(
            self.terrain,
            &self.frame,
            [a.at.beta, a.h],
            [b.at.beta, b.h],
            guess,
            self.tolerance,
        )
    }
}

/// Lower and upper bounds of `h` over the arc from `a` to `b`, `length`
/// long, from Taylor's bounds at both ends with `|h''| ≤ k`. Each end gives
/// a parabola in `u` (the distance from `a`); the two lower ones differ by
/// a linear function of `u`, so their maximum is smallest at an end or where
/// they meet, and likewise for the upper ones.
fn enclosure(a: &Node, b: &Node, length: f64, k: f64) -> (f64, f64) {
    let l = length;
    let half = 0.5 * k;
    let from_a = |u: f64, sign: f64| a.h + a.slope * u + sign * half * u * u;
    let from_b = |u: f64, sign: f64| {
        let v = l - u;
        b.h - b.slope * v + sign * half * v * v
    };
    let bound = |sign: f64| {
        // from_a − from_b = c0 + c1·u.
        let c0 = a.h - b.h + b.slope * l - sign * half * l * l;
        let c1 = a.slope - b.slope + sign * k * l;
        let pick = |u: f64| {
            let (p, q) = (from_a(u, sign), from_b(u, sign));
            if sign < 0.0 { p.max(q) } else { p.min(q) }
        };
        let ends = [a.h, b.h];
        let meet = if c1 != 0.0 { -c0 / c1 } else { f64::NAN };
        let inner = (meet > 0.0 && meet < l).then(|| pick(meet));
        let (lo, hi) = (ends[0].min(ends[1]), ends[0].max(ends[1]));
        match (sign < 0.0, inner) {
            (true, Some(v)) => lo.min(v),
            (true, None) => lo,
            (false, Some(v)) => hi.max(v),
            (false, None) => hi,
        }
    };
    (bound(-1.0), bound(1.0))
}

/// Whether `h'` provably keeps one sign over the arc (so `h` crosses zero at
/// most once there, and has no dip or ridge): `h'` lies above
/// `max(h'_a − k·u, h'_b − k·(l − u))` and below `min(h'_a + k·u, h'_b + k·(l − u))`.
fn monotone(a: &Node, b: &Node, l: f64, k: f64) -> bool {
    let lowest = {
        let u = ((a.slope - b.slope + k * l) / (2.0 * k)).clamp(0.0, l);
        (a.slope - k * u).max(b.slope - k * (l - u))
    };
    let highest = {
        let u = ((b.slope - a.slope + k * l) / (2.0 * k)).clamp(0.0, l);
        (a.slope + k * u).min(b.slope + k * (l - u))
    };
    lowest > 0.0 || highest < 0.0
}

/// The runs below ground as the search reports nodes and crossings in rim
/// order.
#[derive(Default)]
struct Scan {
    runs: Runs,
    /// Start of the run the rim is in, if below ground.
    start: Option<RimAngle>,
    /// Deepest penetration seen in that run \[m\].
    depth: f64,
    /// A run touches an end of the half rim.
    deep: bool,
}

impl Scan {
    /// The first node: an end of the half rim when it is below ground.
    fn begin(&mut self, n: &Node) {
        if n.h < 0.0 {
            self.start = Some(n.at);
            self.depth = -n.h;
            self.deep = true;
        }
    }

    fn node(&mut self, n: &Node) {
        if self.start.is_some() {
            self.depth = self.depth.max(-n.h);
        }
    }

    fn cross(&mut self, at: RimAngle) {
        match self.start.take() {
            None => {
                self.start = Some(at);
                self.depth = 0.0;
            }
            Some(a) => self.runs.push(a, at, self.depth),
        }
    }

    /// The last node: a run still open ends there, at an end of the half rim.
    fn end(&mut self, n: &Node) {
        if let Some(a) = self.start.take() {
            self.deep = true;
            self.runs.push(a, n.at, self.depth);
        }
    }
}

/// The part of the half rim that can reach below height `top`.
enum Reach {
    /// β in `[lo, hi]`; the rim is above `top` at an end that is not an end
    /// of the half rim.
    Arc(f64, f64),
    /// The rim stays above `top`.
    Nothing,
}

/// The rim height is `Z(β) = Z_G − R·A·cos(β − β_m)` with `A = |(d_z, f_z)|`
/// and β_m the lowest point, so `Z(β) ≤ z` on `|β − β_m| ≤ acos((Z_G − z)/(R·A))`.
fn reach(frame: &RimFrame, top: f64) -> Reach {
    let half = core::f64::consts::FRAC_PI_2;
    let whole = Reach::Arc(-half, half);
    let (cz, r) = (frame.centre[2], frame.radius);
    // Rounding of the rim points and of the terrain's bound: far below 1 nm.
    let z = top + 1e-9 * (1.0 + top.abs() + cz.abs());
    let (dz, fz) = (frame.down[2], frame.forward[2]);
    let a = dz.hypot(fz);
    if !(a > 1e-6 && z.is_finite() && cz.is_finite() && r > 0.0) {
        return whole;
    }
    let c = (cz - z) / (r * a);
    if c > 1.0 {
        return Reach::Nothing;
    }
    let width = c.clamp(-1.0, 1.0).acos();
    let lowest = (-fz).atan2(-dz);
    let (lo, hi) = ((lowest - width).max(-half), (lowest + width).min(half));
    if lo >= hi {
        return Reach::Nothing;
    }
    Reach::Arc(lo, hi)
}

impl BoundedContact {
    /// The patches of a wheel with centre `centre`, unit spin axis `axis`
    /// (both inertial) and radius `radius`, written into `out` (reset
    /// first). On `Err`, `out` holds what was found before the failure.
    pub fn find_into<H: HeightField + ?Sized>(
        &self,
        terrain: &H,
        centre: [f64; 3],
        axis: [f64; 3],
        radius: f64,
        out: &mut Contact,
    ) -> Result<(), OffMap> {
        *out = Contact::default();
        let Some(frame) = RimFrame::new(centre, axis, radius) else {
            return Ok(());
        };
        let area = frame.area();
        let bounds = (
            terrain.plane(),
            terrain.max_height_in(&area),
            terrain.max_slope_in(&area),
            terrain.max_curvature_in(&area),
        );
        let (None, Some(top), Some(slope), Some(curvature)) = bounds else {
            return self
                .fallback
                .find_into(terrain, centre, axis, radius, out);
        };
        let k = (radius * slope.hypot(1.0) + curvature * radius * radius) * (1.0 + 1e-9);
        // Rounding of a clearance: of the rim point and of the interpolant.
        let rounding = 1e-12 * (1.0 + centre[2].abs() + radius + top.abs());
        if !(k.is_finite() && rounding.is_finite()) {
            return self
                .fallback
                .find_into(terrain, centre, axis, radius, out);
        }
        let Reach::Arc(lo, hi) = reach(&frame, top) else {
            return Ok(());
        };
        // A terrain without curvature under the wheel is a plane there: one
        // query gives it, and the rim is cut in closed form.
        if curvature == 0.0 {
            let (height, gradient) = terrain.height_gradient(centre[0], centre[1])?;
            let plane = Plane {
                origin: [centre[0], centre[1]],
                height,
                gradient,
            };
            let n = self.fallback.sampling.samples.max(3);
            let step = core::f64::consts::PI / (n - 1) as f64;
            if cut_by_plane(&plane, &frame, n, step, out) {
                return Ok(());
            }
        }
        let search = Bounds {
            terrain,
            frame,
            k,
            rounding,
            tolerance: self.fallback.sampling.tolerance,
        };
        let (first, last) = (search.node(lo)?, search.node(hi)?);
        let mut scan = Scan::default();
        scan.begin(&first);
        search.settle(first, last, 0, &mut scan)?;
        scan.end(&last);
        out.deep = scan.deep;
        let mut runs = scan.runs;
        runs.measure_shallow(terrain, &frame)?;
        runs.emit(terrain, &frame, out)
    }

    /// [`BoundedContact::find_into`] returning the contact.
    pub fn find<H: HeightField + ?Sized>(
        &self,
        terrain: &H,
        centre: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    ) -> Result<Contact, OffMap> {
        let mut contact = Contact::default();
        self.find_into(terrain, centre, axis, radius, &mut contact)?;
        Ok(contact)
    }
}
