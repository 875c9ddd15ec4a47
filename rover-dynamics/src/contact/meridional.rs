//! Contact by the meridional profile (MODEL.md §6, the paper's first method).
//!
//! ```text
//! P(β) = G_j + R_w·(cos β·d + sin β·f),   β ∈ [−90°, 90°]
//! h(β) = Z_P − Z_G(X_P, Y_P)
//! ```
//! Every maximal run of samples with h < 0 is a patch; its crossings A and B
//! are refined between samples by Newton steps on h with its exact slope
//! (from the terrain's gradient), safeguarded by a secant (Illinois) search.
//! Two patches whose gap the rim clears by less than [`SPLIT_BAND`] are
//! blended towards one chord (ours, see [`Runs::emit`]): the paper's chord
//! law would make the force jump where a patch splits.
//!
//! Only the samples that can reach the ground are evaluated: when the
//! terrain bounds its height under the wheel ([`HeightField::max_height_in`]),
//! the rim arc above that bound is skipped. Every skipped sample would have
//! had a clearance above the dip threshold, where it can start no patch, end
//! none and hide no dip, so the result is the same, bit for bit, as sampling
//! all of them (a test holds the two against each other). Within that arc,
//! when the terrain bounds its slope under the wheel
//! ([`HeightField::max_slope_in`]), the samples that provably stay on the
//! last queried sample's side of the ground are skipped too ([`Skip`]),
//! again without changing a bit: on rough ground a wheel's search queries
//! about a quarter of the samples it did.
//!
//! On a terrain that is one plane ([`HeightField::plane`]: flat ground, a
//! slope) nothing is sampled: the rim meets the plane where a sinusoid of β
//! crosses zero, so the run below ground and its ends are found in closed
//! form ([`plane_cut`]), the same patch as the sampled search's to its
//! crossing tolerance, for a tenth of its cost (a test holds the two
//! against each other).

use crate::height_field::{Bounds, HeightField, OffMap};

use super::math;
use super::patch::{Below, Contact, Patch, RimAngle, RimFrame, cross};

/// How the rim is sampled and how precisely crossings are located.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RimSampling {
    /// Number of rim samples over β ∈ [−90°, 90°]; 181 puts them 1° apart
    /// (MODEL.md §11), fine enough that a bump narrower than 1° of rim
    /// (1.6 mm on a 9 cm wheel) is the smallest feature missed.
    pub samples: usize,
    /// Crossings are located to this height residual \[m\] (1e-9).
    pub tolerance: f64,
}

impl Default for RimSampling {
    fn default() -> Self {
        Self {
            samples: 181,
            tolerance: 1e-9,
        }
    }
}

/// The meridional-profile search; stateless.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeridionalContact {
    /// Sampling of the rim.
    pub sampling: RimSampling,
}

/// Height of rim point β above the ground.
pub(crate) fn clearance<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    beta: f64,
) -> Result<f64, OffMap> {
    let (sin, cos) = math::sin_cos(beta);
    clearance_sc(terrain, frame, sin, cos)
}

/// [`clearance`] from sin β and cos β.
#[inline]
fn clearance_sc<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    sin: f64,
    cos: f64,
) -> Result<f64, OffMap> {
    let p = frame.point_sc(sin, cos);
    Ok(p[2] - terrain.height(p[0], p[1])?)
}

/// Samples of the default sampling (MODEL.md §11), whose sines and cosines
/// are tabulated once.
const DEFAULT_SAMPLES: usize = 181;

/// `(sin β_i, cos β_i)` of the default sampling's angles, computed by the
/// same expression as an untabulated sample, so the results do not change.
/// Kept once per process with `std`; without it (a firmware build, no
/// `OnceLock`) every sample computes its own.
#[cfg(feature = "std")]
fn default_table() -> Option<&'static [(f64, f64); DEFAULT_SAMPLES]> {
    static TABLE: std::sync::OnceLock<[(f64, f64); DEFAULT_SAMPLES]> = std::sync::OnceLock::new();
    Some(TABLE.get_or_init(|| {
        let step = core::f64::consts::PI / (DEFAULT_SAMPLES - 1) as f64;
        core::array::from_fn(|i| math::sin_cos(-core::f64::consts::FRAC_PI_2 + i as f64 * step))
    }))
}

#[cfg(not(feature = "std"))]
fn default_table() -> Option<&'static [(f64, f64); DEFAULT_SAMPLES]> {
    None
}

