//! `rover simulate <rover> --scenario <file> --out <dir>`.

use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rover_scenario::output::{RowSink, Status, Summary};
use rover_scenario::prepare::Prepared;

use rover_files::{OutputDir, same_file};

use crate::error::CliError;

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
    /// Also write `run.mcap` beside run.csv: the run as an MCAP log of
    /// Foxglove messages, for Foxglove or Lichtblick (docs/VIEW.md); as the
    /// scenario's `[output] mcap = true`.
    #[arg(long)]
    pub mcap: bool,
}

/// What a run produced.
#[derive(Debug)]
pub struct SimulateReport {
    /// The summary (also written as `summary.json`).
    pub summary: Summary,
    /// Every file written.
    pub files: Vec<PathBuf>,
}

/// The output folder of a run that is still being prepared (its terrain
/// generated or decoded, its rover loaded): nothing is written yet, so
/// Ctrl-C ends the process at once instead of waiting for the first step.
static PREPARING: Mutex<Option<PathBuf>> = Mutex::new(None);

/// The Ctrl-C flag, installed once per process.
fn interrupt_flag() -> Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let f = flag.clone();
        // A second handler cannot be installed (tests call this repeatedly
        // in one process); the first one serves them all.
        let _ = ctrlc::set_handler(move || {
            let preparing = PREPARING.lock().map(|mut p| p.take());
            if let Ok(Some(out)) = preparing {
                let why = "interrupted while preparing the run: nothing was computed";
                if out.is_dir() {
                    interrupted_outputs(&out, why);
                }
                eprintln!("error: {why}");
                std::process::exit(1);
            }
            f.store(true, Ordering::Relaxed);
        });
        flag
    })
    .clone()
}

/// The outputs of a run interrupted before its first step: no CSV nor
/// sensor log, and a summary that says so.
fn interrupted_outputs(out: &Path, why: &str) {
    for name in ["run.csv", SENSORS_CSV, RUN_MCAP] {
        remove_regular(&out.join(name));
    }
    let json = serde_json::json!({ "status": "interrupted", "complete": false, "error": why });
    let _ = rover_files::write_whole(&out.join("summary.json"), format!("{json:#}\n").as_bytes());
}

/// Marks the run as being prepared (its rover loaded, its terrain built or
/// decoded, no row computed) until dropped.
struct Preparing;

impl Preparing {
    fn start(out: &Path) -> Self {
        if let Ok(mut p) = PREPARING.lock() {
            *p = Some(out.to_path_buf());
        }
        Preparing
    }
}

impl Drop for Preparing {
    fn drop(&mut self) {
        if let Ok(mut p) = PREPARING.lock() {
            *p = None;
        }
    }
}

/// The sensor log's name, beside `run.csv` when the scenario has
/// `[sensors]`.
const SENSORS_CSV: &str = "sensors.csv";

/// The MCAP log's name, beside `run.csv` with `--mcap` or `[output] mcap`.
pub const RUN_MCAP: &str = "run.mcap";

/// Remove `path` if it is a regular file (a link of that name stays, and
/// nothing it points to is touched); best effort.
fn remove_regular(path: &Path) {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        let _ = std::fs::remove_file(path);
    }
}

