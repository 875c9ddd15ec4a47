//! The native half of the Python package `rover`: loading rovers, whole
//! runs (with their sensor logs), sensor logs estimated, step-wise runs
//! and sweep tasks, all through `rover-scenario`'s preparation of a run,
//! and the single-wheel testbed through `rover-runtime`'s, as the command
//! line runs them, so that Python gets the command line's numbers and
//! messages. The Python half (python/rover/) turns what crosses here into
//! numpy arrays, dicts and tables.
//!
//! Arrays cross as buffers: numpy arrays come in through the buffer
//! protocol (read or written in place, no copy held), whole trajectories go
//! out as bytes that numpy views. Long work runs with the interpreter
//! released, so other Python threads (and Ray's) go on meanwhile; it takes
//! the interpreter back every 50 ms (`SIGNAL_POLL`) to run Python's signal
//! handlers, so that Ctrl-C stops it (see `Signals`).

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use pyo3::create_exception;
use pyo3::exceptions::PyBaseException;
use pyo3::exceptions::{PyException, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use rover_runtime::row::Columns;
use rover_scenario::Stepper;
use rover_scenario::prepare::{PrepareError, Prepared, RunPlant, load_rover};
use rover_scenario::sweep::{Plan, SweepError};

create_exception!(
    _native,
    RoverError,
    PyException,
    "A rover, scenario or plan that cannot run; the message is the command line's, located at the offending file, line and field."
);
create_exception!(
    _native,
    RunFailed,
    RoverError,
    "A step-wise run failed (the integrator gave up, the rover rolled over or left the map); reset() starts it again."
);

/// A run that cannot be prepared, as the exception the Python side raises
/// (the command line's message).
fn py_err(e: PrepareError) -> PyErr {
    RoverError::new_err(e.user_message())
}

/// A sweep that cannot run, likewise.
fn sweep_err(e: SweepError) -> PyErr {
    RoverError::new_err(e.user_message())
}

/// How often long work, run with the interpreter released, takes it back
/// to run Python's signal handlers.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Python's signal handlers, run from work that released the interpreter:
/// [`Signals::poll`] takes the interpreter back at most every
/// [`SIGNAL_POLL`] and runs them (`Python::check_signals`; handlers run on
/// the main thread only, elsewhere this does nothing). The exception a
/// handler raises (KeyboardInterrupt for Ctrl-C) is kept for the caller to
/// raise once the work has stopped where it stands.
struct Signals {
    last: Instant,
    raised: Option<PyErr>,
}

impl Signals {
    fn new() -> Self {
        Self {
            last: Instant::now(),
            raised: None,
        }
    }

    /// Whether a handler raised (now or before): the work should stop.
    fn poll(&mut self) -> bool {
        if self.raised.is_none() && self.last.elapsed() >= SIGNAL_POLL {
            self.last = Instant::now();
            self.raised = Python::attach(|py| py.check_signals()).err();
        }
        self.raised.is_some()
    }
}

/// A loaded rover: its description, and the name or path it came from
/// (a built-in name also picks its generated plant, as on the CLI).
#[pyclass(frozen, module = "rover._native")]
struct Rover {
    spec: rover_spec::Spec,
    key: String,
    text: bool,
}

#[pymethods]
impl Rover {
    /// The rover's name.
    #[getter]
    fn name(&self) -> String {
        self.spec.name.clone()
    }
    /// Number of generalized coordinates N.
    #[getter]
    fn dof(&self) -> usize {
        self.spec.model.dof()
    }
    /// The suspension coordinates' names, y1 ... in the state.
    #[getter]
    fn coordinate_names(&self) -> Vec<String> {
        self.spec.coordinate_names.clone()
    }
    /// The wheels' names, in the description's order (the order of every
    /// per-wheel command).
    #[getter]
    fn wheel_names(&self) -> Vec<String> {
        self.spec.wheel_names.clone()
    }
    /// Each wheel's motor torque limit [N·m].
    #[getter]
    fn max_torque(&self) -> Vec<f64> {
        self.spec
            .model
            .wheels
            .iter()
            .map(|w| w.max_torque)
            .collect()
    }
    /// Whether each wheel steers.
    #[getter]
    fn steerable(&self) -> Vec<bool> {
        self.spec.model.wheels.iter().map(|w| w.steerable).collect()
    }
    /// What `rover check` prints.
    fn report(&self) -> String {
        rover_spec::report::check_report(&self.spec)
    }
    /// What the rover was loaded from: a built-in name, a path, or a
    /// description's TOML text.
    #[getter]
    fn source(&self) -> String {
        self.key.clone()
    }
    /// Pickled as what it was loaded from, loaded again on unpickling.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, bool))> {
        let load = slf.py().import("rover._native")?.getattr("load")?;
        let r = slf.get();
        Ok((load, (r.key.clone(), r.text)))
    }
    fn __repr__(&self) -> String {
        format!(
            "<rover {} ({} DOF, {} wheels)>",
            self.spec.name,
            self.spec.model.dof(),
            self.spec.model.wheels.len()
        )
    }
}

