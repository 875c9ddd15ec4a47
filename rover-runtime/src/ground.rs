//! The ground acting on the wheels: contact geometry, force law and the
//! reduction of the patch forces to loads on the plant (MODEL.md §6–§7).

use rover_dynamics::Model;
use rover_dynamics::plant::{WheelLoad, WheelState};
use serde::{Deserialize, Serialize};

use crate::contact::{
    BoundedContact, Contact, MeridionalContact, RimSampling, SearchMemory, TrackedContact,
};
use crate::contact::{cross, dot};
use crate::terrain::{HeightField, OffMap};
use crate::wheel_law::{PatchMotion, Tyre, WheelLaw, WheelLawConfig};

/// Which contact search the run uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
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
    /// Torque the ground took from the motor, Σ |G_jH|·F_d [N·m].
    pub torque: f64,
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

/// Terrain, contact search and wheel law, with the per-wheel tracking state.
#[derive(Clone, Debug)]
pub struct Ground<H> {
    /// The terrain.
    pub terrain: H,
    /// The force law.
    pub law: WheelLawConfig,
    method: ContactMethod,
    meridional: MeridionalContact,
    trackers: Vec<TrackedContact>,
    /// The terrain's bounds under each wheel, for the bounded search.
    bounds: Vec<SearchMemory>,
    contacts: Vec<Contact>,
    tyres: Vec<Tyre>,
    radii: Vec<f64>,
}

impl<H: HeightField> Ground<H> {
    /// Ground for the wheels of `model`.
    pub fn new(
        terrain: H,
        model: &Model,
        method: ContactMethod,
        sampling: RimSampling,
        law: WheelLawConfig,
    ) -> Self {
        let meridional = MeridionalContact { sampling };
        let tyres = model
            .wheels
            .iter()
            .map(|w| Tyre {
                stiffness: w.stiffness,
                damping: w.damping,
                mu_x: w.mu_x,
                mu_y: w.mu_y,
                cornering_stiffness: w.cornering_stiffness,
                rolling_resistance: 0.0,
            })
            .collect();
        Self {
            terrain,
            law,
            method,
            meridional,
            trackers: vec![TrackedContact::new(meridional); model.wheels.len()],
            bounds: vec![SearchMemory::default(); model.wheels.len()],
            contacts: vec![Contact::default(); model.wheels.len()],
            tyres,
            radii: model.wheels.iter().map(|w| w.radius).collect(),
        }
    }

    /// The same ground with rolling-resistance coefficient `c_rr` on every
    /// wheel ([`crate::wheel_law::rolling_resistance`]; 0 by default).
    pub fn with_rolling_resistance(mut self, c_rr: f64) -> Self {
        for t in &mut self.tyres {
            t.rolling_resistance = c_rr;
        }
        self
    }

    /// Contact of wheel k in state `s`.
    pub fn contact(&mut self, k: usize, s: &WheelState) -> Result<Contact, OffMap> {
        let mut c = Contact::default();
        self.contact_into(k, s, &mut c)?;
        Ok(c)
    }

    /// [`Ground::contact`] written into `out`: a contact is a few hundred
    /// bytes, not worth returning by value on every right-hand side.
    fn contact_into(&mut self, k: usize, s: &WheelState, out: &mut Contact) -> Result<(), OffMap> {
        let (terrain, radius) = (&self.terrain, self.radii[k]);
        match self.method {
            ContactMethod::Meridional => {
                self.meridional
                    .find_into(terrain, s.centre, s.spin_axis, radius, out)
            }
            ContactMethod::Tracked => {
                self.trackers[k].find_into(terrain, s.centre, s.spin_axis, radius, out)
            }
            ContactMethod::Bounded => BoundedContact {
                fallback: self.meridional,
            }
            .find_with(
                terrain,
                s.centre,
                s.spin_axis,
                radius,
                &mut self.bounds[k],
                out,
            ),
        }
    }

