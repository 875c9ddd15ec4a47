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
//!   Newton's method from the end nearer the ground, with the meridional
//!   search's Illinois steps as the safeguard), none otherwise;
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
//! Each wheel keeps what its last search proved ([`SearchMemory`]): after a
//! small move only the arcs whose margins no longer hold are searched
//! again, and the crossings are refined from their last roots.
//!
//! A plane, and a wheel over a part of a map without curvature, is cut in
//! closed form. A terrain that gives no curvature bound (a step, a bilinear
//! grid, a square reaching off a clamped map) takes the meridional search.

use core::cell::RefCell;

use crate::bicubic::{BicubicCell, KeptCells};
use crate::height_field::{Bounds, HeightField, OffMap, Plane};

use super::math;
use super::meridional::{MeridionalContact, Runs, clearance_slope, crossing_from, cut_by_plane};
use super::patch::{Below, Contact, RimAngle, RimFrame, norm};

/// Height \[m\] below which a feature's excursion through the rim is not
/// resolved: an arc whose ends are on the same side of the ground and whose
/// enclosure reaches less than this across it is taken as on that side.
pub const NEGLIGIBLE: f64 = 1e-10;

/// Height above the terrain's highest point, as a fraction of the wheel
/// radius, up to which a full search covers the rim (see `find_with`).
const PAD: f64 = 1.0 / 16.0;

/// Most halvings of the half rim (2⁻⁴⁰ of π: far below what [`NEGLIGIBLE`]
/// needs; a guard against a non-finite bound).
const MAX_LEVEL: u32 = 40;

/// Crossings are refined to this clearance \[m\], far below the sampled
/// search's 1e-9 m: Newton's last step then lands within rounding of the
/// root wherever it started, so the patches do not depend on which arcs the
/// search happened to halve (which depends on the terrain's bounds, and so
/// on the lattice square the bounds were taken over, see [`SearchMemory`]).
/// A finite-difference Jacobian of the right-hand side, which perturbs a
/// wheel by nanometres, sees the patches move with the wheel, not jump.
pub const CROSSING_TOLERANCE: f64 = 1e-12;

/// What the bounded search keeps about one wheel between calls (one per
/// wheel, kept by the caller), to spare work whose outcome it can prove
/// unchanged. The patches do not depend on it (up to the rounding of the
/// crossings' last Newton step): a fresh memory gives the same contact.
///
/// - The terrain's bounds under the wheel (highest point, steepest slope,
///   largest curvature), taken over the wheel's square snapped outwards to
///   a lattice of side R/2, so that a wheel that moves a little keeps the
///   same square: the pyramid queries behind them cost more than the
///   search's own terrain queries.
/// - The last search's certificate, arc by arc: the margin by which each
///   settled arc cleared the ground or stayed below it, and for each
///   crossing its arc, root, and the margins by which the arc's ends kept
///   their sides and its slope its sign. A wheel that has moved by δ since
///   (every rim point within δ of where it was, clearances within
///   `δ·sqrt(1 + G²)`, their slopes within `δ·(sqrt(1 + G²) + C·R)`) keeps
///   the outcome of every arc whose margins hold: a crossing is refined by
///   Newton's method from where its last root has moved to first order
///   (its last gradient and slope), and only the arcs whose margins no
///   longer hold are searched again. While all hold, the certificate is
///   kept in place and only its roots are written.
/// - The last few bicubic cells the wheel's queries fell in
///   ([`KeptCells`]), which answer with the terrain's bits.
///
/// All of it belongs to one terrain ([`HeightField::surface`]): a memory
/// used on another forgets it first.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SearchMemory {
    /// The lattice cell of the wheel's centre and the lattice's side
    /// \[m\]; `None` before the first query.
    key: Option<([i64; 2], f64)>,
    /// Highest point \[m\], steepest slope, largest curvature \[1/m\];
    /// `None` where the terrain gives no bound.
    bounds: Option<[f64; 3]>,
    /// The ground over the square where the terrain has no curvature there
    /// (a plane), once asked for.
    plane: Option<Plane>,
    /// The last search's certificate in `certificates[current]`, valid when
    /// `proven`; the other slot is where the next search writes its own (two
    /// slots: a certificate is a kilobyte, not worth copying per call).
    certificates: [Certificate; 2],
    current: usize,
    proven: bool,
    /// The terrain all this was learnt on ([`HeightField::surface`]): a
    /// wheel put on another terrain forgets everything.
    surface: u64,
    /// The last few bicubic cells the wheel's queries fell in: a query in
    /// one of them is the cell's polynomial, evaluated from the kept
    /// nodes, with the terrain's bits ([`KeptCells`]).
    cells: KeptCells,
}

