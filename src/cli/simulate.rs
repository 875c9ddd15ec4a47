//! `rover simulate <rover> --scenario <file> --out <dir>`.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rover_runtime::GenericPlant;
use rover_scenario::output::{Status, Summary};
use rover_scenario::scenario::Scenario;

use crate::rover_source::{builtin_names, load_rover};

use super::CliError;

/// Arguments of `rover simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file;
    /// overrides the scenario's `rover`.
    pub rover: Option<String>,
    /// The scenario file (TOML).
    #[arg(long)]
    pub scenario: PathBuf,
    /// Output directory (created if missing).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Skip the PNG/SVG plots.
    #[arg(long)]
    pub no_plots: bool,
    /// Use the generic (interpreted) plant even for a built-in rover, whose
    /// generated plant is used by default (full fidelity; swing4 also at the
    /// simplified and linearized levels).
    #[arg(long)]
    pub generic: bool,
}

/// What a run produced.
#[derive(Debug)]
pub struct SimulateReport {
    /// The summary (also written as `summary.json`).
    pub summary: Summary,
    /// Every file written.
    pub files: Vec<PathBuf>,
}

/// The Ctrl-C flag, installed once per process.
fn interrupt_flag() -> Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let f = flag.clone();
        // A second handler cannot be installed (tests call this repeatedly
        // in one process); the first one serves them all.
        let _ = ctrlc::set_handler(move || f.store(true, Ordering::Relaxed));
        flag
    })
    .clone()
}

/// An output that cannot be written: the path, what was being done, the
/// system's reason.
fn io_err(path: &Path, doing: &str, e: std::io::Error) -> CliError {
    CliError::Other(format!("{}: cannot {doing}: {e}", path.display()))
}

/// A scenario read and its rover loaded: everything a run needs before it
/// writes anything. The CLI and the Python package both start here, so a
/// run from either gives the same numbers and the same messages.
#[derive(Debug)]
pub struct Prepared {
    /// The rover's description.
    pub spec: rover_spec::Spec,
    /// The rover as named (built-in name or path), which picks the plant.
    pub rover: String,
    /// The scenario.
    pub scenario: Scenario,
    /// Where the scenario's relative paths start.
    pub base: PathBuf,
    /// The scenario's name in messages (its path, or a stand-in for text).
    pub origin: PathBuf,
    /// The scenario's text, to locate a field that a message names.
    pub text: String,
}

impl Prepared {
    /// Read the scenario file at `path` and load its rover (`rover`
    /// overrides the scenario's).
    pub fn from_file(rover: Option<&str>, path: &Path) -> Result<Self, CliError> {
        let scenario = Scenario::load(path)?;
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::new(rover, scenario, text, path, &base)
    }

    /// A scenario given as TOML `text`, named `origin` in messages, its
    /// relative paths taken from `base`.
    pub fn from_text(
        rover: Option<&str>,
        text: &str,
        origin: &Path,
        base: &Path,
    ) -> Result<Self, CliError> {
        let scenario = Scenario::parse(text, origin)?;
        Self::new(rover, scenario, text.to_string(), origin, base)
    }

    fn new(
        rover: Option<&str>,
        scenario: Scenario,
        text: String,
        origin: &Path,
        base: &Path,
    ) -> Result<Self, CliError> {
        let rover = rover
            .map(str::to_string)
            .or_else(|| scenario.rover.clone())
            .ok_or_else(|| {
                CliError::Other(format!(
                    "no rover: give one on the command line or as `rover = \"...\"` in {} (built-in: {})",
                    origin.display(),
                    builtin_names()
                ))
            })?;
        let spec = load_rover(&rover, Some(base))?;
        Ok(Self {
            spec,
            rover,
            scenario,
            base: base.to_path_buf(),
            origin: origin.to_path_buf(),
            text,
        })
    }

    /// A run that could not start, located at the scenario's offending
    /// field (`file:line: `) when the error names one.
    pub fn locate(&self, source: rover_scenario::simulate::SetupError) -> CliError {
        let line = source
            .field_path()
            .and_then(|f| rover_scenario::scenario::line_of_field(&self.text, &f));
        let location = match line {
            Some(l) => format!("{}:{l}: ", self.origin.display()),
            None => format!("{}: ", self.origin.display()),
        };
        CliError::Setup { location, source }
    }

