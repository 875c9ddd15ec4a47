//! Parameter sweeps: a plan (a base scenario, a grid of values and/or
//! random samples, terrain seeds) expanded into numbered tasks, each one
//! run of the base scenario with some fields replaced. The expansion and
//! the record of each run live here, so that `rover sweep` (one indexed
//! task of a Slurm job array or a Kubernetes Indexed Job) and the Python
//! package's Ray sweep give the same tasks and the same table.
//!
//! The plan, in TOML (relative paths from the plan's folder):
//!
//! ```toml
//! scenario = "base.toml"   # the base scenario
//! rover = "swing4"         # optional: overrides the scenario's rover
//! out = "sweep-out"        # where the task records and the table go
//! seeds = [1, 2, 3]        # optional: each parameter set once per terrain.seed
//! samples = 20             # optional: random parameter sets drawn from [ranges]
//! sample_seed = 7          # the draw's seed (default 0)
//!
//! [grid]                   # every combination of these values
//! "control.speed.speed" = [0.05, 0.1]
//!
//! [ranges]                 # for samples: uniform in [low, high]
//! "control.speed.kp" = [5.0, 20.0]
//! ```
//!
//! A plan is checked whole before any task runs ([`Plan::check`]): at most
//! [`MAX_TASKS`] tasks, every value finite, every task's scenario one that
//! the scenario check accepts, seeds only on a random terrain.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use serde::Deserialize;

use crate::output::{WriteError, write_whole};
use crate::prepare::{PrepareError, Prepared, builtin_names, load_rover};
use crate::scenario::Scenario;

/// The most tasks a plan may have: a larger sweep is several plans (each
/// task's parameters are held in memory, and every worker checks them all).
pub const MAX_TASKS: usize = 1_000_000;

