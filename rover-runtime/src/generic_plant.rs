//! The generic back end: the equations of `rover-dynamics` run with `f64` on
//! a model read at run time, so that any rover runs without a build. The
//! other back end, a plant generated from the same description
//! (`rover-codegen`), is faster; the tests hold the two equal.

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::eom::derivatives;
use rover_dynamics::fidelity::{Fidelity, Frozen, linear_wheel_kinematics, reduced_derivatives};
use rover_dynamics::forces::Load;
use rover_dynamics::kinematics::{body_kinematics, wheel_kinematics};
use rover_dynamics::mass::{MAX_DOF, mass_matrix};
use rover_dynamics::plant::{MIN_COS_ROLL, Plant, PlantError, WheelLoad, WheelState};
use rover_dynamics::workspace::Workspace;

/// A plant that interprets a [`Model`]: any rover, no recompilation. Sized
/// once in [`GenericPlant::new`]; no call allocates.
#[derive(Clone, Debug)]
pub struct GenericPlant {
    model: Model,
    ws: Workspace<f64>,
    neutral: Vec<f64>,
    loads: Vec<Load<f64>>,
    level: Fidelity,
    frozen: Option<Frozen<f64>>,
}

/// The model is larger than the dense buffers support.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("the rover has {dof} degrees of freedom; at most {max} are supported")]
pub struct TooLarge {
    /// 6 + m of the model.
    pub dof: usize,
    /// The limit.
    pub max: usize,
}

impl GenericPlant {
    /// A plant for `model`.
    pub fn new(model: Model) -> Result<Self, TooLarge> {
        if model.dof() > MAX_DOF {
            return Err(TooLarge {
                dof: model.dof(),
                max: MAX_DOF,
            });
        }
        let ws = Workspace::new(&model);
        let neutral = model.coordinates.iter().map(|c| c.neutral).collect();
        let zero = Load {
            force: [0.0; 3],
            moment: [0.0; 3],
            stator_torque: [0.0; 3],
        };
        let loads = vec![zero; model.wheels.len()];
        Ok(Self {
            model,
            ws,
            neutral,
            loads,
            level: Fidelity::Full,
            frozen: None,
        })
    }

    /// A plant for `model` at a fidelity level (MODEL.md §9), reduced
    /// levels frozen at the rest values y_c.
    pub fn with_fidelity(model: Model, level: Fidelity) -> Result<Self, TooLarge> {
        let rest = model.rest();
        Self::with_fidelity_at(model, level, &rest)
    }

    /// The fidelity level it computes.
    pub fn level(&self) -> Fidelity {
        self.level
    }

    /// As [`GenericPlant::with_fidelity`], reduced levels frozen at `y_ref`.
    pub fn with_fidelity_at(
        model: Model,
        level: Fidelity,
        y_ref: &[f64],
    ) -> Result<Self, TooLarge> {
        let mut p = Self::new(model)?;
        p.level = level;
        if level != Fidelity::Full {
            p.frozen = Some(Frozen::at(&p.model, y_ref));
        }
        Ok(p)
    }

    /// The fidelity level.
    pub fn fidelity(&self) -> Fidelity {
        self.level
    }

    /// The model this plant runs.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The current spring neutrals y_0.
    pub fn spring_neutrals(&self) -> &[f64] {
        &self.neutral
    }
}

impl Plant for GenericPlant {
    fn name(&self) -> &'static str {
        match self.level {
            Fidelity::Full => "generic",
            Fidelity::Simplified => "generic (simplified level)",
            Fidelity::Linearized => "generic (linearized level)",
            Fidelity::LinearizedExactRotation => "generic (linearized level, exact rotation)",
        }
    }

    fn dof(&self) -> usize {
        self.model.dof()
    }

    fn wheel_count(&self) -> usize {
        self.model.wheels.len()
    }

    fn wheels(&mut self, x: &[f64], w: &[f64], steer: &[f64], out: &mut [WheelState]) {
        if let (true, Some(frozen)) = (self.level.is_linearized(), &self.frozen) {
            for (k, o) in out.iter_mut().enumerate() {
                let steer_k = steer.get(k).copied().unwrap_or(0.0);
                let wk = linear_wheel_kinematics(&self.model, self.level, frozen, x, w, k, steer_k);
                *o = WheelState {
                    centre: wk.centre,
                    velocity: wk.velocity,
                    spin_axis: wk.spin_axis,
                };
            }
            return;
        }
        let ws = &mut self.ws;
        body_kinematics(&self.model, &x[6..], ws);
        let att = Attitude::new(x[3], x[4], x[5]);
        for (k, o) in out.iter_mut().enumerate() {
            let wk = wheel_kinematics(
                &self.model,
                ws,
                &att,
                x,
                w,
                k,
                steer.get(k).copied().unwrap_or(0.0),
            );
            *o = WheelState {
                centre: wk.centre,
                velocity: wk.velocity,
                spin_axis: wk.spin_axis,
            };
        }
    }

    fn derivatives(
        &mut self,
        x: &[f64],
        w: &[f64],
        loads: &[WheelLoad],
        xdot: &mut [f64],
        wdot: &mut [f64],
    ) -> Result<(), PlantError> {
        if x[3].cos().abs() < MIN_COS_ROLL {
            return Err(PlantError::AttitudeSingular { roll: x[3] });
        }
        for (l, src) in self.loads.iter_mut().zip(loads) {
            *l = Load {
                force: src.force,
                moment: src.moment,
                stator_torque: src.stator_torque,
            };
        }
        if let Some(frozen) = &mut self.frozen {
            let (model, neutral, loads) = (&self.model, &self.neutral, &self.loads);
            reduced_derivatives(model, self.level, frozen, neutral, x, w, loads, xdot, wdot);
            return Ok(());
        }
        derivatives(
            &self.model,
            &mut self.ws,
            &self.neutral,
            x,
            w,
            &self.loads,
            xdot,
            wdot,
        );
        let n = self.ws.dof;
        for row in 0..n {
            let pivot = self.ws.mass[row * n + row];
            if pivot.is_nan() || pivot <= 0.0 {
                return Err(PlantError::SingularMass { row, pivot });
            }
        }
        Ok(())
    }

    fn mass_matrix(&mut self, x: &[f64], out: &mut [f64]) {
        if let Some(frozen) = &self.frozen {
            out.copy_from_slice(&frozen.ws.mass);
            return;
        }
        body_kinematics(&self.model, &x[6..], &mut self.ws);
        mass_matrix(&self.model, &mut self.ws);
        out.copy_from_slice(&self.ws.mass);
    }

    fn set_spring_neutral(&mut self, coord: usize, neutral: f64) {
        if let Some(n) = self.neutral.get_mut(coord) {
            *n = neutral;
        }
    }
}