/// Sample i's angle of `n` samples `step` apart, its sine and cosine from
/// the table of the default sampling when there is one.
fn sample_angle(n: usize, step: f64, i: usize) -> RimAngle {
    tabulated_angle(
        (n == DEFAULT_SAMPLES).then(default_table).flatten(),
        step,
        i,
    )
}

/// [`sample_angle`] with the table looked up once by the caller.
#[inline]
fn tabulated_angle(table: Option<&[(f64, f64); DEFAULT_SAMPLES]>, step: f64, i: usize) -> RimAngle {
    let beta = sample_beta(step, i);
    let (sin, cos) = tabulated_sin_cos(table, step, i);
    RimAngle { beta, sin, cos }
}

/// Sample i's angle, `step` apart from −90°. Through i64: the same value
/// (i < 2⁵³), without the unsigned conversion's fix-ups at the baseline
/// x86-64 target.
#[inline]
fn sample_beta(step: f64, i: usize) -> f64 {
    -core::f64::consts::FRAC_PI_2 + i as i64 as f64 * step
}

/// Sample i's sine and cosine, from the table when there is one (the angle
/// is computed only when there is not).
#[inline]
fn tabulated_sin_cos(
    table: Option<&[(f64, f64); DEFAULT_SAMPLES]>,
    step: f64,
    i: usize,
) -> (f64, f64) {
    match table.and_then(|t| t.get(i)) {
        Some(&sc) => sc,
        None => math::sin_cos(sample_beta(step, i)),
    }
}

/// What [`plane_cut`] found.
enum PlaneCut {
    /// The one run below the plane lies inside the half rim: its patch.
    Inside(Patch),
    /// The one run of the half rim below the plane: its ends A, B, and
    /// whether an end is an end of the half rim (`deep`).
    Run(RimAngle, RimAngle, bool),
    /// No point of the half rim is below the plane.
    Clear,
    /// A case for the sampled search: a wheel buried past its centre (the
    /// run could wrap round onto both ends), a wheel plane parallel to the
    /// ground plane, a non-finite state.
    Sample,
}

/// The rim cut by a plane, in closed form.
///
/// On a plane the clearance is a sinusoid of β,
/// ```text
/// h(β) = c0 + R·(A·cos β + B·sin β) = c0 + R·ρ·cos(β − φ)
/// c0 = Z_G − Z(X_G, Y_G),  A = d_z − ∇Z·d_xy,  B = f_z − ∇Z·f_xy,  ρ = |(A, B)|
/// ```
/// lowest at β_m = φ ± π, below ground on `|β − β_m| < w = acos(c0/(R·ρ))`.
/// When the run lies inside the half rim (the usual case: both ends of
/// the half rim above the plane), its chord's midpoint H is at distance
/// `R·cos w = c0/ρ` from G along the lowest direction, so the patch
/// follows without its ends (one `atan2`, for β_m itself). Otherwise (an
/// end of the half rim below the plane) the ends' sines and cosines follow
/// from those of β_m (−B/ρ, −A/ρ) and of w (c0/(R·ρ), its complement) by
/// the angle sums, without evaluating any. The sampled search finds the same run (a plane has no dip or ridge
/// between samples to miss) with its ends to the crossing tolerance
/// (1e-9 m of height); here they are exact to rounding.
fn plane_cut(
    plane: &crate::height_field::Plane,
    frame: &RimFrame,
    n: usize,
    step: f64,
) -> PlaneCut {
    let (g, d, f, r) = (frame.centre, frame.down, frame.forward, frame.radius);
    let [gx, gy] = plane.gradient;
    let c0 = g[2] - plane.height_at(g[0], g[1]);
    let a = d[2] - gx * d[0] - gy * d[1];
    let b = f[2] - gx * f[0] - gy * f[1];
    let rho = math::sqrt(a * a + b * b);
    if !(c0.is_finite() && rho.is_finite() && rho > 1e-9 && r > 0.0) {
        return PlaneCut::Sample;
    }
    let ratio = c0 / (r * rho);
    if ratio >= 1.0 {
        return PlaneCut::Clear;
    }
    // (sin β_m, cos β_m): the lowest rim point's direction is
    // cos β_m·d + sin β_m·f. It lies in the half rim when cos β_m ≥ 0, and
    // the run is narrower than a quarter turn (w < 90°) when c0 > 0.
    let (sin_m, cos_m) = (-b / rho, -a / rho);
    if !(ratio > 0.0 && cos_m >= 0.0) {
        return PlaneCut::Sample;
    }
    // Both ends of the half rim (β = ∓90°, h = c0 ∓ R·B) above the plane:
    // the run lies inside, and its chord's midpoint is the lowest
    // direction's point at the distance c0/ρ = R·cos w from G. Nothing
    // else is needed: no end, no inverse trigonometry but β_m itself.
    if r * b.abs() < c0 {
        let lever = c0 / rho;
        let normal = [0, 1, 2].map(|k| -(cos_m * d[k] + sin_m * f[k]));
        let tangent = [0, 1, 2].map(|k| cos_m * f[k] - sin_m * d[k]);
        return PlaneCut::Inside(Patch {
            point: [0, 1, 2].map(|k| g[k] - lever * normal[k]),
            normal,
            tangent,
            lateral: cross(normal, tangent),
            deflection: r - lever,
            lever,
            angle: math::atan2(sin_m, cos_m),
        });
    }
    let half = core::f64::consts::FRAC_PI_2;
    let lowest = math::atan2(sin_m, cos_m);
    let width = math::acos(ratio);
    let (cos_w, sin_w) = (ratio, math::sqrt((1.0 - ratio) * (1.0 + ratio)));
    let (lo, hi) = (lowest - width, lowest + width);
    let start = if lo <= -half {
        sample_angle(n, step, 0)
    } else {
        RimAngle {
            beta: lo,
            sin: sin_m * cos_w - cos_m * sin_w,
            cos: cos_m * cos_w + sin_m * sin_w,
        }
    };
    let end = if hi >= half {
        sample_angle(n, step, n - 1)
    } else {
        RimAngle {
            beta: hi,
            sin: sin_m * cos_w + cos_m * sin_w,
            cos: cos_m * cos_w - sin_m * sin_w,
        }
    };
    PlaneCut::Run(start, end, lo <= -half || hi >= half)
}

