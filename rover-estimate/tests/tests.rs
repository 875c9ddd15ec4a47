//! The estimator's tests, one binary: a linear model against the textbook
//! Kalman filter; swing4 on the paper's rough terrain and MER on sand over
//! it (feature `runtime`).

mod linear;
#[cfg(feature = "runtime")]
mod support {
    pub mod rover;
}
#[cfg(feature = "runtime")]
mod soil;
#[cfg(feature = "runtime")]
mod swing4;