/// Load a rover: a built-in name, a description file, or a description's
/// TOML text; `text` says which of text (true) or a name or path (false)
/// `source` is, else a line break (which no name has) tells them apart.
/// `origin` names text in messages (default `<string>`).
#[pyfunction]
#[pyo3(signature = (source, text=None, origin=None))]
fn load(source: &str, text: Option<bool>, origin: Option<&str>) -> PyResult<Rover> {
    let text = text.unwrap_or_else(|| source.contains('\n'));
    let spec = if text {
        rover_spec::load_str(source, origin.unwrap_or("<string>"))
    } else {
        load_rover(source, None)
    };
    let spec = spec.map_err(|e| py_err(e.into()))?;
    Ok(Rover {
        spec,
        key: source.to_string(),
        text,
    })
}

/// The scenario, ready to run: from TOML `text` named `origin` in
/// messages, relative paths from `base`; `rover` overrides its rover.
fn prepare(
    rover: Option<&Rover>,
    text: &str,
    origin: &str,
    base: &str,
) -> Result<Prepared, PrepareError> {
    let (origin, base) = (Path::new(origin), Path::new(base));
    match rover {
        None => Prepared::from_text(None, text, origin, base),
        Some(r) => Prepared::with_rover(r.spec.clone(), &r.key, text, origin, base),
    }
}

/// A table of numbers as it crosses to Python: its column names, its
/// values as native-endian f64 bytes (row after row, or column after
/// column), and its row count.
type Table<'py> = (Vec<String>, Bound<'py, PyBytes>, usize);

/// How a table's values are laid out in its bytes.
#[derive(Clone, Copy, PartialEq)]
enum Layout {
    /// Row after row (an array of shape (rows, columns)).
    Rows,
    /// Column after column (shape (columns, rows): each column
    /// contiguous).
    Columns,
}

/// A CSV written by the library (a header, then numbers in their
/// shortest exact form, which parse back to the computed values bit for
/// bit) as a [`Table`]. An empty cell (a fix not due in a sensor log)
/// reads NaN where `empty` allows it, else it is an error like any cell
/// that is not a number.
fn csv_table<'py>(
    py: Python<'py>,
    csv: &[u8],
    layout: Layout,
    empty: bool,
) -> PyResult<Table<'py>> {
    let text = String::from_utf8_lossy(csv);
    let mut lines = text.lines();
    let columns: Vec<String> = lines
        .next()
        .unwrap_or("")
        .split(',')
        .map(str::to_string)
        .collect();
    let mut values: Vec<f64> = Vec::with_capacity(csv.len() / 8);
    let mut rows = 0;
    for line in lines {
        for cell in line.split(',') {
            let v: f64 = match cell.parse() {
                Ok(v) => v,
                Err(_) if empty && cell.is_empty() => f64::NAN,
                Err(_) => {
                    return Err(RoverError::new_err(format!(
                        "error: not a number in the run's output: {cell}"
                    )));
                }
            };
            values.push(v);
        }
        rows += 1;
    }
    let width = columns.len();
    let mut data: Vec<u8> = Vec::with_capacity(8 * values.len());
    match layout {
        Layout::Rows => values
            .iter()
            .for_each(|v| data.extend_from_slice(&v.to_ne_bytes())),
        Layout::Columns => {
            for c in 0..width {
                for r in 0..rows {
                    data.extend_from_slice(&values[r * width + c].to_ne_bytes());
                }
            }
        }
    }
    Ok((columns, PyBytes::new(py, &data), rows))
}

/// A whole run as it crosses to Python: the trajectory (a [`Table`], row
/// after row), the summary as JSON, the columns' units, the sensor log
/// when the scenario has `[sensors]` (a [`Table`], column after column,
/// NaN in a fix's columns where no fix was due), and the exception a
/// signal handler raised, which stopped the run where it stood: the rows
/// are those computed, the summary's status `interrupted`; the Python side
/// raises it with the result attached.
type WholeRun<'py> = (
    Table<'py>,
    String,
    Vec<&'static str>,
    Option<Table<'py>>,
    Option<Py<PyBaseException>>,
);

