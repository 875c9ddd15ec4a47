//! The FMI 3.0 Co-Simulation interface, written against the standard's
//! function signatures (fmi3Functions.h): what the exported `fmi3*`
//! symbols call ([`crate::entry_points`] defines the symbols). Only
//! Float64 variables exist; the functions of Model Exchange, Scheduled
//! Execution, event mode, FMU states and derivatives answer with an error
//! and a logged message.

use std::ffi::{c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use crate::handle::{self, Fmi3Log, Handle, Logger, Mode, Outcome, Slot, log_to, status};
use crate::instance::Instance;
use crate::run::Factory;

/// `fmi3GetVersion`.
pub fn version() -> *const c_char {
    c"3.0".as_ptr()
}

/// Open the plant packed in `resources` for an importer that gave
/// `token`; the message says what is wrong.
pub(crate) fn open(resources: &Path, token: &str, factory: Factory) -> Result<Instance, String> {
    let instance = Instance::open(resources, factory)?;
    if !instance.settings.token.is_empty() && token != instance.settings.token {
        return Err(format!(
            "the instantiation token {token:?} is not this FMU's ({:?}): the importer read another FMU's modelDescription.xml",
            instance.settings.token
        ));
    }
    Ok(instance)
}

/// `fmi3InstantiateCoSimulation`.
///
/// # Safety
///
/// The arguments as FMI 3.0 defines them.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate_co_simulation(
    factory: Factory,
    instance_name: *const c_char,
    instantiation_token: *const c_char,
    resource_path: *const c_char,
    event_mode_used: bool,
    logging_on: bool,
    instance_environment: *mut c_void,
    log_message: Option<Fmi3Log>,
) -> *mut c_void {
    let logger = Logger::Fmi3 {
        env: instance_environment,
        log: log_message,
    };
    let made = catch_unwind(AssertUnwindSafe(|| -> Result<*mut c_void, String> {
        let name = unsafe { handle::text(instance_name, "instanceName") }?;
        let token = unsafe { handle::text(instantiation_token, "instantiationToken") }?;
        if event_mode_used {
            return Err("eventModeUsed: this FMU has no event mode (hasEventMode = false)".into());
        }
        let resources = unsafe { handle::text(resource_path, "resourcePath") }.map_err(|e| {
            format!("{e}: the plant reads its scenario from the FMU's resources folder")
        })?;
        let instance = open(Path::new(resources), token, factory)?;
        let ptr = Handle::create(instance, logger_copy(&logger), name, Mode::Instantiated);
        let h: &Handle = unsafe { &*ptr.cast::<Handle>() };
        h.logging_on
            .store(logging_on, std::sync::atomic::Ordering::Relaxed);
        Ok(ptr)
    }));
    let message = match made {
        Ok(Ok(ptr)) => return ptr,
        Ok(Err(m)) => m,
        Err(_) => "internal error (a bug in rover-export; please report it)".into(),
    };
    let _ = catch_unwind(AssertUnwindSafe(|| {
        log_to(
            &logger,
            c"",
            status::ERROR,
            &format!("fmi3InstantiateCoSimulation: {message}"),
        )
    }));
    std::ptr::null_mut()
}

fn logger_copy(l: &Logger) -> Logger {
    match l {
        Logger::None => Logger::None,
        Logger::Fmi3 { env, log } => Logger::Fmi3 {
            env: *env,
            log: *log,
        },
        Logger::Fmi2 { env, log } => Logger::Fmi2 {
            env: *env,
            log: *log,
        },
    }
}

/// A function of the standard that this FMU does not provide.
///
/// # Safety
///
/// `instance` as [`handle::call`] takes it.
pub unsafe fn unsupported(instance: *mut c_void, function: &str) -> c_int {
    unsafe {
        handle::call(instance, function, |_, _| {
            Err("not supported: this FMU is Co-Simulation only, with Float64 variables, no event mode, no FMU state and no derivatives".into())
        })
    }
    .status()
}

/// The run of a slot checked live by [`handle::call`].
pub(crate) fn live(slot: &mut Slot) -> &mut Instance {
    slot.instance
        .as_mut()
        .expect("handle::call checks the instance")
}

/// Start time and the initialization mode (FMI 3's EnterInitializationMode,
/// FMI 2's SetupExperiment and EnterInitializationMode).
pub(crate) fn check_start(start_time: f64) -> Result<(), String> {
    if start_time != 0.0 {
        return Err(format!(
            "startTime = {start_time}: the plant's run starts at t = 0 (the scenario's start, settling included); start the experiment there"
        ));
    }
    Ok(())
}

/// `fmi3EnterInitializationMode`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn enter_initialization_mode(instance: *mut c_void, start_time: f64) -> c_int {
    unsafe {
        handle::call(instance, "fmi3EnterInitializationMode", |slot, _| {
            if slot.mode != Mode::Instantiated {
                return Err(format!(
                    "called in {:?} mode: call it once after instantiating or resetting",
                    slot.mode
                ));
            }
            check_start(start_time)?;
            slot.mode = Mode::Initialization;
            Ok(())
        })
    }
    .status()
}

