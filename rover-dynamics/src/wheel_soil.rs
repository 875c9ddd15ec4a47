//! The soil acting on one wheel (docs/MODEL.md, "Soft soil"): a rigid
//! wheel of the description's radius and width, sunk into the soil as deep
//! as its contact patch reaches below the surface, spinning at its own rate
//! (a state of the run), under the terramechanics law of [`crate::soil`];
//! the forces reduced to a load at the wheel centre as the rigid-ground
//! law's are ([`crate::wheel_ground`]). `no_std` and allocation-free, so that
//! the runtime's ground and a generated plant's force path run this one
//! copy; generic over the scalar where the Jacobian differentiates it.
//!
//! Slip is measured in the wheel's direction of travel: with u = r·ω the
//! rim's speed and v the centre's along the patch heading t, in the frame
//! where the travel is forward (v ≥ 0),
//! ```text
//! s = (u − v) / max(|u|, v, v_ε),   clamped to [−1, 1]
//! ```
//! which is `1 − v/(r·ω)` driving and `r·ω/v − 1` braking, and stays finite
//! at standstill; the shear displacement takes a = u/D and b = v/D, D the
//! same denominator ([`crate::soil::Shear`]), so a wheel turning against
//! its travel shears the soil the other way, continuously. Reversing mirrors the law (a wheel driven backwards is the
//! forward law seen in a mirror); within ±v_ε of standstill the forward and
//! mirrored forces are blended with a smooth step, so the forces stay
//! continuous through a stop, and a parked wheel is held by the soil as a
//! stiff damper (it creeps at a fraction of v_ε on a slope, as a parked
//! rover with rolling resistance does).

use crate::contact::{Contact, Patch};
#[cfg(doc)]
use crate::dual::Dual;
use crate::height_field::HeightField;
use crate::linalg::{cross, dot, v3};
use crate::plant::{WheelLoad, WheelState};
use crate::scalar::Scalar;
use crate::soil::{
    Compaction, EntryAngle, GaussLegendre, Reload, Shear, SoilForces, SoilWheel, forces_on_arc,
};
use crate::wheel_ground::{LoadDerivative, WheelReport, lever_gradient};
use crate::wheel_law::DAMPING_RAMP;

/// Quadrature points on each piece of the contact arc in a run: the forces
/// to 1e-4 of their converged values (docs/SOIL.md) for 0.36 µs a wheel.
pub const RUN_POINTS: usize = 4;

/// The quadrature a run takes.
pub type RunRule = GaussLegendre<RUN_POINTS>;

/// Speed [m/s] below which the slip's denominator is held and the travel
/// direction blends between forward and mirrored: the slip is undefined at
/// standstill. 1 mm/s is far below a rover's driving speed (5 cm/s for the
/// paper's) and keeps a parked wheel's soil force a stiff, finite damper.
pub const SOIL_V_EPS: f64 = 1e-3;

/// A wheel on a soil: the soil's constants for its radius and width, and
/// its radial damper (the description's c_w, ramped in as on rigid ground:
/// the pressure–sinkage law is static, and without a damper a wheel landing
/// on soil would bounce on it as on an undamped spring).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoilTyre {
    /// The wheel in the soil.
    pub wheel: SoilWheel,
    /// Radial damping c_w [N·s/m].
    pub damping: f64,
}

/// The soil under one wheel as earlier passes left it (docs/MODEL.md,
/// "Ruts and multipass"), read from the ground's memory where the wheel
/// stands: fresh soil is the default.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SoilUnder {
    /// How far the soil's surface lies below the terrain's, d \[m\] (the
    /// rut): the wheel sinks into the soil from there.
    pub rut: f64,
    /// `[∂d/∂X, ∂d/∂Y]` [m/m]: how the rut's depth changes as the wheel
    /// moves (the assembled Jacobian's share of it).
    pub rut_gradient: [f64; 2],
    /// What the soil under the rut was pressed to.
    pub compaction: Compaction,
}

/// What the soil does to one patch of a wheel, reduced to its centre.
struct SoilPatchLoad<S> {
    /// Resultant force (normal, pull, lateral) \[N\].
    force: [S; 3],
    /// Its moment about the centre, less the component along the axle [N·m].
    moment: [S; 3],
    /// The soil's torque against the wheel's spin, T [N·m].
    torque: S,
    /// Normal force \[N\].
    normal: S,
    /// Drawbar pull along t \[N\].
    drawbar: S,
    /// Lateral force along c \[N\].
    lateral: S,
    /// Slip in the direction of travel.
    slip: S,
    /// Slip angle \[rad\].
    slip_angle: S,
    /// Sinkage \[m\].
    sinkage: S,
}

