//! The FMI 2.0 Co-Simulation interface, written against the standard's
//! function signatures (fmi2Functions.h): what the exported `fmi2*`
//! symbols call ([`crate::entry_points`] defines them). The same instance
//! as FMI 3's; only Real variables exist.

use std::ffi::{c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

use crate::fmi3;
use crate::handle::{self, Fmi2Log, Handle, Logger, Mode, log_to, status};
use crate::run::Factory;

/// FMI 2's `fmi2CallbackFunctions`.
#[repr(C)]
#[derive(Debug)]
pub struct CallbackFunctions {
    /// The logger.
    pub logger: Option<Fmi2Log>,
    /// The importer's allocator (not used: the FMU allocates its own).
    pub allocate_memory: *const c_void,
    /// The importer's deallocator (not used).
    pub free_memory: *const c_void,
    /// Asynchronous steps' callback (not used).
    pub step_finished: *const c_void,
    /// Given back to the logger.
    pub component_environment: *mut c_void,
}

/// `fmi2GetVersion`.
pub fn version() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2GetTypesPlatform`.
pub fn types_platform() -> *const c_char {
    c"default".as_ptr()
}

/// The folder of a `file:` URI (FMI 2's resource location), its
/// percent-escapes decoded.
pub fn path_of_uri(uri: &str) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file://localhost/")
        .map(|r| format!("/{r}"))
        .or_else(|| uri.strip_prefix("file:///").map(|r| format!("/{r}")))
        .or_else(|| uri.strip_prefix("file:/").map(|r| format!("/{r}")))
        .ok_or_else(|| format!("fmuResourceLocation {uri:?} is not a file: URI"))?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(b) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(b);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    let path =
        String::from_utf8(out).map_err(|_| format!("fmuResourceLocation {uri:?} is not UTF-8"))?;
    // On Windows, `/C:/…`.
    #[cfg(windows)]
    let path = path.trim_start_matches('/').to_string();
    Ok(PathBuf::from(path))
}

/// `fmi2Instantiate`.
///
/// # Safety
///
/// The arguments as FMI 2.0 defines them.
pub unsafe fn instantiate(
    factory: Factory,
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    resource_location: *const c_char,
    functions: *const CallbackFunctions,
    logging_on: c_int,
) -> *mut c_void {
    let (env, log) = if functions.is_null() {
        (std::ptr::null_mut(), None)
    } else {
        let f = unsafe { &*functions };
        (f.component_environment, f.logger)
    };
    let made = catch_unwind(AssertUnwindSafe(|| -> Result<*mut c_void, String> {
        let name = unsafe { handle::text(instance_name, "instanceName") }?;
        let guid = unsafe { handle::text(guid, "fmuGUID") }?;
        if fmu_type != 1 {
            return Err(format!(
                "fmuType = {fmu_type}: this FMU is Co-Simulation only (fmi2CoSimulation = 1)"
            ));
        }
        let location =
            unsafe { handle::text(resource_location, "fmuResourceLocation") }.map_err(|e| {
                format!("{e}: the plant reads its scenario from the FMU's resources folder")
            })?;
        let instance = fmi3::open(&path_of_uri(location)?, guid, factory)?;
        let ptr = Handle::create(
            instance,
            Logger::Fmi2 { env, log },
            name,
            Mode::Instantiated,
        );
        let h: &Handle = unsafe { &*ptr.cast::<Handle>() };
        h.logging_on
            .store(logging_on != 0, std::sync::atomic::Ordering::Relaxed);
        Ok(ptr)
    }));
    let message = match made {
        Ok(Ok(ptr)) => return ptr,
        Ok(Err(m)) => m,
        Err(_) => "internal error (a bug in rover-export; please report it)".into(),
    };
    let name = if instance_name.is_null() {
        c"".to_owned()
    } else {
        unsafe { std::ffi::CStr::from_ptr(instance_name) }.to_owned()
    };
    let _ = catch_unwind(AssertUnwindSafe(|| {
        log_to(
            &Logger::Fmi2 { env, log },
            &name,
            status::ERROR,
            &format!("fmi2Instantiate: {message}"),
        )
    }));
    std::ptr::null_mut()
}

/// `fmi2SetupExperiment`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn setup_experiment(instance: *mut c_void, start_time: f64) -> c_int {
    unsafe {
        handle::call(instance, "fmi2SetupExperiment", |slot, _| {
            if slot.mode != Mode::Instantiated {
                return Err(format!(
                    "called in {:?} mode: call it after instantiating or resetting",
                    slot.mode
                ));
            }
            fmi3::check_start(start_time)
        })
    }
    .status()
}

/// `fmi2EnterInitializationMode`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn enter_initialization_mode(instance: *mut c_void) -> c_int {
    unsafe {
        handle::call(instance, "fmi2EnterInitializationMode", |slot, _| {
            if slot.mode != Mode::Instantiated {
                return Err(format!(
                    "called in {:?} mode: call it once after instantiating or resetting",
                    slot.mode
                ));
            }
            slot.mode = Mode::Initialization;
            Ok(())
        })
    }
    .status()
}

/// `fmi2DoStep`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn do_step(instance: *mut c_void, current: f64, step: f64) -> c_int {
    let mut reached = current;
    unsafe {
        handle::call(instance, "fmi2DoStep", |slot, _| {
            fmi3::step(slot, current, step, &mut reached)
        })
    }
    .status()
}

/// `fmi2GetStatus`, `fmi2GetRealStatus` (`fmi2LastSuccessfulTime` = 2) and
/// the like: only the last successful time is known.
///
/// # Safety
///
/// As [`handle::call`]; `value` null or writable.
pub unsafe fn get_real_status(instance: *mut c_void, kind: c_int, value: *mut f64) -> c_int {
    unsafe {
        handle::call(instance, "fmi2GetRealStatus", |slot, _| {
            if kind != 2 {
                return Err(format!(
                    "status kind {kind}: only fmi2LastSuccessfulTime (2) is a Real status"
                ));
            }
            let v = handle::slice_mut(value, 1, "value")?;
            v[0] = fmi3::live(slot).time();
            Ok(())
        })
    }
    .status()
}