/// Run the scenario and write `run.csv` and `summary.json` into `args.out`,
/// and `sensors.csv` when the scenario has `[sensors]`.
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
    let flag = interrupt_flag();
    // Until the first row: the terrain is built when the run starts.
    let mut preparing = Some(Preparing::start(&args.out));
    let prepared = Prepared::from_file(args.rover.as_deref(), &args.scenario)?;
    let (spec, scenario) = (&prepared.spec, &prepared.scenario);
    let out = OutputDir::create(&args.out)
        .map_err(|e| CliError::Usage(format!("--out {}: {e}", args.out.display())))?;
    let csv_path = out.join("run.csv");
    let summary_path = out.join("summary.json");
    let sensors_path = out.join(SENSORS_CSV);
    let mcap_path = out.join(RUN_MCAP);
    let inputs = [
        Some(args.scenario.as_path()),
        args.rover.as_deref().map(Path::new),
    ];
    for input in inputs.into_iter().flatten() {
        for output in [&csv_path, &summary_path, &sensors_path, &mcap_path] {
            if same_file(input, output) {
                return Err(CliError::Usage(format!(
                    "--out {}: its {} is the input {}, which the run would overwrite; give another folder",
                    args.out.display(),
                    output
                        .file_name()
                        .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                    input.display()
                )));
            }
        }
    }
    // A summary saying "running" first: a run killed hard leaves no
    // summary that claims completion.
    out.write_whole(
        "summary.json",
        b"{\"status\": \"running\", \"complete\": false}\n",
    )
    .map_err(|e| CliError::io(&summary_path, "write the summary", e))?;
    let (_, csv) = out
        .create_fresh("run.csv")
        .map_err(|e| CliError::io(&csv_path, "create the CSV", e))?;
    let csv = BufWriter::new(csv);
    // The sensor log is written as the run goes, like the CSV; without
    // `[sensors]` an earlier run's is removed, so that it never passes
    // for this one's.
    let sensors = match &scenario.sensors {
        Some(_) => {
            let (_, file) = out
                .create_fresh(SENSORS_CSV)
                .map_err(|e| CliError::io(&sensors_path, "create the sensor log", e))?;
            Some(BufWriter::new(file))
        }
        None => {
            if std::fs::symlink_metadata(&sensors_path).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&sensors_path).map_err(|e| {
                    CliError::io(&sensors_path, "remove an earlier run's sensor log", e)
                })?;
            }
            None
        }
    };
    // The MCAP log, written as the run goes; without it an earlier run's
    // is removed, so that it never passes for this one's.
    let with_mcap = args.mcap || scenario.output.mcap;
    let mut mcap = if with_mcap {
        Some(mcap_log(&out, &mcap_path, spec)?)
    } else {
        if std::fs::symlink_metadata(&mcap_path).is_ok_and(|m| m.is_file()) {
            std::fs::remove_file(&mcap_path)
                .map_err(|e| CliError::io(&mcap_path, "remove an earlier run's MCAP log", e))?;
        }
        None
    };
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
    let progress = |t: f64| {
        preparing.take();
        bar.set_position((1000.0 * t / duration) as u64);
    };
    // The ground under the path for `rover view`, sampled from the run's
    // own terrain at its end.
    let mut view = rover_scenario::output::PathGround::new(rover_scenario::output::VIEW_NODES);
    let mut sinks = (&mut view, mcap.as_mut());
    let summary = prepared.run_with_outputs(
        args.generic,
        csv,
        sensors,
        Some(&mut sinks as &mut dyn RowSink),
        &flag,
        progress,
    )?;
    bar.finish_and_clear();
    // The rut grids before the summary that says the run is done: a
    // summary never points at an earlier run's ruts.
    let mut files = vec![csv_path.clone(), summary_path.clone()];
    if scenario.sensors.is_some() {
        files.push(sensors_path);
    }
    if with_mcap {
        files.push(mcap_path);
    }
    files.extend(rut_files(&out, &prepared, &summary)?);
    let json = serde_json::to_string_pretty(&summary)
        .map_err(|e| CliError::io(&summary_path, "write the summary", e.into()))?;
    out.write_whole("summary.json", (json + "\n").as_bytes())
        .map_err(|e| CliError::io(&summary_path, "write the summary", e))?;
    *summarized = true;
    #[cfg(feature = "drive")]
    crate::drive::write_view_terrain(
        &out,
        &prepared,
        &view,
        summary.status == Status::Interrupted,
    );
    // A user who stopped the run wants it to stop: no plots, which take
    // seconds for a long run.
    if !args.no_plots && summary.status != Status::Interrupted {
        files.extend(plots(&csv_path, &args.out, spec, scenario.settle)?);
        if let Some(grid) = &summary.rut_grid {
            files.extend(rut_plot(&csv_path, &args.out, spec, grid)?);
        }
    }
    bar.suspend(|| {
        report_end(&spec.name, &summary, &args.out);
        stalled_warning(spec, &summary);
        runaway_warning(spec, &summary);
    });
    Ok(SimulateReport { summary, files })
}

/// The rut map beside the CSV (`ruts.csv`, `ruts.png`, `ground.csv`;
/// docs/CLI.md), each written whole, when the run's ground keeps ruts.
/// Without ruts, an earlier run's rut files in the folder are removed
/// (regular files only, and never the scenario's own terrain file: a run
/// on the last run's `ground.csv` may write into the same folder).
fn rut_files(
    out: &OutputDir,
    prepared: &Prepared,
    summary: &Summary,
) -> Result<Vec<PathBuf>, CliError> {
    let Some(grid) = &summary.rut_grid else {
        let terrain = match &prepared.scenario.terrain.shape {
            rover_terrain::TerrainConfig::File(f) => Some(prepared.base.join(&f.path)),
            _ => None,
        };
        let stale = rover_scenario::output::RUT_FILES
            .iter()
            .chain(&["ruts_map.png", "ruts_map.svg"]);
        for name in stale {
            let path = out.join(name);
            let input = terrain.as_deref().is_some_and(|t| same_file(t, &path));
            if !input && std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&path)
                    .map_err(|e| CliError::io(&path, "remove an earlier run's rut map", e))?;
            }
        }
        return Ok(Vec::new());
    };
    let files = grid.files().map_err(|e| {
        CliError::Usage(format!(
            "{}: cannot write the rut map: {e}",
            out.path().display()
        ))
    })?;
    files
        .into_iter()
        .map(|(name, bytes)| {
            out.write_whole(name, &bytes)
                .map_err(|e| CliError::io(out.join(name), "write the rut map", e))
        })
        .collect()
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