impl SearchMemory {
    /// The bounds under a wheel of radius `radius` centred at (`x`, `y`),
    /// over the lattice square that holds it: with `q = R/2` and the wheel's
    /// centre in lattice cell `(i, j)`, the square of cells `i − 2 … i + 2`
    /// by `j − 2 … j + 2` holds the wheel's square of side 2R = 4q (widened
    /// by a rounding margin). From the memory when it holds that square; a
    /// new square forgets the certificate.
    fn over<H: HeightField + ?Sized>(
        &mut self,
        terrain: &H,
        [x, y]: [f64; 2],
        radius: f64,
    ) -> Option<[f64; 3]> {
        let quantum = 0.5 * radius;
        // Beyond ±2⁵² cells (or for a non-finite centre) nothing is kept.
        let limit = 4.5e15;
        // The floor by truncation through i64 (exact below the limit): the
        // baseline x86-64 target has no floor instruction, and a call to
        // the software one per coordinate showed in the profile.
        let cell = |v: f64| {
            let q = v / quantum;
            if q.is_nan() || q.abs() >= limit {
                return None;
            }
            let t = q as i64;
            let k = if (t as f64) > q { t - 1 } else { t };
            ((k as f64).abs() < limit).then_some(k)
        };
        let (Some(i), Some(j)) = (cell(x), cell(y)) else {
            *self = SearchMemory {
                surface: self.surface,
                ..SearchMemory::default()
            };
            return None;
        };
        let key = [i, j];
        if self.key == Some((key, quantum)) {
            return self.bounds;
        }
        let slack = 1e-9 * (quantum + x.abs() + y.abs());
        let at = |k: i64| k as f64 * quantum;
        let square = Bounds {
            x_min: at(i - 2) - slack,
            x_max: at(i + 3) + slack,
            y_min: at(j - 2) - slack,
            y_max: at(j + 3) + slack,
        };
        self.key = Some((key, quantum));
        self.proven = false;
        self.plane = None;
        self.bounds = match (
            terrain.max_height_in(&square),
            terrain.max_slope_in(&square),
            terrain.max_curvature_in(&square),
        ) {
            (Some(top), Some(slope), Some(curvature)) => Some([top, slope, curvature]),
            _ => None,
        };
        self.bounds
    }

    /// The plane the ground is over the current square, where its
    /// curvature bound is 0 there: one query at the centre cell's middle,
    /// the first time.
    fn plane<H: HeightField + ?Sized>(&mut self, terrain: &H) -> Result<Option<Plane>, OffMap> {
        if self.plane.is_none()
            && let (Some((key, quantum)), Some([_, _, 0.0])) = (self.key, self.bounds)
        {
            let x = (key[0] as f64 + 0.5) * quantum;
            let y = (key[1] as f64 + 0.5) * quantum;
            let (height, gradient) = terrain.height_gradient(x, y)?;
            self.plane = Some(Plane {
                origin: [x, y],
                height,
                gradient,
            });
        }
        Ok(self.plane)
    }
}

/// Most arcs a certificate keeps.
const MAX_LEAVES: usize = 32;

/// What the last search proved, arc by arc, for the rim it was made for
/// (see [`SearchMemory`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Certificate {
    centre: [f64; 3],
    down: [f64; 3],
    forward: [f64; 3],
    radius: f64,
    /// How far the rim can come down before it can reach the ground beyond
    /// the searched arc \[m\].
    cover: f64,
    /// The rim (centre, down, forward) where the crossings' roots were last
    /// refined: `centre`, `down` and `forward` until a search keeps the
    /// certificate in place ([`Search::reuse_in_place`]).
    refined: [[f64; 3]; 3],
    leaves: [Leaf; MAX_LEAVES],
    count: usize,
}

