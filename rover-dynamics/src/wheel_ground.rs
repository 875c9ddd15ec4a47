//! The ground acting on one wheel: its contact search, the force law on each
//! patch and their reduction to a load at the wheel centre (MODEL.md §6–§7),
//! with what the search keeps between evaluations. `no_std` and
//! allocation-free, so that the generic plant's runtime and a generated
//! plant's own force path ([`FixedGround`]) run this one copy.

use crate::contact::{
    BoundedContact, Contact, MAX_PATCHES, MeridionalContact, Patch, RimSampling, SearchMemory,
    TrackedContact,
};
use crate::dual::Dual;
use crate::height_field::{HeightField, OffMap};
use crate::linalg::{cross, dot, v3};
use crate::plant::{PlantError, WheelLoad, WheelState};
use crate::scalar::Scalar;
use crate::wheel_law::{
    PatchForces, PatchMotion, Tyre, WheelLaw, normal_force, rolling_resistance,
};
use crate::wheel_soil::{RunRule, SoilTyre, SoilUnder, soil_wheel_loads, spin_rates};

/// Which contact search a run uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum ContactMethod {
    /// The meridional profile, every evaluation (the paper's first method).
    Meridional,
    /// Track the contact centre from the previous evaluation (eq. 35).
    Tracked,
    /// The rim's crossings with the ground proved and found from the
    /// terrain's bounds of height, slope and curvature, without sampling
    /// ([`BoundedContact`]); the meridional search where the terrain gives no
    /// curvature bound. The default: the same patches as a dense sampling,
    /// none missed between samples, for fewer terrain queries.
    #[default]
    Bounded,
}

/// What the contact did on one wheel, for the CSV and the summary.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WheelReport {
    /// Contact point H of the patch with the largest normal force; the
    /// wheel centre when the wheel is airborne \[m\].
    pub point: [f64; 3],
    /// Sum of the normal forces \[N\].
    pub normal: f64,
    /// Sum of the drawbar pulls \[N\].
    pub drawbar: f64,
    /// Sum of the lateral forces \[N\].
    pub lateral: f64,
    /// Torque the ground took from the wheel: Σ |G_jH|·F_d on rigid
    /// ground (the motor's, the wheel's rotation being massless), the
    /// soil's torque against the spin Σ T on a soil [N·m].
    pub torque: f64,
    /// Slip in the direction of travel, on a soil (0 on rigid ground, whose
    /// law has none): positive driving, negative braking.
    pub slip: f64,
    /// Slip angle between the heading and the centre's velocity on a soil
    /// \[rad\] (0 on rigid ground).
    pub slip_angle: f64,
    /// Sinkage: the rim's depth below the soil's surface on a soil \[m\]
    /// (0 on rigid ground). Where an earlier pass left a rut, below the
    /// rut's floor: `rut + sinkage` is the depth below the undisturbed
    /// ground.
    pub sinkage: f64,
    /// The depth of the rut under the wheel \[m\]: how far earlier passes
    /// lowered the soil's surface below the terrain's (0 on fresh soil and
    /// on rigid ground).
    pub rut: f64,
    /// Number of patches.
    pub patches: usize,
    /// The whole lower half of the wheel was below ground.
    pub deep: bool,
}

/// A wheel left the terrain map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelOffMap {
    /// Wheel index (0-based).
    pub wheel: usize,
    /// The failed query.
    pub off: OffMap,
}

impl core::fmt::Display for WheelOffMap {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "wheel {} left the terrain: {}", self.wheel + 1, self.off)
    }
}

/// Why a right-hand side on the ground could not be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GroundError {
    /// A wheel left the terrain map.
    OffMap(WheelOffMap),
    /// The plant could not produce accelerations.
    Plant(PlantError),
}

impl core::error::Error for WheelOffMap {}

impl core::error::Error for GroundError {}

impl core::fmt::Display for GroundError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            GroundError::OffMap(off) => off.fmt(f),
            GroundError::Plant(e) => e.fmt(f),
        }
    }
}

/// How a run finds contacts: the method, and the rim sampling of the
/// meridional search (the method itself, the tracked search's fallback, and
/// the bounded search's on terrains it cannot bound).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Search {
    /// The method.
    pub method: ContactMethod,
    /// The sampled search.
    pub meridional: MeridionalContact,
}