/// The patch of the rim cut by `plane` into `out` (empty), true when the
/// cut settles the contact; false for the cases [`plane_cut`] leaves to a
/// search.
pub(crate) fn cut_by_plane(
    plane: &crate::height_field::Plane,
    frame: &RimFrame,
    n: usize,
    step: f64,
    out: &mut Contact,
) -> bool {
    match plane_cut(plane, frame, n, step) {
        PlaneCut::Inside(patch) => {
            out.push(patch);
            true
        }
        PlaneCut::Run(a, b, deep) => {
            out.deep = deep;
            out.push(frame.patch(a, b));
            true
        }
        PlaneCut::Clear => true,
        PlaneCut::Sample => false,
    }
}

/// Height of rim point β above the ground and its slope,
/// `dh/dβ = dZ_P/dβ − ∇Z_G·(dX_P/dβ, dY_P/dβ)`: one query of the height
/// with its gradient.
pub(crate) fn clearance_slope<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    at: RimAngle,
) -> Result<(f64, f64), OffMap> {
    let (s, c) = (at.sin, at.cos);
    let p = frame.point_sc(s, c);
    let (z, [zx, zy]) = terrain.height_gradient(p[0], p[1])?;
    let t = frame.tangent_sc(s, c);
    Ok((p[2] - z, t[2] - zx * t[0] - zy * t[1]))
}

/// Root of h between `lo` (h_lo) and `hi` (h_hi) of opposite signs: Newton
/// steps on the clearance's slope while they stay inside the bracket
/// (quadratic: from a secant step off samples 1° apart, one Newton step
/// usually meets the tolerance), else the Illinois variant of regula falsi
/// (superlinear, never leaves the bracket), else bisection.
pub(crate) fn crossing<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    lo: f64,
    h_lo: f64,
    hi: f64,
    h_hi: f64,
    tolerance: f64,
) -> Result<RimAngle, OffMap> {
    crossing_from(terrain, frame, [lo, h_lo], [hi, h_hi], None, tolerance)
}

