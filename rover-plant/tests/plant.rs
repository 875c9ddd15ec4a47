//! The plant library through its C symbols, as an importer calls them:
//! an FMU instance stepped at the output instants gives `rover simulate`'s
//! rows; bad input (an unknown value reference, a step the integrator
//! cannot take, a missing or corrupt terrain resource, an instance used
//! after it was freed) gives FMI's error status and a logged message,
//! never a crash; the C API's handles behave the same.

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

use rover_export::handle::status;
use rover_export::resources::{SCENARIO_FILE, pack};
use rover_export::variables::Inputs;
use rover_scenario::prepare::Prepared;

// Link the library whose symbols are declared below.
use rover_plant as _;

type Log = unsafe extern "C" fn(*mut c_void, c_int, *const c_char, *const c_char);

unsafe extern "C" {
    fn fmi3InstantiateCoSimulation(
        name: *const c_char,
        token: *const c_char,
        resources: *const c_char,
        visible: bool,
        logging_on: bool,
        event_mode_used: bool,
        early_return_allowed: bool,
        required: *const u32,
        n_required: usize,
        env: *mut c_void,
        log: Option<Log>,
        intermediate_update: *const c_void,
    ) -> *mut c_void;
    fn fmi3EnterInitializationMode(
        i: *mut c_void,
        tol_defined: bool,
        tol: f64,
        start: f64,
        stop_defined: bool,
        stop: f64,
    ) -> c_int;
    fn fmi3ExitInitializationMode(i: *mut c_void) -> c_int;
    fn fmi3GetFloat64(i: *mut c_void, vr: *const u32, nvr: usize, v: *mut f64, nv: usize) -> c_int;
    fn fmi3SetFloat64(
        i: *mut c_void,
        vr: *const u32,
        nvr: usize,
        v: *const f64,
        nv: usize,
    ) -> c_int;
    fn fmi3DoStep(
        i: *mut c_void,
        current: f64,
        step: f64,
        no_set_prior: bool,
        event_handling_needed: *mut bool,
        terminate: *mut bool,
        early_return: *mut bool,
        last_successful_time: *mut f64,
    ) -> c_int;
    fn fmi3Reset(i: *mut c_void) -> c_int;
    fn fmi3FreeInstance(i: *mut c_void);
    fn rover_create(
        scenario: *const c_char,
        out: *mut *mut c_void,
        message: *mut c_char,
        size: usize,
    ) -> c_int;
    fn rover_step(p: *mut c_void, dt: f64) -> c_int;
    fn rover_outputs(p: *mut c_void, out: *mut f64, n: usize) -> c_int;
    fn rover_output_count(p: *mut c_void, n: *mut usize) -> c_int;
    fn rover_set_torques(p: *mut c_void, v: *const f64, n: usize) -> c_int;
    fn rover_error_message(p: *mut c_void) -> *const c_char;
    fn rover_destroy(p: *mut c_void);
}

/// The messages an instance logged.
struct Messages(Mutex<Vec<(c_int, String)>>);

unsafe extern "C" fn record(env: *mut c_void, status: c_int, _c: *const c_char, m: *const c_char) {
    let messages = unsafe { &*env.cast::<Messages>() };
    let text = unsafe { CStr::from_ptr(m) }.to_string_lossy().into_owned();
    messages.0.lock().unwrap().push((status, text));
}

impl Messages {
    fn new() -> Box<Self> {
        Box::new(Messages(Mutex::new(Vec::new())))
    }
    fn env(&self) -> *mut c_void {
        (self as *const Self).cast_mut().cast()
    }
    fn last(&self) -> String {
        self.0
            .lock()
            .unwrap()
            .last()
            .map(|m| m.1.clone())
            .unwrap_or_default()
    }
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The shipped rough-ground scenario packed into a fresh folder `name`.
fn packed(name: &str, inputs: Inputs) -> (PathBuf, String) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("rover-plant")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    let p = pack(
        None,
        &root().join("scenarios/export_rough.toml"),
        &dir,
        inputs,
    )
    .unwrap();
    (dir, p.settings.token)
}

