//! Why the estimator refused a setting, an input or a step.

use core::fmt;

/// Why the estimator refused a setting, an input or a step. A call that
/// fails leaves the estimate (state, covariance, time, encoder memory) as
/// it was before the call.
#[derive(Clone, Debug, PartialEq)]
pub enum EstimateError<E> {
    /// A setting is out of its range.
    Config {
        /// The setting, as its field is named (`imu.bias_time`,
        /// `filter.velocity_noise`, `initial.attitude`).
        field: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// The process model's state is not `[x; w; ω]`.
    Layout {
        /// The model's state length.
        dim: usize,
        /// Its coordinates N.
        dof: usize,
        /// Its spin states.
        spins: usize,
    },
    /// A slice has the wrong length.
    Length {
        /// What it holds.
        what: &'static str,
        /// The length expected.
        expected: usize,
        /// The length given.
        given: usize,
    },
    /// A reading, command or state entry is NaN or infinite.
    NotFinite {
        /// The estimate's time \[s\].
        t: f64,
        /// What it is.
        what: &'static str,
        /// Its index (0-based) in what holds it.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A sample's time is not the estimate's.
    Time {
        /// The estimate's time \[s\].
        t: f64,
        /// The sample's time \[s\].
        sample: f64,
    },
    /// A prediction's length is not positive and finite.
    Step {
        /// The estimate's time \[s\].
        t: f64,
        /// The length asked \[s\].
        dt: f64,
    },
    /// A reading of a sensor the configuration does not declare.
    NoSensor {
        /// The estimate's time \[s\].
        t: f64,
        /// The sensor (`imu`, `wheel_encoders`, …).
        sensor: &'static str,
    },
    /// Two wheel-angle readings at one instant: no rate between them.
    EncoderInterval {
        /// The estimate's time \[s\].
        t: f64,
        /// The interval since the previous reading \[s\].
        interval: f64,
    },
    /// The process model failed.
    Model {
        /// The time of the evaluation \[s\].
        t: f64,
        /// Why.
        source: E,
    },
    /// The step's matrix `I − h·J` is singular.
    SingularStep {
        /// The estimate's time \[s\].
        t: f64,
    },
    /// The covariance lost positive definiteness: an innovation variance
    /// or a diagonal entry not positive (or not finite).
    NotPositiveDefinite {
        /// The estimate's time \[s\].
        t: f64,
        /// Where it showed.
        what: &'static str,
        /// The measurement row or error-state component (0-based).
        index: usize,
        /// The variance found.
        value: f64,
    },
}

impl<E: fmt::Display> fmt::Display for EstimateError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EstimateError::Config {
                field,
                value,
                expected,
            } => write!(f, "{field} must be {expected}, got {value}"),
            EstimateError::Layout { dim, dof, spins } => write!(
                f,
                "the process model's state has {dim} entries, not 2N + spins = {} \
                 (N = {dof}, {spins} spins): build it without controller loops \
                 (`RoverSystem::open_loop`)",
                2 * dof + spins
            ),
            EstimateError::Length {
                what,
                expected,
                given,
            } => write!(f, "{what}: expected {expected} values, got {given}"),
            EstimateError::NotFinite {
                t,
                what,
                index,
                value,
            } => write!(
                f,
                "at t = {t} s: {what}[{index}] is {value}; readings, commands and states must be finite"
            ),
            EstimateError::Time { t, sample } => write!(
                f,
                "a sample at t = {sample} s given to the estimate at t = {t} s: predict to the sample's time first"
            ),
            EstimateError::Step { t, dt } => write!(
                f,
                "at t = {t} s: a prediction over {dt} s; the step must be positive and finite"
            ),
            EstimateError::NoSensor { t, sensor } => write!(
                f,
                "at t = {t} s: a reading of `{sensor}`, which the sensor configuration does not declare"
            ),
            EstimateError::EncoderInterval { t, interval } => write!(
                f,
                "at t = {t} s: wheel angles read {interval} s after the previous reading; \
                 the rate needs a positive interval"
            ),
            EstimateError::Model { t, source } => {
                write!(f, "at t = {t} s: the process model failed: {source}")
            }
            EstimateError::SingularStep { t } => write!(
                f,
                "at t = {t} s: the prediction's matrix I − h·J is singular; shorten the step \
                 (`filter.substeps`)"
            ),
            EstimateError::NotPositiveDefinite {
                t,
                what,
                index,
                value,
            } => write!(
                f,
                "at t = {t} s: the covariance lost positive definiteness ({what} {index} is {value}); \
                 a reading far from the model, or process noises too small"
            ),
        }
    }
}

impl<E: fmt::Display + fmt::Debug> core::error::Error for EstimateError<E> {}