/// [`crossing`] between `[β, h]` ends `lo` and `hi`, trying `guess` first
/// (a Newton step from a bracket end whose slope the caller knows) instead
/// of a secant step.
pub(crate) fn crossing_from<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    [mut lo, mut h_lo]: [f64; 2],
    [mut hi, mut h_hi]: [f64; 2],
    guess: Option<f64>,
    tolerance: f64,
) -> Result<RimAngle, OffMap> {
    let mut side = 0i8;
    let mut newton = guess;
    for _ in 0..60 {
        let inside = |b: f64| b > lo.min(hi) && b < lo.max(hi);
        let b = match newton.filter(|&b| inside(b)) {
            Some(b) => b,
            None => {
                let denom = h_hi - h_lo;
                let b = if denom != 0.0 {
                    hi - h_hi * (hi - lo) / denom
                } else {
                    0.5 * (lo + hi)
                };
                if inside(b) { b } else { 0.5 * (lo + hi) }
            }
        };
        let at = RimAngle::new(b);
        let (hb, slope) = clearance_slope(terrain, frame, at)?;
        if hb.abs() <= tolerance || (hi - lo).abs() < 1e-15 {
            return Ok(at);
        }
        newton = (slope != 0.0).then(|| b - hb / slope);
        if (hb < 0.0) == (h_hi < 0.0) {
            hi = b;
            h_hi = hb;
            if side == -1 {
                h_lo *= 0.5;
            }
            side = -1;
        } else {
            lo = b;
            h_lo = hb;
            if side == 1 {
                h_hi *= 0.5;
            }
            side = 1;
        }
    }
    Ok(RimAngle::new(0.5 * (lo + hi)))
}

impl MeridionalContact {
    /// The patches of a wheel with centre `centre`, unit spin axis `axis`
    /// (both inertial) and radius `radius`.
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

