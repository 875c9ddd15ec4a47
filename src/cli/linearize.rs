//! `rover linearize <rover> [--out file.json] [--generic]`: the parked
//! rover's small motions about its static equilibrium on flat ground.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;
use rover_scenario::linearize::{Linearization, Mode, ModeKind, OperatingPoint, linearize_at};
use rover_scenario::scenario::Scenario;

use rover_scenario::output::write_whole;
use rover_scenario::prepare::{RunPlant, load_rover};

use crate::error::CliError;

/// Arguments of `rover linearize`.
#[derive(Debug, Args)]
// A negative number is a value (`--load -5` is then refused as a load, not
// taken for an unknown flag).
#[command(allow_negative_numbers = true)]
pub struct LinearizeArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file.
    pub rover: String,
    /// Also write the state matrix, the input matrix (spring neutrals, motor
    /// torques, steering angles), the equilibrium and every mode (with its
    /// shape) as JSON to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Use the generic plant even for a built-in rover.
    #[arg(long)]
    pub generic: bool,
    /// Take the contact search, wheel law, rolling resistance, the
    /// controllers (speed loop, heading hold) and the fidelity level from
    /// this scenario (its terrain and initial state are not used: the
    /// ground is flat).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Forward speed of the straight, steady drive to linearize about [m/s]
    /// (0: parked); a scenario's speed loop holds it.
    #[arg(long, default_value_t = 0.0)]
    pub speed: f64,
}

/// Linearize the rover, write the JSON if asked, and return the report
/// `rover linearize` prints.
pub fn linearize_cmd(args: &LinearizeArgs) -> Result<String, CliError> {
    if let Some(out) = &args.out {
        let mut inputs = vec![Path::new(&args.rover)];
        inputs.extend(args.scenario.as_deref());
        CliError::check_output_file("--out", out, &inputs)?;
    }
    let spec = load_rover(&args.rover, None)?;
    let model = &spec.model;
    let mut point = OperatingPoint {
        speed: args.speed,
        ..Default::default()
    };
    let mut level = rover_dynamics::fidelity::Fidelity::Full;
    if let Some(path) = &args.scenario {
        let scenario = Scenario::load(path)?;
        point.contact = scenario.contact;
        point.control = scenario.control;
        level = scenario.fidelity.dynamic().ok_or_else(|| {
            CliError::Usage(format!(
                "{}: fidelity = \"quasi_static\" has no dynamics to linearize; use full, simplified or linearized",
                path.display()
            ))
        })?;
    }
    let plant = RunPlant::new(&args.rover, model, level, args.generic)?;
    let backend = match (&plant, level) {
        (RunPlant::Generated(p), _) => format!("generated plant {}", p.name()),
        (RunPlant::Generic(_), rover_dynamics::fidelity::Fidelity::Full) => {
            "generic plant".to_string()
        }
        (RunPlant::Generic(_), other) => format!("generic plant, {} level", other.name()),
    };
    let lin = linearize_at(model, plant, &point).map_err(|source| CliError::Linearize {
        rover: spec.name.clone(),
        source,
    })?;
    if let Some(path) = &args.out {
        #[derive(serde::Serialize)]
        struct Output<'a> {
            rover: &'a str,
            plant: &'a str,
            #[serde(flatten)]
            linearization: &'a Linearization,
        }
        let json = serde_json::to_string_pretty(&Output {
            rover: &spec.name,
            plant: &backend,
            linearization: &lin,
        })
        .map_err(|e| CliError::io(path, "write the linearization as JSON", e.into()))?;
        write_whole(path, &(json + "\n"))?;
    }
    Ok(report(&spec.name, &backend, &lin, &point))
}

