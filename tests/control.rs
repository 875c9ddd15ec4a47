//! Runs with the controllers (issue 5): the paper's Fig. 5 turn, the speed
//! loop, slip steering, active suspension, the integrators against each
//! other.

use crate::support::run::run;

const BDF: &str = "[integrator.bdf]\nrtol = 1e-6\natol = 1e-8\n";

#[test]
fn ackermann_turn_on_flat_ground_has_the_kinematic_radius() {
    // Paper Fig. 5: Example 1, V = 0.05 m/s, turn centre on the middle axle.
    for radius in [2.0, -3.0] {
        let r = run(
            "exomars",
            &format!(
                "duration = 40.0\nsettle = 6.0\noutput_rate = 10.0\n[control.speed]\nspeed = 0.05\nki = 5.0\n\
                 [control.steering]\nkind = \"ackermann\"\nradius = {radius}\n{BDF}"
            ),
        );
        let fitted = r.summary.turning_circle.expect("a circle").radius;
        let rk = r.summary.kinematic_radius.expect("R_k");
        assert!(
            (fitted - rk).abs() < 0.02 * rk,
            "R = {fitted} m against R_k = {rk} m"
        );
        // The centre lies on the commanded side.
        let yc = r.summary.turning_circle.unwrap().y;
        assert!(
            yc * radius > 0.0,
            "turn centre at Y = {yc} for R = {radius}"
        );
    }
}

#[test]
fn speed_loop_holds_the_set_point_after_settling() {
    for (rover, v) in [("exomars", 0.05), ("swing4", 0.1)] {
        let r = run(
            rover,
            &format!(
                "duration = 20.0\nsettle = 6.0\n[control.speed]\nspeed = {v}\nki = 5.0\n{BDF}"
            ),
        );
        // After a 2 s transient.
        for vx in r.after("vx", 8.0) {
            assert!(
                (vx - v).abs() < 0.05 * v,
                "{rover}: vx = {vx} m/s against V = {v} m/s"
            );
        }
    }
}

#[test]
fn slip_steering_turns_left_for_positive_delta_tau() {
    let heading = |dt: f64| {
        let r = run(
            "swing4",
            &format!(
                "duration = 16.0\nsettle = 6.0\n[control.speed]\nspeed = 0.1\n\
                 [control.steering]\nkind = \"slip\"\ndelta_tau = {dt}\n{BDF}"
            ),
        );
        let psi = r.col("psi");
        let y = r.col("Y");
        (psi[psi.len() - 1], y[y.len() - 1])
    };
    let (left, yl) = heading(0.2);
    let (right, yr) = heading(-0.2);
    let (straight, ys) = heading(0.0);
    assert!(
        left > 0.05 && yl > 0.01,
        "Δτ > 0: yaw {left} rad, Y {yl} m (expected a left turn)"
    );
    assert!(
        right < -0.05 && yr < -0.01,
        "Δτ < 0: yaw {right} rad, Y {yr} m (expected a right turn)"
    );
    assert!(
        straight.abs() < 1e-6 && ys.abs() < 1e-6,
        "Δτ = 0: yaw {straight} rad, Y {ys} m (expected straight)"
    );
    assert!(
        (left + right).abs() < 1e-3 * left.abs(),
        "left and right turns are mirror images: {left} vs {right}"
    );
}

#[test]
fn active_suspension_lowers_roll_and_pitch_on_rough_ground() {
    let base = "duration = 40.0\nsettle = 6.0\n[terrain]\nkind = \"random\"\nz_r = 0.2\nseed = 1\npatch_radius = 0.6\n\
                [control.speed]\nspeed = 0.05\n[control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n\
                [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n";
    let passive = run("swing4", base);
    let active = run(
        "swing4",
        &format!(
            "{base}[control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.3\nkd_pitch = 0.03\nkp_roll = 0.3\nkd_roll = 0.03\n"
        ),
    );
    let (p, a) = (&passive.summary, &active.summary);
    assert!(p.complete && a.complete, "{:?} {:?}", p.error, a.error);
    assert!(
        a.max_roll_deg < p.max_roll_deg,
        "roll: active {} vs passive {}",
        a.max_roll_deg,
        p.max_roll_deg
    );
    assert!(
        a.max_pitch_deg < p.max_pitch_deg,
        "pitch: active {} vs passive {}",
        a.max_pitch_deg,
        p.max_pitch_deg
    );
}

#[test]
fn integrators_agree_on_a_smooth_run() {
    // Example 2 rolling at 0.1 m/s on flat ground from a rolling start (no
    // standstill, where the regularized cornering law is stiff).
    let base = "duration = 3.0\noutput_rate = 10.0\n[initial]\nvelocity = [0.1, 0.0, 0.0]\nz = 0.285\n\
                [control.speed]\nspeed = 0.1\n";
    let runs = [
        run(
            "swing4",
            &format!("{base}[integrator.dopri5]\nrtol = 1e-9\natol = 1e-11\n"),
        ),
        run(
            "swing4",
            &format!("{base}[integrator.bdf]\nrtol = 1e-7\natol = 1e-9\n"),
        ),
        run("swing4", &format!("{base}[integrator.rk4]\nstep = 2e-4\n")),
        run(
            "swing4",
            &format!("{base}[integrator.semi_implicit_euler]\nstep = 2e-5\n"),
        ),
    ];
    let reference = &runs[0];
    // Bounds: 10·rtol for BDF, the O(h⁴) and O(h) global errors of the
    // fixed-step methods at these steps (measured 4e-8, 2e-11, 3e-6).
    for (name, r, tol) in [
        ("bdf", &runs[1], 1e-6),
        ("rk4", &runs[2], 1e-9),
        ("semi-implicit Euler", &runs[3], 2e-5),
    ] {
        for col in ["X", "Z", "theta", "y1", "y3", "vx"] {
            let (a, b) = (reference.col(col), r.col(col));
            for (k, (u, v)) in a.iter().zip(&b).enumerate() {
                assert!(
                    (u - v).abs() < tol,
                    "{name}: {col} at row {k}: {v} vs dopri5 {u}"
                );
            }
        }
    }
}

#[test]
fn torque_by_static_load_follows_the_flat_ground_equilibrium() {
    use rover_runtime::control::{Controller, ControllerConfig};
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let model = spec.model;
    let loads = rover_runtime::quasi_static::flat_ground_loads(&model).unwrap();
    let weight = model.total_mass() * model.gravity;
    assert!(
        (loads.iter().sum::<f64>() - weight).abs() < 1e-6 * weight,
        "the static loads carry the weight: {loads:?}"
    );
    let config: ControllerConfig =
        toml::from_str("[speed]\nspeed = 0.1\nkp = 2.0\ndistribution = \"static_load\"").unwrap();
    let control = Controller::new(config, &model, 0.0).unwrap();
    let n = model.dof();
    let w = vec![0.0; n];
    let mut tau = vec![0.0; 4];
    // Measured loads are ignored: the static ones decide.
    control.torques(1.0, &w, 0.0, &[1.0, 0.0, 0.0, 0.0], &mut tau);
    let tau0 = 2.0 * 0.1;
    let total: f64 = loads.iter().sum();
    for (t, l) in tau.iter().zip(&loads) {
        assert!(
            (t - tau0 * 4.0 * l / total).abs() < 1e-12,
            "τ {tau:?} against loads {loads:?}"
        );
    }
    assert!(
        (loads[0] - loads[2]).abs() > 0.01 * weight,
        "front and rear loads differ on Example 2: {loads:?}"
    );
}