    /// [`MeridionalContact::find`] written into `out` (reset first), for a
    /// caller that keeps its contacts: no copy of the patches on the way
    /// back. On `Err`, `out` holds what was found before the failure.
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
        let n = self.sampling.samples.max(3);
        let step = core::f64::consts::PI / (n - 1) as f64;
        if let Some(plane) = terrain.plane()
            && cut_by_plane(&plane, &frame, n, step, out)
        {
            return Ok(());
        }
        // A dip between samples: a local minimum of the sampled clearance
        // that is shallow enough to hide a crossing is refined, so a patch
        // is born with zero deflection instead of appearing at the depth
        // the next sample would have shown (a force jump that stalls
        // step-size control). Smooth ground cannot hide more than the rim's
        // sagitta over one interval, R·Δβ²/2; four times that is searched.
        let hidden = 2.0 * radius * step * step;
        let area = frame.area();
        let (first, last) = match reach(terrain, &frame, &area, n, step, hidden) {
            Reach::Samples(first, last) => (first, last),
            Reach::Nothing => return Ok(()),
        };
        let skip = terrain
            .max_slope_in(&area)
            .and_then(|slope| Skip::new(&frame, slope, step, hidden));
        self.scan(terrain, &frame, [first, last], step, hidden, skip, out)
    }

    /// The sampled search over samples `range[0] ..= range[1]` only, into
    /// `contact` (empty); the caller guarantees that every sample outside
    /// has a clearance above `hidden`.
    #[allow(clippy::too_many_arguments)]
    fn scan<H: HeightField + ?Sized>(
        &self,
        terrain: &H,
        frame: &RimFrame,
        range: [usize; 2],
        step: f64,
        hidden: f64,
        skip: Option<Skip>,
        contact: &mut Contact,
    ) -> Result<(), OffMap> {
        let frame = *frame;
        let n = self.sampling.samples.max(3);
        let beta = |i: usize| sample_beta(step, i);
        let table = (n == DEFAULT_SAMPLES).then(default_table).flatten();
        let angle = |i: usize| tabulated_angle(table, step, i);
        let sample = |i: usize| -> Result<f64, OffMap> {
            let a = angle(i);
            clearance_sc(terrain, &frame, a.sin, a.cos)
        };
        let tol = self.sampling.tolerance;
        let mut runs = Runs::default();
        let mut prev = sample(range[0])?;
        // Start of the current run below ground: (angle, is it a sample end?)
        let mut start: Option<RimAngle> = if prev < 0.0 {
            contact.deep = true;
            Some(angle(0))
        } else {
            None
        };
        // Deepest sampled penetration of the current run (see `Runs::emit`).
        let mut depth = (-prev).max(0.0);
        let mut prev2 = f64::NAN;
        let mut i = range[0];
        while i < range[1] {
            i += 1;
            // Samples that provably stay on the last one's side of the
            // ground, clear of every threshold the checks below use, are
            // skipped; the last of them is queried all the same, as the
            // next crossing's bracket end (see `Skip`).
            if let Some(skip) = skip
                && let Some(side) = skip.side(prev)
            {
                // The rim's height from the table alone (no angle): this
                // loop runs over every sample of a skipped stretch.
                let rim = |k: usize| {
                    let (sin, cos) = tabulated_sin_cos(table, step, k);
                    frame.point_sc(sin, cos)[2]
                };
                let ground = rim(i - 1) - prev;
                let mut last = i;
                // The ground's reach `rise·k + rounding`, k = last + 1 − i,
                // kept by additions: a `usize` to `f64` conversion a sample
                // was a fifth of the scan's own work (callgrind).
                let mut reach = skip.rise + skip.rounding;
                while last < range[1] && skip.proves(side, rim(last) - ground, reach) {
                    last += 1;
                    reach += skip.rise;
                }
                // Samples i .. last − 1 are proven.
                if last >= i + 2 {
                    prev = sample(last - 1)?;
                    prev2 = match side {
                        Side::Above => f64::INFINITY,
                        Side::Below => {
                            depth = depth.max(skip.deep).max(-prev);
                            f64::NEG_INFINITY
                        }
                    };
                    i = last - 1;
                    continue;
                }
            }
            let b = beta(i);
            let h = sample(i)?;
            if prev >= 0.0 && h >= 0.0 && prev < prev2 && prev < h && prev < hidden {
                let (lo, hi) = (beta(i - 2), b);
                let (bm, hm) = extremum(terrain, &frame, lo, hi, Extremum::Lowest)?;
                if hm < 0.0 {
                    let a = crossing(terrain, &frame, lo, prev2, bm, hm, tol)?;
                    let e = crossing(terrain, &frame, bm, hm, hi, h, tol)?;
                    runs.push(a, e, -hm);
                }
            }
            // A ridge between samples, the mirror image of a dip: the rim
            // clears it between two samples below ground, which splits the
            // patch there (and the split is blended in, see `emit`).
            if prev < 0.0 && prev > -hidden && h < prev && prev > prev2 {
                let (lo, hi) = (beta(i - 2), b);
                let (bm, hm) = extremum(terrain, &frame, lo, hi, Extremum::Highest)?;
                if hm >= 0.0
                    && let Some(a) = start.take()
                {
                    runs.push(a, crossing(terrain, &frame, lo, prev2, bm, hm, tol)?, depth);
                    start = Some(crossing(terrain, &frame, bm, hm, hi, h, tol)?);
                    depth = -h;
                }
            }
            prev2 = prev;
            // Reset where a run starts, so this only ever counts its samples.
            depth = depth.max(-h);
            if prev >= 0.0 && h < 0.0 {
                start = Some(crossing(terrain, &frame, beta(i - 1), prev, b, h, tol)?);
                depth = -h;
            } else if prev < 0.0 && h >= 0.0 {
                let end = crossing(terrain, &frame, beta(i - 1), prev, b, h, tol)?;
                if let Some(a) = start.take() {
                    runs.push(a, end, depth);
                }
            }
            prev = h;
        }
        if let Some(a) = start {
            contact.deep = true;
            runs.push(a, angle(n - 1), depth);
        }
        runs.emit(terrain, &frame, contact)
    }
}

/// Which rim samples provably stay on the same side of the ground as a
/// queried one, from a bound `G` of the terrain's slope under the wheel.
///
/// Between rim samples k apart the rim point moves at most `k·R·Δβ`
/// horizontally, so the ground under it is within `G·k·R·Δβ` of the
/// height `z` queried under the first, while the rim's own height is
/// known exactly. A later sample is skipped when that bounds its clearance
/// - above `hidden` (the dip threshold), after a sample above `hidden`:
///   it can then start no run, end none, and be no dip's bottom;
/// - below `−deep` (`deep` = the dip threshold or [`SPLIT_BAND`], the
///   larger), after a sample below `−deep`: it can then end no run and be
///   no ridge's top, and the run's depth, which matters only up to
///   [`SPLIT_BAND`] (in [`Runs::blend`]), is at least `deep`.
///
/// Every check of [`MeridionalContact::scan`] then sees what it would
/// have seen with every sample queried, so the patches are the same bit
/// for bit (a test holds the two against each other).
#[derive(Clone, Copy, Debug)]
struct Skip {
    /// `G·R·Δβ`: how much the ground can rise or fall per sample \[m\].
    rise: f64,
    /// The dip threshold \[m\].
    hidden: f64,
    /// The depth below which a sample is deep \[m\].
    deep: f64,
    /// Rounding of the rim points and of the interpolant \[m\].
    rounding: f64,
}

