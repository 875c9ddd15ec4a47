//! `rover drive`: the simulation paced to the wall clock, driven live from
//! a browser or a rig over a WebSocket; `rover view`: a finished run's CSV
//! animated in the same page. docs/DRIVE.md is the user's guide and the
//! protocol's reference.
//!
//! The web side (a small HTTP server and tungstenite) is behind the
//! `drive` feature of the `rover` package only: the plant and runtime
//! crates never depend on it.

pub mod access;
#[cfg(feature = "mcap")]
pub mod foxglove;
pub mod ghost;
pub mod live;
pub mod protocol;
pub mod row_feed;
pub mod rut_feed;
pub mod server;

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::thread::JoinHandle;

use clap::Args;
use rover_dynamics::plant::Plant;
use rover_runtime::row::Columns;
use rover_runtime::terrain::Terrain;
use rover_scenario::output::{HeightGrid, PathGround, VIEW_NODES};
use rover_scenario::prepare::{Prepared, RunPlant, load_rover};
use rover_scenario::scenario::Scenario;
use rover_spec::sketch::Sketch;
use serde_json::json;

use crate::error::CliError;

use access::Access;
use live::{LoopConfig, Method, Pacing, RATE_RANGE, RoverInfo, Shared, Sim, Timing};
use server::{App, Content, Server};

/// The ground `rover drive` runs on without a scenario: the paper's rough
/// terrain (Z_R = 0.2, as Figs. 13–14), flat where the rover starts.
pub const DEFAULT_SCENARIO: &str = "duration = 1.0
[terrain]
kind = \"random\"
z_r = 0.2
node_amplitude = 0.25
patch_radius = 0.6
patch_blend = 0.5
";

/// Arguments of `rover drive`.
#[derive(Debug, Args)]
// A negative number is a value (`--rate -5` is refused as a rate, not taken
// for an unknown flag).
#[command(allow_negative_numbers = true)]
pub struct DriveArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file;
    /// overrides the scenario's `rover`.
    pub rover: Option<String>,
    /// A scenario file for the terrain, contact, initial state, speed loop
    /// gains and torque distribution, and active suspension (its duration,
    /// integrator, speed profile, steering and command file are not used);
    /// default: rough random terrain.
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// TCP port on 127.0.0.1 (0: any free port, printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// A web origin (scheme://host, or scheme://host:port) whose pages may
    /// use the server besides its own page, e.g. a rig's dashboard;
    /// repeatable.
    #[arg(long = "allow-origin", value_name = "URL")]
    pub allow_origin: Vec<String>,
    /// The token a WebSocket client without an Origin header (a program,
    /// not a browser page) presents, as `/ws?token=…` or `Authorization:
    /// Bearer …`; default: `ROVER_DRIVE_TOKEN`, else a random one, printed.
    #[arg(long, value_name = "TOKEN")]
    pub token: Option<String>,
    /// Steps per second of wall-clock time.
    #[arg(long, default_value_t = 1000.0)]
    pub rate: f64,
    /// The fixed-step method; default RK4 from 500 Hz up, ROS2 below.
    #[arg(long, value_enum)]
    pub method: Option<Method>,
    /// Use the generic plant even for a built-in rover.
    #[arg(long)]
    pub generic: bool,
    /// No server: drive straight ahead at `--report-speed` for this many
    /// seconds and print the step latencies, jitter and overruns.
    #[arg(long, value_name = "SECONDS")]
    pub report: Option<f64>,
    /// The speed set-point of a `--report` run [m/s].
    #[arg(long, default_value_t = 0.1)]
    pub report_speed: f64,
    /// How the loop waits for a tick: sleep, then spin the last tens of µs
    /// (default), or sleep only (no CPU spent waiting, more jitter).
    #[arg(long, value_enum, default_value_t = Pacing::Spin)]
    pub pacing: Pacing,
    /// Run the state estimator on the rover's sensors (the scenario's
    /// `[sensors]`, or a default MEMS set) and send its estimate: the page
    /// draws it as a ghost beside the rover (docs/DRIVE.md).
    #[arg(long)]
    pub estimate: bool,
}

/// The loop's settings from the command line and the scenario.
fn loop_config(args: &DriveArgs, scenario: &Scenario) -> LoopConfig {
    LoopConfig {
        pacing: args.pacing,
        ..LoopConfig::new(args.rate, args.method, scenario)
    }
}