/// The slip a wheel reports, rim speed `u` and travel speed `v`:
/// `(u − v)·sgn(u + v)/max(|u|, |v|, v_ε)` in [−1, 1], positive when the
/// rim outruns the travel in the direction the wheel turns (driving, 1
/// spinning in place), negative when it lags behind the travel (braking,
/// −1 locked), whichever way the wheel goes.
fn reported_slip<S: Scalar + PartialOrd>(u: S, v: S) -> S {
    let scale = u.abs().max(v.abs()).max(S::cst(SOIL_V_EPS));
    ((u - v) * S::one().copysign(u + v) / scale)
        .max(-S::one())
        .min(S::one())
}

/// The slip of wheel `s` on its soil at the patches of `contact`, spinning
/// at `spin` \[rad/s\] with radius `radius` \[m\], for a controller to
/// read in the same evaluation (before the loads): the deepest patch's,
/// rim speed r·ω against the centre's speed along that patch's tangent, as
/// [`soil_wheel_load`] reports it, except that the sign of the travel is
/// blended over |u + v| < v_ε ([`SOIL_V_EPS`]) so that the slip is
/// continuous through standstill (the report's flips sign there, and a
/// controller fed a jump would chatter); `None` for a wheel in the air.
pub fn wheel_slip(s: &WheelState, contact: &Contact, spin: f64, radius: f64) -> Option<f64> {
    // The first patch of the largest clamped sinkage, as the report takes.
    let mut deepest: Option<(&Patch, f64)> = None;
    for p in contact.patches() {
        let sinkage = p.deflection.max(1e-12 * radius).min(radius);
        if deepest.is_none_or(|(_, d)| sinkage > d) {
            deepest = Some((p, sinkage));
        }
    }
    let (p, _) = deepest?;
    let (u, v) = (radius * spin, dot(s.velocity, p.tangent));
    let scale = u.abs().max(v.abs()).max(SOIL_V_EPS);
    let sign = 2.0 * forward_weight(u + v) - 1.0;
    Some(((u - v) * sign / scale).clamp(-1.0, 1.0))
}

/// The weight of the forward frame: 1 for v ≥ v_ε, 0 for v ≤ −v_ε, a
/// smooth step (C¹) between.
fn forward_weight<S: Scalar + PartialOrd>(v: S) -> S {
    let x = (v / S::cst(SOIL_V_EPS)).max(-S::one()).min(S::one());
    S::cst(0.5) + x * (S::cst(0.75) - S::cst(0.25) * x * x)
}

/// The soil's forces and the slip angle in the frame whose travel is
/// `sign` (±1) times the heading t, for rim speed `u`, travel speed `v`
/// and lateral speed `v_c` (all along the heading's frame).
fn in_frame<S: Scalar + PartialOrd>(
    tyre: &SoilTyre,
    rule: &RunRule,
    (entry, reload): (EntryAngle<S>, Option<&Reload>),
    sign: f64,
    [u, v, v_c]: [S; 3],
) -> (SoilForces<S>, S) {
    let (u, v) = (u * S::cst(sign), v * S::cst(sign));
    let eps = S::cst(SOIL_V_EPS);
    let scale = u.abs().max(v).max(eps);
    let shear = Shear {
        rim: u / scale,
        travel: v / scale,
    };
    let slip = (shear.rim - shear.travel).max(-S::one()).min(S::one());
    let forward = v.max(eps);
    let slip_angle = v_c.atan2(forward);
    // tan β of β = atan2(v_c, forward), forward > 0.
    let tan_beta = v_c / forward;
    let forces = forces_on_arc(&tyre.wheel, entry, slip, tan_beta, shear, reload, rule);
    (forces, slip_angle)
}