/// Which side of the ground a skip stays on.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Side {
    Above,
    Below,
}

impl Skip {
    fn new(frame: &RimFrame, slope: f64, step: f64, hidden: f64) -> Option<Skip> {
        let rise = slope * frame.radius * step;
        let rounding = 1e-9 * (1.0 + frame.centre[2].abs() + frame.radius);
        (rise.is_finite() && rounding.is_finite() && hidden.is_finite()).then_some(Skip {
            rise,
            hidden,
            deep: hidden.max(SPLIT_BAND),
            rounding,
        })
    }

    /// The side a skip after a sample of clearance `h` can stay on, if any.
    #[inline]
    fn side(&self, h: f64) -> Option<Side> {
        if h >= self.hidden {
            Some(Side::Above)
        } else if h < -self.deep {
            Some(Side::Below)
        } else {
            None
        }
    }

    /// Whether a rim point whose height above the last queried ground is
    /// `above` provably stays on `side`, the ground under it being within
    /// `reach` (`rise·k + rounding`, k samples on) of the last queried.
    #[inline]
    fn proves(&self, side: Side, above: f64, reach: f64) -> bool {
        match side {
            Side::Above => above - reach > self.hidden,
            Side::Below => above + reach < -self.deep,
        }
    }
}

/// Width of the ridge clearance over which a patch that splits in two
/// hands over from one chord to two \[m\] (see [`Runs::emit`]).
pub const SPLIT_BAND: f64 = 1e-3;

/// Most runs below ground one search keeps: each gives at most one patch
/// (fewer where a blend merges two), so more could not be reported.
const MAX_RUNS: usize = super::MAX_PATCHES;

/// One run below ground: its crossings A, B and its deepest sampled
/// penetration \[m\].
#[derive(Clone, Copy, Default)]
struct Run {
    a: RimAngle,
    b: RimAngle,
    depth: f64,
}

/// The runs below ground found by the scan, in rim order.
#[derive(Clone, Copy, Default)]
pub(crate) struct Runs {
    runs: [Run; MAX_RUNS],
    count: usize,
}

impl Runs {
    pub(crate) fn push(&mut self, a: RimAngle, b: RimAngle, depth: f64) {
        if self.count < MAX_RUNS {
            self.runs[self.count] = Run {
                a,
                b,
                depth: depth.max(0.0),
            };
            self.count += 1;
        }
    }

    /// The patches of the runs. The paper's chord law makes the normal
    /// force jump when a ridge rises through the rim inside a patch: one
    /// chord AB of deflection Δ becomes two shorter chords whose
    /// deflections sum to about Δ/2. A rover can come to rest on that
    /// jump (the force on one side pushes it to the other), where no
    /// implicit integrator converges. So a split is blended in over the
    /// ridge's clearance g: with w = smoothstep(g/s), the inner ends of the
    /// two patches move from the merged chord's end B (w = 0: one chord AB
    /// and a chord of zero length at B, which carries no force) to their
    /// crossings (w = 1), along the rim. The scale s is SPLIT_BAND, or the
    /// shallower run's depth if less: a patch being born next to another
    /// (depth 0) is then a separate patch of zero length, so its birth
    /// stays continuous too. Gaps whose ridge clears the rim by a band or
    /// more, and single patches, are exactly the paper's.
    pub(crate) fn emit<H: HeightField + ?Sized>(
        self,
        terrain: &H,
        frame: &RimFrame,
        contact: &mut Contact,
    ) -> Result<(), OffMap> {
        let n = self.count;
        if n <= 1 {
            // The common case: nothing to blend.
            if let Some(run) = self.runs[..n].first() {
                contact.push(frame.patch(run.a, run.b));
            }
            return Ok(());
        }
        self.blend(terrain, frame, contact)
    }

    /// Where a blend needs it (two runs or more), each run shallower than
    /// [`SPLIT_BAND`] gets its true depth, the clearance's minimum between
    /// its crossings, instead of the deepest point a search happened to
    /// evaluate (for a search that evaluates few points).
    pub(crate) fn measure_shallow<H: HeightField + ?Sized>(
        &mut self,
        terrain: &H,
        frame: &RimFrame,
    ) -> Result<(), OffMap> {
        if self.count < 2 {
            return Ok(());
        }
        for run in &mut self.runs[..self.count.min(MAX_RUNS)] {
            if run.depth < SPLIT_BAND {
                let (_, lowest) =
                    extremum(terrain, frame, run.a.beta, run.b.beta, Extremum::Lowest)?;
                run.depth = run.depth.max(-lowest);
            }
        }
        Ok(())
    }