impl Search {
    /// The search `method` with the meridional search sampling `sampling`.
    pub fn new(method: ContactMethod, sampling: RimSampling) -> Self {
        Self {
            method,
            meridional: MeridionalContact { sampling },
        }
    }
}

/// The ground under one wheel: its last contact and what its search keeps
/// between evaluations (the tracked search's centre, the bounded search's
/// bounds and certificate). A few kilobytes, fixed: nothing allocates.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WheelContact {
    tracker: TrackedContact,
    memory: SearchMemory,
    contact: Contact,
}

impl WheelContact {
    /// A wheel not yet searched, for `search`.
    pub fn new(search: &Search) -> Self {
        Self {
            tracker: TrackedContact::new(search.meridional),
            memory: SearchMemory::default(),
            contact: Contact::default(),
        }
    }

    /// The contact of the last [`WheelContact::find`].
    pub fn contact(&self) -> &Contact {
        &self.contact
    }

    /// Finds the patches of a wheel of radius `radius` in state `s`.
    pub fn find<H: HeightField + ?Sized>(
        &mut self,
        search: &Search,
        terrain: &H,
        s: &WheelState,
        radius: f64,
    ) -> Result<(), OffMap> {
        let out = &mut self.contact;
        match search.method {
            ContactMethod::Meridional => {
                search
                    .meridional
                    .find_into(terrain, s.centre, s.spin_axis, radius, out)
            }
            ContactMethod::Tracked => {
                self.tracker
                    .find_into(terrain, s.centre, s.spin_axis, radius, out)
            }
            ContactMethod::Bounded => BoundedContact {
                fallback: search.meridional,
            }
            .find_with(
                terrain,
                s.centre,
                s.spin_axis,
                radius,
                &mut self.memory,
                out,
            ),
        }
    }

    /// The sum of the patches' normal forces \[N\] (it does not depend on
    /// the drive torque, so a torque distribution by measured load can use
    /// it before the loads are computed).
    pub fn normal(&self, tyre: &Tyre, s: &WheelState) -> f64 {
        self.contact
            .patches()
            .iter()
            .map(|p| patch_normal(tyre, s, p))
            .sum()
    }

    /// The load on the wheel and its report under the motor torque `torque`
    /// [N·m] ([`wheel_load`]).
    #[inline]
    pub fn load<L: WheelLaw>(
        &self,
        law: &L,
        tyre: &Tyre,
        s: &WheelState,
        torque: f64,
    ) -> (WheelLoad, WheelReport) {
        wheel_load(law, tyre, s, &self.contact, torque)
    }

    /// [`load_derivative`] at the last contact.
    pub fn load_derivative<L: WheelLaw, H: HeightField + ?Sized>(
        &self,
        law: &L,
        tyre: &Tyre,
        terrain: &H,
        s: &WheelState,
        torque: f64,
    ) -> LoadDerivative {
        load_derivative(law, tyre, terrain, s, &self.contact, torque)
    }
}

/// The ground under `W` wheels, fixed in size: the force path of a
/// generated plant (`derivatives_on_ground` in the module `rover codegen`
/// writes), which passes its tyres and radii as constants. `Clone`, not
/// `Copy`: it is a few kilobytes a wheel.
#[derive(Clone, Debug)]
pub struct FixedGround<const W: usize> {
    /// The contact search.
    pub search: Search,
    /// The soil under each wheel, if the ground is soft ([`FixedGround::on_soil`]).
    soil: Option<[SoilTyre; W]>,
    rule: RunRule,
    spins: [f64; W],
    unders: [SoilUnder; W],
    wheels: [WheelContact; W],
    normals: [f64; W],
    loads: [WheelLoad; W],
    reports: [WheelReport; W],
}

impl<const W: usize> FixedGround<W> {
    /// A ground searched by `search`, no wheel searched yet.
    pub fn new(search: Search) -> Self {
        Self {
            search,
            soil: None,
            rule: RunRule::new(),
            spins: [0.0; W],
            unders: [SoilUnder::default(); W],
            wheels: [WheelContact::new(&search); W],
            normals: [0.0; W],
            loads: [WheelLoad::default(); W],
            reports: [WheelReport::default(); W],
        }
    }

