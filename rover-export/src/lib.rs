//! A rover's plant for the tools of hardware-in-the-loop rigs: an FMI 3.0
//! or 2.0 Co-Simulation FMU, and a C library (docs/EXPORT.md).
//!
//! Both are packaging around one scenario's step-wise run
//! ([`rover_scenario::Stepper`]): an FMU's `fmi3DoStep` and the C
//! library's `rover_step` advance the same driver as `rover simulate`, so
//! that an FMU stepped at the scenario's output instants gives the rows
//! of its CSV. The plant library is built once, ahead of time (the
//! `rover-plant` crate, `cargo build -p rover-plant`), and reads the
//! scenario, the rover and the terrain from a folder at run time (an
//! FMU's resources): a built-in rover or a rover file exports without a
//! Rust toolchain.
//!
//! - [`resources`] packs a scenario and the files it names into a folder;
//! - [`variables`] lists the exported variables (the CSV's columns as
//!   outputs; the torques, steering angles and spring neutrals as inputs);
//! - [`instance`] is one plant, opened from such a folder;
//! - [`handle`], [`fmi3`], [`fmi2`] and [`capi`] are the C interfaces
//!   (no panic crosses them, a freed handle is detected, each instance is
//!   locked by its calls);
//! - [`model_description`] and [`zip`] write the FMU; [`package`] is
//!   `rover export`.
//!
//! The exported symbols are defined by the [`entry_points!`] macro in the
//! crate that builds the library, with the [`run::Factory`] that makes its
//! plant: `rover-plant` uses [`run::builtin`] (a built-in rover's generated
//! plant, or the generic plant of a rover file). A rover derived in Rust
//! source gets its generated plant into an FMU the same way, from a crate
//! of its own (docs/EXPORT.md, "A rover derived in Rust"):
//!
//! ```ignore
//! // Cargo.toml: [lib] crate-type = ["cdylib", "staticlib"]
//! fn factory(p: &Prepared) -> Result<Box<dyn Run>, PrepareError> {
//!     let stepper = Stepper::new(MyRover::default(), &p.spec.model, &p.scenario, &p.base)
//!         .map_err(|e| p.locate(e))?;
//!     Ok(Box::new(stepper))
//! }
//! rover_export::entry_points!(factory);
//! ```

#![warn(missing_docs)]

pub mod capi;
pub mod error;
pub mod fmi2;
pub mod fmi3;
pub mod handle;
pub mod instance;
pub mod model_description;
pub mod package;
pub mod resources;
pub mod run;
pub mod variables;
pub mod zip;

pub use error::ExportError;