/// [`SoilPatchLoad`] of patch `p` of a wheel spinning at `spin` \[rad/s\],
/// its centre displaced by `shift` from where the patch was found and
/// moving at `velocity`, the patch's frame held (as the rigid law's
/// `patch_load`), over the soil `under` (its reloading law `reload`):
/// the sinkage is the patch's depth below the rut's floor,
/// `Δ₀ − g·shift − d − ∇d·shift`.
#[allow(clippy::too_many_arguments)]
fn soil_patch_load<S: Scalar + PartialOrd>(
    tyre: &SoilTyre,
    rule: &RunRule,
    s: &WheelState,
    p: &Patch,
    lever_gradient: [f64; 3],
    (under, reload): (&SoilUnder, Option<&Reload>),
    shift: [S; 3],
    velocity: [S; 3],
    spin: S,
) -> SoilPatchLoad<S> {
    let radius = tyre.wheel.radius;
    let (n, t, c) = (v3::<S>(p.normal), v3::<S>(p.tangent), v3::<S>(p.lateral));
    let moved = dot(v3::<S>(lever_gradient), shift);
    let [gx, gy] = under.rut_gradient;
    let rut = S::cst(under.rut) + S::cst(gx) * shift[0] + S::cst(gy) * shift[1];
    // The rim's depth below the soil's surface, within the wheel.
    let sinkage = (S::cst(p.deflection) - moved - rut)
        .max(S::cst(1e-12 * radius))
        .min(S::cst(radius));
    let r = S::cst(radius);
    // θ1 = acos(1 − z/r), by atan2 (defined to the axle); its sine and
    // cosine are the rim's chord and height over r.
    let (chord, height) = ((sinkage * (S::cst(2.0) * r - sinkage)).sqrt(), r - sinkage);
    let entry = EntryAngle {
        angle: chord.atan2(height),
        sin: chord / r,
        cos: height / r,
    };
    let speeds = [r * spin, dot(velocity, t), dot(velocity, c)];
    let forward = forward_weight(speeds[1]);
    let mut sum = SoilForces {
        vertical: S::zero(),
        drawbar: S::zero(),
        torque: S::zero(),
        lateral: S::zero(),
    };
    let mut slip_angle = S::zero();
    for (sign, weight) in [(1.0, forward), (-1.0, S::one() - forward)] {
        if weight <= S::zero() {
            continue;
        }
        let (f, beta) = in_frame(tyre, rule, (entry, reload), sign, speeds);
        sum.vertical += weight * f.vertical;
        sum.drawbar += weight * S::cst(sign) * f.drawbar;
        sum.torque += weight * S::cst(sign) * f.torque;
        sum.lateral += weight * f.lateral;
        slip_angle += weight * beta;
    }
    let slip = reported_slip(speeds[0], speeds[1]);
    // The soil's pressure, and the damper ramped in over its first 0.1 mm.
    let ramp = (sinkage / S::cst(DAMPING_RAMP)).min(S::one());
    let rate = -dot(velocity, n);
    let normal = (sum.vertical + S::cst(tyre.damping) * rate * ramp).max(S::zero());
    // The lateral shear resists the sideways slide.
    let lateral = -sum.lateral;
    let force = [0, 1, 2].map(|k| normal * n[k] + sum.drawbar * t[k] + lateral * c[k]);
    let arm = [0, 1, 2].map(|k| S::cst(p.point[k] - s.centre[k]) - moved * n[k]);
    let moment = cross(arm, force);
    let axis = v3::<S>(s.spin_axis);
    let axial = dot(moment, axis);
    SoilPatchLoad {
        force,
        moment: [0, 1, 2].map(|k| moment[k] - axial * axis[k]),
        torque: sum.torque,
        normal,
        drawbar: sum.drawbar,
        lateral,
        slip,
        slip_angle,
        sinkage,
    }
}

/// The load on a wheel on the soil, spinning at `spin` \[rad/s\] under the
/// motor torque `torque` [N·m], and its report (whose `torque` is the
/// soil's against the spin, Σ T):
/// ```text
/// F = Σ (F_n·n + DP·t + F_y·c)                       at G_j
/// μ = Σ (H − G_j) × F_patch, less its axle component     on the carrier
/// τ_stator = −τ·a_w                                    on the stator
/// I_w·ω̇ = τ − Σ T                                      the wheel's spin
/// ```
/// The report's slip, slip angle and sinkage are the deepest patch's; the
/// soil under every patch is `under` (what earlier passes left where the
/// wheel stands).
pub fn soil_wheel_load(
    tyre: &SoilTyre,
    rule: &RunRule,
    (s, under): (&WheelState, &SoilUnder),
    contact: &Contact,
    torque: f64,
    spin: f64,
) -> (WheelLoad, WheelReport) {
    let mut load = WheelLoad {
        stator_torque: s.spin_axis.map(|a| -torque * a),
        ..WheelLoad::default()
    };
    let mut report = WheelReport {
        point: s.centre,
        patches: contact.count,
        deep: contact.deep,
        ..Default::default()
    };
    let reload = tyre.wheel.reload(under.compaction);
    let soil = (under, reload.as_ref());
    let mut deepest = f64::NEG_INFINITY;
    for p in contact.patches() {
        let pl = soil_patch_load(tyre, rule, s, p, p.normal, soil, [0.0; 3], s.velocity, spin);
        for k in 0..3 {
            load.force[k] += pl.force[k];
            load.moment[k] += pl.moment[k];
        }
        report.normal += pl.normal;
        report.drawbar += pl.drawbar;
        report.lateral += pl.lateral;
        report.torque += pl.torque;
        if pl.sinkage > deepest {
            deepest = pl.sinkage;
            report.point = p.point;
            report.slip = pl.slip;
            report.slip_angle = pl.slip_angle;
            report.sinkage = pl.sinkage;
            report.rut = under.rut;
        }
    }
    (load, report)
}

