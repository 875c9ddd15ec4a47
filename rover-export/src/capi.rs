//! The C library's functions (`rover_plant.h`): a plant created from a
//! scenario file, reset, given its inputs, stepped, read and destroyed.
//! Every function returns [`ROVER_OK`], [`ROVER_ERROR`] (the call was
//! refused or the run failed: `rover_error_message` says why, the handle
//! stays usable) or [`ROVER_UNUSABLE`] (a null, destroyed or broken
//! handle). Nothing allocates after `rover_create` but an error's message;
//! calls on one handle from several threads take turns.

use std::ffi::{c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use crate::handle::{self, Handle, Logger, Mode, Outcome};
use crate::instance::Instance;
use crate::resources::ExportSettings;
use crate::run::Factory;
use crate::variables::Inputs;

/// Done.
pub const ROVER_OK: c_int = 0;
/// Refused or failed; the message says why.
pub const ROVER_ERROR: c_int = 1;
/// A null, destroyed or broken handle.
pub const ROVER_UNUSABLE: c_int = 2;

fn code(o: Outcome) -> c_int {
    match o {
        Outcome::Ok => ROVER_OK,
        Outcome::Error => ROVER_ERROR,
        Outcome::Fatal => ROVER_UNUSABLE,
    }
}

/// Copy `message` into the caller's buffer (truncated, NUL-terminated).
unsafe fn write_message(buffer: *mut c_char, size: usize, message: &str) {
    if buffer.is_null() || size == 0 {
        return;
    }
    let bytes = message.as_bytes();
    let n = bytes.len().min(size - 1);
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr().cast::<c_char>(), buffer, n);
        *buffer.add(n) = 0;
    }
}

/// `rover_create`.
///
/// # Safety
///
/// `scenario` a NUL-terminated path, `out` writable, `message` null or
/// `message_size` writable bytes.
pub unsafe fn create(
    factory: Factory,
    scenario: *const c_char,
    out: *mut *mut c_void,
    message: *mut c_char,
    message_size: usize,
) -> c_int {
    let made = catch_unwind(AssertUnwindSafe(|| -> Result<*mut c_void, String> {
        if out.is_null() {
            return Err("rover_create: the handle's destination is null".into());
        }
        let path = unsafe { handle::text(scenario, "the scenario path") }?;
        let settings = ExportSettings {
            inputs: Inputs::Torques,
            token: String::new(),
        };
        let instance = Instance::open_scenario(Path::new(path), settings, factory)?;
        Ok(Handle::create(instance, Logger::None, path, Mode::Step))
    }));
    let text = match made {
        Ok(Ok(ptr)) => {
            unsafe { *out = ptr };
            unsafe { write_message(message, message_size, "") };
            return ROVER_OK;
        }
        Ok(Err(m)) => m,
        Err(_) => "rover_create: internal error (a bug in rover-export; please report it)".into(),
    };
    unsafe {
        if !out.is_null() {
            *out = std::ptr::null_mut();
        }
        write_message(message, message_size, &text);
    }
    ROVER_ERROR
}

/// `rover_destroy`.
///
/// # Safety
///
/// As [`handle::free`].
pub unsafe fn destroy(plant: *mut c_void) {
    unsafe { handle::free(plant, "rover_destroy") }
}

/// `rover_reset`.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn reset(plant: *mut c_void) -> c_int {
    code(unsafe {
        handle::call(plant, "rover_reset", |slot, _| {
            crate::fmi3::live(slot).reset();
            Ok(())
        })
    })
}

/// `rover_step`: advance by `dt` seconds.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn step(plant: *mut c_void, dt: f64) -> c_int {
    code(unsafe {
        handle::call(plant, "rover_step", |slot, _| {
            let inst = crate::fmi3::live(slot);
            inst.step(inst.time(), dt)
        })
    })
}

/// Which inputs a setter sets.
#[derive(Clone, Copy, Debug)]
pub enum Setter {
    /// Motor torques.
    Torques,
    /// Steering angles.
    Steering,
    /// Spring neutrals.
    Neutrals,
}