/// A whole run, as `rover simulate` runs it ([`WholeRun`]); Ctrl-C stops
/// it as it stops the command line's.
///
/// With `mcap` (a file's path), the run's MCAP log is written there as
/// `rover simulate --mcap` writes it; a path that cannot be written is an
/// error before the run starts. (A scenario's `[output] mcap` names no
/// file: Python writes one only where `mcap` says.)
#[pyfunction]
#[pyo3(signature = (rover, text, origin, base, generic=false, mcap=None))]
fn simulate<'py>(
    py: Python<'py>,
    rover: Option<&Rover>,
    text: &str,
    origin: &str,
    base: &str,
    generic: bool,
    mcap: Option<std::path::PathBuf>,
) -> PyResult<WholeRun<'py>> {
    use rover_scenario::output::foxglove::McapLog;
    let prepared = prepare(rover, text, origin, base).map_err(py_err)?;
    let with_sensors = prepared.scenario.sensors.is_some();
    let mut log_file = match &mcap {
        Some(path) => {
            let file = rover_files::create_fresh(path).map_err(|e| {
                RoverError::new_err(format!(
                    "error: mcap={}: cannot create the MCAP log: {e}\n  = help: give the path of a file in a folder you can write",
                    path.display()
                ))
            })?;
            let log = McapLog::new(
                std::io::BufWriter::new(file),
                &prepared.spec,
                path.display().to_string(),
            )
            .map_err(|e| RoverError::new_err(format!("error: {e}")))?;
            Some(log)
        }
        None => None,
    };
    let run = py.detach(|| -> Result<_, PrepareError> {
        let mut csv = Vec::new();
        let mut log = Vec::new();
        let stop = AtomicBool::new(false);
        let mut signals = Signals::new();
        // Polled at each output row, as the run polls `stop`.
        let summary = prepared.run_with_outputs(
            generic,
            &mut csv,
            with_sensors.then_some(&mut log),
            log_file
                .as_mut()
                .map(|l| l as &mut dyn rover_scenario::output::RowSink),
            &stop,
            |_| {
                if signals.poll() {
                    stop.store(true, Ordering::Relaxed);
                }
            },
        )?;
        let json = serde_json::to_string_pretty(&summary);
        Ok((csv, log, json, signals.raised))
    });
    let (csv, log, json, raised) = run.map_err(py_err)?;
    let json = json.map_err(|e| RoverError::new_err(format!("error: the summary: {e}")))?;
    let trajectory = csv_table(py, &csv, Layout::Rows, false)?;
    let sensors = with_sensors
        .then(|| csv_table(py, &log, Layout::Columns, true))
        .transpose()?;
    let model = &prepared.spec.model;
    let soil = prepared.scenario.soft();
    let units = Columns::on_ground(model.m(), model.wheels.len(), soil)
        .units(&prepared.spec.coordinate_linear);
    let raised = raised.map(|e| e.into_value(py));
    Ok((trajectory, json, units, sensors, raised))
}