/// [`LoadDerivative`] of a wheel on the soil at the patches of its last
/// contact: forward derivatives through the very `soil_patch_load` a run
/// evaluates, each patch's depth moving with the centre as
/// `lever_gradient` says, the patch frames held (as the rigid law's
/// derivative holds them). Row 9 is the soil's torque against the spin;
/// column 7 the spin. One pass a patch carries the seven directions
/// together (a jet of dual numbers), each as a [`Dual`] pass would.
pub fn soil_load_derivative<H: HeightField + ?Sized>(
    tyre: &SoilTyre,
    rule: &RunRule,
    terrain: &H,
    (s, under): (&WheelState, &SoilUnder),
    contact: &Contact,
    spin: f64,
) -> LoadDerivative {
    let mut d = [[0.0; 8]; 10];
    // The stator takes −τ·a_w.
    for k in 0..3 {
        d[6 + k][6] = -s.spin_axis[k];
    }
    // The directions: the centre's shift (3), its velocity (3), the spin;
    // the torque's column (6) is the stator's alone.
    const COLUMNS: [usize; DIRECTIONS] = [0, 1, 2, 3, 4, 5, 7];
    let shift = core::array::from_fn(|k| Jet::var(0.0, k));
    let velocity = core::array::from_fn(|k| Jet::var(s.velocity[k], 3 + k));
    let spin = Jet::var(spin, 6);
    let reload = tyre.wheel.reload(under.compaction);
    let soil = (under, reload.as_ref());
    for p in contact.patches() {
        let gradient = lever_gradient(terrain, s, p);
        let pl = soil_patch_load(tyre, rule, s, p, gradient, soil, shift, velocity, spin);
        for (i, &col) in COLUMNS.iter().enumerate() {
            for k in 0..3 {
                d[k][col] += pl.force[k].eps[i];
                d[3 + k][col] += pl.moment[k].eps[i];
            }
            d[9][col] += pl.torque.eps[i];
        }
    }
    d
}

/// The directions a [`Jet`] carries: a wheel's centre (3), velocity (3)
/// and spin (1).
const DIRECTIONS: usize = 7;

/// A value and its derivatives along [`DIRECTIONS`] directions at once:
/// component by component the arithmetic of a [`Dual`] (the same
/// formulas in the same order, so each derivative is the one a `Dual`
/// pass along its direction gives), with the value and its functions
/// (`exp`, `sin`, …) evaluated once for all directions.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Jet {
    re: f64,
    eps: [f64; DIRECTIONS],
}

impl Jet {
    /// The variable of direction `k`, at `re`.
    fn var(re: f64, k: usize) -> Self {
        let mut eps = [0.0; DIRECTIONS];
        eps[k] = 1.0;
        Self { re, eps }
    }

    /// `re` with derivatives `f(eps_i)`.
    #[inline(always)]
    fn with(re: f64, eps: [f64; DIRECTIONS], f: impl Fn(f64) -> f64) -> Self {
        Self {
            re,
            eps: eps.map(f),
        }
    }

    /// `re` with derivatives `f(a_i, b_i)`.
    #[inline(always)]
    fn zip(re: f64, a: &Self, b: &Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Self {
            re,
            eps: core::array::from_fn(|i| f(a.eps[i], b.eps[i])),
        }
    }
}