/// An FMI 3 instance of the plant packed in `dir`, or null.
fn instantiate(dir: &Path, token: &str, log: &Messages) -> *mut c_void {
    let res = CString::new(format!("{}/", dir.display())).unwrap();
    let token = CString::new(token).unwrap();
    unsafe {
        fmi3InstantiateCoSimulation(
            c"test".as_ptr(),
            token.as_ptr(),
            res.as_ptr(),
            false,
            false,
            false,
            false,
            std::ptr::null(),
            0,
            log.env(),
            Some(record),
            std::ptr::null(),
        )
    }
}

fn initialized(dir: &Path, token: &str, log: &Messages) -> *mut c_void {
    let i = instantiate(dir, token, log);
    assert!(!i.is_null(), "instantiate: {}", log.last());
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, true, 10.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(i), status::OK);
    }
    i
}

fn step(i: *mut c_void, t: f64, h: f64) -> (c_int, f64) {
    let (mut a, mut b, mut c, mut last) = (false, false, false, f64::NAN);
    let s = unsafe { fmi3DoStep(i, t, h, true, &mut a, &mut b, &mut c, &mut last) };
    (s, last)
}

fn get(i: *mut c_void, vrs: &[u32]) -> (c_int, Vec<f64>) {
    let mut v = vec![f64::NAN; vrs.len()];
    let s = unsafe { fmi3GetFloat64(i, vrs.as_ptr(), vrs.len(), v.as_mut_ptr(), v.len()) };
    (s, v)
}