/// A log handed to [`estimate`]: a file's path, or columns by name (each
/// a 1-D float64 array, C-contiguous).
#[derive(FromPyObject)]
enum LogArg<'py> {
    Path(std::path::PathBuf),
    Columns(Vec<(String, Bound<'py, PyAny>)>),
}

/// The values of columns handed over as arrays, copied out of their
/// buffers (`table` names them in messages).
fn column_values(
    table: &str,
    columns: &[(String, Bound<'_, PyAny>)],
) -> PyResult<Vec<(String, Vec<f64>)>> {
    columns
        .iter()
        .map(|(name, array)| {
            let what = format!("{table}[\"{name}\"]");
            let len = array.len()?;
            let values = with_buffer(array, false, &what, len, |v| Ok(v.to_vec()))?;
            Ok((name.clone(), values))
        })
        .collect()
}

/// Columns as the readers take them: names and slices.
fn borrowed(columns: &[(String, Vec<f64>)]) -> Vec<(&str, &[f64])> {
    columns
        .iter()
        .map(|(n, v)| (n.as_str(), v.as_slice()))
        .collect()
}

/// An estimation as it crosses to Python: `estimate.csv` and
/// `dead_reckoning.csv` as [`Table`]s (column after column), and the
/// summary (`estimate.json`) as JSON.
type EstimateRun<'py> = (Table<'py>, Table<'py>, String);

/// A sensor log estimated as `rover estimate` estimates it ([`EstimateRun`]):
/// the scenario (from TOML `text` named `origin`, relative paths from
/// `base`, `rover` overriding its rover), the log (`sensors`: a
/// sensors.csv's path or its columns), the truth to measure against
/// (`truth`: a run.csv's path, a run's columns, or none), the map (the
/// scenario's terrain, or smoothed below `smoothed` metres). A log or a
/// truth that does not fit is an error naming the file and line, or the
/// column and element; an estimation that fails on the way is a summary
/// of status `failed` with the rows before it.
#[pyfunction]
#[pyo3(signature = (rover, text, origin, base, sensors, truth=None, smoothed=None, generic=false))]
#[allow(clippy::too_many_arguments)]
fn estimate<'py>(
    py: Python<'py>,
    rover: Option<&Rover>,
    text: &str,
    origin: &str,
    base: &str,
    sensors: LogArg<'py>,
    truth: Option<LogArg<'py>>,
    smoothed: Option<f64>,
    generic: bool,
) -> PyResult<EstimateRun<'py>> {
    use rover_scenario::estimate::{EstimateMap, EstimateOptions};
    let prepared = prepare(rover, text, origin, base).map_err(py_err)?;
    let config = prepared.sensor_config().map_err(py_err)?;
    let model = &prepared.spec.model;
    let (wheels, m) = (model.wheels.len(), model.m());
    let located = |e: &dyn std::fmt::Display| RoverError::new_err(format!("error: {e}"));
    let samples = match &sensors {
        LogArg::Path(path) => {
            rover_scenario::read_sensor_log(path, config, wheels, m).map_err(|e| located(&e))?
        }
        LogArg::Columns(columns) => {
            let values = column_values("sensors", columns)?;
            rover_scenario::sensor_log::samples_from_columns(&borrowed(&values), config, wheels, m)
                .map_err(|e| located(&e))?
        }
    };
    let truth = match &truth {
        None => None,
        Some(LogArg::Path(path)) => {
            Some(rover_scenario::truth_log::read_truth(path, m, wheels).map_err(|e| located(&e))?)
        }
        Some(LogArg::Columns(columns)) => {
            let values = column_values("truth", columns)?;
            Some(
                rover_scenario::truth_log::truth_from_columns(&borrowed(&values), m, wheels)
                    .map_err(|e| located(&e))?,
            )
        }
    };
    let options = EstimateOptions {
        map: match smoothed {
            None => EstimateMap::True,
            Some(cutoff) => EstimateMap::Smoothed { cutoff },
        },
        ..EstimateOptions::default()
    };
    let run = py.detach(|| {
        let (mut est, mut dr) = (Vec::new(), Vec::new());
        let summary = prepared.estimate(
            generic,
            &samples,
            truth.as_ref(),
            &options,
            &mut est,
            &mut dr,
        )?;
        Ok::<_, PrepareError>((est, dr, serde_json::to_string_pretty(&summary)))
    });
    let (est, dr, json) = run.map_err(py_err)?;
    let json = json.map_err(|e| RoverError::new_err(format!("error: the summary: {e}")))?;
    let est = csv_table(py, &est, Layout::Columns, false)?;
    let dr = csv_table(py, &dr, Layout::Columns, false)?;
    Ok((est, dr, json))
}

/// Steps of a run up to this many hold the interpreter: releasing and
/// taking it back costs more than a few steps of a small rover.
const HOLD_GIL_STEPS: u64 = 1;

/// A scenario run step by step: `step(n)` advances n output intervals;
/// between steps the state can be read and the commands and set-points
/// changed. Arrays in and out are the caller's numpy arrays (float64, one
/// value per wheel for commands), read or filled in place.
#[pyclass(subclass, module = "rover._native")]
struct Simulation {
    inner: Stepper<RunPlant>,
    dof: usize,
    wheels: usize,
    units: Vec<&'static str>,
    /// What the run was set up from (rover, scenario, origin, base,
    /// plant): a snapshot restores only into a run set up alike.
    setup: Arc<str>,
    /// The calls since t = 0 that changed the run (for pickling).
    log: Log,
}

/// A call that changed a step-wise run: replayed in order on a run set up
/// alike, the calls since t = 0 give the run's condition bit for bit.
enum Op {
    Step(u64),
    Torques(Vec<f64>),
    Steering(Vec<f64>),
    Speed(f64),
    SteeringSetpoint(f64),
    State(Vec<f64>),
}

/// The calls since t = 0 that changed a run, newest first, each entry
/// shared by the snapshots taken after it (a snapshot's copy costs one
/// reference count, whatever the run's length).
#[derive(Clone, Default)]
struct Log(Option<Arc<Entry>>);

struct Entry {
    op: Op,
    prev: Log,
}

impl Log {
    fn push(&mut self, op: Op) {
        let prev = std::mem::take(self);
        self.0 = Some(Arc::new(Entry { op, prev }));
    }

    /// `n` more steps: added to the newest entry when it is steps that no
    /// snapshot shares.
    fn steps(&mut self, n: u64) {
        if n == 0 {
            return;
        }
        if let Some(Entry {
            op: Op::Step(k), ..
        }) = self.0.as_mut().and_then(Arc::get_mut)
        {
            *k += n;
            return;
        }
        self.push(Op::Step(n));
    }

    /// Oldest first, as (method, arguments) for the Python side to replay.
    fn calls(&self) -> Vec<(&'static str, Vec<f64>)> {
        let mut out = Vec::new();
        let mut cur = self.0.as_deref();
        while let Some(e) = cur {
            out.push(match &e.op {
                Op::Step(n) => ("step", vec![*n as f64]),
                Op::Torques(v) => ("set_torques", v.clone()),
                Op::Steering(v) => ("set_steering", v.clone()),
                Op::Speed(v) => ("set_speed", vec![*v]),
                Op::SteeringSetpoint(v) => ("set_steering_setpoint", vec![*v]),
                Op::State(v) => ("set_state", v.clone()),
            });
            cur = e.prev.0.as_deref();
        }
        out.reverse();
        out
    }
}

impl Drop for Log {
    /// Entry after entry, not recursively: a long run's log would
    /// overflow the stack.
    fn drop(&mut self) {
        let mut cur = self.0.take();
        while let Some(entry) = cur {
            match Arc::try_unwrap(entry) {
                Ok(mut e) => cur = e.prev.0.take(),
                Err(_) => break,
            }
        }
    }
}

/// A step-wise run's complete condition at one instant, taken by
/// `Simulation.snapshot()`: the state, the time, the integrator's step and
/// history, the controllers' integral states, the commands and set-points.
/// `Simulation.restore()` puts it back, and the run then continues bit for
/// bit as it did from the instant it was taken. Opaque; restores only into
/// a simulation of the same rover and scenario.
#[pyclass(module = "rover._native")]
struct Snapshot {
    inner: Stepper<RunPlant>,
    setup: Arc<str>,
    log: Log,
}

#[pymethods]
impl Snapshot {
    /// The time it was taken at \[s\].
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }
    fn __repr__(&self) -> String {
        format!("<rover snapshot at t = {} s>", self.inner.time())
    }
}