/// Arguments of `rover view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A `rover simulate` output folder (its `run.csv` is animated).
    pub out: PathBuf,
    /// The rover, when `summary.json` does not name one (for its wheel
    /// sizes; without one they are estimated from the CSV).
    #[arg(long)]
    pub rover: Option<String>,
    /// A scenario whose terrain is drawn under the run, instead of the
    /// output folder's `terrain.json` (without either the ground is drawn
    /// flat at the contact points' mean height).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// TCP port on 127.0.0.1 (0: any free port, printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// A web origin (scheme://host, or scheme://host:port) whose pages may use the server
    /// besides its own page; repeatable.
    #[arg(long = "allow-origin", value_name = "URL")]
    pub allow_origin: Vec<String>,
}

/// A running `rover drive`: its address, and a way to stop it.
pub struct Running {
    /// The port it listens on.
    pub port: u16,
    /// The token a WebSocket client without an Origin header presents.
    pub token: String,
    /// Shared with the loop.
    pub shared: Arc<Shared>,
    sim: JoinHandle<Timing>,
    server: Server,
}

impl Running {
    /// Stop the loop and the server and return the loop's timing. When it
    /// returns, every thread it started has ended (the WebSocket clients
    /// were sent a close frame) and the port is free.
    pub fn stop(self) -> Timing {
        self.shared.stop.store(true, Ordering::Relaxed);
        let timing = self.sim.join().unwrap_or_default();
        self.server.stop();
        timing
    }

    /// The server's live threads (its accept loop and its connections).
    pub fn server_threads(&self) -> Arc<AtomicUsize> {
        self.server.threads()
    }
}

/// A running `rover view`: its address, and a way to stop it.
pub struct Viewing {
    /// The port it listens on.
    pub port: u16,
    server: Server,
}

impl std::fmt::Debug for Viewing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Viewing").field("port", &self.port).finish()
    }
}

impl Viewing {
    /// Stop the server; when it returns its threads have ended and the
    /// port is free.
    pub fn stop(self) {
        self.server.stop();
    }

    /// The server's live threads (its accept loop and its connections).
    pub fn server_threads(&self) -> Arc<AtomicUsize> {
        self.server.threads()
    }
}

fn other(e: impl std::fmt::Display) -> CliError {
    CliError::Drive(e.to_string())
}

/// Where the built-in drive scenario's relative paths start, and its name
/// in messages.
const DEFAULT_ORIGIN: &str = "<built-in drive scenario>";

/// The scenario and the folder its relative paths are read from.
fn load_scenario(path: Option<&Path>) -> Result<(Scenario, PathBuf), CliError> {
    Ok(match path {
        Some(p) => (
            Scenario::load(p)?,
            p.parent().map(Path::to_path_buf).unwrap_or_default(),
        ),
        None => (
            Scenario::parse(DEFAULT_SCENARIO, Path::new(DEFAULT_ORIGIN))?,
            PathBuf::from("."),
        ),
    })
}

/// The run `rover drive` serves: its scenario (or the built-in one) read
/// once and its rover loaded.
fn prepare(args: &DriveArgs) -> Result<Prepared, CliError> {
    let rover = args.rover.as_deref();
    Ok(match &args.scenario {
        Some(p) => Prepared::from_file(rover, p)?,
        None => Prepared::from_text(
            rover,
            DEFAULT_SCENARIO,
            Path::new(DEFAULT_ORIGIN),
            Path::new("."),
        )?,
    })
}

fn check_rate(rate: f64) -> Result<(), CliError> {
    if !RATE_RANGE.contains(&rate) {
        return Err(CliError::Usage(format!(
            "--rate {rate:?}: steps per second, between {} and {} (1000 is the default)",
            RATE_RANGE.start(),
            RATE_RANGE.end()
        )));
    }
    Ok(())
}

/// The `--allow-origin` values, checked and normalised.
fn allowed_origins(given: &[String]) -> Result<Vec<String>, CliError> {
    given
        .iter()
        .map(|o| access::parse_origin(o).map_err(CliError::Usage))
        .collect()
}

/// The WebSocket's token: `--token`, else `ROVER_DRIVE_TOKEN`, else a
/// random one.
fn token(args: &DriveArgs) -> Result<String, CliError> {
    if let Some(t) = &args.token {
        return access::check_token("--token", t).map_err(CliError::Usage);
    }
    match std::env::var("ROVER_DRIVE_TOKEN") {
        Ok(t) => access::check_token("ROVER_DRIVE_TOKEN", &t).map_err(CliError::Usage),
        Err(std::env::VarError::NotPresent) => Ok(access::random_token()),
        Err(std::env::VarError::NotUnicode(_)) => Err(CliError::Usage(
            "ROVER_DRIVE_TOKEN is not valid text: set it to 16 to 256 characters of A–Z, a–z, 0–9, `-`, `_`, `.`, `~`, or unset it".to_string(),
        )),
    }
}

