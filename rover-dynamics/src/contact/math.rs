//! The few elementary functions the contact search calls. The rounded
//! ones come from `std` when the crate is built with its `std` feature
//! (the runtime's build: the platform's functions) and from `libm` without
//! it (a firmware build); they may differ in the last bit between the two.
//! `sqrt`, `floor` and `ceil` are exact, so `libm`'s serve both.

#[cfg(feature = "std")]
mod imp {
    #[inline(always)]
    pub fn sin_cos(x: f64) -> (f64, f64) {
        x.sin_cos()
    }
    #[inline(always)]
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
    #[inline(always)]
    pub fn acos(x: f64) -> f64 {
        x.acos()
    }
    #[inline(always)]
    pub fn hypot(x: f64, y: f64) -> f64 {
        x.hypot(y)
    }
}

#[cfg(not(feature = "std"))]
mod imp {
    #[inline(always)]
    pub fn sin_cos(x: f64) -> (f64, f64) {
        libm::sincos(x)
    }
    #[inline(always)]
    pub fn atan2(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
    #[inline(always)]
    pub fn acos(x: f64) -> f64 {
        libm::acos(x)
    }
    #[inline(always)]
    pub fn hypot(x: f64, y: f64) -> f64 {
        libm::hypot(x, y)
    }
}

pub(crate) use imp::*;
pub(crate) use libm::{ceil, floor, sqrt};
