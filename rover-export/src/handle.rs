//! What an FMU instance or a C handle points at, and the guard every
//! exported function goes through: a null or freed handle is refused with
//! a message, a panic is caught before it crosses the boundary, each
//! instance is locked while a call uses it (one instance may be shared by
//! threads; two instances never wait for each other).
//!
//! A freed handle keeps its few bytes (the magic number, the logger and
//! the name; the run itself is dropped) so that a call on it afterwards is
//! told apart from a live one and reported, instead of reading freed
//! memory: each instance ever freed leaks about a hundred bytes.

use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use crate::instance::Instance;

/// FMI's status codes (the same numbers in FMI 2 and 3).
pub mod status {
    /// All went well.
    pub const OK: i32 = 0;
    /// Done, with a warning logged.
    pub const WARNING: i32 = 1;
    /// The step was not completed.
    pub const DISCARD: i32 = 2;
    /// The call failed; the instance may still be used (reset, freed).
    pub const ERROR: i32 = 3;
    /// The instance cannot be used any more.
    pub const FATAL: i32 = 4;
}

const LIVE: u64 = 0x524f_5645_525f_4c56; // "ROVER_LV"
const FREED: u64 = 0x524f_5645_525f_4644; // "ROVER_FD"

/// FMI 3's `fmi3LogMessageCallback`.
pub type Fmi3Log = unsafe extern "C" fn(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
);

/// FMI 2's `fmi2CallbackLogger` (variadic: the message is a format).
pub type Fmi2Log = unsafe extern "C" fn(
    env: *mut c_void,
    instance_name: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
    ...
);

/// Where an instance's messages go.
#[derive(Debug)]
pub enum Logger {
    /// Nowhere but the handle's last message (the C library).
    None,
    /// FMI 3's callback.
    Fmi3 {
        /// The importer's environment pointer.
        env: *mut c_void,
        /// The callback.
        log: Option<Fmi3Log>,
    },
    /// FMI 2's callback.
    Fmi2 {
        /// The importer's environment pointer.
        env: *mut c_void,
        /// The callback.
        log: Option<Fmi2Log>,
    },
}

/// What a call may change: the run, the FMI state, the last message.
#[derive(Debug)]
pub struct Slot {
    /// The run; `None` once freed.
    pub instance: Option<Instance>,
    /// Where the instance is in FMI's state machine.
    pub mode: Mode,
    /// The last error's message (the C library's `rover_error_message`).
    pub message: CString,
    /// The row's column names (the C library's `rover_output_name`).
    pub names: Vec<CString>,
}

/// FMI's states, as far as a Co-Simulation plant tells them apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Instantiated: inputs may be set, no step taken.
    Instantiated,
    /// Between EnterInitializationMode and ExitInitializationMode.
    Initialization,
    /// Stepping.
    Step,
    /// Terminated: outputs may be read, no step taken.
    Terminated,
}

/// An exported instance (see the module's documentation).
#[derive(Debug)]
pub struct Handle {
    magic: AtomicU64,
    logger: Logger,
    /// The instance's name, for FMI 2's logger.
    name: CString,
    /// Whether the importer asked for debug messages.
    pub logging_on: AtomicBool,
    slot: Mutex<Slot>,
}

// The logger's pointers are the importer's, which FMI lets any thread use
// with its instance.
unsafe impl Send for Logger {}
unsafe impl Sync for Logger {}

/// How a guarded call ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Done.
    Ok,
    /// Refused or failed, the message logged; the instance is usable.
    Error,
    /// A null or freed handle, or an internal error (a panic): logged
    /// where a logger is known.
    Fatal,
}

impl Outcome {
    /// FMI's status for it.
    pub fn status(self) -> c_int {
        match self {
            Outcome::Ok => status::OK,
            Outcome::Error => status::ERROR,
            Outcome::Fatal => status::FATAL,
        }
    }
}

impl Handle {
    /// A live handle holding `instance`, as a pointer for the importer.
    pub fn create(instance: Instance, logger: Logger, name: &str, mode: Mode) -> *mut c_void {
        let names = instance
            .vars
            .list
            .iter()
            .filter(|v| {
                matches!(
                    v.role,
                    crate::variables::Role::Time | crate::variables::Role::Output(_)
                )
            })
            .map(|v| {
                CString::new(if v.role == crate::variables::Role::Time {
                    "t"
                } else {
                    v.name.as_str()
                })
                .unwrap_or_default()
            })
            .collect();
        let handle = Box::new(Handle {
            magic: AtomicU64::new(LIVE),
            logger,
            name: CString::new(name.replace('\0', " ")).unwrap_or_default(),
            logging_on: AtomicBool::new(false),
            slot: Mutex::new(Slot {
                instance: Some(instance),
                mode,
                message: CString::default(),
                names,
            }),
        });
        Box::into_raw(handle).cast()
    }

    /// Log `message` with `status` through the instance's logger.
    pub fn log(&self, status: c_int, message: &str) {
        log_to(&self.logger, &self.name, status, message);
    }
}