/// `--report-speed` within what the rover's wheels reach.
fn check_report_speed(speed: f64, info: &RoverInfo) -> Result<(), CliError> {
    let max = info.max_speed();
    if !(-max..=max).contains(&speed) {
        return Err(CliError::Usage(format!(
            "--report-speed {speed:?}: m/s, within ±{max} m/s for this rover ({} wheel radii a second; 0.1 is the default)",
            live::MAX_SPEED_RADII
        )));
    }
    Ok(())
}

/// The suspension members as joints (each a polynomial in the
/// coordinates, as the description's raw polynomials are written) and the
/// links between them (docs/DRIVE.md, "Rover geometry").
pub fn sketch_json(sketch: &Sketch) -> serde_json::Value {
    let joints: Vec<serde_json::Value> = sketch
        .joints
        .iter()
        .map(|j| {
            let terms: Vec<serde_json::Value> = j
                .position
                .terms
                .iter()
                .map(|t| json!({"coord": t.coord, "center": t.center, "coeffs": t.coeffs}))
                .collect();
            json!({"wheel": j.wheel, "c": j.position.constant, "terms": terms})
        })
        .collect();
    let links: Vec<serde_json::Value> = sketch
        .links
        .iter()
        .map(|l| json!({"suspension": l.suspension, "member": l.member, "joints": l.joints}))
        .collect();
    json!({"joints": joints, "links": links})
}

/// The sensors `rover drive --estimate` reads: the scenario's
/// `[sensors]`, else [`ghost::default_sensors`]; and which.
fn estimate_sensors(scenario: &Scenario) -> (rover_estimate::SensorConfig, &'static str) {
    match &scenario.sensors {
        Some(s) => (s.clone(), "scenario"),
        None => (ghost::default_sensors(), "default"),
    }
}

/// The rover's geometry and the loop's settings, for the page and rigs.
fn meta(
    mode: &str,
    spec: Option<&rover_spec::Spec>,
    columns: &[String],
    info: Option<&RoverInfo>,
    loop_config: Option<(&LoopConfig, &[String])>,
    estimate: Option<serde_json::Value>,
) -> String {
    let mut m = json!({
        "mode": mode,
        "rover": spec.map_or("run", |s| s.name.as_str()),
        "columns": columns,
        "wheels": columns.iter().filter(|c| c.starts_with("Fn")).count(),
    });
    if let Some(spec) = spec {
        m["coordinates"] = json!(spec.coordinate_names);
        m["mass"] = json!(spec.model.total_mass());
        m["gravity"] = json!(spec.model.gravity);
        m["sketch"] = sketch_json(&spec.sketch);
        let (m_, k) = (spec.model.m(), spec.model.wheels.len());
        let row = [false, true]
            .map(|soil| Columns::on_ground(m_, k, soil))
            .into_iter()
            .find(|row| row.names() == columns);
        if let Some(row) = row {
            m["units"] = json!(row.units(&spec.coordinate_linear));
        }
    }
    if let Some(info) = info {
        let r_max = info.radius.iter().cloned().fold(0.0, f64::max);
        let [length, width, height] = rover_scenario::output::body_box(&info.rest, &info.radius);
        m["rest"] = json!(info.rest);
        m["radius"] = json!(info.radius);
        m["steerable"] = json!(info.steerable);
        m["steering"] = json!(if info.ackermann() {
            "ackermann"
        } else {
            "slip"
        });
        m["max_steer"] = json!(0.5);
        m["max_torque"] = json!(info.max_torque);
        m["max_delta_tau"] = json!(
            0.5 * info
                .max_torque
                .iter()
                .cloned()
                .fold(f64::INFINITY, f64::min)
        );
        // A brisk walking pace for the rover's size: two wheel radii a second.
        m["speed_hint"] = json!(2.0 * r_max);
        m["max_speed"] = json!(info.max_speed());
        m["body"] = json!({"length": length, "width": width, "height": height});
    }
    if let Some(e) = estimate {
        m["estimate"] = e;
    }
    if let Some((c, estimate)) = loop_config {
        m["binary_layout"] = json!(protocol::binary_layout(columns, estimate));
        m["rate_hz"] = json!(c.rate_hz);
        m["step_s"] = json!(1.0 / c.rate_hz);
        m["method"] = json!(c.method.name());
    }
    m.to_string()
}

