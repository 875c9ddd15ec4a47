//! A scenario's rover as a state estimator's process model: the same
//! plant, ground and contact as the run that made the sensor log, on the
//! map the estimator carries, with no controller loops (the commands the
//! rover's computer issued are the filter's inputs).

use std::path::Path;

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_integrate::OdeSystem;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;

use crate::scenario::Scenario;
use crate::simulate::{SetupError, ground_of, initial_state, settle_into_soil};

/// The terrain map an estimator carries.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum EstimateMap {
    /// The scenario's own terrain: the truth's.
    #[default]
    True,
    /// The scenario's terrain with features shorter than `cutoff` \[m\]
    /// removed, as an orbital map would give it
    /// ([`Terrain::smoothed`]).
    Smoothed {
        /// The shortest wavelength kept \[m\].
        cutoff: f64,
    },
}

/// The rover of `scenario` as the filter's process model, on `map`, and
/// the run's initial state `[x; w; ζ; ω]` (computed on the true terrain:
/// the rover knows where it starts). The controller has no loops: the
/// filter sets the torques and steering it read from the log.
pub fn process_system<P: Plant>(
    plant: P,
    model: &Model,
    scenario: &Scenario,
    base_dir: &Path,
    map: EstimateMap,
) -> Result<(RoverSystem<P, Terrain>, Vec<f64>), SetupError> {
    if scenario.free_flight {
        return Err(SetupError::Initial {
            field: "free_flight",
            message: "a rover in free flight has no ground for the estimator's model; estimate a run on a terrain".into(),
        });
    }
    let truth = scenario.terrain.build(base_dir)?;
    let mut y = initial_state(model, scenario, Some(&truth))?;
    let carried = match map {
        EstimateMap::True => truth,
        EstimateMap::Smoothed { cutoff } => truth.smoothed(cutoff)?,
    };
    let ground = ground_of(scenario, carried, model, base_dir)?;
    settle_into_soil(&ground, model, scenario, &mut y);
    let control = Controller::new_in(
        ControllerConfig::default(),
        model,
        scenario.settle,
        base_dir,
    )?;
    let mut sys = RoverSystem::new(plant, Some(ground), control);
    y.resize(sys.dim(), 0.0);
    sys.roll_spins(0.0, &mut y);
    Ok((sys, y))
}