/// `fmi3ExitInitializationMode` (FMI 2's too).
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn exit_initialization_mode(instance: *mut c_void, function: &str) -> c_int {
    unsafe {
        handle::call(instance, function, |slot, _| {
            if slot.mode != Mode::Initialization {
                return Err(format!(
                    "called in {:?} mode: enter the initialization mode first",
                    slot.mode
                ));
            }
            slot.mode = Mode::Step;
            Ok(())
        })
    }
    .status()
}

/// `fmi3Terminate` (FMI 2's too).
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn terminate(instance: *mut c_void, function: &str) -> c_int {
    unsafe {
        handle::call(instance, function, |slot, _| {
            slot.mode = Mode::Terminated;
            Ok(())
        })
    }
    .status()
}

/// `fmi3Reset` (FMI 2's too).
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn reset(instance: *mut c_void, function: &str) -> c_int {
    unsafe {
        handle::call(instance, function, |slot, _| {
            live(slot).reset();
            slot.mode = Mode::Instantiated;
            Ok(())
        })
    }
    .status()
}

/// `fmi3GetFloat64` (FMI 2's GetReal with `n_values` = `n_vr`).
///
/// # Safety
///
/// As FMI defines the arguments.
pub unsafe fn get_float64(
    instance: *mut c_void,
    function: &str,
    vrs: *const u32,
    n_vr: usize,
    values: *mut f64,
    n_values: usize,
) -> c_int {
    unsafe {
        handle::call(instance, function, |slot, _| {
            if n_values != n_vr {
                return Err(format!("{n_vr} value references but room for {n_values} values: every variable is a scalar"));
            }
            let vrs = handle::slice(vrs, n_vr, "valueReferences")?;
            let values = handle::slice_mut(values, n_values, "values")?;
            let inst = live(slot);
            for (v, &vr) in values.iter_mut().zip(vrs) {
                *v = inst.get(vr)?;
            }
            Ok(())
        })
    }
    .status()
}

/// `fmi3SetFloat64` (FMI 2's SetReal with `n_values` = `n_vr`).
///
/// # Safety
///
/// As FMI defines the arguments.
pub unsafe fn set_float64(
    instance: *mut c_void,
    function: &str,
    vrs: *const u32,
    n_vr: usize,
    values: *const f64,
    n_values: usize,
) -> c_int {
    unsafe {
        handle::call(instance, function, |slot, _| {
            if n_values != n_vr {
                return Err(format!(
                    "{n_vr} value references but {n_values} values: every variable is a scalar"
                ));
            }
            if slot.mode == Mode::Terminated {
                return Err("the instance is terminated: reset it to set inputs".into());
            }
            let vrs = handle::slice(vrs, n_vr, "valueReferences")?;
            let values = handle::slice(values, n_values, "values")?;
            let inst = live(slot);
            for (&v, &vr) in values.iter().zip(vrs) {
                inst.set(vr, v)?;
            }
            Ok(())
        })
    }
    .status()
}

/// One communication step (FMI 3's DoStep and FMI 2's); `time_after`
/// takes the time reached, whether or not the step failed.
pub(crate) fn step(
    slot: &mut Slot,
    current: f64,
    step: f64,
    time_after: &mut f64,
) -> Result<(), String> {
    if slot.mode != Mode::Step {
        return Err(format!(
            "called in {:?} mode: exit the initialization mode first",
            slot.mode
        ));
    }
    let inst = live(slot);
    let stepped = inst.step(current, step);
    *time_after = inst.time();
    stepped
}

/// `fmi3DoStep`.
///
/// # Safety
///
/// As FMI 3.0 defines the arguments (the output pointers may be null).
#[allow(clippy::too_many_arguments)]
pub unsafe fn do_step(
    instance: *mut c_void,
    current_communication_point: f64,
    communication_step_size: f64,
    event_handling_needed: *mut bool,
    terminate_simulation: *mut bool,
    early_return: *mut bool,
    last_successful_time: *mut f64,
) -> c_int {
    let mut reached = current_communication_point;
    let outcome = unsafe {
        handle::call(instance, "fmi3DoStep", |slot, _| {
            step(
                slot,
                current_communication_point,
                communication_step_size,
                &mut reached,
            )
        })
    };
    unsafe {
        for flag in [event_handling_needed, early_return] {
            if !flag.is_null() {
                *flag = false;
            }
        }
        if !terminate_simulation.is_null() {
            *terminate_simulation = outcome == Outcome::Fatal;
        }
        if !last_successful_time.is_null() {
            *last_successful_time = reached;
        }
    }
    outcome.status()
}

/// `fmi3FreeInstance`.
///
/// # Safety
///
/// As [`handle::free`].
pub unsafe fn free_instance(instance: *mut c_void) {
    unsafe { handle::free(instance, "fmi3FreeInstance") }
}

/// `fmi3SetDebugLogging`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn set_debug_logging(instance: *mut c_void, function: &str, on: bool) -> c_int {
    unsafe {
        handle::call(instance, function, |_, h| {
            h.logging_on.store(on, std::sync::atomic::Ordering::Relaxed);
            Ok(())
        })
    }
    .status()
}