/// One settled arc of a certificate, in rim order.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Leaf {
    lo: f64,
    hi: f64,
    /// Below ground at `lo`.
    below: bool,
    /// Smallest |h| the arc provably keeps (settled on one side), or that
    /// its ends have (a crossing's arc) \[m\].
    margin: f64,
    /// Deepest penetration at its ends, 0 above ground \[m\].
    depth: f64,
    /// A crossing's root, or `None` for an arc on one side.
    root: Option<RimAngle>,
    /// Smallest |h'| a crossing's arc provably keeps \[m/rad\].
    slope: f64,
    /// The ground's gradient and the clearance's slope `h'` \[m/rad\] from
    /// the last query of a crossing's Newton iteration, next to its root:
    /// what predicts where the crossing moves ([`Search::predicted`]); a
    /// zero slope where the crossing was found without them.
    gradient: [f64; 2],
    rate: f64,
}

/// How a certificate kept in place fared ([`Search::reuse_in_place`]).
enum InPlace {
    /// Every arc kept its outcome; the certificate holds for this rim.
    Done,
    /// The arc at this index is to be searched again; the arcs before it
    /// are in the scan; the changes of the clearances and their slopes.
    Stopped(usize, [f64; 2]),
    /// The certificate does not cover this rim: a fresh search.
    Invalid,
}

/// A crossing, with the ground's gradient and the clearance's slope from
/// the last query before it (see [`Leaf`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Root {
    at: RimAngle,
    gradient: [f64; 2],
    rate: f64,
}

impl Leaf {
    fn settled(a: &Node, b: &Node, margin: f64) -> Leaf {
        Leaf {
            lo: a.at.beta,
            hi: b.at.beta,
            below: a.h < 0.0,
            margin,
            depth: (-a.h).max(-b.h).max(0.0),
            root: None,
            slope: 0.0,
            gradient: [0.0; 2],
            rate: 0.0,
        }
    }
}

/// The bounded search, with the meridional search for the terrains it cannot
/// bound. Stateless.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoundedContact {
    /// The search for planes and for terrains without bounds.
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
/// `K` of `|h''|` and the rounding of `h`.
struct Search<'a, H: ?Sized> {
    terrain: &'a H,
    frame: RimFrame,
    k: f64,
    rounding: f64,
}