/// Why a sweep plan, or one of its tasks, cannot run.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// The plan (or its base scenario) cannot be read or does not hold.
    #[error("{}: {message}", file.display())]
    Plan {
        /// The file at fault.
        file: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A task number beyond the plan's.
    #[error("no task {index}: the plan has {tasks}")]
    NoTask {
        /// The task asked for.
        index: usize,
        /// The plan's number of tasks.
        tasks: usize,
    },
    /// A task's field cannot be set in the base scenario.
    #[error("task {index}: {message}")]
    Task {
        /// The task.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// A task's run could not be prepared or could not start.
    #[error("{0}")]
    Run(#[from] PrepareError),
    /// A file could not be written.
    #[error("{0}")]
    Write(#[from] WriteError),
    /// The gathered table lacks some tasks' results.
    #[error("{}", incomplete_message(.0))]
    Incomplete(Gathered),
}

/// What `--gather` says of a table that lacks results.
fn incomplete_message(g: &Gathered) -> String {
    let mut parts = Vec::new();
    if !g.missing.is_empty() {
        parts.push(format!(
            "{} missing ({})",
            g.missing.len(),
            list_tasks(g.missing.iter().copied())
        ));
    }
    if !g.unreadable.is_empty() {
        let shown: Vec<String> = g
            .unreadable
            .iter()
            .take(LISTED)
            .map(|(_, why)| why.clone())
            .collect();
        let more = g.unreadable.len().saturating_sub(LISTED);
        parts.push(format!(
            "{} unreadable ({}{})",
            g.unreadable.len(),
            shown.join("; "),
            if more > 0 {
                format!("; and {more} more")
            } else {
                String::new()
            }
        ));
    }
    format!(
        "{}: written, but {} of {} tasks have no result: {}\n  = help: run the workers again: they run every task without a record; delete an unreadable record to run its task again",
        g.table.display(),
        g.missing.len() + g.unreadable.len(),
        g.tasks,
        parts.join(", ")
    )
}

/// How many tasks a message lists by number before it counts the rest.
const LISTED: usize = 10;

/// `tasks 3, 5, 8` (the first [`LISTED`], then how many more).
fn list_tasks(tasks: impl ExactSizeIterator<Item = usize>) -> String {
    let n = tasks.len();
    let shown: Vec<String> = tasks.take(LISTED).map(|i| i.to_string()).collect();
    let word = if n == 1 { "task" } else { "tasks" };
    if n > LISTED {
        format!("{word} {} and {} more", shown.join(", "), n - LISTED)
    } else {
        format!("{word} {}", shown.join(", "))
    }
}

impl SweepError {
    /// The message as the command line prints it (see
    /// [`PrepareError::user_message`]).
    pub fn user_message(&self) -> String {
        match self {
            SweepError::Run(e) => e.user_message(),
            e => format!("error: {e}"),
        }
    }
}

/// A sweep plan as written (see the module's documentation).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanFile {
    /// The base scenario's path.
    pub scenario: PathBuf,
    /// A rover overriding the scenario's.
    #[serde(default)]
    pub rover: Option<String>,
    /// The results folder.
    #[serde(default = "default_out")]
    pub out: PathBuf,
    /// Terrain seeds: every parameter set runs once with each.
    #[serde(default)]
    pub seeds: Vec<i64>,
    /// The number of random parameter sets drawn from `ranges`.
    #[serde(default)]
    pub samples: usize,
    /// The seed of the random draw.
    #[serde(default)]
    pub sample_seed: u64,
    /// Values of each field, every combination taken.
    #[serde(default)]
    pub grid: toml::Table,
    /// `[low, high]` of each sampled field.
    #[serde(default)]
    pub ranges: toml::Table,
}

fn default_out() -> PathBuf {
    PathBuf::from("sweep-out")
}

/// A plan ready to run: its file, the base scenario's text, and the
/// tasks' parameters.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The plan as written.
    pub file: PlanFile,
    /// The base scenario, parsed as TOML.
    pub base: toml::Table,
    /// The base scenario's folder (its relative paths start there).
    pub base_dir: PathBuf,
    /// The base scenario's path, as messages name it.
    pub base_origin: PathBuf,
    /// The plan's path, as messages name it.
    pub origin: PathBuf,
    /// The results folder.
    pub out: PathBuf,
    /// Each task's fields and values, in task order.
    pub tasks: Vec<Vec<(String, toml::Value)>>,
}

/// A plan that cannot be run.
fn plan_err(origin: &Path, message: impl std::fmt::Display) -> SweepError {
    SweepError::Plan {
        file: origin.to_path_buf(),
        message: message.to_string(),
    }
}

impl Plan {
    /// Read the plan file at `path`.
    pub fn load(path: &Path) -> Result<Self, SweepError> {
        let text = rover_files::read_text(path, rover_files::Limit::Text)
            .map_err(|e| plan_err(path, format!("cannot read the plan: {e}")))?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::parse(&text, path, &dir)
    }

    /// A plan from its TOML `text`, named `origin`, paths from `dir`.
    pub fn parse(text: &str, origin: &Path, dir: &Path) -> Result<Self, SweepError> {
        Self::parse_with(text, origin, dir, None)
    }

    /// [`Plan::parse`], given the base scenario's text rather than reading
    /// its file: a worker on another machine, without the plan's folder,
    /// runs its tasks from the texts alone.
    pub fn parse_with(
        text: &str,
        origin: &Path,
        dir: &Path,
        base_text: Option<&str>,
    ) -> Result<Self, SweepError> {
        // toml's rendering ends in a line break; the message's printer adds one.
        let file: PlanFile =
            toml::from_str(text).map_err(|e| plan_err(origin, e.to_string().trim_end()))?;
        let base_origin = dir.join(&file.scenario);
        let base_text = match base_text {
            Some(t) => t.to_string(),
            None => {
                rover_files::read_text(&base_origin, rover_files::Limit::Text).map_err(|e| {
                    plan_err(origin, format!("scenario {}: {e}", base_origin.display()))
                })?
            }
        };
        let base: toml::Table = toml::from_str(&base_text).map_err(|e| {
            plan_err(
                &base_origin,
                format!("not a TOML table: {}", e.to_string().trim_end()),
            )
        })?;
        let base_dir = base_origin
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let out = dir.join(&file.out);
        let tasks = expand(&file).map_err(|m| plan_err(origin, m))?;
        Ok(Self {
            file,
            base,
            base_dir,
            base_origin,
            origin: origin.to_path_buf(),
            out,
            tasks,
        })
    }

    /// The scenario of task `index` as TOML text: the base with the task's
    /// fields replaced.
    pub fn scenario_text(&self, index: usize) -> Result<String, SweepError> {
        let params = self.tasks.get(index).ok_or(SweepError::NoTask {
            index,
            tasks: self.tasks.len(),
        })?;
        let table = with_fields(&self.base, params)
            .map_err(|(_, message)| SweepError::Task { index, message })?;
        toml::to_string(&table).map_err(|e| SweepError::Task {
            index,
            message: e.to_string(),
        })
    }

    /// Check that every task can start: each task's scenario passes the
    /// scenario check (the fields exist, each value has the field's type
    /// and range), names a rover that loads, and has a random terrain
    /// where `seeds` set its seed. Tasks that differ only in their seed
    /// are checked once. The error names the plan's field and value at
    /// fault (or the base scenario) and the task.
    ///
    /// Checks that need the rover's model built (the controllers' gains,
    /// the terrain's files) are left to the run: such a task's record says
    /// `error`.
    pub fn check(&self) -> Result<(), SweepError> {
        let per_set = self.file.seeds.len().max(1);
        let mut rovers: HashMap<String, Result<(), String>> = HashMap::new();
        for index in (0..self.tasks.len()).step_by(per_set) {
            let params = &self.tasks[index];
            let table = with_fields(&self.base, params).map_err(|(path, message)| {
                self.plan_err(format!("{}: {message}", self.source_of(path, params)))
            })?;
            if !self.file.seeds.is_empty() {
                self.check_random_terrain(index, &table)?;
            }
            if let Err(message) = scenario_check(&table) {
                return Err(self.plan_err(self.blame(index, &message)));
            }
            let rover = self.file.rover.clone().or_else(|| {
                table
                    .get("rover")
                    .and_then(|r| r.as_str())
                    .map(String::from)
            });
            let Some(rover) = rover else {
                return Err(self.plan_err(format!(
                    "task {index} names no rover: give `rover = \"...\"` in the plan or in the base scenario {} (built-in: {})",
                    self.base_origin.display(),
                    builtin_names()
                )));
            };
            let loaded = rovers.entry(rover.clone()).or_insert_with(|| {
                load_rover(&rover, Some(&self.base_dir))
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            });
            if let Err(e) = loaded {
                return Err(self.plan_err(format!(
                    "task {index}: rover `{rover}` cannot be loaded:\n{e}"
                )));
            }
        }
        Ok(())
    }

    /// `seeds` set `terrain.seed`, which only a random terrain has.
    fn check_random_terrain(&self, index: usize, table: &toml::Table) -> Result<(), SweepError> {
        let kind = table
            .get("terrain")
            .and_then(|t| t.as_table())
            .and_then(|t| t.get("kind"));
        if kind.and_then(|k| k.as_str()) == Some("random") {
            return Ok(());
        }
        let terrain = match kind {
            None => "flat (no `kind` in [terrain])".to_string(),
            Some(k) => format!("kind = {k}"),
        };
        Err(self.plan_err(format!(
            "seeds: each task sets terrain.seed, which only a random terrain has, but task {index}'s terrain is {terrain}\n  = help: give the base scenario {} a random terrain ([terrain] kind = \"random\", z_r = ...), or remove `seeds`",
            self.base_origin.display()
        )))
    }

    /// The error of a task whose scenario is refused, naming what is at
    /// fault: the base scenario when it is refused alike on its own, else
    /// the first of the task's fields that, set alone in the base, is
    /// refused alike, else the task's fields together.
    fn blame(&self, index: usize, message: &str) -> String {
        let params = &self.tasks[index];
        let refused_alike = |t: &toml::Table| scenario_check(t).err().as_deref() == Some(message);
        if refused_alike(&self.base) {
            return format!(
                "the base scenario {} is refused: {message}",
                self.base_origin.display()
            );
        }
        let alone = params.iter().find(|p| {
            with_fields(&self.base, std::slice::from_ref(*p)).is_ok_and(|t| refused_alike(&t))
        });
        let at_fault = match alone {
            Some((path, _)) => self.source_of(path, params),
            None => params
                .iter()
                .map(|(path, _)| self.source_of(path, params))
                .collect::<Vec<_>>()
                .join(" with "),
        };
        format!(
            "{at_fault}: task {index}'s scenario is refused: {message}\n  = help: every task of a plan must be a scenario that can run: correct the plan's field or value, then check it with `rover sweep <plan> --list`"
        )
    }

    /// Where a task's field comes from, with its value:
    /// `grid."terrain.z_r" = 0.2`, `ranges."control.speed.kp" (sampled: 7.5)`
    /// or `seeds (terrain.seed = 3)`.
    fn source_of(&self, path: &str, params: &[(String, toml::Value)]) -> String {
        let value = params
            .iter()
            .find(|(p, _)| p == path)
            .map(|(_, v)| v.to_string())
            .unwrap_or_default();
        if self.file.grid.contains_key(path) {
            format!("grid.\"{path}\" = {value}")
        } else if self.file.ranges.contains_key(path) {
            format!("ranges.\"{path}\" (sampled: {value})")
        } else {
            format!("seeds ({path} = {value})")
        }
    }

    fn plan_err(&self, message: impl std::fmt::Display) -> SweepError {
        plan_err(&self.origin, message)
    }

    /// Run task `index` and return its record (see [`record`]).
    pub fn run_task(&self, index: usize) -> serde_json::Value {
        let params = self.tasks.get(index).cloned().unwrap_or_default();
        let outcome = self.scenario_text(index).and_then(|text| {
            // Named by its task alone: the same message on every machine,
            // whatever the plan's folder there.
            let origin = PathBuf::from(format!("task {index}"));
            run_text(self.file.rover.as_deref(), &text, &origin, &self.base_dir)
                .map_err(SweepError::from)
        });
        record(index, &params, outcome)
    }

    /// Where task `index`'s record goes.
    pub fn task_path(&self, index: usize) -> PathBuf {
        self.out.join("tasks").join(format!("{index:06}.json"))
    }
}

/// Run a scenario given as text; the summary as JSON.
pub fn run_text(
    rover: Option<&str>,
    text: &str,
    origin: &Path,
    base_dir: &Path,
) -> Result<serde_json::Value, PrepareError> {
    let mut prepared = Prepared::from_text(rover, text, origin, base_dir)?;
    // A line of the generated text would point nowhere the user can see:
    // a run that cannot start names the field alone.
    prepared.text.clear();
    let never = AtomicBool::new(false);
    let summary = prepared.run(false, std::io::sink(), &never, |_| {})?;
    // A summary holds strings and finite numbers only: it always converts.
    Ok(serde_json::to_value(&summary).unwrap_or_default())
}

/// The record of one task: its number, its parameters (`param.<field>`),
/// its status (`completed`, `failed`, `embedded`, `interrupted`, or `error` for a run
/// that could not start), the error, and the summary's figures: every
/// number at its top level, the final state as `final.<coordinate>`, and
/// on a soil each wheel's slip and sinkage as `soil.mean_slip<j>` and the
/// like.
pub fn record(
    index: usize,
    params: &[(String, toml::Value)],
    outcome: Result<serde_json::Value, SweepError>,
) -> serde_json::Value {
    let mut r = serde_json::Map::new();
    r.insert("task".into(), index.into());
    for (path, value) in params {
        let v = serde_json::to_value(value).unwrap_or(serde_json::Value::Null);
        r.insert(format!("param.{path}"), v);
    }
    match outcome {
        Ok(summary) => {
            let status = summary.get("status").cloned().unwrap_or_default();
            r.insert("status".into(), status);
            r.insert(
                "error".into(),
                summary.get("error").cloned().unwrap_or_default(),
            );
            if let Some(map) = summary.as_object() {
                for (k, v) in map {
                    if v.is_number() {
                        r.insert(k.clone(), v.clone());
                    }
                }
                if let Some(fin) = map.get("final_state").and_then(|v| v.as_object()) {
                    for (k, v) in fin {
                        r.insert(format!("final.{k}"), v.clone());
                    }
                }
                // On a soil, each wheel's slip and sinkage as `soil.<field><j>`.
                for wheel in map
                    .get("soil")
                    .and_then(|v| v.as_array())
                    .into_iter()
                    .flatten()
                {
                    let Some(w) = wheel.as_object() else { continue };
                    let j = w.get("wheel").cloned().unwrap_or_default();
                    for (k, v) in w.iter().filter(|(k, v)| *k != "wheel" && v.is_number()) {
                        r.insert(format!("soil.{k}{j}"), v.clone());
                    }
                }
            }
        }
        Err(e) => {
            r.insert("status".into(), "error".into());
            r.insert("error".into(), e.user_message().into());
        }
    }
    serde_json::Value::Object(r)
}

/// `base` with each of `params` set; the error names the field that
/// cannot be set.
fn with_fields<'a>(
    base: &toml::Table,
    params: &'a [(String, toml::Value)],
) -> Result<toml::Table, (&'a str, String)> {
    let mut table = base.clone();
    for (path, value) in params {
        set_field(&mut table, path, value.clone()).map_err(|m| (path.as_str(), m))?;
    }
    Ok(table)
}