    /// A ground searched by `search` whose surface is the soil `soil`
    /// under each wheel: [`FixedGround::loads`] then takes the soil law
    /// (its `law` and the tyres' friction unused), each wheel spinning at
    /// the rate last given to [`FixedGround::set_spins`], and each report's
    /// `torque` is the soil's against the spin, from which
    /// [`FixedGround::spin_rates`] gives the spins' accelerations.
    pub fn on_soil(search: Search, soil: [SoilTyre; W]) -> Self {
        Self {
            soil: Some(soil),
            ..Self::new(search)
        }
    }

    /// Each wheel's spin rate ω \[rad/s\] for the next [`FixedGround::loads`]
    /// on a soil (positive rolling forward; unused on rigid ground).
    pub fn set_spins(&mut self, spins: &[f64; W]) {
        self.spins = *spins;
    }

    /// The soil under each wheel for the next [`FixedGround::loads`] on a
    /// soil: the rut and compaction earlier passes left where it stands
    /// (fresh soil until set). A rig keeping its own rut map reads it at
    /// each wheel's contact point after [`FixedGround::find_contacts`].
    pub fn set_soil_under(&mut self, unders: &[SoilUnder; W]) {
        self.unders = *unders;
    }

    /// Each wheel's spin acceleration `(τ − T)/I_w` \[rad/s²\] after
    /// [`FixedGround::loads`] under the motor torques `torques` [N·m], for
    /// the spin inertias `inertias` [kg·m²] (on a soil).
    pub fn spin_rates(&self, torques: &[f64; W], inertias: &[f64; W]) -> [f64; W] {
        let mut out = [0.0; W];
        spin_rates(torques, &self.reports, inertias, &mut out);
        out
    }

    /// Finds every wheel's contact (the first phase of a right-hand side)
    /// and returns each wheel's total normal force \[N\].
    #[inline]
    pub fn find_contacts<H: HeightField + ?Sized>(
        &mut self,
        terrain: &H,
        states: &[WheelState; W],
        tyres: &[Tyre; W],
        radii: &[f64; W],
    ) -> Result<&[f64; W], WheelOffMap> {
        let ground = (&self.search, terrain);
        find_contacts(
            ground,
            &mut self.wheels,
            states,
            tyres,
            radii,
            &mut self.normals,
        )?;
        Ok(&self.normals)
    }

    /// The loads on every wheel from the contacts of
    /// [`FixedGround::find_contacts`] under the motor torques `torques`
    /// [N·m] (the second phase).
    #[inline]
    pub fn loads<L: WheelLaw>(
        &mut self,
        law: &L,
        states: &[WheelState; W],
        tyres: &[Tyre; W],
        torques: &[f64; W],
    ) -> &[WheelLoad; W] {
        match &self.soil {
            Some(soil) => soil_wheel_loads(
                soil,
                &self.rule,
                (&self.wheels[..], &states[..], &self.unders[..]),
                torques,
                &self.spins,
                &mut self.loads,
                &mut self.reports,
            ),
            None => {
                let wheels = (&self.wheels[..], &states[..], &tyres[..]);
                wheel_loads(law, wheels, torques, &mut self.loads, &mut self.reports);
            }
        }
        &self.loads
    }

    /// The reports of the last [`FixedGround::loads`].
    pub fn reports(&self) -> &[WheelReport; W] {
        &self.reports
    }

    /// Each wheel's last contact.
    pub fn contacts(&self) -> [&Contact; W] {
        core::array::from_fn(|k| self.wheels[k].contact())
    }
}

/// Finds the contact of every wheel (states, tyres and radii in the same
/// order as `wheels`) on the ground `(search, terrain)`, and each wheel's
/// total normal force into `normals`: the first phase of a right-hand
/// side, for any number of wheels ([`FixedGround`], the runtime's ground).
pub fn find_contacts<H: HeightField + ?Sized>(
    (search, terrain): (&Search, &H),
    wheels: &mut [WheelContact],
    states: &[WheelState],
    tyres: &[Tyre],
    radii: &[f64],
    normals: &mut [f64],
) -> Result<(), WheelOffMap> {
    let each = wheels.iter_mut().zip(states).zip(tyres.iter().zip(radii));
    for (k, (((wheel, s), (tyre, &radius)), normal)) in each.zip(normals).enumerate() {
        wheel
            .find(search, terrain, s, radius)
            .map_err(|off| WheelOffMap { wheel: k, off })?;
        *normal = wheel.normal(tyre, s);
    }
    Ok(())
}