impl<H: HeightField + ?Sized> Search<'_, H> {
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
                scan.record(Leaf::settled(&a, &b, low.max(-high)));
                true
            } else if let Some(slope) = monotone(&a, &b, length, self.k) {
                let sides = a.h.abs().min(b.h.abs());
                let mut leaf = Leaf::settled(&a, &b, sides);
                if below_a != below_b {
                    let root = self.crossing(&a, &b)?;
                    scan.cross(root.at);
                    leaf.root = Some(root.at);
                    leaf.slope = slope;
                    leaf.gradient = root.gradient;
                    leaf.rate = root.rate;
                }
                scan.record(leaf);
                true
            } else if below_a == below_b
                && (if below_a {
                    high < NEGLIGIBLE
                } else {
                    low > -NEGLIGIBLE
                })
            {
                scan.unproven();
                true
            } else if level >= MAX_LEVEL {
                scan.unproven();
                if below_a != below_b {
                    scan.cross(self.crossing(&a, &b)?.at);
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

    /// The search of a wheel that has moved since `c` was made, with `c`
    /// kept in place: while every arc's margins still hold for the whole
    /// move since `c`'s search (the margins are not touched, the move is
    /// measured from where they were proved), only the crossings' roots are
    /// refined again and written back, and nothing is copied. Where an
    /// arc's margins no longer hold (or a root's Newton iteration leaves its
    /// arc), [`InPlace::Stopped`] says at which arc; the roots before it are
    /// refined for this rim already, and [`Search::reuse`] takes over from
    /// there into a new certificate. `slopes` are `sqrt(1 + G²)` and
    /// `sqrt(1 + G²) + C·R`, the factors from the rim's displacement to the
    /// clearances' and to their slopes' (see [`SearchMemory`]).
    fn reuse_in_place(
        &self,
        c: &mut Certificate,
        slopes: [f64; 2],
        scan: &mut Scan,
    ) -> Result<InPlace, OffMap> {
        let Some((dh, ds)) = self.change_since(c, slopes) else {
            return Ok(InPlace::Invalid);
        };
        scan.restart_in_place();
        // (NaN never holds.)
        let holds = |change: f64, margin: f64| change < margin;
        let refined = c.refined;
        let count = c.count.min(MAX_LEAVES);
        for (i, leaf) in c.leaves[..count].iter_mut().enumerate() {
            if leaf.below != scan.start.is_some() {
                return Ok(InPlace::Invalid);
            }
            if !holds(dh, leaf.margin) {
                return Ok(InPlace::Stopped(i, [dh, ds]));
            }
            if let Some(last_root) = leaf.root {
                if !holds(ds, leaf.slope) {
                    return Ok(InPlace::Stopped(i, [dh, ds]));
                }
                let start = self.predicted(&refined, leaf, last_root);
                let Some(root) = self.newton_from(leaf.lo, leaf.hi, start)? else {
                    return Ok(InPlace::Stopped(i, [dh, ds]));
                };
                leaf.root = Some(root.at);
                leaf.gradient = root.gradient;
                leaf.rate = root.rate;
                scan.cross(root.at);
            }
            scan.deepen((leaf.depth - dh).max(0.0));
        }
        if scan.start.is_some() {
            return Ok(InPlace::Invalid);
        }
        let f = &self.frame;
        c.refined = [f.centre, f.down, f.forward];
        Ok(InPlace::Done)
    }

    /// How much the clearances (`dh`) and their slopes (`ds`) along the rim
    /// can have changed since `c`'s search, rounding included; `None` when
    /// `c` is for another radius or no longer covers the rim.
    fn change_since(&self, c: &Certificate, slopes: [f64; 2]) -> Option<(f64, f64)> {
        let f = &self.frame;
        if f.radius != c.radius {
            return None;
        }
        let apart = |a: [f64; 3], b: [f64; 3]| norm([0, 1, 2].map(|k| a[k] - b[k]));
        // Every rim point P = G + R·(cos β·d + sin β·f) moved by at most δ.
        let moved = apart(f.centre, c.centre)
            + f.radius * (apart(f.down, c.down) + apart(f.forward, c.forward));
        let (dh, ds) = (
            moved * slopes[0] + self.rounding,
            moved * slopes[1] + self.rounding,
        );
        // (NaN never holds.)
        (dh < c.cover).then_some((dh, ds))
    }

    /// The search of a wheel that has moved since `c` was made, into `scan`
    /// (new, for this rim): every arc of `c` whose margins still hold keeps
    /// its outcome (a crossing refined by Newton's method from its last
    /// root), the others are searched again from fresh queries at their
    /// ends. The first `refined` arcs were kept by
    /// [`Search::reuse_in_place`], and are in `scan` already; `dh` and `ds`
    /// are the changes it measured. False if the certificate does not
    /// cover the rim any more (the caller searches afresh).
    fn reuse(
        &self,
        c: &Certificate,
        [dh, ds]: [f64; 2],
        scan: &mut Scan,
        refined: usize,
    ) -> Result<bool, OffMap> {
        let f = &self.frame;
        // (NaN never holds.)
        let holds = |change: f64, margin: f64| change < margin;
        // The first `refined` arcs are in the scan already.
        scan.certify(f, c.cover - dh);
        let mut last: Option<Node> = None;
        for (i, leaf) in c.leaves[..c.count.min(MAX_LEAVES)].iter().enumerate() {
            let moved_leaf = Leaf {
                margin: leaf.margin - dh,
                depth: (leaf.depth - dh).max(0.0),
                slope: leaf.slope - ds,
                ..*leaf
            };
            if i < refined {
                scan.record(moved_leaf);
                continue;
            }
            if leaf.below != scan.start.is_some() {
                return Ok(false);
            }
            // The arc's outcome, if its margins still hold.
            let kept = match leaf.root {
                _ if !holds(dh, leaf.margin) => None,
                None => Some(moved_leaf),
                Some(_) if !holds(ds, leaf.slope) => None,
                Some(last_root) => self
                    .newton_from(
                        leaf.lo,
                        leaf.hi,
                        self.predicted(&c.refined, leaf, last_root),
                    )?
                    .map(|root| Leaf {
                        root: Some(root.at),
                        gradient: root.gradient,
                        rate: root.rate,
                        ..moved_leaf
                    }),
            };
            if let Some(kept) = kept {
                if let Some(root) = kept.root {
                    scan.cross(root);
                }
                scan.deepen(kept.depth);
                scan.record(kept);
                last = None;
                continue;
            }
            let a = match last {
                Some(n) if n.at.beta == leaf.lo => n,
                _ => self.node(leaf.lo)?,
            };
            if (a.h < 0.0) != scan.start.is_some() {
                return Ok(false);
            }
            let b = self.node(leaf.hi)?;
            self.settle(a, b, 1, scan)?;
            last = Some(b);
        }
        Ok(scan.start.is_none() && scan.proven)
    }

    /// Newton's method for the root of `h` on `(lo, hi)` from `beta`. A step
    /// `Δ = −h/h'` lands where `|h| ≤ K·Δ²/2` (Taylor, `|h''| ≤ K`): once that
    /// is below the tolerance, the landing point is the root without another
    /// query. `None` if a step leaves the interval or eight do not settle.
    fn newton_in(&self, lo: f64, hi: f64, beta: f64) -> Result<Option<Root>, OffMap> {
        self.newton_from(lo, hi, RimAngle::new(beta))
    }

    /// [`Search::newton_in`] from a rim angle whose sine and cosine are known.
    fn newton_from(&self, lo: f64, hi: f64, start: RimAngle) -> Result<Option<Root>, OffMap> {
        let mut at = start;
        for _ in 0..8 {
            let (h, slope, gradient) = clearance_slope_gradient(self.terrain, &self.frame, at)?;
            let root = |at: RimAngle| Root {
                at,
                gradient,
                rate: slope,
            };
            if h.abs() <= CROSSING_TOLERANCE {
                return Ok(Some(root(at)));
            }
            let step = -h / slope;
            at = turned(at, step);
            if !(at.beta > lo && at.beta < hi) {
                return Ok(None);
            }
            if 0.5 * self.k * step * step <= CROSSING_TOLERANCE {
                return Ok(Some(root(at)));
            }
        }
        Ok(None)
    }

    /// Where the crossing of `leaf`, last at `last` on the rim `refined`
    /// (centre, down, forward), is now, to first order: the rim point at
    /// `last` has moved by `Δ` since,
    /// which changes the clearance there by `Δz − ∇Z_G·Δxy` (the ground's
    /// gradient from the last query); one step along the clearance's last
    /// slope from there. The last root itself where that step is not finite,
    /// leaves the arc, or is so short that Newton's first step from there
    /// settles anyway. Newton's method starts from here: the root it
    /// finds does not depend on the start beyond the tolerance, and from a
    /// start this near it often settles in one query instead of two.
    fn predicted(&self, refined: &[[f64; 3]; 3], leaf: &Leaf, last: RimAngle) -> RimAngle {
        let f = &self.frame;
        let [centre, down, forward] = refined;
        let (sin, cos) = (last.sin, last.cos);
        // Written out: `array::map` was left a call per element here.
        let moved = |k: usize| {
            (f.centre[k] - centre[k])
                + f.radius * (cos * (f.down[k] - down[k]) + sin * (f.forward[k] - forward[k]))
        };
        let d = [moved(0), moved(1), moved(2)];
        let h = d[2] - leaf.gradient[0] * d[0] - leaf.gradient[1] * d[1];
        let step = -h / leaf.rate;
        // From the last root, Newton's first step would settle at once
        // (see `newton_from`), or the prediction is out of reach.
        let within_reach = step.abs() < 0.05;
        if !within_reach || 0.5 * self.k * step * step <= CROSSING_TOLERANCE {
            return last;
        }
        let at = turned(last, step);
        if at.beta > leaf.lo && at.beta < leaf.hi {
            at
        } else {
            last
        }
    }

    /// The crossing between `a` and `b` (on opposite sides, `h` monotone
    /// between them): Newton's method from the end nearer the ground, or the
    /// meridional search's safeguarded iteration if it leaves the arc.
    fn crossing(&self, a: &Node, b: &Node) -> Result<Root, OffMap> {
        let near = if a.h.abs() <= b.h.abs() { a } else { b };
        let guess = (near.slope != 0.0).then(|| near.at.beta - near.h / near.slope);
        if let Some(start) = guess
            && start > a.at.beta
            && start < b.at.beta
            && let Some(root) = self.newton_in(a.at.beta, b.at.beta, start)?
        {
            return Ok(root);
        }
        let at = crossing_from(
            self.terrain,
            &self.frame,
            [a.at.beta, a.h],
            [b.at.beta, b.h],
            guess,
            CROSSING_TOLERANCE,
        )?;
        Ok(Root {
            at,
            gradient: [0.0; 2],
            rate: 0.0,
        })
    }
}

/// [`clearance_slope`] with the ground's gradient at the rim point.
#[inline]
fn clearance_slope_gradient<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    at: RimAngle,
) -> Result<(f64, f64, [f64; 2]), OffMap> {
    let (s, c) = (at.sin, at.cos);
    let p = frame.point_sc(s, c);
    let (z, [zx, zy]) = terrain.height_gradient(p[0], p[1])?;
    let t = frame.tangent_sc(s, c);
    Ok((p[2] - z, t[2] - zx * t[0] - zy * t[1], [zx, zy]))
}

