//! The few elementary functions the contact search calls, from `std` when
//! the crate is built with its `std` feature (the runtime's build: the
//! platform's functions, as before the search became `no_std`) and from
//! `libm` without it (a firmware build). `sqrt`, `floor` and `ceil` are
//! exact in both; the others may differ in the last bit between the two.

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
    #[inline(always)]
    pub fn sqrt(x: f64) -> f64 {
        x.sqrt()
    }
    #[inline(always)]
    pub fn floor(x: f64) -> f64 {
        x.floor()
    }
    #[inline(always)]
    pub fn ceil(x: f64) -> f64 {
        x.ceil()
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
    #[inline(always)]
    pub fn sqrt(x: f64) -> f64 {
        libm::sqrt(x)
    }
    #[inline(always)]
    pub fn floor(x: f64) -> f64 {
        libm::floor(x)
    }
    #[inline(always)]
    pub fn ceil(x: f64) -> f64 {
        libm::ceil(x)
    }
}

pub(crate) use imp::*;