/// The f64 buffer of a Python object (a C-contiguous, 1-D float64 numpy
/// array of `len` values), lent to `f` without a copy or an allocation;
/// `writable` asks for write access. Anything else is a ValueError naming
/// the argument (`what`), what it was given and what it takes.
fn with_buffer<R>(
    obj: &Bound<'_, PyAny>,
    writable: bool,
    what: &str,
    len: usize,
    f: impl FnOnce(&mut [f64]) -> PyResult<R>,
) -> PyResult<R> {
    use pyo3::ffi;
    let mut flags = ffi::PyBUF_C_CONTIGUOUS | ffi::PyBUF_FORMAT;
    if writable {
        flags |= ffi::PyBUF_WRITABLE;
    }
    let expected = format!("a 1-D float64 array of {len} values (shape ({len},))");
    let mut view = std::mem::MaybeUninit::<ffi::Py_buffer>::zeroed();
    // SAFETY: `view` is filled by the interpreter on success and released
    // below on every path; `shape` holds `ndim` lengths (asked for by
    // PyBUF_C_CONTIGUOUS); the slice lives only during `f`, while the
    // buffer is held.
    unsafe {
        if ffi::PyObject_GetBuffer(obj.as_ptr(), view.as_mut_ptr(), flags) != 0 {
            let cause = PyErr::fetch(obj.py());
            let given = obj
                .get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default();
            let message = format!("{what}: expected {expected}, got {given} ({cause})");
            // No buffer at all (a list) is the wrong type; a buffer that
            // cannot be lent so (not contiguous, read-only) a wrong value.
            let err = if ffi::PyObject_CheckBuffer(obj.as_ptr()) == 0 {
                PyTypeError::new_err(message)
            } else {
                PyValueError::new_err(message)
            };
            err.set_cause(obj.py(), Some(cause));
            return Err(err);
        }
        let mut view = view.assume_init();
        let format = if view.format.is_null() {
            "B".to_string()
        } else {
            String::from_utf8_lossy(std::ffi::CStr::from_ptr(view.format).to_bytes()).into_owned()
        };
        let format_ok = matches!(format.as_str(), "d" | "<d" | "=d" | "@d") && view.itemsize == 8;
        let shape: Vec<isize> = if view.shape.is_null() || view.ndim <= 0 {
            Vec::new()
        } else {
            std::slice::from_raw_parts(view.shape, view.ndim as usize).to_vec()
        };
        let result = if !format_ok {
            Err(PyValueError::new_err(format!(
                "{what}: expected {expected}, got items of format '{format}' (convert with numpy.asarray(..., dtype=numpy.float64))"
            )))
        } else if view.ndim != 1 || shape.first() != Some(&(len as isize)) {
            let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
            let given = match dims.len() {
                1 => format!("({},)", dims[0]),
                _ => format!("({})", dims.join(", ")),
            };
            Err(PyValueError::new_err(format!(
                "{what}: expected {expected}, got shape {given}"
            )))
        } else {
            let slice = if len == 0 {
                &mut [][..]
            } else {
                std::slice::from_raw_parts_mut(view.buf.cast::<f64>(), len)
            };
            f(slice)
        };
        ffi::PyBuffer_Release(&mut view);
        result
    }
}

