//! The no_std canary: a generated plant in a crate without std (see Cargo.toml).
#![no_std]

#[path = "../../../models/src/generated/swing4.rs"]
pub mod swing4;

use rover_dynamics::nalgebra::SVector;
use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad};

/// Vertical acceleration of swing4 in free fall at roll `phi`, through the
/// `Plant` trait and through `FixedPlant` on nalgebra vectors (C ABI, so
/// the code is kept).
#[unsafe(no_mangle)]
pub extern "C" fn rover_canary_free_fall(phi: f64) -> f64 {
    let mut plant = swing4::Swing4::new();
    let mut x = [0.0; 10];
    x[3] = phi;
    x[6..].copy_from_slice(&swing4::Swing4::SPRING_NEUTRALS);
    let w = [0.0; 10];
    let loads = [WheelLoad::default(); 4];
    let (mut xdot, mut wdot) = ([0.0; 10], [0.0; 10]);
    if plant.derivatives(&x, &w, &loads, &mut xdot, &mut wdot).is_err() {
        return f64::NAN;
    }
    let xs = SVector::<f64, 10>::from(x);
    let (mut xd, mut wd) = (SVector::<f64, 10>::zeros(), SVector::<f64, 10>::zeros());
    if plant
        .derivatives_fixed(&xs, &SVector::zeros(), &loads, &mut xd, &mut wd)
        .is_err()
    {
        return f64::NAN;
    }
    let m = plant.mass_matrix_fixed(&xs);
    (wdot[2] + wd[2]) / 2.0 + 0.0 * m[(0, 0)]
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
