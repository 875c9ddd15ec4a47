//! The no_std canary: a generated plant in a crate without std (see Cargo.toml).
#![no_std]

#[path = "../../../models/src/generated/exomars.rs"]
pub mod exomars;
#[path = "../../../models/src/generated/lrv.rs"]
pub mod lrv;
#[path = "../../../models/src/generated/mer.rs"]
pub mod mer;
#[path = "../../../models/src/generated/swing4.rs"]
pub mod swing4;

use rover_dynamics::nalgebra::SVector;
use rover_dynamics::height_field::{Bounds, OffMap};
use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad};
use rover_dynamics::wheel_ground::{FixedGround, GroundError, Search};
use rover_dynamics::wheel_law::Lateral;

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
    if plant
        .derivatives(&x, &w, &loads, &mut xdot, &mut wdot)
        .is_err()
    {
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

/// Every entry of a generated plant with inputs the compiler cannot see
/// (C ABI, so each body is kept and nothing is constant-folded), one
/// function per built-in rover: tests/no_std.rs reads this crate's release
/// assembly and checks that no path of it can reach a panic. `len` picks
/// the slice lengths handed to the `Plant` trait, so that its length
/// checks are compiled too.
macro_rules! every_entry {
    ($name:ident, $module:ident :: $plant:ident, $n:literal, $w:literal) => {
        #[unsafe(no_mangle)]
        pub extern "C" fn $name(
            plant: &mut $module::$plant,
            x: &[f64; 16],
            w: &[f64; 16],
            loads: &[WheelLoad; 6],
            len: usize,
            out: &mut [f64; 512],
        ) -> i32 {
            let n = len.min(16);
            let (head, rest) = out.split_at_mut(16);
            let (wdot, rest) = rest.split_at_mut(16);
            let mut status = 0;
            if plant
                .derivatives(
                    &x[..n],
                    &w[..n],
                    &loads[..n.min(6)],
                    &mut head[..n],
                    &mut wdot[..n],
                )
                .is_err()
            {
                status |= 1;
            }
            plant.mass_matrix(&x[..n], &mut rest[..n * n]);
            plant.set_spring_neutral(len, x[0]);
            let mut states = [rover_dynamics::plant::WheelState::default(); 6];
            plant.wheels(&x[..n], &w[..n], &w[..n.min(6)], &mut states[..n.min(6)]);
            let Ok(fixed) = <&[WheelLoad; $w]>::try_from(&loads[..$w]) else {
                return -1;
            };
            let xs = SVector::<f64, $n>::from_fn(|i, _| x[i]);
            let ws = SVector::<f64, $n>::from_fn(|i, _| w[i]);
            let (mut xd, mut wd) = (SVector::<f64, $n>::zeros(), SVector::<f64, $n>::zeros());
            if plant
                .derivatives_fixed(&xs, &ws, fixed, &mut xd, &mut wd)
                .is_err()
            {
                status |= 2;
            }
            let m = plant.mass_matrix_fixed(&xs);
            let j = plant.jacobian_fixed(&xs, &ws, fixed);
            let steer = SVector::<f64, $w>::from_fn(|i, _| w[i]);
            let wheels = plant.wheels_fixed(&xs, &ws, &steer);
            rest[256] = xd[0]
                + wd[$n - 1]
                + m[($n - 1, $n - 1)]
                + j[(2 * $n - 1, 0)]
                + wheels[$w - 1].velocity[2]
                + states[5].centre[0];
            status
        }
    };
}

every_entry!(rover_canary_swing4, swing4::Swing4, 10, 4);
every_entry!(rover_canary_exomars, exomars::Exomars, 9, 6);
every_entry!(rover_canary_mer, mer::Mer, 9, 6);
every_entry!(rover_canary_lrv, lrv::Lrv, 10, 4);

/// A wavy ground whose constants the caller gives (so that nothing is
/// folded), with the bounds the bounded search needs:
/// `Z = a·sin(k·X)·sin(k·Y)`.
pub struct Waves {
    a: f64,
    k: f64,
}

impl rover_dynamics::HeightField for Waves {
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        Ok(self.a * libm::sin(self.k * x) * libm::sin(self.k * y))
    }

    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        let (sx, cx) = libm::sincos(self.k * x);
        let (sy, cy) = libm::sincos(self.k * y);
        let ak = self.a * self.k;
        Ok((self.a * sx * sy, [ak * cx * sy, ak * sx * cy]))
    }

    fn max_height_in(&self, _: &Bounds) -> Option<f64> {
        Some(self.a.abs())
    }

    fn max_slope_in(&self, _: &Bounds) -> Option<f64> {
        Some(2.0 * (self.a * self.k).abs())
    }

    fn max_curvature_in(&self, _: &Bounds) -> Option<f64> {
        Some(2.0 * (self.a * self.k * self.k).abs())
    }
}

/// swing4's whole right-hand side on the ground, its own force path
/// (`derivatives_on_ground`: the contact search, the wheel law, the
/// plant), on a ground, a state and torques the compiler cannot see; held
/// to the same no-panic check as the plants' entries.
#[unsafe(no_mangle)]
pub extern "C" fn rover_canary_ground(
    ground: &mut FixedGround<4>,
    terrain: &Waves,
    x: &[f64; 10],
    w: &[f64; 10],
    torques: &[f64; 4],
    out: &mut [f64; 20],
) -> i32 {
    let plant = swing4::Swing4::new();
    let law = Lateral::Exponential { v_eps: 1e-3 };
    let (mut xd, mut wd) = ([0.0; 10], [0.0; 10]);
    let status = plant.derivatives_on_ground(
        ground,
        terrain,
        &law,
        &swing4::Swing4::TYRES,
        x,
        w,
        &[0.0; 4],
        |_| *torques,
        &mut xd,
        &mut wd,
    );
    out[..10].copy_from_slice(&xd);
    out[10..].copy_from_slice(&wd);
    match status {
        Ok(()) => 0,
        Err(GroundError::OffMap(_)) => 1,
        Err(GroundError::Plant(_)) => 2,
    }
}

/// A ground for [`rover_canary_ground`], searched by the default
/// (bounded) search.
#[unsafe(no_mangle)]
pub extern "C" fn rover_canary_new_ground(out: &mut FixedGround<4>) {
    *out = swing4::Swing4::ground(Search::default());
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