/// The load on every wheel of `(wheels, states, tyres)` from its last
/// contact under the motor torques `torques` [N·m], with its report: the
/// second phase of a right-hand side ([`find_contacts`]).
pub fn wheel_loads<L: WheelLaw>(
    law: &L,
    (wheels, states, tyres): (&[WheelContact], &[WheelState], &[Tyre]),
    torques: &[f64],
    loads: &mut [WheelLoad],
    reports: &mut [WheelReport],
) {
    let each = wheels.iter().zip(states).zip(tyres.iter().zip(torques));
    for (((wheel, s), (tyre, &torque)), (load, report)) in each.zip(loads.iter_mut().zip(reports)) {
        (*load, *report) = wheel.load(law, tyre, s, torque);
    }
}

/// How patch `p`'s lever |G_jH| changes as the wheel centre moves, the rim
/// and the ground held: `∂|G_jH|/∂G_j`. The chord's ends A and B slide
/// along the ground; by the implicit function theorem on the rim angle at
/// which the rim meets the ground (`ν` the ground's upward normal
/// `(−∂h/∂X, −∂h/∂Y, 1)` there, `u′` the rim's direction of travel),
/// ```text
/// ∂|G_jH|/∂G_j = ½·Σ_{A, B} (n·u′)/(ν·u′)·ν
/// ```
/// which is `n` on a plane under an upright wheel and grows as `1/(1 − κR)`
/// in a hollow of curvature κ (a large wheel in a dip presses harder than
/// the plane through its contact point says). An end the ground cannot be
/// queried at, or where the rim runs along the ground, counts as on a plane
/// through H.
pub(crate) fn lever_gradient<H: HeightField + ?Sized>(
    terrain: &H,
    s: &WheelState,
    p: &Patch,
) -> [f64; 3] {
    let radius = p.lever + p.deflection;
    let half = Scalar::sqrt((radius * radius - p.lever * p.lever).max(0.0));
    let ends = [-1.0, 1.0].map(|side| {
        let end = [0, 1, 2].map(|k| p.point[k] + side * half * p.tangent[k]);
        let radial = [0, 1, 2].map(|k| end[k] - s.centre[k]);
        // The rim's direction of travel at the end, in the wheel's plane.
        let travel = cross(s.spin_axis, radial);
        let ground = match terrain.height_gradient(end[0], end[1]) {
            Ok((_, [gx, gy])) => [-gx, -gy, 1.0],
            Err(_) => p.normal,
        };
        let across = dot(ground, travel);
        if across.abs() < 1e-9 * radius {
            return p.normal;
        }
        let ratio = dot(p.normal, travel) / across;
        [0, 1, 2].map(|k| ratio * ground[k])
    });
    [0, 1, 2].map(|k| 0.5 * (ends[0][k] + ends[1][k]))
}

/// Smallest drive lever, as a fraction of the wheel radius. Eq. 38's
/// `F_d = τ/|G_jH|` is singular for a wheel buried to its centre (a chord
/// through G_j, `|G_jH| = 0`): any drive torque saturates the pull at
/// `±μx·F_n`, which flips sign with the torque (a 58 N jump on ExoMars when
/// its speed loop was at its setpoint), and no motor reaction balances it.
/// A deflection beyond half the radius is far outside the tyre law anyway
/// (the run summary lists such wheels as deep penetrations); the floor keeps
/// the pull continuous there and the paper's law untouched elsewhere.
pub const MIN_LEVER_FRACTION: f64 = 0.5;

/// The motion of patch `p` of a wheel whose centre is displaced by `shift`
/// from where the patch was found and moves at `velocity`, with the patch's
/// frame held: `|G_jH| = |G_jH|₀ + g·shift` (`g` = `lever_gradient`, see
/// [`lever_gradient`]), `Δ = Δ₀ − g·shift`, `Δ̇ = −V·n`, `v_t = V·t`,
/// `v_c = V·c`. A run evaluates it with `shift = 0` (exactly the patch
/// found); the Jacobian differentiates it in `shift` and `velocity`.
#[inline]
fn motion<S: Scalar>(
    p: &Patch,
    lever_gradient: [f64; 3],
    shift: [S; 3],
    velocity: [S; 3],
    torque: S,
) -> PatchMotion<S> {
    let normal = v3::<S>(p.normal);
    let along = dot(v3::<S>(lever_gradient), shift);
    let lever = S::cst(p.lever) + along;
    // R = |G_jH| + Δ for every patch.
    let radius = p.lever + p.deflection;
    PatchMotion {
        deflection: S::cst(p.deflection) - along,
        deflection_rate: -dot(velocity, normal),
        v_t: dot(velocity, v3(p.tangent)),
        v_c: dot(velocity, v3(p.lateral)),
        lever: lever.max(S::cst(MIN_LEVER_FRACTION * radius)),
        torque,
    }
}