#[pymethods]
impl Simulation {
    /// Set up the scenario's run (from its TOML text, as for `simulate`),
    /// placed at t = 0.
    #[new]
    #[pyo3(
        signature = (rover, text, origin, base, generic=false),
        text_signature = "(rover, text, origin, base, generic=False)"
    )]
    fn new(
        rover: Option<&Rover>,
        text: &str,
        origin: &str,
        base: &str,
        generic: bool,
    ) -> PyResult<Self> {
        let p = prepare(rover, text, origin, base).map_err(py_err)?;
        let inner = p.stepper(generic).map_err(py_err)?;
        let model = &p.spec.model;
        let key = rover.map(|r| r.key.as_str()).unwrap_or("");
        // Unit separators: no name, path or TOML text holds one.
        let setup = format!("{key}\u{1f}{text}\u{1f}{origin}\u{1f}{base}\u{1f}{generic}");
        Ok(Self {
            units: inner.columns().units(&p.spec.coordinate_linear),
            inner,
            dof: model.dof(),
            wheels: model.wheels.len(),
            setup: setup.into(),
            log: Log::default(),
        })
    }

    /// Back to t = 0 with the scenario's commands and set-points.
    fn reset(&mut self) {
        self.inner.reset();
        self.log = Log::default();
    }

    /// Advance `n` output intervals; the time reached. Raises RunFailed
    /// when the run fails (it then stays failed until reset()). Ctrl-C (a
    /// signal handler that raises) stops a long call after the step in
    /// progress: the exception is raised and the simulation stays at the
    /// last step completed, ready to step on.
    #[pyo3(signature = (n=1))]
    fn step(&mut self, py: Python<'_>, n: u64) -> PyResult<f64> {
        let inner = &mut self.inner;
        let mut done = n;
        let result = if n > HOLD_GIL_STEPS {
            py.detach(|| {
                let mut signals = Signals::new();
                for i in 1..=n {
                    inner.step(1)?;
                    if signals.poll() {
                        done = i;
                        break;
                    }
                }
                Ok(signals.raised)
            })
        } else {
            inner.step(n).map(|()| None)
        };
        // A failed step is logged too: replayed, it fails again.
        self.log.steps(done);
        match result {
            Ok(None) => Ok(self.inner.time()),
            Ok(Some(raised)) => Err(raised),
            Err(e) => Err(RunFailed::new_err(format!("error: {e}"))),
        }
    }

    /// Time \[s\].
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    /// One step: the output interval \[s\].
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt()
    }

    /// Number of generalized coordinates N (the state has 2N values).
    #[getter]
    fn dof(&self) -> usize {
        self.dof
    }

    /// Number of wheels (the length of each command).
    #[getter]
    fn wheel_count(&self) -> usize {
        self.wheels
    }

    /// The trajectory's column names (as in `run.csv`).
    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.columns().names().to_vec()
    }

    /// Each column's unit (`m`, `rad`, `N`, `N·m`, ...), in the columns'
    /// order.
    #[getter]
    fn units(&self) -> Vec<&'static str> {
        self.units.clone()
    }

    /// The failed run's message, or None.
    #[getter]
    fn error(&self) -> Option<String> {
        self.inner.failure().map(|e| format!("error: {e}"))
    }

    /// Write the state [x; w] (2N values, the trajectory's columns after
    /// `t`) into `out`.
    fn state_into(&self, out: &Bound<'_, PyAny>) -> PyResult<()> {
        let y = self.inner.state();
        let n2 = 2 * self.dof;
        with_buffer(out, true, "state", n2, |o| {
            o.copy_from_slice(&y[..n2]);
            Ok(())
        })
    }

    /// Length of the full state (`get_state()`): 2N values [x; w], then
    /// the run's internal states (soil and controller states), if any.
    #[getter]
    fn state_size(&self) -> usize {
        self.inner.state().len()
    }

    /// Write the full state (`state_size` values: [x; w], then the run's
    /// internal states) into `out`.
    fn full_state_into(&self, out: &Bound<'_, PyAny>) -> PyResult<()> {
        let y = self.inner.state();
        with_buffer(out, true, "state", y.len(), |o| {
            o.copy_from_slice(y);
            Ok(())
        })
    }

    /// Replace the state at the current time with `values`: a float64
    /// array of 2N values [x; w] (the run's internal states kept) or of
    /// `state_size` values (the full state). The integrator restarts from
    /// it. Raises RunFailed if the run has failed or the state cannot be
    /// evaluated (a wheel off the map).
    fn set_state(&mut self, values: &Bound<'_, PyAny>) -> PyResult<()> {
        let full = self.inner.state().len();
        let n2 = 2 * self.dof;
        let len = match values.len() {
            Ok(l) if l == n2 => n2,
            _ => full,
        };
        let mut y = self.inner.state().to_vec();
        with_buffer(values, false, "state", len, |v| {
            y[..len].copy_from_slice(v);
            Ok(())
        })
        .map_err(|e| {
            if len == full && full != n2 {
                PyValueError::new_err(format!(
                    "{}; or 2N = {n2} values [x; w]",
                    e.value(values.py())
                ))
            } else {
                e
            }
        })?;
        if let Some(i) = y.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "state: value {i} is {}: every value must be finite",
                y[i]
            )));
        }
        let was_failed = self.inner.failure().is_some();
        let set = self.inner.set_state(&y);
        if !was_failed {
            // Replayed, a state that fails the run fails it again.
            self.log.push(Op::State(y));
        }
        set.map_err(|e| RunFailed::new_err(format!("error: {e}")))
    }

    /// The run's complete condition now (state, time, integrator,
    /// controllers, commands, set-points), for `restore()`.
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            inner: self.inner.clone(),
            setup: self.setup.clone(),
            log: self.log.clone(),
        }
    }

    /// Put back a snapshot taken of this run (or of one set up from the
    /// same rover and scenario): the run continues bit for bit as it did
    /// from the instant the snapshot was taken.
    fn restore(&mut self, snapshot: &Bound<'_, Snapshot>) -> PyResult<()> {
        let snap = snapshot.borrow();
        if snap.setup != self.setup {
            return Err(PyValueError::new_err(
                "snapshot: taken of a simulation of another rover or scenario; restore it into a simulation set up as the one it was taken of",
            ));
        }
        self.inner.clone_from(&snap.inner);
        self.log = snap.log.clone();
        Ok(())
    }

    /// Write the current trajectory row (every column of `run.csv`) into
    /// `out`.
    fn row_into(&self, out: &Bound<'_, PyAny>) -> PyResult<()> {
        let cols = self.inner.columns().len();
        with_buffer(out, true, "row", cols, |o| {
            self.inner.row_into(o);
            Ok(())
        })
    }

    /// Open-loop motor torques [N·m] per wheel, added to the controller's
    /// and held until changed.
    fn set_torques(&mut self, torques: &Bound<'_, PyAny>) -> PyResult<()> {
        self.command(torques, true)
    }

    /// Open-loop steering angles \[rad\] per wheel, added to the
    /// controller's and held until changed.
    fn set_steering(&mut self, angles: &Bound<'_, PyAny>) -> PyResult<()> {
        self.command(angles, false)
    }

    /// Hold the speed set-point at `speed` [m/s].
    fn set_speed(&mut self, speed: f64) -> PyResult<()> {
        self.inner
            .set_speed(speed)
            .map_err(|e| RoverError::new_err(format!("error: {e}")))?;
        self.log.push(Op::Speed(speed));
        Ok(())
    }

    /// Hold the steering set-point at `value` (slip steering's Δτ [N·m],
    /// or Ackermann steering's radius [m] or front-left angle [°]).
    fn set_steering_setpoint(&mut self, value: f64) -> PyResult<()> {
        self.inner
            .set_steering_setpoint(value)
            .map_err(|e| RoverError::new_err(format!("error: {e}")))?;
        self.log.push(Op::SteeringSetpoint(value));
        Ok(())
    }

    /// The calls since t = 0 that changed the run (after a reset; a
    /// restored snapshot brings its own), oldest first, as (method,
    /// arguments): replayed on a simulation set up alike, they give this
    /// run's condition bit for bit. Pickling replays them.
    fn calls(&self) -> Vec<(&'static str, Vec<f64>)> {
        self.log.calls()
    }
}