/// Heights on a grid of at most [`VIEW_NODES`] × [`VIEW_NODES`] nodes over
/// the terrain's map (or 40 m × 40 m around `centre` on an unbounded
/// terrain), for the page's mesh. Nodes off the map are `null`.
pub fn terrain_json(terrain: &Terrain, centre: [f64; 2]) -> String {
    let half = 20.0;
    grid_json(&HeightGrid::sample(
        terrain,
        [centre[0] - half, centre[1] - half],
        [centre[0] + half, centre[1] + half],
        VIEW_NODES,
    ))
}

/// The margin around a run's path that its replay's ground covers \[m\].
pub use rover_scenario::output::PATH_MARGIN;

/// The ground under a run's path, for its replay: heights on a grid of at
/// most [`VIEW_NODES`] nodes a side over the rectangle the path (`lo`…`hi`
/// in X and Y) covers, [`PATH_MARGIN`] wider on every side, within the
/// terrain's map; the same form as [`terrain_json`].
pub fn path_terrain_json(terrain: &Terrain, lo: [f64; 2], hi: [f64; 2]) -> String {
    grid_json(&HeightGrid::sample(
        terrain,
        [lo[0] - PATH_MARGIN, lo[1] - PATH_MARGIN],
        [hi[0] + PATH_MARGIN, hi[1] + PATH_MARGIN],
        VIEW_NODES,
    ))
}

/// `g` as the page's JSON: `x0`, `y0`, `dx`, `dy`, `nx`, `ny` and the
/// heights `z` row after row, each to 0.1 mm (`null` off the map).
fn grid_json(g: &HeightGrid) -> String {
    let mut z = String::with_capacity(g.z.len() * 8);
    for (k, h) in g.z.iter().enumerate() {
        if k > 0 {
            z.push(',');
        }
        match h {
            Some(h) => push_tenths_of_mm(&mut z, *h),
            None => z.push_str("null"),
        }
    }
    format!(
        "{{\"x0\":{},\"y0\":{},\"dx\":{},\"dy\":{},\"nx\":{},\"ny\":{},\"z\":[{z}]}}",
        g.x0, g.y0, g.dx, g.dy, g.nx, g.ny
    )
}

/// `metres` with four decimals, rounded to the nearest 0.1 mm, written
/// from integers: formatting 65,536 heights with `{:.4}` was a sixth of a
/// short `rover simulate` (its exact-precision path, an allocation each).
/// A height beyond ±9e14 m (none on any map) is written as Rust prints it.
fn push_tenths_of_mm(out: &mut String, metres: f64) {
    use std::fmt::Write;
    let tenths = (metres * 1e4).round();
    if tenths.abs() >= 9e18 {
        let _ = write!(out, "{metres}");
        return;
    }
    let tenths = tenths as i64;
    if tenths < 0 {
        out.push('-');
    }
    let magnitude = tenths.unsigned_abs();
    let _ = write!(out, "{}.{:04}", magnitude / 10_000, magnitude % 10_000);
}

/// The rectangle (lowest X and Y, highest X and Y) a run's path covers,
/// from the `X` and `Y` columns of its CSV; `None` without a row.
fn path_box(text: &str) -> Option<([f64; 2], [f64; 2])> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next()?.split(',').map(str::trim).collect();
    let ix = header.iter().position(|h| *h == "X")?;
    let iy = header.iter().position(|h| *h == "Y")?;
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for line in lines {
        let v: Vec<&str> = line.split(',').collect();
        let get = |i: usize| v.get(i).and_then(|s| s.trim().parse::<f64>().ok());
        if let (Some(x), Some(y)) = (get(ix), get(iy))
            && x.is_finite()
            && y.is_finite()
        {
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
    }
    (lo[0] <= hi[0]).then_some((lo, hi))
}

/// The file of a `rover simulate` output folder that `rover view` draws
/// the ground from.
pub const VIEW_TERRAIN: &str = "terrain.json";