    /// [`Runs::emit`] for two runs or more.
    #[cold]
    #[inline(never)]
    fn blend<H: HeightField + ?Sized>(
        mut self,
        terrain: &H,
        frame: &RimFrame,
        contact: &mut Contact,
    ) -> Result<(), OffMap> {
        let runs = &mut self.runs[..self.count.min(MAX_RUNS)];
        // Walk from the last run back, moving the ends in place: once the
        // splits to its right are blended in, run i + 1 is final.
        let mut merged = [false; MAX_RUNS];
        for i in (0..runs.len().saturating_sub(1)).rev() {
            let Some(&[left, right]) = runs.get(i..i + 2) else {
                continue;
            };
            let scale = SPLIT_BAND.min(left.depth).min(right.depth);
            let w = split_weight(terrain, frame, left.b.beta, right.a.beta, scale)?;
            if w <= 0.0 {
                // One chord over both.
                if let Some(l) = runs.get_mut(i) {
                    l.b = right.b;
                }
                if let Some(m) = merged.get_mut(i + 1) {
                    *m = true;
                }
            } else if w < 1.0 {
                let end = right.b;
                let along = |to: RimAngle| RimAngle::new(end.beta + w * (to.beta - end.beta));
                if let Some([l, r]) = runs.get_mut(i..i + 2) {
                    r.a = along(right.a);
                    l.b = along(left.b);
                }
            }
        }
        for (run, merged) in runs.iter().zip(merged) {
            if !merged {
                contact.push(frame.patch(run.a, run.b));
            }
        }
        Ok(())
    }
}

/// The blend weight of the split between a patch ending at `from` and the
/// next starting at `to`: smoothstep of the ridge's clearance over `scale`
/// (at most [`SPLIT_BAND`]), 1 (a plain split) as soon as the rim clears it
/// by that, and for a scale of 0.
fn split_weight<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    from: f64,
    to: f64,
    scale: f64,
) -> Result<f64, OffMap> {
    if scale <= 0.0 {
        return Ok(1.0);
    }
    let mid = clearance(terrain, frame, 0.5 * (from + to))?;
    if mid >= scale {
        return Ok(1.0);
    }
    let (_, g) = extremum(terrain, frame, from, to, Extremum::Highest)?;
    let x = (g.max(mid) / scale).clamp(0.0, 1.0);
    Ok(x * x * (3.0 - 2.0 * x))
}

/// Which rim samples can reach the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Reach {
    /// Samples `first ..= last` (the others stay above the dip threshold).
    Samples(usize, usize),
    /// No sample comes within the dip threshold of the ground: no contact.
    Nothing,
}

/// The samples of the rim that can come within `hidden` of the ground, from
/// the terrain's height bound under the wheel, widened by two samples on
/// each side (the search looks two samples back) and one for rounding. All
/// samples when the terrain gives no bound ([`RimFrame::below`]).
fn reach<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    area: &Bounds,
    n: usize,
    step: f64,
    hidden: f64,
) -> Reach {
    let all = Reach::Samples(0, n - 1);
    let cz = frame.centre[2];
    let Some(top) = terrain.max_height_in(area) else {
        return all;
    };
    // Rounding of the rim points and of the interpolant: far below 1 nm.
    let z = top + hidden + 1e-9 * (1.0 + top.abs() + cz.abs());
    let (lowest, width) = match frame.below(z) {
        Below::Unknown => return all,
        Below::Nowhere => return Reach::Nothing,
        Below::Around { lowest, width } => (lowest, width),
    };
    let half = core::f64::consts::FRAC_PI_2;
    // Beyond a quarter turn the arc could wrap onto both ends of the half rim.
    if width > half - 0.01 {
        return all;
    }
    let last = (n - 1) as f64;
    let from = math::floor((lowest - width + half) / step) - 3.0;
    let to = math::ceil((lowest + width + half) / step) + 3.0;
    if to < 0.0 || from > last {
        return Reach::Nothing;
    }
    // Clamped into [0, n − 1]: the casts are exact.
    Reach::Samples(
        from.max(0.0).min(last) as usize,
        to.max(0.0).min(last) as usize,
    )
}