/// The rim angle `at` turned by `step`: its sine and cosine by the angle
/// sums, with those of a step below 0.05 rad from their Taylor series to
/// the ninth order (within 1e-18), and from `sin_cos` otherwise. The series
/// are in Horner's form with their coefficients folded: multiplications
/// only, where a nest of divisions by 6, 20, 42, … was a chain of eight
/// divisions on every Newton step.
fn turned(at: RimAngle, step: f64) -> RimAngle {
    let beta = at.beta + step;
    if step.abs() >= 0.05 {
        return RimAngle::new(beta);
    }
    const S3: f64 = 1.0 / 6.0;
    const S5: f64 = 1.0 / 120.0;
    const S7: f64 = 1.0 / 5040.0;
    const S9: f64 = 1.0 / 362_880.0;
    const C4: f64 = 1.0 / 24.0;
    const C6: f64 = 1.0 / 720.0;
    const C8: f64 = 1.0 / 40_320.0;
    let d2 = step * step;
    let sin = step * (1.0 - d2 * (S3 - d2 * (S5 - d2 * (S7 - d2 * S9))));
    let cos = 1.0 - d2 * (0.5 - d2 * (C4 - d2 * (C6 - d2 * C8)));
    RimAngle {
        beta,
        sin: at.sin * cos + at.cos * sin,
        cos: at.cos * cos - at.sin * sin,
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

/// The smallest |h'| over the arc when `h'` provably keeps one sign there
/// (so `h` crosses zero at most once, and has no dip or ridge), else `None`:
/// `h'` lies above `max(h'_a − k·u, h'_b − k·(l − u))` and below
/// `min(h'_a + k·u, h'_b + k·(l − u))`.
fn monotone(a: &Node, b: &Node, l: f64, k: f64) -> Option<f64> {
    let lowest = {
        let u = ((a.slope - b.slope + k * l) / (2.0 * k)).max(0.0).min(l);
        (a.slope - k * u).max(b.slope - k * (l - u))
    };
    let highest = {
        let u = ((b.slope - a.slope + k * l) / (2.0 * k)).max(0.0).min(l);
        (a.slope + k * u).min(b.slope + k * (l - u))
    };
    if lowest > 0.0 {
        Some(lowest)
    } else if highest < 0.0 {
        Some(-highest)
    } else {
        None
    }
}

/// The runs below ground as the search reports nodes and crossings in rim
/// order.
struct Scan<'m> {
    runs: Runs,
    /// Start of the run the rim is in, if below ground.
    start: Option<RimAngle>,
    /// Deepest penetration seen in that run \[m\].
    depth: f64,
    /// A run touches an end of the half rim.
    deep: bool,
    /// What the search proves, arc by arc; reusable while `proven`.
    certificate: &'m mut Certificate,
    proven: bool,
}

impl<'m> Scan<'m> {
    /// A scan whose certificate is written into `certificate`.
    fn new(certificate: &'m mut Certificate) -> Scan<'m> {
        Scan {
            runs: Runs::default(),
            start: None,
            depth: 0.0,
            deep: false,
            certificate,
            proven: true,
        }
    }

    /// A scan from the start of the rim `frame`, its certificate covering the
    /// rim `cover` below the searched arc's ends (every search starts here).
    fn restart(&mut self, frame: &RimFrame, cover: f64) {
        self.restart_in_place();
        self.certify(frame, cover);
    }

    /// A new certificate for the rim `frame`, covering it `cover` below the
    /// searched arc's ends, without a recorded arc yet.
    fn certify(&mut self, frame: &RimFrame, cover: f64) {
        let c = &mut *self.certificate;
        c.centre = frame.centre;
        c.down = frame.down;
        c.forward = frame.forward;
        c.radius = frame.radius;
        c.cover = cover;
        c.refined = [frame.centre, frame.down, frame.forward];
        c.count = 0;
    }

    /// A scan from the start of the rim whose certificate stays where it is
    /// ([`Search::reuse_in_place`]): no arc is recorded.
    fn restart_in_place(&mut self) {
        self.runs = Runs::default();
        self.start = None;
        self.depth = 0.0;
        self.deep = false;
        self.proven = true;
    }

    /// A settled arc, for the certificate.
    fn record(&mut self, leaf: Leaf) {
        let c = &mut *self.certificate;
        if c.count < MAX_LEAVES {
            c.leaves[c.count] = leaf;
            c.count += 1;
        } else {
            self.proven = false;
        }
    }

    /// The run the rim is in is at least `depth` deep.
    fn deepen(&mut self, depth: f64) {
        if self.start.is_some() {
            self.depth = self.depth.max(depth);
        }
    }

    /// An arc settled without proof (a feature below [`NEGLIGIBLE`], or the
    /// deepest halving): the next call searches again.
    fn unproven(&mut self) {
        self.proven = false;
    }

    /// The first node: an end of the half rim when it is below ground.
    fn begin(&mut self, n: &Node) {
        if n.h < 0.0 {
            self.start = Some(n.at);
            self.depth = -n.h;
            self.deep = true;
            // Runs would not pair the crossings: not reused.
            self.proven = false;
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
            self.proven = false;
            self.runs.push(a, n.at, self.depth);
        }
    }
}

/// The part of the half rim that can reach below height `top`: `[lo, hi]`,
/// where the rim is above `top` at an end that is not an end of the half
/// rim; `None` if the rim stays above it.
fn reach(frame: &RimFrame, top: f64) -> Option<(f64, f64)> {
    let half = core::f64::consts::FRAC_PI_2;
    // Rounding of the rim points and of the terrain's bound: far below 1 nm.
    let z = top + 1e-9 * (1.0 + top.abs() + frame.centre[2].abs());
    match frame.below(z) {
        Below::Unknown => Some((-half, half)),
        Below::Nowhere => None,
        Below::Around { lowest, width } => {
            let (lo, hi) = ((lowest - width).max(-half), (lowest + width).min(half));
            (lo < hi).then_some((lo, hi))
        }
    }
}

/// The terrain as one wheel's search sees it: through the wheel's kept
/// cells ([`KeptCells`]), which answer with the terrain's own bits. A query
/// outside them keeps the terrain's cell there, if it gives one
/// ([`HeightField::bicubic_cell`]).
struct Kept<'a, H: ?Sized> {
    terrain: &'a H,
    /// `None` for a terrain without cells.
    cells: Option<RefCell<&'a mut KeptCells>>,
}

impl<H: HeightField + ?Sized> Kept<'_, H> {
    /// The kept cell's answer `from_cell`, or the terrain's new cell's
    /// (then kept), or `None` where the terrain has none.
    #[inline(always)]
    fn through<T>(
        &self,
        x: f64,
        y: f64,
        from_cell: impl Fn(&KeptCells) -> Option<T>,
        from_new: impl Fn(&BicubicCell) -> Option<T>,
    ) -> Option<T> {
        let mut cells = self.cells.as_ref()?.try_borrow_mut().ok()?;
        if let Some(value) = from_cell(&cells) {
            return Some(value);
        }
        let cell = self.terrain.bicubic_cell(x, y)?;
        cells.keep(&cell);
        from_new(&cell)
    }
}