/// Write [`VIEW_TERRAIN`] into a run's output folder: the ground under the
/// run's path, as `view` (the run's own [`PathGround`] sink) sampled it
/// from the terrain the run drove on, so that `rover view` draws the
/// terrain the run had. Best effort: a failure is a warning on stderr, and
/// the run's outputs stand.
pub fn write_view_terrain(
    out: &rover_files::OutputDir,
    prepared: &Prepared,
    view: &PathGround,
    interrupted: bool,
) {
    let path = out.join(VIEW_TERRAIN);
    if interrupted {
        // Stopped by the user: no earlier run's ground left to pass for
        // this run's.
        let _ = out.write_whole(VIEW_TERRAIN, b"null");
        return;
    }
    let json = match (view.grid(), view.path().covered()) {
        (Some(grid), _) => Ok(grid_json(grid)),
        (None, None) => Err("run.csv has no rows".to_string()),
        // In free flight the run had no ground: the scenario's terrain
        // under the path.
        (None, Some((lo, hi))) => prepared
            .scenario
            .terrain
            .build(&prepared.base)
            .map(|terrain| path_terrain_json(&terrain, lo, hi))
            .map_err(|e| e.to_string()),
    };
    // Without the ground, `null`: an earlier run's terrain never passes
    // for this one's.
    let (json, why) = match json {
        Ok(j) => (j, None),
        Err(e) => ("null".to_string(), Some(e)),
    };
    let written = out.write_whole(VIEW_TERRAIN, json.as_bytes());
    if let Some(e) = why.or(written.err().map(|e| e.to_string())) {
        eprintln!(
            "warning: {}: no terrain for `rover view` ({e}); it draws flat ground unless given `--scenario`",
            path.display()
        );
    }
}

/// The ruts of a run's folder for `rover view`: its `ruts.csv` (read as
/// the folder holds it, not through a link) as one `ruts` message, or
/// `null` without one. A file that is not a rut grid is a warning, and no
/// ruts are drawn.
fn view_ruts(out: &Path) -> String {
    let path = out.join("ruts.csv");
    let grid = rover_files::read_entry(out, "ruts.csv", rover_files::Limit::Data)
        .map_err(|e| (e.kind() != std::io::ErrorKind::NotFound).then(|| e.to_string()))
        .and_then(|bytes| {
            let text = String::from_utf8(bytes).map_err(|_| Some("not UTF-8 text".to_string()))?;
            rover_terrain::csv_grid::parse_csv(&text, &path, None).map_err(|e| Some(e.to_string()))
        });
    match grid {
        Ok(grid) => rut_feed::RutFeed::of_grid(&grid)
            .message(0)
            .map_or_else(|| "null".to_string(), |(m, _)| m),
        Err(why) => {
            if let Some(e) = why {
                eprintln!("warning: {}: {e}; the ruts are not drawn", path.display());
            }
            "null".to_string()
        }
    }
}

/// A terrain file as [`terrain_json`] writes it (or `null`), checked
/// before it is served.
fn check_terrain(bytes: &[u8]) -> Result<String, String> {
    let v: serde_json::Value =
        serde_json::from_slice(bytes).map_err(|e| format!("not JSON: {e}"))?;
    if v.is_null() {
        return Ok("null".to_string());
    }
    let n = |k: &str| v.get(k).and_then(serde_json::Value::as_u64).unwrap_or(0);
    let z = v.get("z").and_then(serde_json::Value::as_array);
    let numbers = ["x0", "y0", "dx", "dy"]
        .iter()
        .all(|k| v.get(*k).is_some_and(serde_json::Value::is_number));
    match z {
        Some(z)
            if numbers
                && n("nx") >= 2
                && n("ny") >= 2
                && z.len() as u64 == n("nx") * n("ny")
                && z.iter().all(|h| h.is_null() || h.is_number()) =>
        {
            Ok(v.to_string())
        }
        _ => Err("not a grid of heights (x0, y0, dx, dy, nx, ny, z)".to_string()),
    }
}

/// Bind 127.0.0.1:`port`, with the reason when that fails.
fn bind(port: u16) -> Result<TcpListener, CliError> {
    TcpListener::bind(("127.0.0.1", port)).map_err(|e| {
        CliError::Drive(format!(
            "cannot listen on 127.0.0.1:{port}: {e}; give another `--port` (0 picks a free one)"
        ))
    })
}

/// Start `rover drive`: the loop on its own thread, the server on another.
pub fn start(args: &DriveArgs) -> Result<Running, CliError> {
    check_rate(args.rate)?;
    let who = Who {
        allowed: allowed_origins(&args.allow_origin)?,
        token: token(args)?,
    };
    let prepared = prepare(args)?;
    // Each kind of plant runs its own instance of the loop: a step calls
    // the generated plant without a second dispatch.
    match prepared.plant(args.generic)? {
        RunPlant::Generated(p) => launch(p, &prepared, args, who),
        RunPlant::Generic(p) => launch(p, &prepared, args, who),
    }
}

/// Who may connect to a `rover drive`, from its flags (checked before
/// anything is loaded or bound).
struct Who {
    allowed: Vec<String>,
    token: String,
}