/// The normal force on patch `p` of a wheel in state `s` \[N\].
#[inline]
fn patch_normal(tyre: &Tyre, s: &WheelState, p: &Patch) -> f64 {
    normal_force(tyre, &motion(p, p.normal, [0.0; 3], s.velocity, 0.0))
}

/// What one patch does to its wheel, reduced to the centre G_j.
struct PatchLoad<S> {
    /// The patch's resultant force F_n·n + (F_d + F_rr)·t + F_c*·c \[N\].
    force: [S; 3],
    /// Its moment about G_j, less the component along the spin axis [N·m].
    moment: [S; 3],
    /// The motor torque that drives the pull, |G_jH|·F_d [N·m].
    motor: S,
    /// The law's forces.
    forces: PatchForces<S>,
    /// The ground's longitudinal force F_d + F_rr \[N\].
    along: S,
}

/// [`PatchLoad`] of patch `p` under the torque `share`, for a centre
/// displaced by `shift` and moving at `velocity` (see [`motion`]); the arm
/// from G_j to H is `(H − G_j)₀ − (g·shift)·n`, the measured arm when
/// `shift = 0`.
#[allow(clippy::too_many_arguments)]
#[inline]
fn patch_load<L: WheelLaw, S: Scalar + PartialOrd>(
    law: &L,
    tyre: &Tyre,
    s: &WheelState,
    p: &Patch,
    lever_gradient: [f64; 3],
    shift: [S; 3],
    velocity: [S; 3],
    share: S,
) -> PatchLoad<S> {
    let m = motion(p, lever_gradient, shift, velocity, share);
    let forces = law.forces(tyre, &m);
    // The ground's longitudinal force: the pull plus the rolling resistance
    // (exactly 0 without it).
    let along = forces.drawbar + rolling_resistance(tyre, &m, forces.normal);
    let (n, t, c) = (v3::<S>(p.normal), v3::<S>(p.tangent), v3::<S>(p.lateral));
    let force = [0, 1, 2].map(|k| forces.normal * n[k] + along * t[k] + forces.lateral * c[k]);
    let moved = dot(v3::<S>(lever_gradient), shift);
    let arm = [0, 1, 2].map(|k| S::cst(p.point[k] - s.centre[k]) - moved * n[k]);
    let moment = cross(arm, force);
    let axis = v3::<S>(s.spin_axis);
    let axial = dot(moment, axis);
    PatchLoad {
        force,
        moment: [0, 1, 2].map(|k| moment[k] - axial * axis[k]),
        motor: m.lever * forces.drawbar,
        forces,
        along,
    }
}

/// Reduce the forces on a wheel's patches to its centre (MODEL.md §7):
/// ```text
/// F = Σ (F_n·n + F_d·t + F_c*·c)                         at G_j
/// μ = Σ (H − G_j) × F_patch,  less its component along a_w   on the carrier
/// τ_stator = −τ_eff·a_w,  τ_eff = Σ |G_jH|·F_d              on the stator
/// ```
/// The drive torque is shared among patches in proportion to their normal forces.
#[inline]
pub fn wheel_load<L: WheelLaw>(
    law: &L,
    tyre: &Tyre,
    s: &WheelState,
    contact: &Contact,
    torque: f64,
) -> (WheelLoad, WheelReport) {
    let mut load = WheelLoad::default();
    let mut report = WheelReport {
        point: s.centre,
        patches: contact.count,
        deep: contact.deep,
        ..Default::default()
    };
    let patches = contact.patches();
    let (normals, total) = patch_normals(tyre, s, patches);
    let mut strongest = 0.0;
    for (i, p) in patches.iter().enumerate() {
        let share = torque_share(torque, &normals, total, i);
        let pl = patch_load(law, tyre, s, p, p.normal, [0.0; 3], s.velocity, share);
        for k in 0..3 {
            load.force[k] += pl.force[k];
            load.moment[k] += pl.moment[k];
            load.stator_torque[k] -= pl.motor * s.spin_axis[k];
        }
        report.normal += pl.forces.normal;
        report.drawbar += pl.along;
        report.lateral += pl.forces.lateral;
        report.torque += pl.motor;
        if pl.forces.normal > strongest || i == 0 {
            strongest = pl.forces.normal;
            report.point = p.point;
        }
    }
    (load, report)
}