/// The printed table.
fn report(rover: &str, backend: &str, lin: &Linearization, point: &OperatingPoint) -> String {
    let n = lin.equilibrium.len();
    let mut s = String::new();
    let yaw_rate = lin.state[n + 5];
    let what = if yaw_rate.abs() > 1e-9 {
        let ground_speed = lin.state[n].hypot(lin.state[n + 1]);
        format!(
            "turning at {} m/s on flat ground (yaw rate {yaw_rate:.4} rad/s, G on a circle of radius {:.3} m)",
            point.speed,
            ground_speed / yaw_rate.abs()
        )
    } else if point.speed != 0.0 {
        format!("driving straight at {} m/s on flat ground", point.speed)
    } else {
        "parked on flat ground".to_string()
    };
    let loop_ = if point.control.speed.is_some()
        || point.control.steering != rover_runtime::control::Steering::None
    {
        "with its scenario's controllers in the loop"
    } else {
        "motors off"
    };
    let _ = writeln!(
        s,
        "{rover} {what}, {loop_}: small motions about its steady state"
    );
    let pose: Vec<String> = lin.states[2..n]
        .iter()
        .zip(&lin.equilibrium[2..])
        .map(|(name, v)| format!("{name} = {v:.4}"))
        .collect();
    let _ = writeln!(
        s,
        "  steady state (m, rad): {}; its rates ≤ {:.1e} (the quasi-static pose refined by {:.1e})",
        pose.join(", "),
        lin.residual,
        lin.refinement
    );
    let dim = lin.states.len();
    let integrals = if dim > 2 * n {
        format!(", {}", lin.states[2 * n..].join(", "))
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        "  A = ∂(ẋ, ẇ{integrals})/∂(x, w{integrals}), {dim} × {dim}, by central differences of the whole right-hand side ({backend} + contact)",
    );
    let in_loop = loop_ != "motors off";
    let of = |kind| lin.modes.iter().filter(move |m: &&Mode| m.kind == kind);
    if of(ModeKind::Oscillatory).next().is_some() {
        let _ = writeln!(
            s,
            "\noscillatory modes\n  {:>9}  {:>9}  {:>7}  kinetic energy",
            "f_n [Hz]", "f_d [Hz]", "damping"
        );
        for m in of(ModeKind::Oscillatory) {
            let _ = writeln!(
                s,
                "  {:>9.3}  {:>9.3}  {:>7.3}  {}{}",
                m.natural_hz,
                m.damped_hz,
                m.damping_ratio,
                shares(m),
                if m.damping_ratio < 0.0 {
                    "  (grows: an unstable oscillation)"
                } else {
                    ""
                }
            );
        }
    }
    if of(ModeKind::Real).next().is_some() {
        let _ = writeln!(
            s,
            "\nreal modes (no oscillation)\n  {:>11}  {:>10}  kinetic energy",
            "λ [1/s]", "τ [ms]"
        );
        for m in of(ModeKind::Real) {
            let _ = writeln!(
                s,
                "  {:>11.4}  {:>10.3}  {}{}",
                m.eigenvalue[0],
                1e3 * m.time_constant,
                shares(m),
                match (m.eigenvalue[0] > 0.0, in_loop) {
                    (false, _) => "",
                    (true, false) => "  (grows: the rover falls over)",
                    (true, true) => "  (grows: the rover falls over, or a loop is unstable)",
                }
            );
        }
    }
    let _ = writeln!(
        s,
        "\nneutral: {} (no restoring force: on flat ground X, Y and heading{})",
        of(ModeKind::Neutral).count(),
        if point.contact.rolling_resistance == 0.0 {
            "; and rolling: no rolling resistance (`[contact] rolling_resistance` in a --scenario adds one)"
        } else {
            ""
        }
    );
    s
}

/// `vz 95%, Oy 3%` for a mode's dominant pseudo-velocities.
fn shares(m: &Mode) -> String {
    m.dominant
        .iter()
        .map(|(name, share)| format!("{name} {:.0}%", 100.0 * share))
        .collect::<Vec<_>>()
        .join(", ")
}