fn launch<P: Plant + Clone + Send + 'static>(
    plant: P,
    prepared: &Prepared,
    args: &DriveArgs,
    who: Who,
) -> Result<Running, CliError> {
    let (spec, scenario, base) = (&prepared.spec, &prepared.scenario, &prepared.base);
    let model = &spec.model;
    let config = loop_config(args, scenario);
    let mut sim = sim(plant, prepared, &config, args.estimate)?;
    let columns = Arc::new(sim.columns().names().to_vec());
    let shared = sim.shared(args.rate);
    let info = sim.info().clone();
    let estimate = Arc::new(if args.estimate {
        ghost::columns(model.m(), model.wheels.len())
    } else {
        Vec::new()
    });
    let estimate_meta = sim.ghost().map(|g| {
        let (_, from) = estimate_sensors(scenario);
        json!({
            "sensors": from,
            "rate_hz": g.sensors().rate,
            "columns": estimate.as_slice(),
        })
    });
    let terrain = scenario.terrain.build(base).map_err(other)?;
    let start = [sim.y()[0], sim.y()[1]];
    #[cfg(feature = "mcap")]
    let foxglove =
        Arc::new(foxglove::FoxgloveFeed::new(spec, sim.columns(), &terrain, start).map_err(other)?);
    let listener = bind(args.port)?;
    let addr = listener.local_addr().map_err(other)?;
    let port = addr.port();
    let app = App::new(
        meta(
            "drive",
            Some(spec),
            &columns,
            Some(&info),
            Some((&config, &estimate)),
            estimate_meta,
        ),
        terrain_json(&terrain, start),
        Content::Drive {
            shared: shared.clone(),
            columns,
            estimate,
            info,
            rate_hz: args.rate,
            #[cfg(feature = "mcap")]
            foxglove,
        },
        Access::new(addr, &who.allowed, Some(who.token.clone())),
    );
    let server = Server::start(listener, app).map_err(other)?;
    let loop_shared = shared.clone();
    let sim = match std::thread::Builder::new()
        .name("rover-loop".into())
        .spawn(move || live::run(&mut sim, &loop_shared, None))
    {
        Ok(sim) => sim,
        Err(e) => {
            server.stop();
            return Err(other(e));
        }
    };
    Ok(Running {
        port,
        token: who.token,
        shared,
        sim,
        server,
    })
}

/// `rover drive`: serve until Ctrl-C (or, with `--report`, measure and print).
/// With `--report`, the measurement's text to print, and nothing served.
pub fn drive(args: &DriveArgs) -> Result<Option<String>, CliError> {
    if let Some(seconds) = args.report {
        return report(args, seconds).map(Some);
    }
    let running = start(args)?;
    let port = running.port;
    let shown = if args.token.is_some() || std::env::var_os("ROVER_DRIVE_TOKEN").is_some() {
        "<your token>"
    } else {
        running.token.as_str()
    };
    eprintln!(
        "driving at http://127.0.0.1:{port}/ (WebSocket at /ws; docs/DRIVE.md); Ctrl-C ends\n\
         a program (no Origin header) connects with the token: ws://127.0.0.1:{port}/ws?token={shown}"
    );
    let (tx, rx) = std::sync::mpsc::channel();
    // A second handler cannot be installed in one process; then only the
    // loop's own end stops the wait.
    let _ = ctrlc::set_handler(move || {
        let _ = tx.send(());
    });
    let _ = rx.recv();
    let timing = running.stop();
    eprintln!("{}", timing_text(&timing, args.rate));
    Ok(None)
}

/// The timing of a loop as a few lines of text.
pub fn timing_text(t: &Timing, rate: f64) -> String {
    let us = |s: f64| s * 1e6;
    format!(
        "{} steps at {rate} Hz in {:.1} s (simulated {:.2} s, real-time factor {:.3})\n\
         step computing time: median {:.0} µs, 99.9th percentile {:.0} µs, max {:.0} µs (period {:.0} µs)\n\
         start lateness (jitter): median {:.0} µs, 99th percentile {:.0} µs, 99.9th percentile {:.0} µs, max {:.0} µs{}\n\
         overruns: {} ({} ticks dropped){}",
        t.compute.count(),
        t.wall_s,
        t.simulated_s,
        if t.wall_s > 0.0 {
            t.simulated_s / t.wall_s
        } else {
            0.0
        },
        us(t.compute.quantile(0.5)),
        us(t.compute.quantile(0.999)),
        us(t.compute.max()),
        1e6 / rate,
        us(t.late.quantile(0.5)),
        us(t.late.quantile(0.99)),
        us(t.late.quantile(0.999)),
        us(t.late.max()),
        match t.spin_margin_s {
            Some(m) => format!(
                " (sleeping to {:.0} µs before each tick, then spinning)",
                us(m)
            ),
            None => String::new(),
        },
        t.overruns,
        t.dropped_ticks,
        match &t.error {
            Some(e) => format!("\nthe simulation stopped: {e}"),
            None => String::new(),
        },
    ) + &estimate_text(t)
}