impl<H: HeightField + ?Sized> HeightField for Kept<'_, H> {
    #[inline]
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        match self.through(x, y, |c| c.height(x, y), |c| c.height(x, y)) {
            Some(z) => Ok(z),
            None => self.terrain.height(x, y),
        }
    }

    #[inline]
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        let found = self.through(
            x,
            y,
            |c| c.height_gradient(x, y),
            |c| c.height_gradient(x, y),
        );
        match found {
            Some(value) => Ok(value),
            None => self.terrain.height_gradient(x, y),
        }
    }

    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_height_in(area)
    }

    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_slope_in(area)
    }

    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_curvature_in(area)
    }

    fn plane(&self) -> Option<Plane> {
        self.terrain.plane()
    }

    fn surface(&self) -> u64 {
        self.terrain.surface()
    }

    fn bicubic_cell(&self, x: f64, y: f64) -> Option<BicubicCell> {
        self.terrain.bicubic_cell(x, y)
    }
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
        let mut memory = SearchMemory::default();
        self.find_with(terrain, centre, axis, radius, &mut memory, out)
    }

    /// [`BoundedContact::find_into`] with what the search learns about the
    /// wheel kept in `memory` between calls (one per wheel, see
    /// [`SearchMemory`]): the same patches, for fewer queries.
    pub fn find_with<H: HeightField + ?Sized>(
        &self,
        terrain: &H,
        centre: [f64; 3],
        axis: [f64; 3],
        radius: f64,
        memory: &mut SearchMemory,
        out: &mut Contact,
    ) -> Result<(), OffMap> {
        *out = Contact::default();
        let surface = terrain.surface();
        if memory.surface != surface {
            *memory = SearchMemory {
                surface,
                ..SearchMemory::default()
            };
        }
        let Some(frame) = RimFrame::new(centre, axis, radius) else {
            return Ok(());
        };
        let known = match terrain.plane() {
            None => memory.over(terrain, [centre[0], centre[1]], radius),
            Some(_) => None,
        };
        let Some([top, slope, curvature]) = known else {
            return self.fallback.find_into(terrain, centre, axis, radius, out);
        };
        // sqrt(1 + G²), not hypot: G is a slope, far from overflowing.
        let secant = math::sqrt(1.0 + slope * slope);
        let k = (radius * secant + curvature * radius * radius) * (1.0 + 1e-9);
        // Rounding of a clearance: of the rim point and of the interpolant.
        let rounding = 1e-12 * (1.0 + centre[2].abs() + radius + top.abs());
        if !(k.is_finite() && rounding.is_finite()) {
            return self.fallback.find_into(terrain, centre, axis, radius, out);
        }
        // A terrain without curvature under the wheel is a plane there: one
        // query gives it (kept with the bounds), and the rim is cut in
        // closed form.
        if curvature == 0.0
            && let Some(plane) = memory.plane(terrain)?
        {
            let n = self.fallback.sampling.samples.max(3);
            let step = core::f64::consts::PI / (n - 1) as f64;
            if cut_by_plane(&plane, &frame, n, step, out) {
                return Ok(());
            }
        }
        let kept = Kept {
            terrain,
            cells: (surface != 0).then(|| RefCell::new(&mut memory.cells)),
        };
        let search = Search {
            terrain: &kept,
            frame,
            k,
            rounding,
        };
        let slopes = [secant, secant + curvature * radius];
        let (old, new) = {
            let [first, second] = &mut memory.certificates;
            if memory.current == 0 {
                (first, second)
            } else {
                (second, first)
            }
        };
        let mut scan = Scan::new(new);
        let mut in_place = false;
        let reused = memory.proven
            && match search.reuse_in_place(old, slopes, &mut scan)? {
                InPlace::Done => {
                    in_place = true;
                    true
                }
                InPlace::Stopped(refined, change) => {
                    search.reuse(old, change, &mut scan, refined)?
                }
                InPlace::Invalid => false,
            };
        if !reused {
            // The arc searched reaches `PAD` above the terrain's highest
            // point, so that a certificate still covers every rim point that
            // can reach the ground after the wheel moves by less than that.
            let pad = PAD * radius;
            let Some((lo, hi)) = reach(&frame, top + pad) else {
                memory.proven = false;
                return Ok(());
            };
            let (first, last) = (search.node(lo)?, search.node(hi)?);
            scan.restart(&frame, pad);
            scan.begin(&first);
            search.settle(first, last, 0, &mut scan)?;
            scan.end(&last);
        }
        let (mut runs, deep, proven) = (scan.runs, scan.deep, scan.proven);
        memory.proven = proven;
        if !in_place {
            memory.current ^= 1;
        }
        out.deep = deep;
        runs.measure_shallow(&kept, &frame)?;
        runs.emit(&kept, &frame, out)
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