/// Log `message` through `logger` (errors go out whether or not debug
/// logging is on).
pub fn log_to(logger: &Logger, name: &CStr, status: c_int, message: &str) {
    let category: &CStr = if status >= status::ERROR {
        c"logStatusError"
    } else {
        c"logStatusWarning"
    };
    match logger {
        Logger::None => {}
        Logger::Fmi3 {
            env,
            log: Some(log),
        } => {
            let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
            unsafe { log(*env, status, category.as_ptr(), text.as_ptr()) };
        }
        Logger::Fmi2 {
            env,
            log: Some(log),
        } => {
            // The message is a format: its percent signs are doubled.
            let text =
                CString::new(message.replace('\0', " ").replace('%', "%%")).unwrap_or_default();
            unsafe {
                log(
                    *env,
                    name.as_ptr(),
                    status,
                    category.as_ptr(),
                    text.as_ptr(),
                )
            };
        }
        Logger::Fmi3 { log: None, .. } | Logger::Fmi2 { log: None, .. } => {}
    }
}

/// The panic's message, for the log.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".into())
}

/// Run `f` on the instance behind `ptr`, for the exported function
/// `function`: refused on a null or freed handle, a failed instance
/// (`f`'s `Err`) logged with the function's name, a panic caught.
///
/// # Safety
///
/// `ptr` is null or a pointer [`Handle::create`] returned (freed or not).
pub unsafe fn call(
    ptr: *mut c_void,
    function: &str,
    f: impl FnOnce(&mut Slot, &Handle) -> Result<(), String>,
) -> Outcome {
    if ptr.is_null() {
        return Outcome::Fatal;
    }
    let handle: &Handle = unsafe { &*ptr.cast::<Handle>() };
    let run = catch_unwind(AssertUnwindSafe(|| {
        if handle.magic.load(Ordering::Acquire) != LIVE {
            let message = format!("{function}: the instance was freed; create a new one");
            handle.log(status::FATAL, &message);
            return Outcome::Fatal;
        }
        let mut slot = match handle.slot.lock() {
            Ok(s) => s,
            Err(_) => {
                handle.log(
                    status::FATAL,
                    &format!(
                        "{function}: the instance is unusable after an internal error; free it"
                    ),
                );
                return Outcome::Fatal;
            }
        };
        if slot.instance.is_none() {
            handle.log(
                status::FATAL,
                &format!("{function}: the instance was freed; create a new one"),
            );
            return Outcome::Fatal;
        }
        match f(&mut slot, handle) {
            Ok(()) => Outcome::Ok,
            Err(message) => {
                let message = format!("{function}: {message}");
                handle.log(status::ERROR, &message);
                slot.message = CString::new(message.replace('\0', " ")).unwrap_or_default();
                Outcome::Error
            }
        }
    }));
    run.unwrap_or_else(|payload| {
        let message = format!(
            "{function}: internal error (a bug in rover-export; please report it): {}",
            panic_message(&*payload)
        );
        let _ = catch_unwind(AssertUnwindSafe(|| handle.log(status::FATAL, &message)));
        Outcome::Fatal
    })
}

/// Free the instance behind `ptr`: its run is dropped, the handle marked
/// freed (and kept: see the module's documentation). A second free is
/// logged and otherwise ignored.
///
/// # Safety
///
/// As [`call`].
pub unsafe fn free(ptr: *mut c_void, function: &str) {
    if ptr.is_null() {
        return;
    }
    let handle: &Handle = unsafe { &*ptr.cast::<Handle>() };
    let _ = catch_unwind(AssertUnwindSafe(|| {
        if handle.magic.swap(FREED, Ordering::AcqRel) != LIVE {
            handle.log(
                status::ERROR,
                &format!("{function}: the instance was already freed"),
            );
            return;
        }
        let taken = match handle.slot.lock() {
            Ok(mut s) => s.instance.take(),
            Err(poisoned) => poisoned.into_inner().instance.take(),
        };
        drop(taken);
    }));
}

/// The last error's message of the handle behind `ptr` (empty when none),
/// valid until the next call on it; a null pointer gives null, a freed
/// handle a fixed message.
///
/// # Safety
///
/// As [`call`].
pub unsafe fn last_message(ptr: *mut c_void) -> *const c_char {
    if ptr.is_null() {
        return std::ptr::null();
    }
    let handle: &Handle = unsafe { &*ptr.cast::<Handle>() };
    if handle.magic.load(Ordering::Acquire) != LIVE {
        return c"the instance was destroyed; create a new one".as_ptr();
    }
    match handle.slot.lock() {
        Ok(s) => s.message.as_ptr(),
        Err(_) => c"the instance is unusable after an internal error; destroy it".as_ptr(),
    }
}

/// A C string argument as text, or the message why it cannot be.
///
/// # Safety
///
/// `s` is null or a NUL-terminated string.
pub unsafe fn text<'a>(s: *const c_char, what: &str) -> Result<&'a str, String> {
    if s.is_null() {
        return Err(format!("{what} is null"));
    }
    unsafe { CStr::from_ptr(s) }
        .to_str()
        .map_err(|_| format!("{what} is not UTF-8"))
}

/// A C array argument as a slice (empty for n = 0 whatever the pointer).
///
/// # Safety
///
/// `p` points at `n` values, or `n` is 0.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], String> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(format!("{what} is null but {n} values were announced"));
    }
    Ok(unsafe { std::slice::from_raw_parts(p, n) })
}

/// A C array argument to write, as a slice.
///
/// # Safety
///
/// `p` points at `n` writable values, or `n` is 0.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Result<&'a mut [T], String> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(format!("{what} is null but {n} values were announced"));
    }
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}