    /// Find every wheel's contact (phase 1 of a right-hand side): the
    /// patches, and each wheel's total normal force into `normals` (the
    /// normal force does not depend on the drive torque, so a torque
    /// distribution by measured load can use it before phase 2).
    pub fn find_contacts(
        &mut self,
        states: &[WheelState],
        normals: &mut [f64],
    ) -> Result<(), WheelOffMap> {
        // Out of `self` for the loop (a move of the Vec, not of its items),
        // so that each contact is written in place.
        let mut contacts = std::mem::take(&mut self.contacts);
        let found = states.iter().enumerate().try_for_each(|(k, s)| {
            self.contact_into(k, s, &mut contacts[k])
                .map_err(|off| WheelOffMap { wheel: k, off })?;
            normals[k] = contacts[k]
                .patches()
                .iter()
                .map(|p| normal_force(&self.tyres[k], s, p))
                .sum();
            Ok(())
        });
        self.contacts = contacts;
        found
    }

    /// Loads on every wheel from the contacts of [`Ground::find_contacts`]
    /// and the motor torques (N·m, positive drives forward), with reports
    /// (phase 2).
    pub fn loads(
        &self,
        states: &[WheelState],
        torques: &[f64],
        loads: &mut [WheelLoad],
        reports: &mut [WheelReport],
    ) {
        for k in 0..states.len() {
            let (load, report) = wheel_load(
                &self.law,
                &self.tyres[k],
                &states[k],
                &self.contacts[k],
                torques[k],
            );
            loads[k] = load;
            reports[k] = report;
        }
    }
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

fn motion(s: &WheelState, p: &crate::contact::Patch, torque: f64) -> PatchMotion {
    // R = |G_jH| + Δ for every patch.
    let radius = p.lever + p.deflection;
    PatchMotion {
        deflection: p.deflection,
        deflection_rate: -dot(s.velocity, p.normal),
        v_t: dot(s.velocity, p.tangent),
        v_c: dot(s.velocity, p.lateral),
        lever: p.lever.max(MIN_LEVER_FRACTION * radius),
        torque,
    }
}

fn normal_force(tyre: &Tyre, s: &WheelState, p: &crate::contact::Patch) -> f64 {
    crate::wheel_law::normal_force_of(tyre, &motion(s, p, 0.0))
}

/// Reduce the forces on a wheel's patches to its centre (MODEL.md §7):
/// ```text
/// F = Σ (F_n·n + F_d·t + F_c*·c)                         at G_j
/// μ = Σ (H − G_j) × F_patch,  less its component along a_w   on the carrier
/// τ_stator = −τ_eff·a_w,  τ_eff = Σ |G_jH|·F_d              on the stator
/// ```
/// The drive torque is shared among patches in proportion to their normal forces.
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
    let normals: [f64; crate::contact::MAX_PATCHES] =
        core::array::from_fn(|i| patches.get(i).map_or(0.0, |p| normal_force(tyre, s, p)));
    let total: f64 = normals.iter().sum();
    let mut strongest = 0.0;
    for (i, p) in patches.iter().enumerate() {
        let share = if total > 0.0 {
            torque * normals[i] / total
        } else {
            0.0
        };
        let patch_motion = motion(s, p, share);
        let f = law.forces(tyre, &patch_motion);
        // The ground's longitudinal force: the pull, less the rolling
        // resistance (exactly the pull without it, bit for bit).
        let rolling = crate::wheel_law::rolling_resistance(tyre, &patch_motion, f.normal);
        let along = if rolling != 0.0 {
            f.drawbar + rolling
        } else {
            f.drawbar
        };
        let force = [0, 1, 2]
            .map(|k| f.normal * p.normal[k] + along * p.tangent[k] + f.lateral * p.lateral[k]);
        let arm = [0, 1, 2].map(|k| p.point[k] - s.centre[k]);
        let m = cross(arm, force);
        let axial = dot(m, s.spin_axis);
        // The motor's reaction: the torque that drives the pull.
        let tau = patch_motion.lever * f.drawbar;
        for k in 0..3 {
            load.force[k] += force[k];
            load.moment[k] += m[k] - axial * s.spin_axis[k];
            load.stator_torque[k] -= tau * s.spin_axis[k];
        }
        report.normal += f.normal;
        report.drawbar += along;
        report.lateral += f.lateral;
        report.torque += tau;
        if f.normal > strongest || i == 0 {
            strongest = f.normal;
            report.point = p.point;
        }
    }
    (load, report)
}