/// With `--estimate`: what the sensor instants cost, and why the
/// estimation stopped if it did.
fn estimate_text(t: &Timing) -> String {
    let Some((cost, rate)) = &t.estimate else {
        return String::new();
    };
    let us = |s: f64| s * 1e6;
    format!(
        "\nestimator: {} sensor instants at {rate} Hz (readings, prediction, update): median {:.0} µs, 99.9th percentile {:.0} µs, max {:.0} µs{}",
        cost.count(),
        us(cost.quantile(0.5)),
        us(cost.quantile(0.999)),
        us(cost.max()),
        match &t.estimate_error {
            Some(e) => format!("\n{e}"),
            None => String::new(),
        }
    )
}

/// `--report`: the loop without a server, driving straight ahead.
pub fn report(args: &DriveArgs, seconds: f64) -> Result<String, CliError> {
    if !(seconds.is_finite() && seconds > 0.0) {
        return Err(CliError::Usage(format!(
            "--report {seconds:?}: seconds of driving, > 0"
        )));
    }
    check_rate(args.rate)?;
    let prepared = prepare(args)?;
    check_report_speed(args.report_speed, &RoverInfo::new(&prepared.spec.model))?;
    let config = loop_config(args, &prepared.scenario);
    let timing = match prepared.plant(args.generic)? {
        RunPlant::Generated(p) => measure(p, &prepared, &config, args, seconds)?,
        RunPlant::Generic(p) => measure(p, &prepared, &config, args, seconds)?,
    };
    Ok(format!(
        "{} with {}, pacing {}:\n{}\n",
        prepared.spec.name,
        config.method.name(),
        config.pacing.name(),
        timing_text(&timing, args.rate)
    ))
}

/// The loop of `--report` for `seconds` of wall-clock time.
fn measure<P: Plant + Clone + Send + 'static>(
    plant: P,
    prepared: &Prepared,
    config: &LoopConfig,
    args: &DriveArgs,
    seconds: f64,
) -> Result<Timing, CliError> {
    let mut sim = sim(plant, prepared, config, args.estimate)?;
    let shared = sim.shared(args.rate);
    if let Ok(mut inbox) = shared.inbox.lock() {
        let r = protocol::Request {
            speed: Some(args.report_speed),
            ..Default::default()
        };
        protocol::apply(&r, &mut inbox);
    }
    Ok(live::run(&mut sim, &shared, Some(seconds)))
}

/// The live simulation of a prepared run with `plant`, the one its
/// fidelity level names; with `estimate`, with the rover's own observer.
fn sim<P: Plant + Clone + Send + 'static>(
    plant: P,
    prepared: &Prepared,
    config: &LoopConfig,
    estimate: bool,
) -> Result<Sim<P>, CliError> {
    let (spec, scenario, base) = (&prepared.spec, &prepared.scenario, &prepared.base);
    let locate = |e| -> CliError { prepared.locate(e).into() };
    let sim = Sim::new(plant, &spec.model, scenario, base, config).map_err(locate)?;
    if !estimate {
        return Ok(sim);
    }
    let (sensors, _) = estimate_sensors(scenario);
    sim.with_estimate(&spec.model, scenario, base, &sensors)
        .map_err(locate)
}

/// `rover view`: serve the page animating `<out>/run.csv` until Ctrl-C.
pub fn view(args: &ViewArgs) -> Result<(), CliError> {
    let viewing = start_view(args)?;
    eprintln!(
        "viewing {} at http://127.0.0.1:{}/; Ctrl-C ends",
        args.out.join("run.csv").display(),
        viewing.port
    );
    let (tx, rx) = std::sync::mpsc::channel();
    let _ = ctrlc::set_handler(move || {
        let _ = tx.send(());
    });
    let _ = rx.recv();
    viewing.stop();
    Ok(())
}