    /// Run the scenario, writing the CSV to `csv`; the summary names the
    /// plant that ran. A run that could not start is an error located at
    /// the scenario's offending field.
    pub fn run<W: std::io::Write>(
        &self,
        generic: bool,
        csv: W,
        interrupt: &AtomicBool,
        progress: impl FnMut(f64),
    ) -> Result<Summary, CliError> {
        let level = self.scenario.fidelity.dynamic().unwrap_or_default();
        let run = Run {
            spec: &self.spec,
            scenario: &self.scenario,
            base: &self.base,
            flag: interrupt,
        };
        let (result, backend) = match generated_plant(&self.rover, level, generic) {
            Some(p) => (
                run.go(p, csv, progress),
                format!("generated ({})", p.name()),
            ),
            None => (
                run.go(build_plant(&self.spec.model, level)?, csv, progress),
                "generic".to_string(),
            ),
        };
        let mut summary = result.map_err(|source| self.locate(source))?;
        summary.plant = backend;
        Ok(summary)
    }
}

/// Run the scenario and write `run.csv` and `summary.json` into `args.out`.
///
/// A run that cannot start, for whatever reason, leaves a summary saying
/// `failed` with the error, and no CSV: an earlier run's outputs in the
/// same folder never pass for this one's.
pub fn simulate(args: &SimulateArgs) -> Result<SimulateReport, CliError> {
    let csv_path = args.out.join("run.csv");
    let summary_path = args.out.join("summary.json");
    let mut summarized = false;
    simulate_in(args, &mut summarized).inspect_err(|e| {
        if !summarized && args.out.is_dir() {
            fail_outputs(&csv_path, &summary_path, e);
        }
    })
}

/// The run; `summarized` turns true once its summary is written (later
/// errors, of the plots, leave the run's outputs as they are).
fn simulate_in(args: &SimulateArgs, summarized: &mut bool) -> Result<SimulateReport, CliError> {
    let prepared = Prepared::from_file(args.rover.as_deref(), &args.scenario)?;
    let (spec, scenario) = (&prepared.spec, &prepared.scenario);
    if args.out.exists() && !args.out.is_dir() {
        return Err(CliError::Other(format!(
            "{}: is a file, not a folder; give `--out` a folder (it is created if missing)",
            args.out.display()
        )));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| io_err(&args.out, "create the output folder", e))?;
    let csv_path = args.out.join("run.csv");
    let summary_path = args.out.join("summary.json");
    // A summary saying "running" first: a run killed hard leaves no
    // summary that claims completion.
    std::fs::write(
        &summary_path,
        "{\"status\": \"running\", \"complete\": false}\n",
    )
    .map_err(|e| io_err(&summary_path, "write the summary", e))?;
    let csv = BufWriter::new(
        File::create(&csv_path).map_err(|e| io_err(&csv_path, "create the CSV", e))?,
    );
    let bar = if args.quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr())
    };
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent}% ({elapsed} / ~{eta})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar.set_message(format!("{} t = 0 s", spec.name));
    let duration = scenario.duration;
    let flag = interrupt_flag();
    let progress = |t: f64| bar.set_position((1000.0 * t / duration) as u64);
    let summary = prepared.run(args.generic, csv, &flag, progress)?;
    bar.finish_and_clear();
    let json =
        serde_json::to_string_pretty(&summary).map_err(|e| CliError::Other(e.to_string()))?;
    std::fs::write(&summary_path, json + "\n")
        .map_err(|e| io_err(&summary_path, "write the summary", e))?;
    *summarized = true;
    let mut files = vec![csv_path.clone(), summary_path];
    if !args.no_plots {
        files.extend(plots(&csv_path, &args.out, spec, scenario.settle)?);
    }
    bar.suspend(|| {
        report_end(&spec.name, &summary, &args.out);
        stalled_warning(spec, &summary);
    });
    Ok(SimulateReport { summary, files })
}

/// The line that says how the run ended and where its outputs are.
fn report_end(rover: &str, summary: &Summary, out: &Path) {
    match summary.status {
        Status::Completed => eprintln!(
            "{rover}: {:.1} s simulated in {:.2} s (real-time factor {:.1}); outputs in {}",
            summary.t_end,
            summary.wall_time_s,
            summary.real_time_factor,
            out.display()
        ),
        _ => eprintln!(
            "{rover}: run incomplete at t = {:.3} s: {}; the CSV holds what was computed (marked incomplete in summary.json)",
            summary.t_end,
            summary.error.as_deref().unwrap_or("stopped")
        ),
    }
}

/// A warning when the rover stalled (`summary.json` has the numbers): the
/// run is valid, but it is not the traverse the scenario describes. The
/// motors' last torques against their limits tell which cause it is.
fn stalled_warning(spec: &rover_spec::Spec, summary: &Summary) {
    let Some(s) = &summary.stalled else { return };
    let limits = spec.model.wheels.iter().map(|w| w.max_torque);
    // A motor within 5 % of its limit is at it.
    let at_limit = s
        .final_torques
        .iter()
        .zip(limits)
        .any(|(t, max)| t.abs() >= 0.95 * max);
    let cause = if at_limit {
        "its motors are at their torque limit: it is against an obstacle or on a slope beyond them"
    } else {
        "its motors are below their torque limit: the speed loop asks too little for this rover and ground; raise `kp` or give it an integral gain `ki` in `[control.speed]`"
    };
    eprintln!(
        "warning: {} stalled: {} of progress in the last {:.1} s of the run, where its speed command asked for {:.3} m; {cause}",
        spec.name,
        if s.progress_m.abs() < 1.0 {
            format!("{:.1} mm", 1e3 * s.progress_m)
        } else {
            format!("{:.3} m", s.progress_m)
        },
        s.window_s,
        s.commanded_m
    );
}