impl Simulation {
    fn command(&mut self, values: &Bound<'_, PyAny>, torques: bool) -> PyResult<()> {
        let what = if torques { "torques" } else { "steering" };
        let (s, log) = (&mut self.inner, &mut self.log);
        let wheels = s.command_buffer().len();
        with_buffer(values, false, what, wheels, |v| {
            let held = s.system().commands();
            let changed = if torques { held.0 != v } else { held.1 != v };
            s.command_buffer().copy_from_slice(v);
            let applied = if torques {
                s.apply_torques()
            } else {
                s.apply_steering()
            };
            applied.map_err(|e| RoverError::new_err(format!("error: {e}")))?;
            if changed {
                log.push(if torques {
                    Op::Torques(v.to_vec())
                } else {
                    Op::Steering(v.to_vec())
                });
            }
            Ok(())
        })
    }
}

/// A sweep plan's task count, results folder and base scenario's text
/// (the plan as TOML text, named `origin`, its paths from `dir`), once
/// every task is checked ([`Plan::check`]): a plan whose tasks cannot run
/// is refused before any runs.
#[pyfunction]
#[pyo3(signature = (text, origin, dir, base_text=None))]
fn plan_info(
    py: Python<'_>,
    text: &str,
    origin: &str,
    dir: &str,
    base_text: Option<&str>,
) -> PyResult<(usize, String, String)> {
    let plan =
        Plan::parse_with(text, Path::new(origin), Path::new(dir), base_text).map_err(sweep_err)?;
    py.detach(|| plan.check()).map_err(sweep_err)?;
    let base =
        rover_files::read_text(&plan.base_origin, rover_files::Limit::Text).unwrap_or_default();
    let base = base_text.map(str::to_string).unwrap_or(base);
    Ok((plan.tasks.len(), plan.out.display().to_string(), base))
}