/// Which extremum [`extremum`] looks for.
#[derive(Clone, Copy, PartialEq)]
enum Extremum {
    Lowest,
    Highest,
}

/// Minimum (a dip) or maximum (a ridge) of the clearance on [lo, hi] by
/// golden-section search (the bracket holds one sampled local extremum).
fn extremum<H: HeightField + ?Sized>(
    terrain: &H,
    frame: &RimFrame,
    mut lo: f64,
    mut hi: f64,
    which: Extremum,
) -> Result<(f64, f64), OffMap> {
    const G: f64 = 0.618_033_988_749_894_8;
    // Searching the maximum of h is searching the minimum of −h.
    let sign = if which == Extremum::Lowest { 1.0 } else { -1.0 };
    let h = |b: f64| clearance(terrain, frame, b).map(|v| sign * v);
    let mut c = hi - G * (hi - lo);
    let mut d = lo + G * (hi - lo);
    let mut hc = h(c)?;
    let mut hd = h(d)?;
    for _ in 0..30 {
        if hc < hd {
            hi = d;
            d = c;
            hd = hc;
            c = hi - G * (hi - lo);
            hc = h(c)?;
        } else {
            lo = c;
            c = d;
            hc = hd;
            d = lo + G * (hi - lo);
            hd = h(d)?;
        }
    }
    Ok(if hc < hd {
        (c, sign * hc)
    } else {
        (d, sign * hd)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The skip's thresholds are the ones its argument needs (see
    /// [`Skip`]): it starts only from a sample above the dip threshold
    /// (a sample between 0 and it may be a dip's bottom, which the next
    /// sample must see) or deeper than the split band (a shallower run's
    /// depth sets its blend), and it proves only what clears those by the
    /// ground's reach. The whole-search tests cannot reach every one of
    /// these cases (a run shallower than the band is too short to skip
    /// into on any ground tried), so they are held here.
    #[test]
    fn the_skip_keeps_clear_of_every_threshold_the_scan_uses() {
        let frame = RimFrame::new([0.0, 0.0, 0.1], [0.0, 1.0, 0.0], 0.1).unwrap();
        let step = core::f64::consts::PI / 180.0;
        let hidden = 2.0 * 0.1 * step * step;
        let skip = Skip::new(&frame, 0.2, step, hidden).unwrap();
        assert!(
            hidden < SPLIT_BAND,
            "a 10 cm wheel's dip threshold is below the band"
        );
        assert_eq!(skip.deep, SPLIT_BAND);
        // Where a skip may start.
        assert_eq!(skip.side(hidden), Some(Side::Above));
        assert_eq!(skip.side(0.5 * hidden), None, "a possible dip bottom");
        assert_eq!(skip.side(0.0), None);
        assert_eq!(
            skip.side(-0.5 * SPLIT_BAND),
            None,
            "a run shallower than the band"
        );
        assert_eq!(skip.side(-SPLIT_BAND), None);
        assert_eq!(skip.side(-1.01 * SPLIT_BAND), Some(Side::Below));
        // What it proves, k samples on: the reach is rise·k plus rounding.
        let reach = |k: f64| skip.rise * k + skip.rounding;
        for k in [1.0, 5.0, 40.0] {
            let margin = 1e-12;
            assert!(skip.proves(Side::Above, hidden + reach(k) + margin, reach(k)));
            assert!(!skip.proves(Side::Above, hidden + reach(k) - margin, reach(k)));
            assert!(skip.proves(Side::Below, -SPLIT_BAND - reach(k) - margin, reach(k)));
            assert!(!skip.proves(Side::Below, -SPLIT_BAND - reach(k) + margin, reach(k)));
        }
        // A wheel whose dip threshold exceeds the band keeps the threshold.
        let big = RimFrame::new([0.0, 0.0, 2.0], [0.0, 1.0, 0.0], 2.0).unwrap();
        let big_hidden = 2.0 * 2.0 * step * step;
        let skip = Skip::new(&big, 0.2, step, big_hidden).unwrap();
        assert_eq!(skip.deep, big_hidden.max(SPLIT_BAND));
        // No bound, no skip: a non-finite slope (a sharp step's) makes none.
        assert!(Skip::new(&frame, f64::INFINITY, step, hidden).is_none());
    }
}
