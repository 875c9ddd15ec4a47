//! The ground acting on the wheels: contact geometry, force law and the
//! reduction of the patch forces to loads on the plant (MODEL.md §6–§7),
//! for any number of wheels. Each wheel's work is
//! [`rover_dynamics::wheel_ground`]'s, the very code a generated plant's
//! force path runs.

use rover_dynamics::Model;
use rover_dynamics::contact::{Contact, RimSampling};
use rover_dynamics::height_field::{HeightField, OffMap};
use rover_dynamics::plant::{WheelLoad, WheelState};
use rover_dynamics::soil::{Soil, SoilWheel};
use rover_dynamics::wheel_ground::{
    ContactMethod, LoadDerivative, Search, WheelContact, WheelOffMap, WheelReport, find_contacts,
    wheel_loads,
};
use rover_dynamics::wheel_law::Tyre;
use rover_dynamics::wheel_soil::{
    RunRule, SoilTyre, SoilUnder, soil_load_derivative, soil_wheel_load, spin_rates, wheel_slip,
};

use crate::ruts::Ruts;
use crate::wheel_law::WheelLawConfig;
use rover_terrain::SoilMap;
use rover_terrain::soil_map::SoilWeights;

/// The soils under the wheels: each wheel's constants in each soil, where
/// each soil lies, the quadrature and the wheels' spin inertias (their
/// spins are states of the run).
#[derive(Clone, Debug)]
struct SoilGround {
    /// The soils, by class.
    soils: Vec<Soil>,
    /// `tyres[class][wheel]`.
    tyres: Vec<Vec<SoilTyre>>,
    /// Where each class lies.
    map: SoilMap,
    rule: RunRule,
    inertias: Vec<f64>,
    /// The wheels' ruts, when the ground keeps them.
    ruts: Option<Ruts>,
}

impl SoilGround {
    /// The soil under a wheel at `contact`, read where its deepest patch
    /// lies: what earlier passes left there, and which soils lie there
    /// (in the air, fresh soil and the soils under its centre, where no
    /// soil acts).
    fn under(&self, contact: &Contact, centre: [f64; 3]) -> (SoilUnder, SoilWeights) {
        let patch = deepest_patch(contact);
        let under = match (patch, &self.ruts) {
            (Some(p), Some(ruts)) => ruts.under(p.point),
            _ => SoilUnder::default(),
        };
        let at = patch.map_or(centre, |p| p.point);
        (under, self.map.weights(at[0], at[1]))
    }

    /// The load on wheel `k` and its report: each soil's at the wheel's
    /// contact, weighted as the map says (continuous across a soil's
    /// edge; one soil's own where only one lies).
    fn load(
        &self,
        k: usize,
        (s, contact): (&WheelState, &Contact),
        torque: f64,
        spin: f64,
    ) -> (WheelLoad, WheelReport) {
        let (under, weights) = self.under(contact, s.centre);
        let one = |class: u16| {
            let tyre = &self.tyres[usize::from(class)][k];
            soil_wheel_load(tyre, &self.rule, (s, &under), contact, torque, spin)
        };
        if weights.count == 1 {
            return one(weights.classes[0]);
        }
        let mut load = WheelLoad::default();
        let mut report = WheelReport::default();
        for (i, (class, w)) in weights.iter().enumerate() {
            let (l, r) = one(class);
            for j in 0..3 {
                load.force[j] += w * l.force[j];
                load.moment[j] += w * l.moment[j];
                load.stator_torque[j] += w * l.stator_torque[j];
            }
            report.normal += w * r.normal;
            report.drawbar += w * r.drawbar;
            report.lateral += w * r.lateral;
            report.torque += w * r.torque;
            report.slip += w * r.slip;
            report.slip_angle += w * r.slip_angle;
            report.sinkage += w * r.sinkage;
            if i == 0 {
                (report.point, report.patches, report.deep, report.rut) =
                    (r.point, r.patches, r.deep, r.rut);
            }
        }
        (load, report)
    }

    /// The rut a press to past sinkage `z` \[m\] by wheel `k` at `at`
    /// leaves: the law of the soil that weighs most there.
    fn rut_depth(&self, k: usize, at: [f64; 2], z: f64) -> f64 {
        let weights = self.map.weights(at[0], at[1]);
        let main = weights
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |(class, _)| class);
        self.tyres[usize::from(main)][k].wheel.rut_depth(z)
    }
}