/// Run task `index` of a plan; its record as JSON (never an exception for
/// a run that fails or cannot start: the record says so).
#[pyfunction]
#[pyo3(signature = (text, origin, dir, index, base_text=None))]
fn plan_task(
    py: Python<'_>,
    text: &str,
    origin: &str,
    dir: &str,
    index: usize,
    base_text: Option<&str>,
) -> PyResult<String> {
    let plan =
        Plan::parse_with(text, Path::new(origin), Path::new(dir), base_text).map_err(sweep_err)?;
    if index >= plan.tasks.len() {
        return Err(PyValueError::new_err(format!(
            "no task {index}: the plan has {}",
            plan.tasks.len()
        )));
    }
    Ok(py.detach(|| plan.run_task(index).to_string()))
}

/// The single-wheel testbed, as `rover wheel-test` runs it: the soil a
/// built-in name or a soil file (`soil`), or a soil file's TOML text
/// (`soil_text`, `soil` then naming it in messages). The columns' names
/// and their values column after column, as native-endian f64 bytes.
/// Input the command line refuses raises ValueError with its message.
#[pyfunction]
#[pyo3(signature = (soil, soil_text, radius, width, load, slips, slip_angle_deg))]
fn wheel_test<'py>(
    py: Python<'py>,
    soil: &str,
    soil_text: Option<&str>,
    radius: f64,
    width: f64,
    load: f64,
    slips: Vec<f64>,
    slip_angle_deg: f64,
) -> PyResult<(Vec<&'static str>, Bound<'py, PyBytes>)> {
    use rover_runtime::soil::{SoilConfig, WheelTestPoint};
    let config = match soil_text {
        Some(text) => SoilConfig::from_toml(text),
        None => SoilConfig::named_or_file(soil),
    };
    let soil = config.and_then(|c| c.soil()).map_err(|e| {
        // A TOML error ends in a line break; the command line's
        // eprintln adds another.
        let message = format!("error: --soil {soil}: {e}");
        PyValueError::new_err(message.trim_end().to_string())
    })?;
    let points = py
        .detach(|| {
            rover_runtime::soil::wheel_test(
                &soil,
                radius,
                width,
                load,
                &slips,
                slip_angle_deg.to_radians(),
            )
        })
        .map_err(|e| PyValueError::new_err(format!("error: {e}")))?;
    let rows: Vec<[f64; 8]> = points.iter().map(|p| p.row(load, radius)).collect();
    let mut data = Vec::with_capacity(rows.len() * 8 * 8);
    for column in 0..WheelTestPoint::COLUMNS.len() {
        for row in &rows {
            data.extend_from_slice(&row[column].to_ne_bytes());
        }
    }
    Ok((WheelTestPoint::COLUMNS.to_vec(), PyBytes::new(py, &data)))
}

/// The built-in rovers' names.
#[pyfunction]
fn builtins() -> Vec<&'static str> {
    rover_models::NAMES.to_vec()
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(estimate, m)?)?;
    m.add_function(wrap_pyfunction!(plan_info, m)?)?;
    m.add_function(wrap_pyfunction!(plan_task, m)?)?;
    m.add_function(wrap_pyfunction!(builtins, m)?)?;
    m.add_function(wrap_pyfunction!(wheel_test, m)?)?;
    m.add_class::<Rover>()?;
    m.add_class::<Simulation>()?;
    m.add_class::<Snapshot>()?;
    m.add("RoverError", m.py().get_type::<RoverError>())?;
    m.add("RunFailed", m.py().get_type::<RunFailed>())?;
    Ok(())
}
