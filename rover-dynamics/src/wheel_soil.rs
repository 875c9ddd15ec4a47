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
use crate::dual::Dual;
use crate::height_field::HeightField;
use crate::linalg::{cross, dot, v3};
use crate::plant::{WheelLoad, WheelState};
use crate::scalar::Scalar;
use crate::soil::{EntryAngle, GaussLegendre, Shear, SoilForces, SoilWheel, forces_on_arc};
use crate::wheel_ground::{LoadDerivative, WheelReport, lever_gradient};
use crate::wheel_law::DAMPING_RAMP;

/// Quadrature points on each piece of the contact arc in a run: the forces
/// to 1e-4 of their converged values (docs/SOIL.md) for 0.46 µs a wheel.
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

/// The weight of the forward frame: 1 for v ≥ v_ε, 0 for v ≤ −v_ε, a
/// smooth step (C¹) between.
fn forward_weight<S: Scalar + PartialOrd>(v: S) -> S {
    let x = (v / S::cst(SOIL_V_EPS)).max(-S::one()).min(S::one());
    S::cst(0.5) + x * (S::cst(0.75) - S::cst(0.25) * x * x)
}

/// The soil's forces and the slip and slip angle in the frame whose travel
/// is `sign` (±1) times the heading t, for rim speed `u`, travel speed `v`
/// and lateral speed `v_c` (all along the heading's frame).
fn in_frame<S: Scalar + PartialOrd>(
    tyre: &SoilTyre,
    rule: &RunRule,
    entry: EntryAngle<S>,
    sign: f64,
    [u, v, v_c]: [S; 3],
) -> (SoilForces<S>, S, S) {
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
    let forces = forces_on_arc(&tyre.wheel, entry, slip, tan_beta, shear, rule);
    (forces, slip, slip_angle)
}

/// [`SoilPatchLoad`] of patch `p` of a wheel spinning at `spin` \[rad/s\],
/// its centre displaced by `shift` from where the patch was found and
/// moving at `velocity`, the patch's frame held (as the rigid law's
/// `patch_load`): the sinkage is the patch's depth `Δ₀ − g·shift`.
#[allow(clippy::too_many_arguments)]
fn soil_patch_load<S: Scalar + PartialOrd>(
    tyre: &SoilTyre,
    rule: &RunRule,
    s: &WheelState,
    p: &Patch,
    lever_gradient: [f64; 3],
    shift: [S; 3],
    velocity: [S; 3],
    spin: S,
) -> SoilPatchLoad<S> {
    let radius = tyre.wheel.radius;
    let (n, t, c) = (v3::<S>(p.normal), v3::<S>(p.tangent), v3::<S>(p.lateral));
    let moved = dot(v3::<S>(lever_gradient), shift);
    // The rim's depth below the surface, within the wheel.
    let sinkage = (S::cst(p.deflection) - moved)
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
        let (f, _, beta) = in_frame(tyre, rule, entry, sign, speeds);
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
/// The report's slip, slip angle and sinkage are the deepest patch's.
pub fn soil_wheel_load(
    tyre: &SoilTyre,
    rule: &RunRule,
    s: &WheelState,
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
    let mut deepest = f64::NEG_INFINITY;
    for p in contact.patches() {
        let pl = soil_patch_load(tyre, rule, s, p, p.normal, [0.0; 3], s.velocity, spin);
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
        }
    }
    (load, report)
}

/// [`LoadDerivative`] of a wheel on the soil at the patches of its last
/// contact: dual numbers through the very `soil_patch_load` a run
/// evaluates, each patch's depth moving with the centre as
/// `lever_gradient` says, the patch frames held (as the rigid law's
/// derivative holds them). Row 9 is the soil's torque against the spin;
/// column 7 the spin.
pub fn soil_load_derivative<H: HeightField + ?Sized>(
    tyre: &SoilTyre,
    rule: &RunRule,
    terrain: &H,
    s: &WheelState,
    contact: &Contact,
    spin: f64,
) -> LoadDerivative {
    let mut d = [[0.0; 8]; 10];
    // The stator takes −τ·a_w.
    for k in 0..3 {
        d[6 + k][6] = -s.spin_axis[k];
    }
    for p in contact.patches() {
        let gradient = lever_gradient(terrain, s, p);
        for col in [0, 1, 2, 3, 4, 5, 7] {
            let seed = |j: usize| if col == j { 1.0 } else { 0.0 };
            let shift = [0, 1, 2].map(|k| Dual {
                re: 0.0,
                eps: seed(k),
            });
            let velocity = [0, 1, 2].map(|k| Dual {
                re: s.velocity[k],
                eps: seed(3 + k),
            });
            let spin = Dual {
                re: spin,
                eps: seed(7),
            };
            let pl = soil_patch_load(tyre, rule, s, p, gradient, shift, velocity, spin);
            for k in 0..3 {
                d[k][col] += pl.force[k].eps;
                d[3 + k][col] += pl.moment[k].eps;
            }
            d[9][col] += pl.torque.eps;
        }
    }
    d
}

/// The load on every wheel on the soil (`tyres`, `states`, `spins` and
/// `torques` in the order of `wheels`), from its last contact, with its
/// report: the second phase of a right-hand side on a soil
/// ([`crate::wheel_ground::wheel_loads`] on rigid ground).
#[allow(clippy::too_many_arguments)]
pub fn soil_wheel_loads(
    tyres: &[SoilTyre],
    rule: &RunRule,
    (wheels, states): (&[crate::wheel_ground::WheelContact], &[WheelState]),
    torques: &[f64],
    spins: &[f64],
    loads: &mut [WheelLoad],
    reports: &mut [WheelReport],
) {
    let each = wheels.iter().zip(states).zip(tyres.iter().zip(torques));
    for ((((wheel, s), (tyre, &torque)), &spin), (load, report)) in
        each.zip(spins).zip(loads.iter_mut().zip(reports))
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