/// The outputs of a run that could not start: its CSV (holding not even
/// its header), or an earlier run's, is removed and the summary replaced by
/// a failed one carrying the error. Best effort: the error itself is what
/// the caller reports.
fn fail_outputs(csv: &Path, summary: &Path, e: &CliError) {
    let _ = std::fs::remove_file(csv);
    let json = serde_json::json!({
        "status": "failed",
        "complete": false,
        "error": e.to_string(),
    });
    let _ = std::fs::write(summary, format!("{json:#}\n"));
}

/// The run's plots (PNG and SVG), when built with the `plots` feature.
#[cfg(feature = "plots")]
fn plots(
    csv: &Path,
    out: &Path,
    spec: &rover_spec::Spec,
    settle: f64,
) -> Result<Vec<PathBuf>, CliError> {
    let meta = rover_plot::PlotMeta {
        title: spec.name.clone(),
        coordinate_names: spec.coordinate_names.clone(),
        angular: spec.coordinate_linear.iter().map(|l| !l).collect(),
        wheel_names: spec.wheel_names.clone(),
        settle_time: settle,
        ..Default::default()
    };
    rover_plot::plot_run(csv, out, &meta).map_err(|e| CliError::Other(e.to_string()))
}

#[cfg(not(feature = "plots"))]
fn plots(
    _csv: &Path,
    _out: &Path,
    _spec: &rover_spec::Spec,
    _settle: f64,
) -> Result<Vec<PathBuf>, CliError> {
    Ok(Vec::new())
}

/// The generic plant at a fidelity level; reduced levels are frozen at the
/// loaded static equilibrium on flat ground (docs/FIDELITY.md says why).
/// The generated plant of a built-in rover at `level`, where one exists
/// (and `generic` is not asked for): built-in rovers run it, others the
/// generic plant.
pub fn generated_plant(
    rover: &str,
    level: rover_dynamics::fidelity::Fidelity,
    generic: bool,
) -> Option<rover_models::BuiltinPlant> {
    use rover_dynamics::fidelity::Fidelity;
    match level {
        _ if generic => None,
        Fidelity::Full => rover_models::plant(rover),
        Fidelity::Simplified => rover_models::plant_at(rover, "simplified"),
        Fidelity::Linearized => rover_models::plant_at(rover, "linearized"),
    }
}

/// The generic plant of `model` at `level` (reduced levels frozen where the
/// CLI freezes them: the loaded flat-ground equilibrium).
pub fn build_plant(
    model: &rover_dynamics::Model,
    level: rover_dynamics::fidelity::Fidelity,
) -> Result<GenericPlant, CliError> {
    let y_ref = match level {
        rover_dynamics::fidelity::Fidelity::Full => model.rest(),
        _ => reduced_level_reference(model)?,
    };
    GenericPlant::with_fidelity_at(model.clone(), level, &y_ref)
        .map_err(|e| CliError::Other(e.to_string()))
}

/// Where the CLI freezes a reduced level (MODEL.md §9): the rover's loaded
/// static equilibrium on flat ground, not y_c (docs/FIDELITY.md says why).
/// `simulate` and `codegen` both freeze here, so a generated reduced plant
/// is the generic one.
pub fn reduced_level_reference(model: &rover_dynamics::Model) -> Result<Vec<f64>, CliError> {
    rover_runtime::quasi_static::flat_ground_equilibrium(model).map_err(|e| {
        CliError::Other(format!(
            "cannot find the loaded equilibrium to freeze a reduced fidelity level at: {e}"
        ))
    })
}

/// What every run of `simulate` shares, whichever the plant.
struct Run<'a> {
    spec: &'a rover_spec::Spec,
    scenario: &'a Scenario,
    base: &'a Path,
    flag: &'a AtomicBool,
}

impl Run<'_> {
    fn go<P: rover_dynamics::plant::Plant, W: std::io::Write>(
        &self,
        plant: P,
        csv: W,
        progress: impl FnMut(f64),
    ) -> Result<Summary, rover_scenario::simulate::SetupError> {
        let s = self.spec;
        rover_scenario::simulate::simulate(
            plant,
            &s.model,
            &s.name,
            self.scenario,
            self.base,
            csv,
            self.flag,
            progress,
        )
    }
}