/// Define the FMI 3.0, FMI 2.0 and C library symbols of a plant library
/// whose runs `$factory` (a [`run::Factory`]) builds. Use it once, in the
/// crate that builds the `cdylib` and `staticlib`.
#[macro_export]
macro_rules! entry_points {
    ($factory:path) => {
        // The standard's functions: their safety is FMI's (and the C
        // header's) contract with the caller.
        #[allow(clippy::missing_safety_doc)]
        const _: () = {
            use ::std::ffi::{c_char, c_int, c_void};
            use $crate::{capi, fmi2, fmi3, handle};
            type Inst = *mut c_void;
            type Vr = *const u32;

            // ---- FMI 3.0 (fmi3Functions.h) ----
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi3GetVersion() -> *const c_char {
                fmi3::version()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetDebugLogging(i: Inst, on: bool, _n: usize, _c: *const *const c_char) -> c_int {
                unsafe { fmi3::set_debug_logging(i, "fmi3SetDebugLogging", on) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateModelExchange(
                _name: *const c_char, _token: *const c_char, _res: *const c_char, _visible: bool,
                _logging_on: bool, env: *mut c_void, log: Option<handle::Fmi3Log>,
            ) -> Inst {
                handle::log_to(&handle::Logger::Fmi3 { env, log }, c"", handle::status::ERROR,
                    "fmi3InstantiateModelExchange: this FMU is Co-Simulation only");
                ::std::ptr::null_mut()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
                name: *const c_char, token: *const c_char, res: *const c_char, _visible: bool,
                logging_on: bool, event_mode_used: bool, _early_return_allowed: bool,
                _required: *const u32, _n_required: usize, env: *mut c_void,
                log: Option<handle::Fmi3Log>, _intermediate_update: *const c_void,
            ) -> Inst {
                unsafe { fmi3::instantiate_co_simulation($factory, name, token, res, event_mode_used, logging_on, env, log) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
                _name: *const c_char, _token: *const c_char, _res: *const c_char, _visible: bool,
                _logging_on: bool, env: *mut c_void, log: Option<handle::Fmi3Log>,
                _clock_update: *const c_void, _lock: *const c_void, _unlock: *const c_void,
            ) -> Inst {
                handle::log_to(&handle::Logger::Fmi3 { env, log }, c"", handle::status::ERROR,
                    "fmi3InstantiateScheduledExecution: this FMU is Co-Simulation only");
                ::std::ptr::null_mut()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3FreeInstance(i: Inst) {
                unsafe { fmi3::free_instance(i) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterInitializationMode(i: Inst, _tol_defined: bool, _tol: f64, start: f64, _stop_defined: bool, _stop: f64) -> c_int {
                unsafe { fmi3::enter_initialization_mode(i, start) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3ExitInitializationMode(i: Inst) -> c_int {
                unsafe { fmi3::exit_initialization_mode(i, "fmi3ExitInitializationMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterEventMode(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3EnterEventMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3Terminate(i: Inst) -> c_int {
                unsafe { fmi3::terminate(i, "fmi3Terminate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3Reset(i: Inst) -> c_int {
                unsafe { fmi3::reset(i, "fmi3Reset") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetFloat64(i: Inst, vr: Vr, nvr: usize, v: *mut f64, nv: usize) -> c_int {
                unsafe { fmi3::get_float64(i, "fmi3GetFloat64", vr, nvr, v, nv) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetFloat64(i: Inst, vr: Vr, nvr: usize, v: *const f64, nv: usize) -> c_int {
                unsafe { fmi3::set_float64(i, "fmi3SetFloat64", vr, nvr, v, nv) }
            }
            $crate::entry_points!(@fmi3_typed
                fmi3GetFloat32 fmi3SetFloat32 f32,
                fmi3GetInt8 fmi3SetInt8 i8,
                fmi3GetUInt8 fmi3SetUInt8 u8,
                fmi3GetInt16 fmi3SetInt16 i16,
                fmi3GetUInt16 fmi3SetUInt16 u16,
                fmi3GetInt32 fmi3SetInt32 i32,
                fmi3GetUInt32 fmi3SetUInt32 u32,
                fmi3GetInt64 fmi3SetInt64 i64,
                fmi3GetUInt64 fmi3SetUInt64 u64,
                fmi3GetBoolean fmi3SetBoolean bool,
                fmi3GetString fmi3SetString *const c_char
            );
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetBinary(i: Inst, _vr: Vr, _nvr: usize, _sizes: *mut usize, _v: *mut *const u8, _nv: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetBinary") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetBinary(i: Inst, _vr: Vr, _nvr: usize, _sizes: *const usize, _v: *const *const u8, _nv: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetBinary") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetClock(i: Inst, _vr: Vr, _nvr: usize, _v: *mut bool) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetClock") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetClock(i: Inst, _vr: Vr, _nvr: usize, _v: *const bool) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetClock") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(i: Inst, _vr: u32, _n: *mut usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetNumberOfVariableDependencies") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetVariableDependencies(i: Inst, _vr: u32, _e: *mut usize, _ind: *mut u32, _ei: *mut usize, _k: *mut c_int, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetVariableDependencies") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetFMUState(i: Inst, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetFMUState") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetFMUState(i: Inst, _s: *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetFMUState") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3FreeFMUState(i: Inst, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3FreeFMUState") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SerializedFMUStateSize(i: Inst, _s: *mut c_void, _size: *mut usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SerializedFMUStateSize") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SerializeFMUState(i: Inst, _s: *mut c_void, _b: *mut u8, _size: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SerializeFMUState") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3DeserializeFMUState(i: Inst, _b: *const u8, _size: usize, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3DeserializeFMUState") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetDirectionalDerivative(i: Inst, _u: Vr, _nu: usize, _k: Vr, _nk: usize, _seed: *const f64, _ns: usize, _sens: *mut f64, _nsens: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetDirectionalDerivative") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetAdjointDerivative(i: Inst, _u: Vr, _nu: usize, _k: Vr, _nk: usize, _seed: *const f64, _ns: usize, _sens: *mut f64, _nsens: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetAdjointDerivative") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterConfigurationMode(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3EnterConfigurationMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3ExitConfigurationMode(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3ExitConfigurationMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetIntervalDecimal(i: Inst, _vr: Vr, _nvr: usize, _iv: *mut f64, _q: *mut c_int) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetIntervalDecimal") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetIntervalFraction(i: Inst, _vr: Vr, _nvr: usize, _c: *mut u64, _r: *mut u64, _q: *mut c_int) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetIntervalFraction") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetShiftDecimal(i: Inst, _vr: Vr, _nvr: usize, _s: *mut f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetShiftDecimal") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetShiftFraction(i: Inst, _vr: Vr, _nvr: usize, _c: *mut u64, _r: *mut u64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetShiftFraction") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetIntervalDecimal(i: Inst, _vr: Vr, _nvr: usize, _iv: *const f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetIntervalDecimal") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetIntervalFraction(i: Inst, _vr: Vr, _nvr: usize, _c: *const u64, _r: *const u64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetIntervalFraction") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetShiftDecimal(i: Inst, _vr: Vr, _nvr: usize, _s: *const f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetShiftDecimal") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetShiftFraction(i: Inst, _vr: Vr, _nvr: usize, _c: *const u64, _r: *const u64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetShiftFraction") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3EvaluateDiscreteStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3UpdateDiscreteStates(i: Inst, _a: *mut bool, _b: *mut bool, _c: *mut bool, _d: *mut bool, _e: *mut bool, _t: *mut f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3UpdateDiscreteStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3EnterContinuousTimeMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3CompletedIntegratorStep(i: Inst, _no_set: bool, _enter: *mut bool, _term: *mut bool) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3CompletedIntegratorStep") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetTime(i: Inst, _t: f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetTime") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3SetContinuousStates(i: Inst, _x: *const f64, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3SetContinuousStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(i: Inst, _x: *mut f64, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetContinuousStateDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetEventIndicators(i: Inst, _x: *mut f64, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetEventIndicators") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetContinuousStates(i: Inst, _x: *mut f64, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetContinuousStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(i: Inst, _x: *mut f64, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetNominalsOfContinuousStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(i: Inst, _n: *mut usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetNumberOfEventIndicators") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(i: Inst, _n: *mut usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetNumberOfContinuousStates") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3EnterStepMode(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3EnterStepMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3GetOutputDerivatives(i: Inst, _vr: Vr, _nvr: usize, _o: *const i32, _v: *mut f64, _nv: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3GetOutputDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3DoStep(
                i: Inst, current: f64, step: f64, _no_set_prior: bool, event_handling_needed: *mut bool,
                terminate: *mut bool, early_return: *mut bool, last_successful_time: *mut f64,
            ) -> c_int {
                unsafe { fmi3::do_step(i, current, step, event_handling_needed, terminate, early_return, last_successful_time) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi3ActivateModelPartition(i: Inst, _clock: u32, _t: f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi3ActivateModelPartition") }
            }

            // ---- FMI 2.0 (fmi2Functions.h) ----
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
                fmi2::types_platform()
            }
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetVersion() -> *const c_char {
                fmi2::version()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetDebugLogging(i: Inst, on: c_int, _n: usize, _c: *const *const c_char) -> c_int {
                unsafe { fmi3::set_debug_logging(i, "fmi2SetDebugLogging", on != 0) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Instantiate(
                name: *const c_char, kind: c_int, guid: *const c_char, res: *const c_char,
                functions: *const fmi2::CallbackFunctions, _visible: c_int, logging_on: c_int,
            ) -> Inst {
                unsafe { fmi2::instantiate($factory, name, kind, guid, res, functions, logging_on) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeInstance(i: Inst) {
                unsafe { handle::free(i, "fmi2FreeInstance") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetupExperiment(i: Inst, _tol_defined: c_int, _tol: f64, start: f64, _stop_defined: c_int, _stop: f64) -> c_int {
                unsafe { fmi2::setup_experiment(i, start) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterInitializationMode(i: Inst) -> c_int {
                unsafe { fmi2::enter_initialization_mode(i) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2ExitInitializationMode(i: Inst) -> c_int {
                unsafe { fmi3::exit_initialization_mode(i, "fmi2ExitInitializationMode") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Terminate(i: Inst) -> c_int {
                unsafe { fmi3::terminate(i, "fmi2Terminate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Reset(i: Inst) -> c_int {
                unsafe { fmi3::reset(i, "fmi2Reset") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetReal(i: Inst, vr: Vr, nvr: usize, v: *mut f64) -> c_int {
                unsafe { fmi3::get_float64(i, "fmi2GetReal", vr, nvr, v, nvr) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetReal(i: Inst, vr: Vr, nvr: usize, v: *const f64) -> c_int {
                unsafe { fmi3::set_float64(i, "fmi2SetReal", vr, nvr, v, nvr) }
            }
            $crate::entry_points!(@fmi2_typed
                fmi2GetInteger fmi2SetInteger c_int,
                fmi2GetBoolean fmi2SetBoolean c_int,
                fmi2GetString fmi2SetString *const c_char
            );
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetFMUstate(i: Inst, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetFMUstate(i: Inst, _s: *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2SetFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeFMUstate(i: Inst, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2FreeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(i: Inst, _s: *mut c_void, _n: *mut usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2SerializedFMUstateSize") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(i: Inst, _s: *mut c_void, _b: *mut c_char, _n: usize) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2SerializeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(i: Inst, _b: *const c_char, _n: usize, _s: *mut *mut c_void) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2DeSerializeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(i: Inst, _u: Vr, _nu: usize, _k: Vr, _nk: usize, _dv: *const f64, _dz: *mut f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetDirectionalDerivative") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(i: Inst, _vr: Vr, _nvr: usize, _o: *const c_int, _v: *const f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2SetRealInputDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(i: Inst, _vr: Vr, _nvr: usize, _o: *const c_int, _v: *mut f64) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetRealOutputDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DoStep(i: Inst, current: f64, step: f64, _no_set_prior: c_int) -> c_int {
                unsafe { fmi2::do_step(i, current, step) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CancelStep(i: Inst) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2CancelStep") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStatus(i: Inst, _kind: c_int, _v: *mut c_int) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetStatus") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealStatus(i: Inst, kind: c_int, v: *mut f64) -> c_int {
                unsafe { fmi2::get_real_status(i, kind, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetIntegerStatus(i: Inst, _kind: c_int, _v: *mut c_int) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetIntegerStatus") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetBooleanStatus(i: Inst, _kind: c_int, _v: *mut c_int) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetBooleanStatus") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStringStatus(i: Inst, _kind: c_int, _v: *mut *const c_char) -> c_int {
                unsafe { fmi3::unsupported(i, "fmi2GetStringStatus") }
            }

            // ---- The C library (rover_plant.h) ----
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_create(scenario: *const c_char, out: *mut Inst, message: *mut c_char, size: usize) -> c_int {
                unsafe { capi::create($factory, scenario, out, message, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_destroy(p: Inst) {
                unsafe { capi::destroy(p) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_reset(p: Inst) -> c_int {
                unsafe { capi::reset(p) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_step(p: Inst, dt: f64) -> c_int {
                unsafe { capi::step(p, dt) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_set_torques(p: Inst, v: *const f64, n: usize) -> c_int {
                unsafe { capi::set(p, capi::Setter::Torques, v, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_set_steering(p: Inst, v: *const f64, n: usize) -> c_int {
                unsafe { capi::set(p, capi::Setter::Steering, v, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_set_neutrals(p: Inst, v: *const f64, n: usize) -> c_int {
                unsafe { capi::set(p, capi::Setter::Neutrals, v, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_outputs(p: Inst, out: *mut f64, n: usize) -> c_int {
                unsafe { capi::outputs(p, out, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_output_count(p: Inst, n: *mut usize) -> c_int {
                unsafe { capi::count(p, capi::Count::Outputs, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_wheel_count(p: Inst, n: *mut usize) -> c_int {
                unsafe { capi::count(p, capi::Count::Wheels, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_coordinate_count(p: Inst, n: *mut usize) -> c_int {
                unsafe { capi::count(p, capi::Count::Coordinates, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_output_name(p: Inst, i: usize) -> *const c_char {
                unsafe { capi::output_name(p, i) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_time(p: Inst, t: *mut f64) -> c_int {
                unsafe { capi::time(p, capi::Clock::Time, t) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_output_step(p: Inst, t: *mut f64) -> c_int {
                unsafe { capi::time(p, capi::Clock::OutputStep, t) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn rover_error_message(p: Inst) -> *const c_char {
                unsafe { capi::error_message(p) }
            }
        };
    };
    (@fmi3_typed $($get:ident $set:ident $t:ty),*) => {
        $(
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $get(i: Inst, _vr: Vr, nvr: usize, _v: *mut $t, _nv: usize) -> c_int {
                if nvr == 0 { return handle::status::OK; }
                unsafe { fmi3::unsupported(i, stringify!($get)) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $set(i: Inst, _vr: Vr, nvr: usize, _v: *const $t, _nv: usize) -> c_int {
                if nvr == 0 { return handle::status::OK; }
                unsafe { fmi3::unsupported(i, stringify!($set)) }
            }
        )*
    };
    (@fmi2_typed $($get:ident $set:ident $t:ty),*) => {
        $(
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $get(i: Inst, _vr: Vr, nvr: usize, _v: *mut $t) -> c_int {
                if nvr == 0 { return handle::status::OK; }
                unsafe { fmi3::unsupported(i, stringify!($get)) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn $set(i: Inst, _vr: Vr, nvr: usize, _v: *const $t) -> c_int {
                if nvr == 0 { return handle::status::OK; }
                unsafe { fmi3::unsupported(i, stringify!($set)) }
            }
        )*
    };
}