impl core::ops::Add for Jet {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::zip(self.re + o.re, &self, &o, |a, b| a + b)
    }
}
impl core::ops::Sub for Jet {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::zip(self.re - o.re, &self, &o, |a, b| a - b)
    }
}
impl core::ops::Mul for Jet {
    type Output = Self;
    // The product rule.
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let (x, y) = (self.re, o.re);
        Self::zip(x * y, &self, &o, |a, b| x * b + a * y)
    }
}
impl core::ops::Div for Jet {
    type Output = Self;
    // The quotient rule.
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let x = self.re;
        Self::zip(x * inv, &self, &o, |a, b| (a - x * inv * b) * inv)
    }
}
impl core::ops::Neg for Jet {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::with(-self.re, self.eps, |a| -a)
    }
}
impl core::ops::AddAssign for Jet {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl core::ops::SubAssign for Jet {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl core::ops::MulAssign for Jet {
    #[inline(always)]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

/// Ordered by value only, as [`Dual`] is (`max`, `min` and `abs` pick a
/// branch by it).
impl PartialOrd for Jet {
    fn partial_cmp(&self, other: &Self) -> Option<core::cmp::Ordering> {
        self.re.partial_cmp(&other.re)
    }
}

/// The larger by value, as [`Dual`]'s `pick`.
#[inline(always)]
fn pick(take_a: bool, a: Jet, b: Jet) -> Jet {
    if take_a { a } else { b }
}

impl Scalar for Jet {
    #[inline(always)]
    fn cst(value: f64) -> Self {
        Self {
            re: value,
            eps: [0.0; DIRECTIONS],
        }
    }
    #[inline(always)]
    fn sin(self) -> Self {
        let c = Scalar::cos(self.re);
        Self::with(Scalar::sin(self.re), self.eps, |a| a * c)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        let s = Scalar::sin(self.re);
        Self::with(Scalar::cos(self.re), self.eps, |a| -(a * s))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let r = Scalar::sqrt(self.re);
        // As `Dual`: 0 along a direction that does not move the argument.
        Self::with(r, self.eps, |a| if a == 0.0 { 0.0 } else { a / (r + r) })
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        let (y, xr) = (self.re, x.re);
        let d = xr * xr + y * y;
        Self::zip(Scalar::atan2(y, xr), &self, &x, |a, b| (xr * a - y * b) / d)
    }
    #[inline(always)]
    fn atan(self) -> Self {
        let x = self.re;
        Self::with(Scalar::atan(x), self.eps, |a| a / (1.0 + x * x))
    }
    #[inline(always)]
    fn hypot(self, other: Self) -> Self {
        let (x, y) = (self.re, other.re);
        let h = Scalar::hypot(x, y);
        Self::zip(h, &self, &other, |a, b| (x * a + y * b) / h)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        let e = Scalar::exp(self.re);
        Self::with(e, self.eps, |a| a * e)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        let x = self.re;
        Self::with(Scalar::ln(x), self.eps, |a| a / x)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        pick(self.re >= 0.0, self, -self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        pick(self.re >= other.re, self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        pick(self.re <= other.re, self, other)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        let a = self.abs();
        pick(sign.re >= 0.0, a, -a)
    }
}

/// The load on every wheel on the soil (`tyres`, `states`, the soil
/// `unders` each stands on, `spins` and `torques` in the order of
/// `wheels`), from its last contact, with its report: the second phase of
/// a right-hand side on a soil ([`crate::wheel_ground::wheel_loads`] on
/// rigid ground).
#[allow(clippy::too_many_arguments)]
pub fn soil_wheel_loads(
    tyres: &[SoilTyre],
    rule: &RunRule,
    (wheels, states, unders): (
        &[crate::wheel_ground::WheelContact],
        &[WheelState],
        &[SoilUnder],
    ),
    torques: &[f64],
    spins: &[f64],
    loads: &mut [WheelLoad],
    reports: &mut [WheelReport],
) {
    let each = wheels.iter().zip(states.iter().zip(unders));
    for ((((wheel, s), (tyre, &torque)), &spin), (load, report)) in each
        .zip(tyres.iter().zip(torques))
        .zip(spins)
        .zip(loads.iter_mut().zip(reports))
    {
        (*load, *report) = soil_wheel_load(tyre, rule, s, wheel.contact(), torque, spin);
    }
}

/// Each wheel's spin acceleration `ω̇ = (τ − T)/I_w` \[rad/s²\] from the
/// motor torques `torques` and the soil's torques in `reports` (their
/// `torque`), for the spin inertias `inertias`.
pub fn spin_rates(torques: &[f64], reports: &[WheelReport], inertias: &[f64], out: &mut [f64]) {
    for (((o, tau), r), i) in out.iter_mut().zip(torques).zip(reports).zip(inertias) {
        *o = (tau - r.torque) / i;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height_field::OffMap;
    use crate::soil::{Soil, SoilContact, soil_forces};

    const R: f64 = 0.13;
    const B: f64 = 0.16;

    /// LLL dry sand (Wong), K = 2.5 cm, a wheel of radius R and width B.
    fn tyre() -> SoilTyre {
        let soil = Soil {
            n: 1.1,
            k_c: 0.99e3,
            k_phi: 1528.43e3,
            cohesion: 1.04e3,
            friction_angle: 28f64.to_radians(),
            shear_modulus: 0.025,
            lateral_shear_modulus: 0.025,
            a0: 0.4,
            a1: 0.15,
            rear_ratio: 0.0,
            unit_weight: 0.0,
            reload_k0: 0.0,
            reload_au: 5.03e8,
        };
        SoilTyre {
            wheel: SoilWheel::new(&soil, R, B),
            damping: 300.0,
        }
    }

    /// A wheel sunk `z` into flat ground at Z = 0, its centre moving at
    /// `v` along X.
    fn wheel(z: f64, v: f64) -> (WheelState, Contact) {
        let s = WheelState {
            centre: [0.0, 0.0, R - z],
            velocity: [v, 0.0, 0.0],
            spin_axis: [0.0, 1.0, 0.0],
        };
        let mut contact = Contact::default();
        contact.patches[0] = Patch {
            point: [0.0, 0.0, 0.0],
            normal: [0.0, 0.0, 1.0],
            tangent: [1.0, 0.0, 0.0],
            lateral: [0.0, 1.0, 0.0],
            deflection: z,
            lever: R - z,
            angle: 0.0,
        };
        contact.count = 1;
        (s, contact)
    }

    fn load(z: f64, v: f64, spin: f64) -> (WheelLoad, WheelReport) {
        let (s, contact) = wheel(z, v);
        let fresh = SoilUnder::default();
        soil_wheel_load(&tyre(), &RunRule::new(), (&s, &fresh), &contact, 0.0, spin)
    }

    /// Driving forward at slip s (r·ω = v/(1 − s)), the wheel carries the
    /// law's forces at its depth: vertical, pull along its heading, the
    /// soil's torque against the spin.
    #[test]
    fn a_driven_wheel_carries_the_laws_forces() {
        let (z, v) = (0.01, 0.05);
        let theta1 = libm::acos(1.0 - z / R);
        for slip in [0.05, 0.3, 0.8] {
            let spin = v / (1.0 - slip) / R;
            let (l, report) = load(z, v, spin);
            let want = soil_forces(
                &tyre().wheel,
                SoilContact {
                    entry_angle: theta1,
                    slip,
                    slip_angle: 0.0,
                },
                &RunRule::new(),
            );
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
            assert!(close(l.force[2], want.vertical), "{slip}: vertical");
            assert!(close(l.force[0], want.drawbar), "{slip}: pull");
            assert!(close(report.torque, want.torque), "{slip}: torque");
            assert!(close(report.slip, slip), "{slip}: reported slip");
            assert!((report.sinkage - z).abs() < 1e-15);
        }
    }

    /// Driving backwards is the forward law in a mirror: the same vertical
    /// load and slip, the pull and the torque reversed.
    #[test]
    fn reversing_mirrors_the_law() {
        let (z, v, spin) = (0.012, 0.08, 0.9);
        let (f, rf) = load(z, v, spin);
        let (b, rb) = load(z, -v, -spin);
        assert!((f.force[2] - b.force[2]).abs() < 1e-12 * f.force[2]);
        assert!((f.force[0] + b.force[0]).abs() < 1e-12 * f.force[0].abs());
        assert!((rf.torque + rb.torque).abs() < 1e-12 * rf.torque.abs());
        assert!((rf.slip - rb.slip).abs() < 1e-15 && rf.slip > 0.0);
    }

    /// A parked wheel (no travel, no spin) is pressed straight up: no
    /// pull, no torque, its slip 0.
    #[test]
    fn a_parked_wheel_carries_no_pull() {
        let (l, r) = load(0.01, 0.0, 0.0);
        assert!(l.force[2] > 0.0);
        assert!(l.force[0].abs() < 1e-12 * l.force[2], "{}", l.force[0]);
        assert!(r.torque.abs() < 1e-12 * l.force[2] * R);
        assert_eq!(r.slip, 0.0);
    }

    /// Through standstill the forces are continuous: the forward and
    /// mirrored laws blend over ±v_ε, even for a wheel spinning in place.
    #[test]
    fn the_forces_are_continuous_through_a_stop() {
        for spin in [0.0, 0.3, -0.3] {
            let mut last: Option<(f64, f64)> = None;
            for k in -400..=400 {
                let v = k as f64 * 1e-5;
                let (l, r) = load(0.01, v, spin);
                if let Some((pull, torque)) = last {
                    assert!((l.force[0] - pull).abs() < 0.5, "{spin}, {v}: pull jumps");
                    assert!(
                        (r.torque - torque).abs() < 0.05,
                        "{spin}, {v}: torque jumps"
                    );
                }
                last = Some((l.force[0], r.torque));
            }
        }
    }

    /// The derivative a Jacobian takes is the load's own: central
    /// differences of the load in the centre's height, its velocity and the
    /// spin.
    #[test]
    fn the_load_derivative_is_the_loads_own() {
        struct Flat;
        impl HeightField for Flat {
            fn height(&self, _: f64, _: f64) -> Result<f64, OffMap> {
                Ok(0.0)
            }
            fn height_gradient(&self, _: f64, _: f64) -> Result<(f64, [f64; 2]), OffMap> {
                Ok((0.0, [0.0; 2]))
            }
        }
        let flat = Flat;
        let (z, v, spin) = (0.011, 0.05, 0.6);
        let (s, contact) = wheel(z, v);
        let fresh = SoilUnder::default();
        let d = soil_load_derivative(
            &tyre(),
            &RunRule::new(),
            &flat,
            (&s, &fresh),
            &contact,
            spin,
        );
        let parts = |l: &WheelLoad, r: &WheelReport| {
            let mut p = [0.0; 10];
            p[..3].copy_from_slice(&l.force);
            p[3..6].copy_from_slice(&l.moment);
            p[9] = r.torque;
            p
        };
        let h = 1e-7;
        // The centre down by h sinks the wheel by h.
        let column = |col: usize, plus: (f64, f64, f64), minus: (f64, f64, f64)| {
            let (lp, rp) = load(plus.0, plus.1, plus.2);
            let (lm, rm) = load(minus.0, minus.1, minus.2);
            let (p, m) = (parts(&lp, &rp), parts(&lm, &rm));
            for row in [0, 2, 4, 9] {
                let fd = (p[row] - m[row]) / (2.0 * h);
                let scale = 1.0 + fd.abs();
                assert!(
                    (d[row][col] - fd).abs() < 1e-5 * scale,
                    "row {row}, column {col}: {} vs {fd}",
                    d[row][col]
                );
            }
        };
        let mut down = [[0.0; 8]; 10];
        for row in 0..10 {
            down[row][2] = -d[row][2];
        }
        column(3, (z, v + h, spin), (z, v - h, spin));
        column(7, (z, v, spin + h), (z, v, spin - h));
        // ∂/∂(centre Z) is −∂/∂(sinkage).
        let (lp, rp) = load(z + h, v, spin);
        let (lm, rm) = load(z - h, v, spin);
        let (p, m) = (parts(&lp, &rp), parts(&lm, &rm));
        for row in [0, 2, 9] {
            let fd = (p[row] - m[row]) / (2.0 * h);
            assert!(
                (down[row][2] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                "row {row}, sinkage: {} vs {fd}",
                down[row][2]
            );
        }
    }

    mod jets {
        use super::super::*;
        use crate::soil::{Compaction, Soil};

        /// Wong's LLL dry sand (docs/SOIL.md), a 0.125 m wheel 0.16 m wide.
        fn tyre() -> SoilTyre {
            let soil = Soil {
                n: 1.1,
                k_c: 0.99e3,
                k_phi: 1528.43e3,
                cohesion: 1.04e3,
                friction_angle: 28f64.to_radians(),
                shear_modulus: 0.01,
                lateral_shear_modulus: 0.01,
                a0: 0.4,
                a1: 0.15,
                rear_ratio: 0.0,
                unit_weight: 0.0,
                reload_k0: 0.0,
                reload_au: 5.03e8,
            };
            SoilTyre {
                wheel: SoilWheel::new(&soil, 0.125, 0.16),
                damping: 300.0,
            }
        }

        /// A wheel on a 10° slope rising along X, sunk 15 mm, moving at
        /// `velocity` and spinning at `spin`; its patch, lever gradient
        /// (the slope's normal) and state.
        fn wheel(velocity: [f64; 3], spin: f64) -> (WheelState, Patch, f64) {
            let (s, c) = 10f64.to_radians().sin_cos();
            let normal = [-s, 0.0, c];
            let tangent = [c, 0.0, s];
            let lateral = [0.0, 1.0, 0.0];
            let (radius, sinkage) = (0.125, 0.015);
            let lever = radius - sinkage;
            let state = WheelState {
                centre: [0.0; 3],
                velocity,
                spin_axis: [0.0, 1.0, 0.0],
            };
            let patch = Patch {
                point: normal.map(|v| -lever * v),
                normal,
                tangent,
                lateral,
                deflection: sinkage,
                lever,
                angle: 0.0,
            };
            (state, patch, spin)
        }

        /// Driving, braking, near standstill (both frames blended), reversing,
        /// sliding sideways.
        fn motions() -> [([f64; 3], f64); 6] {
            let (s, c) = 10f64.to_radians().sin_cos();
            [
                ([0.05 * c, 0.0, 0.05 * s], 0.6),
                ([0.05 * c, 0.003, 0.05 * s], 0.2),
                ([0.0004 * c, 0.0, 0.0004 * s - 0.001], 0.01),
                ([-0.0002 * c, 0.0001, -0.0002 * s], -0.002),
                ([-0.04 * c, 0.0, -0.04 * s], -0.5),
                ([0.01 * c, 0.02, 0.01 * s], 0.1),
            ]
        }

        /// Each motion over fresh soil, over a rut sunk past its elastic
        /// knee (the stress's kink inside the arc) and over a rut reloaded
        /// elastically only, the rut deepening across the slope.
        fn motions_over_soils() -> impl Iterator<Item = (([f64; 3], f64), SoilUnder)> {
            let rut = |depth: f64, past: f64| SoilUnder {
                rut: depth,
                rut_gradient: [0.02, -0.3],
                compaction: Compaction { past_sinkage: past },
            };
            let soils = [SoilUnder::default(), rut(0.011, 0.013), rut(0.014, 0.016)];
            soils
                .into_iter()
                .flat_map(|under| motions().into_iter().map(move |m| (m, under)))
        }

        /// The seven directions of one [`Jet`] pass are, bit for bit, the
        /// seven [`Dual`] passes they replace.
        #[test]
        fn one_jet_pass_is_the_dual_passes() {
            use crate::dual::Dual;
            let (tyre, rule) = (tyre(), RunRule::new());
            for ((velocity, spin), under) in motions_over_soils() {
                let reload = tyre.wheel.reload(under.compaction);
                let soil = (&under, reload.as_ref());
                let (s, p, spin) = wheel(velocity, spin);
                let gradient = [0.1, -0.05, 1.0];
                let shift = core::array::from_fn(|k| Jet::var(0.0, k));
                let v = core::array::from_fn(|k| Jet::var(s.velocity[k], 3 + k));
                let jet = soil_patch_load(
                    &tyre,
                    &rule,
                    &s,
                    &p,
                    gradient,
                    soil,
                    shift,
                    v,
                    Jet::var(spin, 6),
                );
                for i in 0..DIRECTIONS {
                    let seed = |j: usize| if i == j { 1.0 } else { 0.0 };
                    let shift = core::array::from_fn(|k| Dual {
                        re: 0.0,
                        eps: seed(k),
                    });
                    let v = core::array::from_fn(|k| Dual {
                        re: s.velocity[k],
                        eps: seed(3 + k),
                    });
                    let w = Dual {
                        re: spin,
                        eps: seed(6),
                    };
                    let dual = soil_patch_load(&tyre, &rule, &s, &p, gradient, soil, shift, v, w);
                    for k in 0..3 {
                        assert_eq!(jet.force[k].re.to_bits(), dual.force[k].re.to_bits());
                        assert_eq!(jet.force[k].eps[i].to_bits(), dual.force[k].eps.to_bits());
                        assert_eq!(jet.moment[k].eps[i].to_bits(), dual.moment[k].eps.to_bits());
                    }
                    assert_eq!(jet.torque.eps[i].to_bits(), dual.torque.eps.to_bits());
                }
            }
        }

        /// The patch load's derivatives against central differences of the
        /// `f64` law, in every direction and every motion (the blend of the
        /// forward and mirrored frames near standstill included).
        #[test]
        fn the_jet_derivatives_are_the_differences_of_the_law() {
            let (tyre, rule) = (tyre(), RunRule::new());
            for ((velocity, spin), under) in motions_over_soils() {
                let reload = tyre.wheel.reload(under.compaction);
                let soil = (&under, reload.as_ref());
                let (s, p, spin) = wheel(velocity, spin);
                let gradient = [0.1, -0.05, 1.0];
                let shift = core::array::from_fn(|k| Jet::var(0.0, k));
                let v = core::array::from_fn(|k| Jet::var(s.velocity[k], 3 + k));
                let jet = soil_patch_load(
                    &tyre,
                    &rule,
                    &s,
                    &p,
                    gradient,
                    soil,
                    shift,
                    v,
                    Jet::var(spin, 6),
                );
                let at = |i: usize, h: f64| {
                    let mut x = [0.0, 0.0, 0.0, velocity[0], velocity[1], velocity[2], spin];
                    x[i] += h;
                    let l = soil_patch_load(
                        &tyre,
                        &rule,
                        &s,
                        &p,
                        gradient,
                        soil,
                        [x[0], x[1], x[2]],
                        [x[3], x[4], x[5]],
                        x[6],
                    );
                    [
                        l.force[0],
                        l.force[1],
                        l.force[2],
                        l.moment[0],
                        l.moment[1],
                        l.moment[2],
                        l.torque,
                    ]
                };
                for i in 0..DIRECTIONS {
                    // Small against the blend's 1 mm/s and the sinkage.
                    let h = 1e-8;
                    let (plus, minus) = (at(i, h), at(i, -h));
                    let got = [
                        jet.force[0],
                        jet.force[1],
                        jet.force[2],
                        jet.moment[0],
                        jet.moment[1],
                        jet.moment[2],
                        jet.torque,
                    ];
                    for k in 0..7 {
                        let fd = (plus[k] - minus[k]) / (2.0 * h);
                        let d = got[k].eps[i];
                        assert!(
                            (d - fd).abs() <= 1e-4 * (1.0 + fd.abs()),
                            "v {velocity:?}, ω {spin}: ∂{k}/∂{i}: {d} vs {fd}"
                        );
                    }
                }
            }
        }
    }
}