/// The scenario check of a task's scenario (as `rover simulate` checks a
/// file): its fields, their types and their values; the message when it
/// is refused.
fn scenario_check(table: &toml::Table) -> Result<(), String> {
    let scenario: Scenario = toml::Value::Table(table.clone())
        .try_into()
        .map_err(|e: toml::de::Error| {
            let message = e.message().trim_end().to_string();
            let help = if message.contains("unknown field") {
                "the fields each table accepts are listed above and in the doc of rover-scenario/src/scenario.rs"
            } else {
                "a scenario's fields and their types are in the doc of rover-scenario/src/scenario.rs"
            };
            format!("{message}\n  = help: {help}")
        })?;
    scenario.validate().map_err(|e| e.message)
}

/// Replace the field at dotted `path` (tables created as needed).
fn set_field(table: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), String> {
    let mut keys = path.split('.').peekable();
    let mut t = table;
    while let Some(k) = keys.next() {
        if keys.peek().is_none() {
            t.insert(k.to_string(), value);
            return Ok(());
        }
        let next = t
            .entry(k.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        t = next
            .as_table_mut()
            .ok_or_else(|| format!("`{path}`: `{k}` is not a table in the base scenario"))?;
    }
    Err(format!("`{path}`: an empty field name"))
}

/// A 64-bit mix (splitmix64's finalizer): the sampled values depend only
/// on the plan's seed, the sample and the field, so any worker draws them
/// alike and in any order.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) for (seed, sample, field).
fn uniform(seed: u64, sample: usize, field: usize) -> f64 {
    let h = mix(mix(mix(seed) ^ sample as u64) ^ field as u64);
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// The tasks of a plan: every grid combination, times every sample, times
/// every seed (each factor one empty set when absent). The plan's fields,
/// values and size are checked before anything is allocated.
fn expand(file: &PlanFile) -> Result<Vec<Vec<(String, toml::Value)>>, String> {
    for (section, table) in [("grid", &file.grid), ("ranges", &file.ranges)] {
        for path in table.keys() {
            if path.split('.').any(str::is_empty) {
                return Err(format!(
                    "{section}.\"{path}\": not a field: give a dotted path into the scenario without empty parts, e.g. \"control.speed.kp\""
                ));
            }
        }
    }
    if let Some(path) = file.grid.keys().find(|p| file.ranges.contains_key(*p)) {
        return Err(format!(
            "\"{path}\" is both in [grid] and in [ranges]: give each field one source of values"
        ));
    }
    if !file.seeds.is_empty() {
        for (section, table) in [("grid", &file.grid), ("ranges", &file.ranges)] {
            if table.contains_key("terrain.seed") {
                return Err(format!(
                    "{section}.\"terrain.seed\" and `seeds` both set the terrain's seed: keep one of them"
                ));
            }
        }
        if let Some(s) = file.seeds.iter().find(|s| **s < 0) {
            return Err(format!(
                "seeds: {s} is not a terrain seed: give integers ≥ 0"
            ));
        }
    }
    let mut grid = Vec::new();
    for (path, values) in &file.grid {
        let values = values
            .as_array()
            .filter(|a| !a.is_empty())
            .ok_or_else(|| format!("grid.\"{path}\": give a non-empty list of values"))?;
        if let Some(v) = values.iter().find_map(non_finite) {
            return Err(format!(
                "grid.\"{path}\": {v} is not a finite number: every value a plan sets must be finite"
            ));
        }
        grid.push((path, values));
    }
    let mut ranges = Vec::new();
    for (path, r) in &file.ranges {
        let pair: Option<Vec<f64>> = r.as_array().and_then(|a| {
            a.iter()
                .map(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
                .collect()
        });
        match pair.as_deref() {
            Some(&[lo, hi]) if lo.is_finite() && hi.is_finite() && lo <= hi => {
                if !(hi - lo).is_finite() {
                    return Err(format!(
                        "ranges.\"{path}\": [{lo:e}, {hi:e}] is wider than the largest number (its width {:e} overflows): give a narrower range",
                        hi - lo
                    ));
                }
                ranges.push((path.clone(), lo, hi));
            }
            _ => {
                return Err(format!(
                    "ranges.\"{path}\": give [low, high], finite, low ≤ high"
                ));
            }
        }
    }
    if file.samples > 0 && ranges.is_empty() {
        return Err("`samples` needs `[ranges]`: the fields to draw and their [low, high]".into());
    }
    if file.samples == 0 && !ranges.is_empty() {
        return Err("`[ranges]` needs `samples = N`: how many sets to draw".into());
    }
    task_count(file, &grid)?;

    let mut sets: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (path, values) in grid {
        sets = sets
            .iter()
            .flat_map(|s| {
                values.iter().map(move |v| {
                    let mut s = s.clone();
                    s.push((path.clone(), v.clone()));
                    s
                })
            })
            .collect();
    }
    if file.samples > 0 {
        sets = sets
            .iter()
            .flat_map(|s| {
                let ranges = &ranges;
                (0..file.samples).map(move |j| {
                    let mut s = s.clone();
                    for (f, (path, lo, hi)) in ranges.iter().enumerate() {
                        let u = uniform(file.sample_seed, j, f);
                        s.push((path.clone(), toml::Value::Float(lo + u * (hi - lo))));
                    }
                    s
                })
            })
            .collect();
    }
    if !file.seeds.is_empty() {
        sets = sets
            .iter()
            .flat_map(|s| {
                file.seeds.iter().map(move |&seed| {
                    let mut s = s.clone();
                    s.push(("terrain.seed".into(), toml::Value::Integer(seed)));
                    s
                })
            })
            .collect();
    }
    Ok(sets)
}

/// The number of tasks of a plan (at most [`MAX_TASKS`]), counted without
/// allocating them; the error names each factor.
fn task_count(file: &PlanFile, grid: &[(&String, &Vec<toml::Value>)]) -> Result<usize, String> {
    let mut factors: Vec<(String, usize)> = grid
        .iter()
        .map(|(path, values)| (format!("grid.\"{path}\""), values.len()))
        .collect();
    if file.samples > 0 {
        factors.push(("samples".into(), file.samples));
    }
    if !file.seeds.is_empty() {
        factors.push(("seeds".into(), file.seeds.len()));
    }
    let total = factors
        .iter()
        .try_fold(1usize, |n, (_, k)| n.checked_mul(*k));
    match total {
        Some(n) if n <= MAX_TASKS => Ok(n),
        _ => {
            let product = factors
                .iter()
                .map(|(field, k)| format!("{k} ({field})"))
                .collect::<Vec<_>>()
                .join(" × ");
            let size = match total {
                Some(n) => n.to_string(),
                None => "more than 2^64".into(),
            };
            Err(format!(
                "the plan has {size} tasks: {product}; a plan has at most {MAX_TASKS}\n  = help: fewer values in [grid], fewer samples or fewer seeds; a larger sweep is several plans, each with its own `out`"
            ))
        }
    }
}

/// The first number in `v` (or in the arrays and tables it holds) that is
/// not finite.
fn non_finite(v: &toml::Value) -> Option<f64> {
    match v {
        toml::Value::Float(f) if !f.is_finite() => Some(*f),
        toml::Value::Array(a) => a.iter().find_map(non_finite),
        toml::Value::Table(t) => t.values().find_map(non_finite),
        _ => None,
    }
}

/// The tasks that worker `index` of `count` runs: every `count`-th from
/// `index`, so that workers of a job array share the plan evenly.
pub fn worker_tasks(total: usize, index: usize, count: usize) -> impl Iterator<Item = usize> {
    (index..total).step_by(count.max(1))
}

/// A gathered table: where it was written, and the tasks without a
/// result in it.
#[derive(Clone, Debug, PartialEq)]
pub struct Gathered {
    /// `results.csv`.
    pub table: PathBuf,
    /// The plan's number of tasks.
    pub tasks: usize,
    /// Tasks with no record (rows with status `missing`).
    pub missing: Vec<usize>,
    /// Tasks whose record exists but cannot be read or is not a record,
    /// with the record's path and the reason (rows with status
    /// `unreadable`).
    pub unreadable: Vec<(usize, String)>,
}

impl Gathered {
    /// Whether every task has its record in the table.
    pub fn complete(&self) -> bool {
        self.missing.is_empty() && self.unreadable.is_empty()
    }
}

/// Gather every task record under the plan's folder into one CSV table,
/// one row per task, the columns the union of the records' fields (the
/// task number first, then the parameters, status and error, then the
/// figures). A task with no record yet is a row with status `missing`; a
/// record that cannot be read, or is not a JSON object, a row with status
/// `unreadable` and the reason as its error (both with the task's
/// parameters). The table is written either
/// way; [`Gathered`] says which tasks it lacks.
pub fn gather_csv(plan: &Plan) -> Result<Gathered, SweepError> {
    let mut rows = Vec::new();
    let mut missing = Vec::new();
    let mut unreadable = Vec::new();
    for i in 0..plan.tasks.len() {
        let path = plan.task_path(i);
        let read = match rover_files::read_text(&path, rover_files::Limit::Data) {
            Ok(text) => match serde_json::from_str::<serde_json::Value>(&text) {
                Ok(v) if v.is_object() => Ok(v),
                Ok(_) => Err("not a task record (a JSON object)".to_string()),
                Err(e) => Err(format!("not JSON: {e}")),
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                missing.push(i);
                rows.push(record_stand_in(i, &plan.tasks[i], "missing", None));
                continue;
            }
            Err(e) => Err(format!("cannot read it: {e}")),
        };
        let row = read.unwrap_or_else(|why| {
            let why = format!("{}: {why}", path.display());
            unreadable.push((i, why.clone()));
            record_stand_in(i, &plan.tasks[i], "unreadable", Some(why))
        });
        rows.push(row);
    }
    let mut columns: Vec<String> = vec!["task".into()];
    let rank = |c: &str| match c {
        "task" => 0,
        c if c.starts_with("param.") => 1,
        "status" => 2,
        "error" => 3,
        _ => 4,
    };
    for r in &rows {
        if let Some(m) = r.as_object() {
            for k in m.keys() {
                if !columns.contains(k) {
                    columns.push(k.clone());
                }
            }
        }
    }
    columns.sort_by_key(|c| rank(c));
    let mut out = String::new();
    out.push_str(
        &columns
            .iter()
            .map(|c| csv_field(c))
            .collect::<Vec<_>>()
            .join(","),
    );
    out.push('\n');
    for r in &rows {
        let cells: Vec<String> = columns
            .iter()
            .map(|c| match r.get(c) {
                None | Some(serde_json::Value::Null) => String::new(),
                Some(serde_json::Value::String(s)) => csv_field(s),
                Some(v) => csv_field(&v.to_string()),
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    let path = plan.out.join("results.csv");
    write_whole(&path, &out)?;
    Ok(Gathered {
        table: path,
        tasks: plan.tasks.len(),
        missing,
        unreadable,
    })
}

/// The row of a task without a readable record: its number, its
/// parameters (from the plan), `status` and `error`.
fn record_stand_in(
    index: usize,
    params: &[(String, toml::Value)],
    status: &str,
    error: Option<String>,
) -> serde_json::Value {
    let mut r = serde_json::Map::new();
    r.insert("task".into(), index.into());
    for (path, value) in params {
        let v = serde_json::to_value(value).unwrap_or(serde_json::Value::Null);
        r.insert(format!("param.{path}"), v);
    }
    r.insert("status".into(), status.into());
    if let Some(e) = error {
        r.insert("error".into(), e.into());
    }
    serde_json::Value::Object(r)
}

/// A CSV cell, quoted when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(text: &str) -> PlanFile {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn a_grid_times_seeds_gives_every_combination_in_order() {
        let f = file("scenario = \"s.toml\"\nseeds = [1, 2]\n[grid]\n\"a.b\" = [1.0, 2.0, 3.0]\n");
        let tasks = expand(&f).unwrap();
        assert_eq!(tasks.len(), 6);
        assert_eq!(tasks[0][0], ("a.b".to_string(), toml::Value::Float(1.0)));
        assert_eq!(
            tasks[1][1],
            ("terrain.seed".to_string(), toml::Value::Integer(2))
        );
        assert_eq!(tasks[5][0], ("a.b".to_string(), toml::Value::Float(3.0)));
    }

    #[test]
    fn samples_lie_in_their_range_and_depend_only_on_the_seed() {
        let f = file(
            "scenario = \"s.toml\"\nsamples = 50\nsample_seed = 3\n[ranges]\nk = [5.0, 20.0]\n",
        );
        let a = expand(&f).unwrap();
        assert_eq!(a, expand(&f).unwrap());
        let values: Vec<f64> = a.iter().map(|s| s[0].1.as_float().unwrap()).collect();
        assert!(values.iter().all(|v| (5.0..20.0).contains(v)));
        assert!(values.windows(2).any(|w| w[0] != w[1]));
        let other = file(
            "scenario = \"s.toml\"\nsamples = 50\nsample_seed = 4\n[ranges]\nk = [5.0, 20.0]\n",
        );
        assert_ne!(a, expand(&other).unwrap());
    }

    #[test]
    fn a_bad_grid_or_range_is_an_error_naming_it() {
        let e = expand(&file("scenario = \"s\"\n[grid]\nx = 1.0\n")).unwrap_err();
        assert!(e.contains("grid.\"x\""), "{e}");
        let e = expand(&file(
            "scenario = \"s\"\nsamples = 2\n[ranges]\nx = [2.0, 1.0]\n",
        ))
        .unwrap_err();
        assert!(e.contains("ranges.\"x\""), "{e}");
    }

    #[test]
    fn a_plan_beyond_the_task_limit_is_refused_before_it_is_expanded() {
        // 10^18 samples: refused at once, without a task allocated.
        let e = expand(&file(
            "scenario = \"s\"\nsamples = 1000000000000000000\n[ranges]\nx = [0.0, 1.0]\n",
        ))
        .unwrap_err();
        assert!(e.contains("1000000000000000000 (samples)"), "{e}");
        assert!(e.contains("at most 1000000"), "{e}");
        // A 10^12-point grid, and one whose size overflows.
        let values = format!("[{}]", vec!["1.0"; 10_000].join(", "));
        let grid = |n: usize| -> String { (0..n).map(|i| format!("f{i} = {values}\n")).collect() };
        let e = expand(&file(&format!("scenario = \"s\"\n[grid]\n{}", grid(3)))).unwrap_err();
        assert!(e.contains("has 1000000000000 tasks"), "{e}");
        assert!(
            e.contains("10000 (grid.\"f0\") × 10000 (grid.\"f1\")"),
            "{e}"
        );
        let e = expand(&file(&format!(
            "scenario = \"s\"\nseeds = [1, 2]\n[grid]\n{}",
            grid(5)
        )))
        .unwrap_err();
        assert!(e.contains("more than 2^64 tasks"), "{e}");
        assert!(e.ends_with("each with its own `out`"), "{e}");
        // At the limit: accepted.
        let f = file("scenario = \"s\"\nsamples = 1000000\n[ranges]\nx = [0.0, 1.0]\n");
        assert_eq!(expand(&f).unwrap().len(), MAX_TASKS);
    }

    #[test]
    fn every_value_a_plan_sets_is_finite() {
        let e = expand(&file(
            "scenario = \"s\"\nsamples = 2\n[ranges]\nx = [-1e308, 1e308]\n",
        ))
        .unwrap_err();
        assert!(
            e.starts_with("ranges.\"x\": [-1e308, 1e308] is wider"),
            "{e}"
        );
        for v in ["inf", "-inf", "nan", "[0.0, inf]"] {
            let e = expand(&file(&format!(
                "scenario = \"s\"\n[grid]\n\"initial.xy\" = [{v}]\n"
            )))
            .unwrap_err();
            assert!(e.starts_with("grid.\"initial.xy\": "), "{e}");
            assert!(e.contains("is not a finite number"), "{e}");
        }
        // The widest range that holds: every draw finite.
        let f = file("scenario = \"s\"\nsamples = 100\n[ranges]\nx = [-8e307, 8e307]\n");
        assert!(
            expand(&f)
                .unwrap()
                .iter()
                .all(|t| t[0].1.as_float().unwrap().is_finite())
        );
    }

    #[test]
    fn fields_set_twice_or_without_a_name_and_negative_seeds_are_refused() {
        let e = expand(&file("scenario = \"s\"\n[grid]\n\"a..b\" = [1]\n")).unwrap_err();
        assert!(e.starts_with("grid.\"a..b\": not a field"), "{e}");
        let e = expand(&file(
            "scenario = \"s\"\nsamples = 1\n[grid]\nx = [1.0]\n[ranges]\nx = [0.0, 1.0]\n",
        ))
        .unwrap_err();
        assert!(e.contains("\"x\" is both in [grid] and in [ranges]"), "{e}");
        let e = expand(&file(
            "scenario = \"s\"\nseeds = [1]\n[grid]\n\"terrain.seed\" = [2]\n",
        ))
        .unwrap_err();
        assert!(e.contains("both set the terrain's seed"), "{e}");
        let e = expand(&file("scenario = \"s\"\nseeds = [3, -1]\n")).unwrap_err();
        assert_eq!(e, "seeds: -1 is not a terrain seed: give integers ≥ 0");
    }

    const BASE: &str = "rover = \"swing4\"\nduration = 1.0\n[terrain]\nkind = \"random\"\nz_r = 0.2\n[control.speed]\nspeed = 0.1\n";

    fn checked(plan: &str, base: &str) -> Result<Plan, String> {
        let plan = Plan::parse_with(plan, Path::new("plan.toml"), Path::new("."), Some(base))
            .map_err(|e| e.to_string())?;
        plan.check().map_err(|e| e.to_string())?;
        Ok(plan)
    }

    #[test]
    fn a_plan_whose_tasks_can_run_passes_the_check() {
        let plan = checked(
            "scenario = \"b.toml\"\nseeds = [1, 2]\nsamples = 3\n[grid]\n\"control.speed.kp\" = [1.0, 5]\n\
             [ranges]\n\"terrain.z_r\" = [0.1, 0.3]\n",
            BASE,
        )
        .unwrap();
        assert_eq!(plan.tasks.len(), 12);
    }

    #[test]
    fn a_field_the_scenario_does_not_have_is_refused_naming_what_exists() {
        let e = checked(
            "scenario = \"b.toml\"\n[grid]\n\"control.speed.kpp\" = [1.0]\n",
            BASE,
        )
        .unwrap_err();
        assert!(
            e.starts_with("plan.toml: grid.\"control.speed.kpp\" = 1.0: task 0's scenario is refused: unknown field `kpp`, expected one of"),
            "{e}"
        );
        assert!(e.contains("`kp`"), "{e}");
    }

    #[test]
    fn a_value_the_field_does_not_take_is_refused_naming_it_and_its_task() {
        let e = checked(
            "scenario = \"b.toml\"\n[grid]\n\"control.speed.kp\" = [1.0, 2.0]\nduration = [1.0, -2.0]\n",
            BASE,
        )
        .unwrap_err();
        assert!(
            e.starts_with("plan.toml: grid.\"duration\" = -2.0: task 1's scenario is refused: duration must be > 0, got -2"),
            "{e}"
        );
        // A sampled float where the field takes an integer.
        let e = checked(
            "scenario = \"b.toml\"\nsamples = 2\n[ranges]\n\"contact.samples\" = [5, 90]\n",
            BASE,
        )
        .unwrap_err();
        assert!(
            e.starts_with("plan.toml: ranges.\"contact.samples\" (sampled: "),
            "{e}"
        );
        assert!(e.contains("invalid type: floating point"), "{e}");
        // Refused only together: both fields named.
        let e = checked(
            "scenario = \"b.toml\"\n[grid]\nduration = [0.5]\nsettle = [0.8]\n",
            BASE,
        )
        .unwrap_err();
        assert!(
            e.starts_with("plan.toml: grid.\"duration\" = 0.5 with grid.\"settle\" = 0.8: task 0's scenario is refused: settle must lie in [0, duration]"),
            "{e}"
        );
        // A base the scenario check refuses on its own is named as such.
        let e = checked(
            "scenario = \"b.toml\"\n[grid]\n\"control.speed.kp\" = [1.0]\n",
            &BASE.replace("duration = 1.0", "duration = 0.0"),
        )
        .unwrap_err();
        assert!(
            e.starts_with("plan.toml: the base scenario ./b.toml is refused: duration must be > 0"),
            "{e}"
        );
    }

    #[test]
    fn seeds_on_a_terrain_that_is_not_random_are_refused() {
        let flat = "rover = \"swing4\"\nduration = 1.0\n";
        let e = checked("scenario = \"b.toml\"\nseeds = [1, 2]\n", flat).unwrap_err();
        assert!(
            e.starts_with("plan.toml: seeds: each task sets terrain.seed, which only a random terrain has, but task 0's terrain is flat"),
            "{e}"
        );
        assert!(e.contains("kind = \"random\""), "{e}");
        // A grid of terrain kinds: the task with the slope is named.
        let e = checked(
            "scenario = \"b.toml\"\nseeds = [1]\n[grid]\n\"terrain.kind\" = [\"random\", \"slope\"]\n",
            BASE,
        )
        .unwrap_err();
        assert!(e.contains("task 1's terrain is kind = \"slope\""), "{e}");
    }

    #[test]
    fn a_task_without_a_rover_or_with_one_that_does_not_load_is_refused() {
        let e = checked("scenario = \"b.toml\"\n", "duration = 1.0\n").unwrap_err();
        assert!(e.contains("task 0 names no rover"), "{e}");
        let e = checked(
            "scenario = \"b.toml\"\n[grid]\nrover = [\"swing4\", \"no-such-rover.toml\"]\n",
            BASE,
        )
        .unwrap_err();
        assert!(
            e.contains("task 1: rover `no-such-rover.toml` cannot be loaded"),
            "{e}"
        );
    }

    #[test]
    fn workers_share_the_tasks_without_overlap() {
        let mut seen: Vec<usize> = (0..3).flat_map(|i| worker_tasks(10, i, 3)).collect();
        seen.sort();
        assert_eq!(seen, (0..10).collect::<Vec<_>>());
    }
}
