//! `rover estimate <rover> --scenario <file> --sensors <log> --out <dir>`.

use std::io::BufWriter;
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use rover_files::{OutputDir, same_file};
use rover_scenario::estimate::{
    EstimateMap, EstimateOptions, EstimateSummary, Tuning, read_tuning,
};
use rover_scenario::prepare::Prepared;
use rover_scenario::read_sensor_log;
use rover_scenario::truth_log::read_truth;

use crate::error::CliError;

/// The map the filter carries.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum MapArg {
    /// The scenario's own terrain.
    #[default]
    True,
    /// The scenario's terrain with features below `--smooth-cutoff` removed.
    Smoothed,
}

/// Arguments of `rover estimate`.
#[derive(Debug, Args)]
pub struct EstimateArgs {
    /// A built-in rover or a description file; overrides the scenario's `rover`.
    pub rover: Option<String>,
    /// The scenario whose run wrote the log (its `[sensors]` table says what
    /// the log holds; its terrain is the filter's map).
    #[arg(long)]
    pub scenario: PathBuf,
    /// The sensor log (`sensors.csv` of `rover simulate`).
    #[arg(long)]
    pub sensors: PathBuf,
    /// Output directory (created if missing).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// The truth to measure against: a run's `run.csv`. By default the
    /// `run.csv` beside the sensor log, if there is one.
    #[arg(long, conflicts_with = "no_truth")]
    pub truth: Option<PathBuf>,
    /// Measure nothing, even with a `run.csv` beside the log.
    #[arg(long)]
    pub no_truth: bool,
    /// The map the filter carries.
    #[arg(long, value_enum, default_value_t = MapArg::True)]
    pub map: MapArg,
    /// With `--map smoothed`: the shortest wavelength the map keeps, in metres.
    #[arg(long, default_value_t = 1.0)]
    pub smooth_cutoff: f64,
    /// A TOML file tuning the filter: `[filter]` (its noises and steps) and
    /// `[initial]` (its starting standard deviations), docs/ESTIMATE.md.
    #[arg(long)]
    pub tuning: Option<PathBuf>,
    /// Use the generic (interpreted) plant even for a built-in rover.
    #[arg(long)]
    pub generic: bool,
    /// Skip the plots.
    #[arg(long)]
    pub no_plots: bool,
}

/// The names of what `rover estimate` writes.
const OUTPUTS: [&str; 3] = ["estimate.csv", "dead_reckoning.csv", "estimate.json"];

/// Estimate the log; the summary (also written as `estimate.json`) and
/// every file written.
pub fn estimate(args: &EstimateArgs) -> Result<(EstimateSummary, Vec<PathBuf>), CliError> {
    let prepared = Prepared::from_file(args.rover.as_deref(), &args.scenario)?;
    let Some(sensors) = prepared.scenario.sensors.as_ref() else {
        return Err(CliError::Usage(format!(
            "--scenario {}: it declares no [sensors]; give the scenario whose run wrote {} (its [sensors] table says what the log holds)",
            args.scenario.display(),
            args.sensors.display()
        )));
    };
    let model = &prepared.spec.model;
    let samples = read_sensor_log(&args.sensors, sensors, model.wheels.len(), model.m())
        .map_err(|e| CliError::SensorLog(Box::new(e)))?;
    let truth_path = match (&args.truth, args.no_truth) {
        (_, true) => None,
        (Some(p), false) => Some(p.clone()),
        (None, false) => {
            let beside = args.sensors.with_file_name("run.csv");
            beside.is_file().then_some(beside)
        }
    };
    let truth = truth_path
        .as_deref()
        .map(|p| read_truth(p, model.m(), model.wheels.len()))
        .transpose()?;
    if !(args.smooth_cutoff.is_finite() && args.smooth_cutoff > 0.0) {
        return Err(CliError::Usage(format!(
            "--smooth-cutoff {}: the shortest wavelength the smoothed map keeps must be a positive number of metres, e.g. 1.0",
            args.smooth_cutoff
        )));
    }
    let map = match args.map {
        MapArg::True => EstimateMap::True,
        MapArg::Smoothed => EstimateMap::Smoothed {
            cutoff: args.smooth_cutoff,
        },
    };
    let tuning = match &args.tuning {
        Some(path) => read_tuning(path).map_err(CliError::Usage)?,
        None => Tuning::default(),
    };
    let options = EstimateOptions {
        map,
        tuning,
        ..EstimateOptions::default()
    };
    let out = OutputDir::create(&args.out)
        .map_err(|e| CliError::Usage(format!("--out {}: {e}", args.out.display())))?;
    check_inputs(args, truth_path.as_deref(), &out)?;
    let create = |name: &str| {
        out.create_fresh(name)
            .map(|(_, f)| BufWriter::new(f))
            .map_err(|e| CliError::io(out.join(name), "create the output", e))
    };
    let summary_path = out.join("estimate.json");
    out.write_whole(
        "estimate.json",
        b"{\"status\": \"running\", \"complete\": false}\n",
    )
    .map_err(|e| CliError::io(&summary_path, "write the summary", e))?;
    let (est, dr) = (create(OUTPUTS[0])?, create(OUTPUTS[1])?);
    let summary = prepared.estimate(args.generic, &samples, truth.as_ref(), &options, est, dr)?;
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| CliError::Usage(format!("the summary: {e}")))?;
    out.write_whole("estimate.json", format!("{json}\n").as_bytes())
        .map_err(|e| CliError::io(&summary_path, "write the summary", e))?;
    let mut files: Vec<PathBuf> = OUTPUTS.iter().map(|n| out.join(n)).collect();
    if !args.no_plots && summary.samples > 0 {
        files.extend(plots(&prepared, &out, truth_path.as_deref())?);
    }
    Ok((summary, files))
}