/// `rover simulate`'s rows of the scenario (what the CLI writes).
fn simulated(scenario: &Path) -> Vec<Vec<f64>> {
    let prepared = Prepared::from_file(None, scenario).unwrap();
    let mut csv = Vec::new();
    let summary = prepared
        .run(false, &mut csv, &AtomicBool::new(false), |_| {})
        .unwrap();
    assert!(summary.complete);
    String::from_utf8(csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn an_fmu_stepped_at_the_output_instants_gives_the_csv_rows() {
    let (dir, token) = packed("rows", Inputs::None);
    let rows = simulated(&dir.join(SCENARIO_FILE));
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    let vrs: Vec<u32> = (0..rows[0].len() as u32).collect();
    let h = 0.01;
    let mut t = 0.0;
    for (k, row) in rows.iter().enumerate().take(301) {
        let (s, values) = get(i, &vrs);
        assert_eq!(s, status::OK);
        assert_eq!(
            &values, row,
            "row {k}: the FMU's outputs are the CSV's, bit for bit"
        );
        let (s, reached) = step(i, t, h);
        assert_eq!(s, status::OK, "{}", log.last());
        t = reached;
    }
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn steps_between_output_instants_land_on_the_communication_points() {
    let (dir, token) = packed("odd_steps", Inputs::None);
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    let mut t = 0.0;
    for _ in 0..400 {
        let (s, reached) = step(i, t, 0.0037);
        assert_eq!(s, status::OK, "{}", log.last());
        assert!((reached - (t + 0.0037)).abs() < 1e-12);
        t = reached;
    }
    assert_eq!(get(i, &[0]).1[0], t);
    // The rover drove, it did not drift: close to the run stepped at the
    // output instants (RK4 at 1 ms, one step in 3.7 shortened).
    let (_, x_odd) = get(i, &[1]);
    assert_eq!(unsafe { fmi3Reset(i) }, status::OK);
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(i), status::OK);
    }
    let mut t2 = 0.0;
    while t2 < t - 1e-9 {
        let h = (t - t2).min(0.01);
        t2 = step(i, t2, h).1;
    }
    let (_, x_even) = get(i, &[1]);
    assert!(
        x_odd[0] > 0.02,
        "the speed loop drove the rover: X = {}",
        x_odd[0]
    );
    assert!(
        (x_odd[0] - x_even[0]).abs() < 1e-4,
        "{} against {}",
        x_odd[0],
        x_even[0]
    );
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn an_unknown_value_reference_is_an_error_with_a_message() {
    let (dir, token) = packed("unknown_vr", Inputs::None);
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    let (s, _) = get(i, &[1, 99_999]);
    assert_eq!(s, status::ERROR);
    assert_eq!(
        log.last(),
        "fmi3GetFloat64: no variable has value reference 99999: this model's are 0 to 69 (modelDescription.xml lists them)"
    );
    // Setting an output, or any variable of a model without inputs.
    let s = unsafe { fmi3SetFloat64(i, [1u32].as_ptr(), 1, [1.0].as_ptr(), 1) };
    assert_eq!(s, status::ERROR);
    assert_eq!(
        log.last(),
        "fmi3SetFloat64: X (value reference 1) is an output: only inputs can be set; this model has none (export it with `--inputs torques`)"
    );
    // Still usable.
    assert_eq!(step(i, 0.0, 0.01).0, status::OK);
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn a_step_the_integrator_cannot_take_is_refused_and_changes_nothing() {
    let (dir, token) = packed("bad_step", Inputs::None);
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    for h in [0.0, -0.01, f64::NAN, f64::INFINITY, 1e-15] {
        let (s, last) = step(i, 0.0, h);
        assert_eq!(s, status::ERROR, "step {h}");
        assert_eq!(last, 0.0);
        assert!(
            log.last().starts_with(&format!("fmi3DoStep: a communication step of {h} s cannot be taken: give a finite step longer than 1e-12 s")),
            "{}",
            log.last()
        );
    }
    let (s, _) = step(i, 0.5, 0.01);
    assert_eq!(s, status::ERROR);
    assert_eq!(
        log.last(),
        "fmi3DoStep: a step from t = 0.5 s, but the plant is at t = 0 s: step from where the last step ended"
    );
    assert_eq!(get(i, &[0]).1[0], 0.0);
    assert_eq!(step(i, 0.0, 0.01).0, status::OK);
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn a_missing_or_corrupt_terrain_resource_fails_instantiation_with_its_name() {
    let (dir, token) = packed("missing_terrain", Inputs::None);
    std::fs::remove_file(dir.join("export_rough.asc")).unwrap();
    let log = Messages::new();
    assert!(instantiate(&dir, &token, &log).is_null());
    let m = log.last();
    assert!(
        m.starts_with("fmi3InstantiateCoSimulation: ") && m.contains("export_rough.asc"),
        "{m}"
    );
    let (dir, token) = packed("corrupt_terrain", Inputs::None);
    std::fs::write(dir.join("export_rough.asc"), "ncols 3\nnrows 2\ngarbage\n").unwrap();
    let log = Messages::new();
    assert!(instantiate(&dir, &token, &log).is_null());
    let m = log.last();
    assert!(m.contains("export_rough.asc"), "{m}");
    // Another FMU's token.
    let (dir, _) = packed("token", Inputs::None);
    let log = Messages::new();
    assert!(instantiate(&dir, "{another}", &log).is_null());
    assert!(log.last().contains("is not this FMU's"), "{}", log.last());
}

#[test]
fn an_instance_used_after_it_was_freed_is_refused_with_a_message() {
    let (dir, token) = packed("freed", Inputs::None);
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    unsafe { fmi3FreeInstance(i) };
    assert_eq!(step(i, 0.0, 0.01).0, status::FATAL);
    assert_eq!(
        log.last(),
        "fmi3DoStep: the instance was freed; create a new one"
    );
    assert_eq!(get(i, &[1]).0, status::FATAL);
    unsafe { fmi3FreeInstance(i) };
    assert_eq!(
        log.last(),
        "fmi3FreeInstance: the instance was already freed"
    );
    // A null instance.
    assert_eq!(step(std::ptr::null_mut(), 0.0, 0.01).0, status::FATAL);
}

#[test]
fn torque_inputs_reach_the_wheels() {
    let (dir, token) = packed("inputs", Inputs::Torques);
    let log = Messages::new();
    let i = initialized(&dir, &token, &log);
    // tau1_cmd .. tau4_cmd follow the time and the 69 outputs.
    let torques = [0.5, 0.5, 0.5, 0.5];
    let vrs = [70u32, 71, 72, 73];
    assert_eq!(
        unsafe { fmi3SetFloat64(i, vrs.as_ptr(), 4, torques.as_ptr(), 4) },
        status::OK,
        "{}",
        log.last()
    );
    assert_eq!(get(i, &vrs).1, torques);
    let nan = [f64::NAN];
    assert_eq!(
        unsafe { fmi3SetFloat64(i, vrs.as_ptr(), 1, nan.as_ptr(), 1) },
        status::ERROR
    );
    assert_eq!(
        log.last(),
        "fmi3SetFloat64: tau1_cmd (value reference 70) set to NaN: give a finite number"
    );
    assert_eq!(step(i, 0.0, 0.01).0, status::OK);
    // The row's torque columns hold the speed loop's plus the command.
    let names = Prepared::from_file(None, &dir.join(SCENARIO_FILE)).unwrap();
    let columns = names.stepper(false).unwrap().columns().clone();
    let tau1 = columns.position("tau1").unwrap() as u32;
    let with = get(i, &[tau1]).1[0];
    assert_eq!(unsafe { fmi3Reset(i) }, status::OK);
    unsafe {
        assert_eq!(
            fmi3EnterInitializationMode(i, false, 0.0, 0.0, false, 0.0),
            status::OK
        );
        assert_eq!(fmi3ExitInitializationMode(i), status::OK);
    }
    assert_eq!(get(i, &vrs).1, [0.0; 4], "a reset puts the inputs back");
    assert_eq!(step(i, 0.0, 0.01).0, status::OK);
    let without = get(i, &[tau1]).1[0];
    assert!(
        (with - without - 0.5).abs() < 0.05,
        "{with} against {without}"
    );
    unsafe { fmi3FreeInstance(i) };
}

#[test]
fn the_c_api_reports_bad_input_and_use_after_destroy() {
    let (dir, _) = packed("capi", Inputs::None);
    let mut p: *mut c_void = std::ptr::null_mut();
    let mut message = [0 as c_char; 512];
    let missing = CString::new(dir.join("nowhere.toml").display().to_string()).unwrap();
    let s = unsafe {
        rover_create(
            missing.as_ptr(),
            &mut p,
            message.as_mut_ptr(),
            message.len(),
        )
    };
    assert_eq!(s, 1);
    assert!(p.is_null());
    let m = unsafe { CStr::from_ptr(message.as_ptr()) }.to_string_lossy();
    assert!(
        m.contains("nowhere.toml") && m.contains("cannot read the scenario file"),
        "{m}"
    );

    let path = CString::new(dir.join(SCENARIO_FILE).display().to_string()).unwrap();
    let s = unsafe { rover_create(path.as_ptr(), &mut p, message.as_mut_ptr(), message.len()) };
    assert_eq!(s, 0);
    let mut n = 0;
    assert_eq!(unsafe { rover_output_count(p, &mut n) }, 0);
    assert_eq!(n, 70);
    let three = [1.0, 2.0, 3.0];
    assert_eq!(unsafe { rover_set_torques(p, three.as_ptr(), 3) }, 1);
    let m = unsafe { CStr::from_ptr(rover_error_message(p)) }
        .to_string_lossy()
        .into_owned();
    assert_eq!(m, "rover_set_torques: 3 torques given, the rover takes 4");
    assert_eq!(unsafe { rover_step(p, -1.0) }, 1);
    assert_eq!(unsafe { rover_step(p, 0.001) }, 0);
    let mut out = vec![0.0; n];
    assert_eq!(unsafe { rover_outputs(p, out.as_mut_ptr(), n - 1) }, 1);
    assert_eq!(unsafe { rover_outputs(p, out.as_mut_ptr(), n) }, 0);
    assert_eq!(out[0], 0.001);
    unsafe { rover_destroy(p) };
    assert_eq!(unsafe { rover_step(p, 0.001) }, 2);
    let m = unsafe { CStr::from_ptr(rover_error_message(p)) }
        .to_string_lossy()
        .into_owned();
    assert_eq!(m, "the instance was destroyed; create a new one");
    assert_eq!(unsafe { rover_step(std::ptr::null_mut(), 0.001) }, 2);
}