/// Start `rover view`'s server.
pub fn start_view(args: &ViewArgs) -> Result<Viewing, CliError> {
    let allowed = allowed_origins(&args.allow_origin)?;
    // Read once, as the folder holds it (not through a link to elsewhere),
    // and served from memory: one copy whatever the number of clients.
    let csv = args.out.join("run.csv");
    let bytes = rover_files::read_entry(&args.out, "run.csv", rover_files::Limit::Data)
        .map_err(|e| CliError::io(&csv, "read", e))?;
    let text = String::from_utf8(bytes).map_err(|_| {
        CliError::Usage(format!(
            "{}: is not UTF-8 text: not a run.csv of `rover simulate`",
            csv.display()
        ))
    })?;
    let columns: Vec<String> = text
        .lines()
        .next()
        .unwrap_or("")
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    for c in ["t", "X", "Y", "Z", "phi", "theta", "psi", "W1X", "Fn1"] {
        if !columns.iter().any(|h| h == c) {
            return Err(CliError::Usage(format!(
                "{}: no column `{c}`: not a run.csv of `rover simulate`",
                csv.display()
            )));
        }
    }
    let name = args.rover.clone().or_else(|| {
        let s =
            rover_files::read_entry(&args.out, "summary.json", rover_files::Limit::Text).ok()?;
        let v: serde_json::Value = serde_json::from_slice(&s).ok()?;
        v.get("rover")?.as_str().map(str::to_string)
    });
    let spec = name.as_deref().and_then(|n| load_rover(n, None).ok());
    let info = spec.as_ref().map(|s| RoverInfo::new(&s.model));
    // The ground: the `--scenario`'s terrain under the path, else the
    // output folder's terrain.json, else none (the page draws a plane).
    let terrain = match &args.scenario {
        Some(p) => {
            let (scenario, base) = load_scenario(Some(p))?;
            let terrain = scenario.terrain.build(&base).map_err(other)?;
            let (lo, hi) = path_box(&text).unwrap_or(([0.0; 2], [0.0; 2]));
            path_terrain_json(&terrain, lo, hi)
        }
        None => match rover_files::read_entry(&args.out, VIEW_TERRAIN, rover_files::Limit::Text) {
            Ok(bytes) => check_terrain(&bytes).unwrap_or_else(|e| {
                eprintln!(
                    "warning: {}: {e}; the ground is drawn flat (give `--scenario` for the run's terrain)",
                    args.out.join(VIEW_TERRAIN).display()
                );
                "null".to_string()
            }),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                eprintln!(
                    "no {} in {}: the ground is drawn flat (give `--scenario` for the run's terrain)",
                    VIEW_TERRAIN,
                    args.out.display()
                );
                "null".to_string()
            }
            Err(e) => return Err(CliError::io(args.out.join(VIEW_TERRAIN), "read", e)),
        },
    };
    let listener = bind(args.port)?;
    let addr = listener.local_addr().map_err(other)?;
    let app = App::new(
        meta("view", spec.as_ref(), &columns, info.as_ref(), None, None),
        terrain,
        Content::View {
            csv: Arc::new(text.into_bytes()),
            ruts: view_ruts(&args.out),
        },
        // No WebSocket: no token.
        Access::new(addr, &allowed, None),
    );
    let port = addr.port();
    let server = Server::start(listener, app).map_err(other)?;
    Ok(Viewing { port, server })
}

#[cfg(test)]
mod tests {
    use super::push_tenths_of_mm;

    fn written(metres: f64) -> String {
        let mut s = String::new();
        push_tenths_of_mm(&mut s, metres);
        s
    }

    /// Four decimals, rounded to the nearest 0.1 mm, as `{:.4}` writes
    /// them away from ties; a height that rounds to zero carries no sign.
    #[test]
    fn heights_are_written_to_a_tenth_of_a_millimetre() {
        for (h, want) in [
            (0.0, "0.0000"),
            (0.25, "0.2500"),
            (-0.25, "-0.2500"),
            (0.123_44, "0.1234"),
            (0.123_46, "0.1235"),
            (-1.000_04, "-1.0000"),
            (-0.000_04, "0.0000"),
            (12.3, "12.3000"),
            (-3_456.789_01, "-3456.7890"),
        ] {
            assert_eq!(written(h), want, "{h}");
        }
        // Against the standard formatting over a sweep of heights away
        // from ties, and read back within half a tenth of a millimetre.
        for k in -2_000..2_000 {
            let h = k as f64 * 0.001_234_7 + 1e-7;
            let w = written(h);
            let want = format!("{h:.4}");
            let want = if want == "-0.0000" {
                "0.0000".into()
            } else {
                want
            };
            assert_eq!(w, want, "{h}");
            assert!((w.parse::<f64>().unwrap() - h).abs() <= 5e-5 + 1e-12, "{h}");
        }
    }
}