/// Each patch's normal force (0 past the last) and their sum: what the
/// drive torque is shared by.
#[inline]
fn patch_normals(tyre: &Tyre, s: &WheelState, patches: &[Patch]) -> ([f64; MAX_PATCHES], f64) {
    let normals: [f64; MAX_PATCHES] =
        core::array::from_fn(|i| patches.get(i).map_or(0.0, |p| patch_normal(tyre, s, p)));
    (normals, normals.iter().sum())
}

/// Patch i's part of the drive torque, in proportion to its normal force.
#[inline]
fn torque_share(torque: f64, normals: &[f64; MAX_PATCHES], total: f64, i: usize) -> f64 {
    if total > 0.0 {
        torque * normals.get(i).copied().unwrap_or(0.0) / total
    } else {
        0.0
    }
}

/// How a wheel's load changes with its centre, velocity, drive torque and
/// spin: `∂(L, T)/∂(G_j, V_j, τ, ω)`, rows the load's force, moment and
/// stator torque (3 each, as in [`WheelLoad`]) and the soil's torque
/// against the spin (1), columns the centre's displacement (3), its
/// velocity (3), the torque (1) and the spin (1). On rigid ground the last
/// row and column are 0 (the wheel's rotation is massless there).
pub type LoadDerivative = [[f64; 8]; 10];

/// The centre's shift (0) and velocity as dual numbers, seeded for column
/// `col` of a [`LoadDerivative`] (0–2 the shift, 3–5 the velocity; any
/// other column leaves both constant).
pub(crate) fn seeded(col: usize, s: &WheelState) -> ([Dual<f64>; 3], [Dual<f64>; 3]) {
    let seed = |j: usize| if col == j { 1.0 } else { 0.0 };
    let shift = [0, 1, 2].map(|k| Dual {
        re: 0.0,
        eps: seed(k),
    });
    let velocity = [0, 1, 2].map(|k| Dual {
        re: s.velocity[k],
        eps: seed(3 + k),
    });
    (shift, velocity)
}

/// [`LoadDerivative`] of one wheel at the patches of its last contact, by
/// dual numbers through the very `patch_load` the run evaluates, each
/// patch's lever moving with the centre as `lever_gradient` says. The
/// patches' frames (n, t, c) are held: what this keeps is the stiff part of
/// the load — the tyre's spring and damper (k_w, c_w), the cornering law's
/// lateral damping and the rolling resistance along the velocity, the pull's
/// dependence on the torque and lever — and what it leaves out turns with
/// the geometry (terms of order F/R, against k_w). The torque split between
/// patches is held too.
pub fn load_derivative<L: WheelLaw, H: HeightField + ?Sized>(
    law: &L,
    tyre: &Tyre,
    terrain: &H,
    s: &WheelState,
    contact: &Contact,
    torque: f64,
) -> LoadDerivative {
    let mut d = [[0.0; 8]; 10];
    let patches = contact.patches();
    let (normals, total) = patch_normals(tyre, s, patches);
    for (i, p) in patches.iter().enumerate() {
        let share = torque_share(torque, &normals, total, i);
        let share_rate = if total > 0.0 {
            normals.get(i).copied().unwrap_or(0.0) / total
        } else {
            0.0
        };
        let gradient = lever_gradient(terrain, s, p);
        for col in 0..7 {
            let (shift, velocity) = seeded(col, s);
            let torque = Dual {
                re: share,
                eps: if col == 6 { share_rate } else { 0.0 },
            };
            let pl = patch_load(law, tyre, s, p, gradient, shift, velocity, torque);
            for k in 0..3 {
                d[k][col] += pl.force[k].eps;
                d[3 + k][col] += pl.moment[k].eps;
                d[6 + k][col] -= pl.motor.eps * s.spin_axis[k];
            }
        }
    }
    d
}