/// The patch of `contact` that reaches deepest, if any.
pub(crate) fn deepest_patch(contact: &Contact) -> Option<&rover_dynamics::contact::Patch> {
    contact
        .patches()
        .iter()
        .max_by(|a, b| a.deflection.total_cmp(&b.deflection))
}

/// A wheel the soil law cannot take.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SoilWheelError {
    /// The description gives the wheel no width.
    #[error("wheel {} has no width: the soil law presses on the wheel's width", .wheel + 1)]
    NoWidth {
        /// Wheel index (0-based).
        wheel: usize,
    },
    /// The wheel's spin has no inertia (a massless wheel without `spin_inertia`).
    #[error("wheel {} has no spin inertia (a massless wheel): on a soil the wheel's spin is a state", .wheel + 1)]
    NoSpinInertia {
        /// Wheel index (0-based).
        wheel: usize,
    },
}

impl SoilWheelError {
    /// The description field to add.
    pub fn field(&self) -> &'static str {
        match self {
            SoilWheelError::NoWidth { .. } => "width",
            SoilWheelError::NoSpinInertia { .. } => "spin_inertia",
        }
    }

    /// The wheel (0-based).
    pub fn wheel(&self) -> usize {
        match self {
            SoilWheelError::NoWidth { wheel } | SoilWheelError::NoSpinInertia { wheel } => *wheel,
        }
    }
}