/// `rover_set_torques`, `rover_set_steering`, `rover_set_neutrals`.
///
/// # Safety
///
/// As [`handle::call`]; `values` points at `n` numbers.
pub unsafe fn set(plant: *mut c_void, which: Setter, values: *const f64, n: usize) -> c_int {
    let function = match which {
        Setter::Torques => "rover_set_torques",
        Setter::Steering => "rover_set_steering",
        Setter::Neutrals => "rover_set_neutrals",
    };
    code(unsafe {
        handle::call(plant, function, |slot, _| {
            let values = handle::slice(values, n, "values")?;
            let inst = crate::fmi3::live(slot);
            match which {
                Setter::Torques => inst.set_torques(values),
                Setter::Steering => inst.set_steering(values),
                Setter::Neutrals => inst.set_neutrals(values),
            }
        })
    })
}

/// `rover_outputs`: the row at the current time into `out` (`n` must be
/// the number of outputs).
///
/// # Safety
///
/// As [`handle::call`]; `out` has room for `n` numbers.
pub unsafe fn outputs(plant: *mut c_void, out: *mut f64, n: usize) -> c_int {
    code(unsafe {
        handle::call(plant, "rover_outputs", |slot, _| {
            let inst = crate::fmi3::live(slot);
            let row = inst.row();
            if n != row.len() {
                return Err(format!(
                    "room for {n} outputs, the rover has {} (rover_output_count)",
                    row.len()
                ));
            }
            handle::slice_mut(out, n, "out")?.copy_from_slice(row);
            Ok(())
        })
    })
}

/// What a size query asks.
#[derive(Clone, Copy, Debug)]
pub enum Count {
    /// Outputs (the row's columns).
    Outputs,
    /// Wheels.
    Wheels,
    /// Suspension coordinates.
    Coordinates,
}

/// `rover_output_count`, `rover_wheel_count`, `rover_coordinate_count`.
///
/// # Safety
///
/// As [`handle::call`]; `n` writable.
pub unsafe fn count(plant: *mut c_void, which: Count, n: *mut usize) -> c_int {
    code(unsafe {
        handle::call(plant, "rover_*_count", |slot, _| {
            let inst = crate::fmi3::live(slot);
            let value = match which {
                Count::Outputs => inst.row().len(),
                Count::Wheels => inst.vars.wheels,
                Count::Coordinates => inst.vars.coordinates,
            };
            handle::slice_mut(n, 1, "the count's destination")?[0] = value;
            Ok(())
        })
    })
}

/// What a time query asks.
#[derive(Clone, Copy, Debug)]
pub enum Clock {
    /// The current time.
    Time,
    /// The scenario's output interval.
    OutputStep,
}

/// `rover_time`, `rover_output_step`.
///
/// # Safety
///
/// As [`handle::call`]; `t` writable.
pub unsafe fn time(plant: *mut c_void, which: Clock, t: *mut f64) -> c_int {
    code(unsafe {
        handle::call(plant, "rover_time", |slot, _| {
            let inst = crate::fmi3::live(slot);
            let value = match which {
                Clock::Time => inst.time(),
                Clock::OutputStep => inst.output_step(),
            };
            handle::slice_mut(t, 1, "the time's destination")?[0] = value;
            Ok(())
        })
    })
}

/// `rover_output_name`: output `i`'s name (the CSV's column), or null.
///
/// # Safety
///
/// As [`handle::call`].
pub unsafe fn output_name(plant: *mut c_void, i: usize) -> *const c_char {
    let mut name = std::ptr::null();
    unsafe {
        handle::call(plant, "rover_output_name", |slot, _| {
            match slot.names.get(i) {
                Some(n) => name = n.as_ptr(),
                None => return Err(format!("no output {i}: there are {}", slot.names.len())),
            }
            Ok(())
        })
    };
    name
}

/// `rover_error_message`.
///
/// # Safety
///
/// As [`handle::last_message`].
pub unsafe fn error_message(plant: *mut c_void) -> *const c_char {
    unsafe { handle::last_message(plant) }
}