/// A warning when the rover ran away (`summary.json` has the numbers): it
/// turned or drove far faster than its commands ask. Motors without a speed
/// limit are the usual cause: a slip-steering torque difference beyond
/// what turning needs spins the rover ever faster.
fn runaway_warning(spec: &rover_spec::Spec, summary: &Summary) {
    let Some(r) = &summary.runaway else { return };
    let unlimited = spec.model.wheels.iter().any(|w| w.motor_curve.is_none());
    let cause = if unlimited {
        "its motors have no speed limit: give them `no_load_speed` in the description, or lower the slip-steering `delta_tau` or the speed command (docs/CLI.md, sizing the control)"
    } else {
        "lower the slip-steering `delta_tau` or the speed command (docs/CLI.md, sizing the control)"
    };
    eprintln!(
        "warning: {} ran away from t = {:.2} s: up to {:.0} °/s of yaw and {:.2} m/s (bounds {:.0} °/s, {:.2} m/s for its commands); {cause}",
        spec.name, r.t, r.yaw_rate_deg_s, r.speed_m_s, r.yaw_rate_bound_deg_s, r.speed_bound_m_s,
    );
}

/// The outputs of a run that could not start: its CSV and sensor log
/// (holding not even their headers), or an earlier run's, are removed and
/// the summary replaced by a failed one carrying the error. Best effort:
/// the error itself is what the caller reports.
fn fail_outputs(csv: &Path, summary: &Path, e: &CliError) {
    // Only a regular file is removed: a link named `run.csv` stays (and
    // nothing it points to is touched).
    remove_regular(csv);
    if let Some(dir) = csv.parent() {
        remove_regular(&dir.join(SENSORS_CSV));
        remove_regular(&dir.join(RUN_MCAP));
    }
    let json = serde_json::json!({
        "status": "failed",
        "complete": false,
        "error": e.to_string(),
    });
    let _ = rover_files::write_whole(summary, format!("{json:#}\n").as_bytes());
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
    Ok(rover_plot::plot_run(csv, out, &meta)?)
}

/// The top view of the ruts with the rover's path (`ruts_map.png` and
/// `.svg`), when built with the `plots` feature.
#[cfg(feature = "plots")]
fn rut_plot(
    csv: &Path,
    out: &Path,
    spec: &rover_spec::Spec,
    grid: &rover_scenario::output::RutGrid,
) -> Result<Vec<PathBuf>, CliError> {
    let depth = grid
        .depth()
        .map_err(|e| CliError::Usage(format!("{}: the rut map: {e}", out.display())))?;
    let map = rover_plot::RutImage {
        origin: depth.origin(),
        spacing: depth.spacing()[0],
        nodes: [depth.nx(), depth.ny()],
        depth: depth.heights(),
    };
    Ok(rover_plot::plot_ruts(csv, out, &spec.name, &map)?)
}

#[cfg(not(feature = "plots"))]
fn rut_plot(
    _csv: &Path,
    _out: &Path,
    _spec: &rover_spec::Spec,
    _grid: &rover_scenario::output::RutGrid,
) -> Result<Vec<PathBuf>, CliError> {
    Ok(Vec::new())
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

/// The MCAP log of a run, `run.mcap` in `out`, started afresh.
#[cfg(feature = "mcap")]
fn mcap_log(
    out: &OutputDir,
    path: &Path,
    spec: &rover_spec::Spec,
) -> Result<rover_scenario::output::foxglove::McapLog<BufWriter<std::fs::File>>, CliError> {
    let (_, file) = out
        .create_fresh(RUN_MCAP)
        .map_err(|e| CliError::io(path, "create the MCAP log", e))?;
    rover_scenario::output::foxglove::McapLog::new(
        BufWriter::new(file),
        spec,
        path.display().to_string(),
    )
    .map_err(|e| CliError::io(path, "write the MCAP log", e))
}

/// Without the `mcap` feature: a clear refusal.
#[cfg(not(feature = "mcap"))]
fn mcap_log(_out: &OutputDir, path: &Path, _spec: &rover_spec::Spec) -> Result<NoMcap, CliError> {
    Err(CliError::Usage(format!(
        "{}: this rover was built without the `mcap` feature: rebuild with `--features mcap` (a default feature), or drop `--mcap` and `[output] mcap`",
        path.display()
    )))
}

/// The MCAP log's place in a build without the `mcap` feature (never made).
#[cfg(not(feature = "mcap"))]
enum NoMcap {}

#[cfg(not(feature = "mcap"))]
impl RowSink for NoMcap {
    fn start(&mut self, _: &rover_runtime::row::Columns) -> std::io::Result<()> {
        match *self {}
    }
    fn row(&mut self, _: &[f64]) -> std::io::Result<()> {
        match *self {}
    }
    fn finish(&mut self, _: Option<&rover_runtime::terrain::Terrain>) -> std::io::Result<()> {
        match *self {}
    }
}
