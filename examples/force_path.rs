//! A rig's loop on a generated plant alone, without the runtime: swing4's
//! own force path (`derivatives_on_ground`: the contact search, the wheel
//! law with the tyres as constants, the plant) on the paper's rough
//! terrain, a proportional speed loop written here, semi-implicit Euler
//! at 1 kHz. What a `no_std` target runs, with its own height field in
//! place of the grid. Run: `cargo run --release --example force_path`
//! (an argument sets the number of steps; under
//! `valgrind --tool=callgrind` it profiles the force path).

use rover_dynamics::attitude::Attitude;
use rover_dynamics::height_field::Bounds;
use rover_dynamics::wheel_ground::Search;
use rover_runtime::terrain::RandomField;
use rover_runtime::wheel_law::WheelLawConfig;

type Swing4 = rover_models::Swing4;
const N: usize = Swing4::DOF;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = match std::env::args().nth(1) {
        Some(s) => s.parse()?,
        None => 10_000,
    };
    let spec = rover_spec::load_str(
        rover_models::builtin("swing4").ok_or("no swing4")?,
        "models/swing4.toml",
    )?;
    let model = spec.model;
    // The paper's rough terrain (Z_R = 0.2), 12 m long.
    let terrain = RandomField {
        z_r: 0.2,
        extent: Bounds {
            x_min: -2.0,
            x_max: 12.0,
            y_min: -2.0,
            y_max: 2.0,
        },
        ..RandomField::default()
    }
    .grid()?;
    let plant = Swing4::new();
    let law = WheelLawConfig::default();
    let mut ground = Swing4::ground(Search::default());

    // At rest, the lowest wheel 2 mm into the ground.
    let (mut x, mut w) = ([0.0; N], [0.0; N]);
    x[6..].copy_from_slice(&model.rest());
    let touch = rover_runtime::ground::touchdown_heights(
        &model,
        [0.0, 0.0],
        Attitude::new(0.0, 0.0, 0.0),
        &x[6..],
        &terrain,
    )?;
    x[2] = touch.iter().copied().fold(f64::NEG_INFINITY, f64::max) - 2e-3;

    // Speed loop: τ = k·(v* − v_x) on every wheel, within the motors' limit.
    let (target, gain, limit): (f64, f64, f64) = (0.1, 20.0, model.wheels[0].max_torque);
    let dt = 1e-3;
    let start = std::time::Instant::now();
    for _ in 0..steps {
        let torque = (gain * (target - w[0])).clamp(-limit, limit);
        let (mut xd, mut wd) = ([0.0; N], [0.0; N]);
        plant.derivatives_on_ground(
            &mut ground,
            &terrain,
            &law,
            &Swing4::TYRES,
            &x,
            &w,
            &[0.0; 4],
            |_normals| [torque; 4],
            &mut xd,
            &mut wd,
        )?;
        // Semi-implicit Euler: the velocities first, the positions from them.
        for i in 0..N {
            w[i] += dt * wd[i];
        }
        let mut rates = [0.0; N];
        rover_dynamics::kinematics::position_rates(&x, &w, &mut rates);
        for i in 0..N {
            x[i] += dt * rates[i];
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    let normal: f64 = ground.reports().iter().map(|r| r.normal).sum();
    println!(
        "{steps} steps of {dt} s: X = {:.3} m, v_x = {:.3} m/s, ΣF_n = {normal:.1} N; \
         {:.2} µs a step ({:.0}× real time)",
        x[0],
        w[0],
        1e6 * elapsed / steps as f64,
        steps as f64 * dt / elapsed
    );
    Ok(())
}
