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

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use serde::Deserialize;

use crate::output::{WriteError, write_whole};
use crate::prepare::{PrepareError, Prepared};

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
        let text = std::fs::read_to_string(path).map_err(|e| plan_err(path, e))?;
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
        let file: PlanFile = toml::from_str(text).map_err(|e| plan_err(origin, e))?;
        let base_origin = dir.join(&file.scenario);
        let base_text = match base_text {
            Some(t) => t.to_string(),
            None => std::fs::read_to_string(&base_origin).map_err(|e| {
                plan_err(origin, format!("scenario {}: {e}", base_origin.display()))
            })?,
        };
        let base: toml::Table = toml::from_str(&base_text)
            .map_err(|e| plan_err(&base_origin, format!("not a TOML table: {e}")))?;
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
        let mut table = self.base.clone();
        for (path, value) in params {
            set_field(&mut table, path, value.clone())
                .map_err(|message| SweepError::Task { index, message })?;
        }
        toml::to_string(&table).map_err(|e| SweepError::Task {
            index,
            message: e.to_string(),
        })
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
/// every seed (each factor one empty set when absent).
fn expand(file: &PlanFile) -> Result<Vec<Vec<(String, toml::Value)>>, String> {
    let mut sets: Vec<Vec<(String, toml::Value)>> = vec![Vec::new()];
    for (path, values) in &file.grid {
        let values = values
            .as_array()
            .filter(|a| !a.is_empty())
            .ok_or_else(|| format!("grid.\"{path}\": give a non-empty list of values"))?;
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
        if file.ranges.is_empty() {
            return Err(
                "`samples` needs `[ranges]`: the fields to draw and their [low, high]".into(),
            );
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
                    ranges.push((path.clone(), lo, hi));
                }
                _ => {
                    return Err(format!(
                        "ranges.\"{path}\": give [low, high], finite, low ≤ high"
                    ));
                }
            }
        }
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
    } else if !file.ranges.is_empty() {
        return Err("`[ranges]` needs `samples = N`: how many sets to draw".into());
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

/// The tasks that worker `index` of `count` runs: every `count`-th from
/// `index`, so that workers of a job array share the plan evenly.
pub fn worker_tasks(total: usize, index: usize, count: usize) -> impl Iterator<Item = usize> {
    (index..total).step_by(count.max(1))
}

/// Gather every task record under the plan's folder into one CSV table,
/// one row per task, the columns the union of the records' fields (the
/// task number first, then the parameters, status and error, then the
/// figures). A task with no record yet is a row with status `missing`.
pub fn gather_csv(plan: &Plan) -> Result<PathBuf, SweepError> {
    let mut rows = Vec::new();
    for i in 0..plan.tasks.len() {
        let path = plan.task_path(i);
        let row = match std::fs::read_to_string(&path) {
            Ok(text) => {
                serde_json::from_str::<serde_json::Value>(&text).map_err(|e| plan_err(&path, e))?
            }
            Err(_) => serde_json::json!({"task": i, "status": "missing"}),
        };
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
    Ok(path)
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
    fn workers_share_the_tasks_without_overlap() {
        let mut seen: Vec<usize> = (0..3).flat_map(|i| worker_tasks(10, i, 3)).collect();
        seen.sort();
        assert_eq!(seen, (0..10).collect::<Vec<_>>());
    }
}