/// Terrain, contact search and wheel law, with the per-wheel tracking state.
#[derive(Clone, Debug)]
pub struct Ground<H> {
    /// The terrain.
    pub terrain: H,
    /// The force law.
    pub law: WheelLawConfig,
    search: Search,
    wheels: Vec<WheelContact>,
    tyres: Vec<Tyre>,
    radii: Vec<f64>,
    soil: Option<SoilGround>,
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
        let search = Search::new(method, sampling);
        Self {
            terrain,
            law,
            search,
            wheels: vec![WheelContact::new(&search); model.wheels.len()],
            tyres: model.wheels.iter().map(|w| w.tyre()).collect(),
            radii: model.wheels.iter().map(|w| w.radius).collect(),
            soil: None,
        }
    }

    /// The same ground covered by `soil`: each wheel of `model` (which
    /// needs a width and a spin inertia) then follows the soil law
    /// (docs/MODEL.md, "Soft soil") in place of `law`, and spins at its own
    /// rate, a state of the run.
    pub fn with_soil(self, soil: &Soil, model: &Model) -> Result<Self, SoilWheelError> {
        self.with_soils(&[*soil], SoilMap::uniform(0), model)
    }

    /// The same ground covered by several soils, `soils[c]` where `map`
    /// puts class c (docs/SOIL.md, "Soil maps"): each wheel takes the
    /// soils at its contact, their loads weighted by the map's weights.
    /// The map's classes must index `soils` (the scenario's layout
    /// guarantees it).
    pub fn with_soils(
        mut self,
        soils: &[Soil],
        map: SoilMap,
        model: &Model,
    ) -> Result<Self, SoilWheelError> {
        let mut tyres = vec![Vec::with_capacity(model.wheels.len()); soils.len()];
        for (wheel, w) in model.wheels.iter().enumerate() {
            let width = w.width.ok_or(SoilWheelError::NoWidth { wheel })?;
            if w.spin_inertia.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return Err(SoilWheelError::NoSpinInertia { wheel });
            }
            for (class, soil) in soils.iter().enumerate() {
                tyres[class].push(SoilTyre {
                    wheel: SoilWheel::new(soil, w.radius, width),
                    damping: w.damping,
                });
            }
        }
        self.soil = Some(SoilGround {
            soils: soils.to_vec(),
            tyres,
            map,
            rule: RunRule::new(),
            inertias: model.wheels.iter().map(|w| w.spin_inertia).collect(),
            ruts: None,
        });
        Ok(self)
    }

    /// The same soft ground keeping the wheels' ruts in cells of side
    /// `cell` \[m\] (docs/MODEL.md, "Ruts and multipass"): each wheel
    /// presses the soil, and the wheels that come after meet the rut and
    /// the compacted soil it left. Nothing on rigid ground.
    pub fn with_ruts(mut self, cell: f64) -> Self {
        if let Some(soil) = &mut self.soil {
            let widths: Vec<f64> = soil.tyres[0].iter().map(|t| t.wheel.width).collect();
            soil.ruts = Some(Ruts::new(cell, &widths, &self.radii));
        }
        self
    }

    /// The ruts, when the ground keeps them.
    pub fn ruts(&self) -> Option<&Ruts> {
        self.soil.as_ref()?.ruts.as_ref()
    }

    /// The ruts, to reserve tiles ahead.
    pub fn ruts_mut(&mut self) -> Option<&mut Ruts> {
        self.soil.as_mut()?.ruts.as_mut()
    }

    /// After an accepted step: the wheels' presses in the states and
    /// reports of the last evaluation go into the ruts they leave
    /// ([`Ruts::record`]). Nothing without ruts.
    pub fn record_ruts(&mut self, states: &[WheelState], reports: &[WheelReport]) {
        let Some(soil) = &mut self.soil else { return };
        // Out of the soil while the soil's laws say what the presses leave.
        let Some(mut ruts) = soil.ruts.take() else {
            return;
        };
        ruts.record(states, reports, |k, at, z| soil.rut_depth(k, at, z));
        soil.ruts = Some(ruts);
    }

    /// The soil, if the ground is soft: the first of its soils (the
    /// background, on a map that has one).
    pub fn soil(&self) -> Option<&Soil> {
        self.soil.as_ref().map(|s| &s.soils[0])
    }

    /// The soils by class, and where each lies, if the ground is soft.
    pub fn soils(&self) -> Option<(&[Soil], &SoilMap)> {
        self.soil.as_ref().map(|s| (&s.soils[..], &s.map))
    }

    /// How many spin states the ground adds to a run: one per wheel on a
    /// soil, none on rigid ground (the wheels' rotation is massless there).
    pub fn spin_states(&self) -> usize {
        self.soil.as_ref().map_or(0, |s| s.inertias.len())
    }

    /// Each wheel's spin acceleration \[rad/s²\] (on a soil) from the
    /// motor torques and the reports of the last [`Ground::loads`].
    pub fn spin_rates(&self, torques: &[f64], reports: &[WheelReport], out: &mut [f64]) {
        if let Some(soil) = &self.soil {
            spin_rates(torques, reports, &soil.inertias, out);
        }
    }

    /// Whether the wheels have a longitudinal slip: on a soil (each wheel's
    /// spin is a state); the rigid law has none (its tyre rolls).
    pub fn has_slip(&self) -> bool {
        self.soil.is_some()
    }

    /// On a soil, each wheel's longitudinal slip at the contacts of the last
    /// [`Ground::find_contacts`] and the spins `spins` into `out`: the slip
    /// its report will give ([`wheel_slip`]), in [−1, 1], positive driving;
    /// a wheel in the air counts as spinning (1). Zeros on rigid ground.
    /// Allocates nothing.
    pub fn slips(&self, states: &[WheelState], spins: &[f64], out: &mut [f64]) {
        if self.soil.is_none() {
            out.iter_mut().for_each(|o| *o = 0.0);
            return;
        }
        for (k, o) in out.iter_mut().enumerate() {
            *o = self.slip(k, &states[k], spins[k]);
        }
    }

    /// Wheel `k`'s slip of [`Ground::slips`] in state `s`, spinning at
    /// `spin` \[rad/s\], at its last contact (0 on rigid ground).
    pub fn slip(&self, k: usize, s: &WheelState, spin: f64) -> f64 {
        if self.soil.is_none() {
            return 0.0;
        }
        wheel_slip(s, self.wheels[k].contact(), spin, self.radii[k]).unwrap_or(1.0)
    }

    /// On a soil, each wheel's sinkage \[m\] at rest under `loads` \[N\]
    /// (one per wheel): the depth at which the soil's pressure, without
    /// shear, carries the load ([`rover_dynamics::soil::rest_state`]), in
    /// the first soil (the background of a map). Empty on rigid ground; a
    /// load the soil cannot carry gives the wheel's radius.
    pub fn rest_sinkages(&self, loads: &[f64]) -> Vec<f64> {
        let Some(soil) = &self.soil else {
            return Vec::new();
        };
        soil.tyres[0]
            .iter()
            .zip(loads)
            .map(|(tyre, &load)| {
                let r = tyre.wheel.radius;
                rover_dynamics::soil::rest_state(&tyre.wheel, load, &soil.rule)
                    .map_or(r, |(entry_angle, _)| r * (1.0 - entry_angle.cos()))
            })
            .collect()
    }

    /// Each wheel's spin inertia [kg·m²], on a soil.
    pub fn spin_inertias(&self) -> &[f64] {
        self.soil.as_ref().map_or(&[], |s| &s.inertias)
    }

    /// The same ground with rolling-resistance coefficient `c_rr` on every
    /// wheel ([`rover_dynamics::wheel_law::rolling_resistance`]; 0 by default).
    pub fn with_rolling_resistance(mut self, c_rr: f64) -> Self {
        for t in &mut self.tyres {
            t.rolling_resistance = c_rr;
        }
        self
    }

    /// Each wheel's radius \[m\].
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Each wheel's tyre.
    pub fn tyres(&self) -> &[Tyre] {
        &self.tyres
    }

    /// The contact search.
    pub fn search(&self) -> Search {
        self.search
    }

    /// Contact of wheel k in state `s`.
    pub fn contact(&mut self, k: usize, s: &WheelState) -> Result<Contact, OffMap> {
        self.wheels[k].find(&self.search, &self.terrain, s, self.radii[k])?;
        Ok(*self.wheels[k].contact())
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
        let ground = (&self.search, &self.terrain);
        let wheels = &mut self.wheels;
        find_contacts(ground, wheels, states, &self.tyres, &self.radii, normals)
    }

    /// Loads on every wheel from the contacts of [`Ground::find_contacts`]
    /// and the motor torques (N·m, positive drives forward), with reports
    /// (phase 2).
    /// On a soil, each wheel spins at `spins` \[rad/s\] (ignored on rigid
    /// ground) and its report's `torque` is the soil's against the spin.
    pub fn loads(
        &self,
        states: &[WheelState],
        torques: &[f64],
        spins: &[f64],
        loads: &mut [WheelLoad],
        reports: &mut [WheelReport],
    ) {
        match &self.soil {
            Some(soil) => {
                for (k, wheel) in self.wheels.iter().enumerate() {
                    let at = (&states[k], wheel.contact());
                    (loads[k], reports[k]) = soil.load(k, at, torques[k], spins[k]);
                }
            }
            None => {
                let wheels = (&self.wheels[..], states, &self.tyres[..]);
                wheel_loads(&self.law, wheels, torques, loads, reports);
            }
        }
    }

    /// Each wheel's [`LoadDerivative`] at the contacts of the last
    /// [`Ground::find_contacts`], the motor torques `torques` and (on a
    /// soil) the spins `spins`.
    pub fn load_derivatives(
        &self,
        states: &[WheelState],
        torques: &[f64],
        spins: &[f64],
        out: &mut [LoadDerivative],
    ) {
        for (k, d) in out.iter_mut().enumerate() {
            *d = match &self.soil {
                Some(soil) => {
                    let contact = self.wheels[k].contact();
                    let (under, weights) = soil.under(contact, states[k].centre);
                    let mut sum = [[0.0; 8]; 10];
                    for (class, w) in weights.iter() {
                        let d = soil_load_derivative(
                            &soil.tyres[usize::from(class)][k],
                            &soil.rule,
                            &self.terrain,
                            (&states[k], &under),
                            contact,
                            spins[k],
                        );
                        for (row, d_row) in sum.iter_mut().zip(&d) {
                            for (s, v) in row.iter_mut().zip(d_row) {
                                *s += w * v;
                            }
                        }
                    }
                    sum
                }
                None => self.wheels[k].load_derivative(
                    &self.law,
                    &self.tyres[k],
                    &self.terrain,
                    &states[k],
                    torques[k],
                ),
            };
        }
    }
}

/// For each wheel of `model`, the height of G at which it just touches the
/// ground, G above `(X, Y)` at `attitude` with suspension coordinates
/// `coordinates` (each wheel's lowest rim point taken straight below its
/// centre: exact for upright wheels over level ground, and where a start
/// or a first solve is placed); the largest is where the lowest wheel
/// touches.
pub fn touchdown_heights<H: HeightField + ?Sized>(
    model: &Model,
    at: [f64; 2],
    attitude: rover_dynamics::attitude::Attitude<f64>,
    coordinates: &[f64],
    terrain: &H,
) -> Result<Vec<f64>, WheelOffMap> {
    let r = attitude.rotation();
    model
        .wheels
        .iter()
        .enumerate()
        .map(|(wheel, w)| {
            let u = model.bodies[w.body].position.value(coordinates);
            let p = [0, 1, 2].map(|k| r[k][0] * u[0] + r[k][1] * u[1] + r[k][2] * u[2]);
            let g = terrain
                .height(at[0] + p[0], at[1] + p[1])
                .map_err(|off| WheelOffMap { wheel, off })?;
            Ok(g + w.radius - p[2])
        })
        .collect()
}