/// The estimate's figure, when built with the `plots` feature.
#[cfg(feature = "plots")]
fn plots(
    prepared: &Prepared,
    out: &OutputDir,
    truth: Option<&Path>,
) -> Result<Vec<PathBuf>, CliError> {
    let spec = &prepared.spec;
    let angular = !spec.coordinate_linear.first().copied().unwrap_or(false);
    Ok(rover_plot::plot_estimate(
        &out.join(OUTPUTS[0]),
        &out.join(OUTPUTS[1]),
        truth,
        out.path(),
        &spec.name,
        angular,
    )?)
}

/// Without the `plots` feature: none.
#[cfg(not(feature = "plots"))]
fn plots(_: &Prepared, _: &OutputDir, _: Option<&Path>) -> Result<Vec<PathBuf>, CliError> {
    Ok(Vec::new())
}

/// An output that is an input would be overwritten: refused.
fn check_inputs(
    args: &EstimateArgs,
    truth: Option<&Path>,
    out: &OutputDir,
) -> Result<(), CliError> {
    let inputs = [
        Some(args.scenario.as_path()),
        Some(args.sensors.as_path()),
        truth,
    ];
    for input in inputs.into_iter().flatten() {
        for name in OUTPUTS {
            if same_file(input, &out.join(name)) {
                return Err(CliError::Usage(format!(
                    "--out {}: its {name} is the input {}, which the estimate would overwrite; give another folder",
                    args.out.display(),
                    input.display()
                )));
            }
        }
    }
    Ok(())
}

/// The summary's lines for the terminal.
pub fn report(summary: &EstimateSummary, files: &[PathBuf]) -> String {
    let mut s = format!(
        "{} samples estimated to t = {} s ({}; {:.1} µs a filter step)",
        summary.samples, summary.t_end, summary.status, summary.step_us
    );
    if let Some(e) = &summary.error {
        s.push_str(&format!("\nerror: {e}"));
    }
    if let (Some(f), Some(d), Some(c)) = (
        &summary.filter,
        &summary.dead_reckoning,
        &summary.consistency,
    ) {
        s.push_str(&format!(
            "\n{:<16}{:>10}{:>10}{:>10}{:>13}{:>12}{:>12}",
            "", "roll [°]", "pitch [°]", "yaw [°]", "susp. [°]", "v [m/s]", "drift [%]"
        ));
        for (name, a) in [("model-based EKF", f), ("dead reckoning", d)] {
            s.push_str(&format!(
                "\n{name:<16}{:>10.4}{:>10.4}{:>10.4}{:>13.4}{:>12.5}{:>12.3}",
                a.roll_deg,
                a.pitch_deg,
                a.yaw_deg,
                a.suspension_deg_max.unwrap_or(0.0),
                a.velocity,
                100.0 * a.drift_fraction
            ));
        }
        s.push_str(&format!(
            "\nNEES inside its 95 % interval at {:.1} % of {} instants (mean {:.1}, 2N = {})",
            100.0 * c.fraction_inside,
            c.samples,
            c.mean,
            c.dof
        ));
    }
    for f in files {
        s.push_str(&format!("\nwrote {}", f.display()));
    }
    s
}
