//! Runs with the controllers: the paper's Fig. 5 turn, the speed
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
    control.torques(
        1.0,
        &vec![0.0; n],
        &w,
        &[0.0],
        &[1.0, 0.0, 0.0, 0.0],
        &[0.0; 4],
        &mut tau,
    );
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

/// The heading law itself: the error is wrapped (170° commanded from −170°
/// is 20° to the right, not 340° to the left), the rate term damps, and a
/// rover left of its line is sent back to the right.
#[test]
fn heading_hold_wraps_the_error_and_steers_back_to_its_line() {
    use rover_runtime::control::HeadingHold;
    let law = |cross_track: f64| HeadingHold {
        via: rover_runtime::control::HeadingActuator::Slip,
        heading_deg: rover_runtime::control::Profile::Constant(170.0),
        kp: Some(2.0),
        kd: Some(0.5),
        ki: None,
        lookahead: None,
        cross_track,
        cross_track_integral: 0.0,
        line_origin: [0.0, 0.0],
        waypoints: Vec::new(),
    };
    let dt = law(0.0).delta_tau(
        law(0.0).line(0.0, 0),
        [0.0, 0.0],
        (-170.0f64).to_radians(),
        0.1,
        Default::default(),
    );
    let want = 2.0 * (-20.0f64).to_radians() - 0.5 * 0.1;
    assert!((dt - want).abs() < 1e-12, "Δτ {dt} vs {want}");
    // Heading 0 along +X: a rover at Y = +1 m (left of the line) turns right.
    let mut along_x = law(1.0);
    along_x.heading_deg = rover_runtime::control::Profile::Constant(0.0);
    let left_of_line = along_x.delta_tau(
        along_x.line(0.0, 0),
        [5.0, 1.0],
        0.0,
        0.0,
        Default::default(),
    );
    assert!(
        (left_of_line - 2.0 * -(1.0f64.atan())).abs() < 1e-12,
        "Δτ {left_of_line}"
    );
}

/// Closed loop: swing4 commanded from heading 0 to 20° on flat ground
/// reaches it without overshoot; on a 10° side slope, where gravity yaws the
/// open-loop rover downhill (3.5° in 38 s, and growing), the heading hold
/// keeps it within 0.2° (the P law's offset under a constant yaw moment)
/// while it slides down the slope; with line following it crabs uphill and
/// holds its line to a few centimetres.
#[test]
fn heading_hold_turns_to_its_set_point_and_holds_a_line_across_a_slope() {
    let drive = |terrain: &str, steering: &str| {
        run(
            "swing4",
            &format!(
                "duration = 40.0\nsettle = 2.0\noutput_rate = 10.0\n{terrain}\
                 [control.speed]\nspeed = 0.1\n{steering}"
            ),
        )
    };
    let hold = "[control.steering]\nkind = \"heading\"\nkp = 5.0\nkd = 0.5\n";
    let last = |v: Vec<f64>| v[v.len() - 1];

    let turn = drive("", &format!("{hold}heading_deg = 20.0\n"));
    let psi: Vec<f64> = turn.col("psi").iter().map(|p| p.to_degrees()).collect();
    let peak = psi.iter().cloned().fold(f64::MIN, f64::max);
    assert!(
        (last(psi.clone()) - 20.0).abs() < 0.05,
        "final heading {}°",
        last(psi)
    );
    assert!(peak < 20.05, "overshoot to {peak}°");

    let slope = "[terrain]\nkind = \"slope\"\nangle_deg = 10.0\ndirection_deg = 90.0\n";
    let free = drive(slope, "");
    let held = drive(slope, hold);
    let line = drive(slope, &format!("{hold}cross_track = 2.0\n"));
    let drift = last(free.col("psi")).to_degrees();
    assert!(drift < -3.0, "open loop yaws downhill: {drift}°");
    let worst = |r: &crate::support::run::Run| {
        r.after("psi", 10.0)
            .iter()
            .fold(0.0f64, |m, p| m.max(p.to_degrees().abs()))
    };
    assert!(worst(&held) < 0.2, "held heading off by {}°", worst(&held));
    assert!(
        last(held.col("Y")) < -0.3,
        "heading alone slides down: Y {}",
        last(held.col("Y"))
    );
    // The summary's path deviation is |Y| here (the line Y = 0 along X).
    let dev = line.summary.path_deviation.expect("a line is followed");
    let max_y = line
        .after("Y", 2.0)
        .iter()
        .fold(0.0f64, |m, y| m.max(y.abs()));
    assert!(
        (dev.max_m - max_y).abs() < 1e-12,
        "{} vs {max_y}",
        dev.max_m
    );
    assert!(
        held.summary.path_deviation.is_none(),
        "no line without cross_track"
    );
    let y_line = line.after("Y", 20.0);
    let spread = y_line.iter().cloned().fold(f64::MIN, f64::max)
        - y_line.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        last(line.col("Y")).abs() < 0.1 && spread < 5e-3,
        "line following: Y {} m, spread {spread} m over the last 20 s",
        last(line.col("Y"))
    );

    // The integrals take the P laws' steady offsets out: the heading's
    // (0.13° under the slope's yaw moment) with `ki`, and the line's (5 cm,
    // where the rover must crab) with `cross_track_integral`.
    let held_pi = drive(
        slope,
        &format!(
            "{hold}ki = 1.0
"
        ),
    );
    let line_pi = drive(
        slope,
        &format!(
            "{hold}cross_track = 2.0
cross_track_integral = 0.2
"
        ),
    );
    let (p_offset, pi_offset) = (
        last(held.col("psi")).to_degrees(),
        last(held_pi.col("psi")).to_degrees(),
    );
    assert!(
        p_offset < -0.1 && pi_offset.abs() < 5e-3,
        "heading offset: P {p_offset}°, PI {pi_offset}°"
    );
    let (p_line, pi_line) = (last(line.col("Y")), last(line_pi.col("Y")));
    assert!(
        p_line < -0.04 && pi_line.abs() < 2e-3,
        "line offset: P {p_line} m, PI {pi_line} m"
    );
}

/// Bad heading-hold settings are refused with the field and the fix.
#[test]
fn heading_hold_settings_are_validated() {
    let m = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4")
        .unwrap()
        .model;
    let error = |text: &str| {
        let config: rover_runtime::control::ControllerConfig = toml::from_str(text).unwrap();
        rover_runtime::control::Controller::new(config, &m, 0.0)
            .unwrap_err()
            .to_string()
    };
    let kp = error("[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 0.0\n");
    assert!(
        kp.contains("control.steering.kp") && kp.contains("> 0"),
        "{kp}"
    );
    let no_speed = error("[steering]\nkind = \"heading\"\nkp = 1.0\n");
    assert!(no_speed.contains("[control.speed]"), "{no_speed}");
    let cross = error(
        "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 1.0\ncross_track = -1.0\n",
    );
    assert!(cross.contains("control.steering.cross_track"), "{cross}");
    let hold = "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 1.0\n";
    let ki = error(&format!("{hold}ki = -0.5\n"));
    assert!(
        ki.contains("control.steering.ki") && ki.contains("≥ 0"),
        "{ki}"
    );
    let alone = error(&format!("{hold}cross_track_integral = 0.2\n"));
    assert!(
        alone.contains("control.steering.cross_track_integral")
            && alone.contains("cross_track > 0"),
        "{alone}"
    );
    let negative = error(&format!(
        "{hold}cross_track = 1.0\ncross_track_integral = -1.0\n"
    ));
    assert!(
        negative.contains("control.steering.cross_track_integral"),
        "{negative}"
    );
    let unknown: Result<rover_runtime::control::ControllerConfig, _> =
        toml::from_str("[steering]\nkind = \"heading\"\nkp = 1.0\nkq = 2.0\n");
    assert!(unknown.is_err_and(|e| e.to_string().contains("kq")));
}

/// The reason for line following: on rough ground (z_r = 0.3) at 0.5 m/s the
/// open-loop swing4 is yawed off its course by the terrain (`rover
/// simulate`, generated plant: 1.6 m off its line after 20 s, 5.6 m after
/// 30 s, off the 20 m wide map at 41 s); holding the line Y = 0 it stays
/// within half a metre of it (0.4 m over 60 s and 30 m).
#[test]
fn line_following_keeps_a_rover_on_course_over_rough_ground() {
    let drive = |steering: &str| {
        run(
            "swing4",
            &format!(
                "duration = 30.0\nsettle = 2.0\noutput_rate = 10.0\n\
                 [terrain]\nkind = \"random\"\nz_r = 0.3\nseed = 2\nextent = [-5.0, 40.0, -10.0, 10.0]\n\
                 [control.speed]\nspeed = 0.5\nki = 5.0\n{steering}"
            ),
        )
    };
    let free = drive("");
    let held =
        drive("[control.steering]\nkind = \"heading\"\nkp = 5.0\nkd = 0.5\ncross_track = 2.0\n");
    let off = |r: &crate::support::run::Run| r.col("Y").iter().fold(0.0f64, |m, y| m.max(y.abs()));
    assert!(off(&free) > 4.0, "open loop: {} m off", off(&free));
    assert!(off(&held) < 0.5, "line following: {} m off", off(&held));
    let x = held.col("X");
    assert!(
        x[x.len() - 1] > 12.0,
        "and it gets somewhere: X = {}",
        x[x.len() - 1]
    );
}

/// Heading hold via Ackermann on the LRV (all four wheels steer, front and
/// rear opposite): commanded 20° on flat ground it turns there (0.01° off
/// at 40 s), and across a 10° side slope, where the open-loop rover slides
/// 0.4 m down in 40 s, it follows its line to 4 cm, crabbing uphill.
#[test]
fn heading_hold_via_ackermann_turns_and_follows_a_line() {
    let drive = |terrain: &str, steering: &str| {
        run(
            "lrv",
            &format!(
                "duration = 40.0\nsettle = 2.0\noutput_rate = 10.0\n{terrain}\
                 [control.speed]\nspeed = 0.5\nki = 50.0\n{steering}"
            ),
        )
    };
    let ackermann =
        "[control.steering]\nkind = \"heading\"\nvia = \"ackermann\"\nlookahead = 5.0\n";
    let last = |v: Vec<f64>| v[v.len() - 1];
    let turn = drive("", &format!("{ackermann}heading_deg = 20.0\n"));
    let psi = last(turn.col("psi")).to_degrees();
    assert!((psi - 20.0).abs() < 0.1, "heading {psi}° at 40 s");
    for (front, rear) in turn.col("delta1").iter().zip(turn.col("delta3")) {
        assert!(
            (front + rear).abs() < 1e-12,
            "front {front} and rear {rear} steer opposite"
        );
    }
    assert!(
        turn.col("delta1").iter().any(|d| d.abs() > 0.01),
        "it steers"
    );
    let slope = "[terrain]\nkind = \"slope\"\nangle_deg = 10.0\ndirection_deg = 90.0\n";
    let free = drive(slope, "");
    let line = drive(slope, &format!("{ackermann}cross_track = 1.0\n"));
    assert!(
        last(free.col("Y")) < -0.3,
        "open loop slides: Y {}",
        last(free.col("Y"))
    );
    let worst = line
        .after("Y", 10.0)
        .iter()
        .fold(0.0f64, |m, y| m.max(y.abs()));
    assert!(worst < 0.04, "line following via Ackermann: {worst} m off");
}

/// Each actuator takes its own settings, and says which are missing.
#[test]
fn heading_hold_actuators_take_their_own_settings() {
    let error = |rover: &str, text: &str| {
        let m = rover_spec::load_str(rover_models::builtin(rover).unwrap(), rover)
            .unwrap()
            .model;
        let config: rover_runtime::control::ControllerConfig = toml::from_str(text).unwrap();
        rover_runtime::control::Controller::new(config, &m, 0.0)
            .unwrap_err()
            .to_string()
    };
    let speed = "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\n";
    let no_kp = error("swing4", speed);
    assert!(no_kp.contains("control.steering.kp: missing"), "{no_kp}");
    let no_wheels = error(
        "swing4",
        &format!("{speed}via = \"ackermann\"\nlookahead = 2.0\n"),
    );
    assert!(no_wheels.contains("steerable"), "{no_wheels}");
    let no_lookahead = error("lrv", &format!("{speed}via = \"ackermann\"\n"));
    assert!(
        no_lookahead.contains("control.steering.lookahead: missing"),
        "{no_lookahead}"
    );
    let gains = error(
        "lrv",
        &format!("{speed}via = \"ackermann\"\nlookahead = 2.0\nkp = 1.0\n"),
    );
    assert!(gains.contains("slip law"), "{gains}");
    let integral = error(
        "lrv",
        &format!("{speed}via = \"ackermann\"\nlookahead = 2.0\nki = 1.0\n"),
    );
    assert!(integral.contains("slip law"), "{integral}");
    let lookahead = error("lrv", &format!("{speed}kp = 1.0\nlookahead = 2.0\n"));
    assert!(
        lookahead.contains("control.steering.lookahead"),
        "{lookahead}"
    );
    let one = error(
        "swing4",
        &format!("{speed}kp = 1.0\nwaypoints = [[0.0, 0.0]]\n"),
    );
    assert!(
        one.contains("control.steering.waypoints") && one.contains("two"),
        "{one}"
    );
    let same = error(
        "swing4",
        &format!("{speed}kp = 1.0\nwaypoints = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]\n"),
    );
    assert!(same.contains("waypoints 2 and 3 coincide"), "{same}");
    let both = error(
        "swing4",
        &format!("{speed}kp = 1.0\nheading_deg = 10.0\nwaypoints = [[0.0, 0.0], [1.0, 0.0]]\n"),
    );
    assert!(both.contains("replace"), "{both}");
}

/// A path of waypoints: swing4 drives three legs of a 6 m square at 0.3 m/s,
/// each followed as a line until G passes the perpendicular through its
/// end; it passes within centimetres of both corners (it reaches each on
/// its line, then turns, overshooting by about half a metre) and ends on
/// the last leg's line, heading back along −X.
#[test]
fn heading_hold_follows_a_path_of_waypoints() {
    let r = run(
        "swing4",
        "duration = 60.0\nsettle = 2.0\noutput_rate = 10.0\n[control.speed]\nspeed = 0.3\n\
         [control.steering]\nkind = \"heading\"\nkp = 5.0\nkd = 2.0\ncross_track = 2.0\n\
         waypoints = [[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]]\n",
    );
    let (x, y) = (r.col("X"), r.col("Y"));
    let closest = |cx: f64, cy: f64| {
        x.iter()
            .zip(&y)
            .map(|(a, b)| (a - cx).hypot(b - cy))
            .fold(f64::MAX, f64::min)
    };
    assert!(
        closest(6.0, 0.0) < 0.03,
        "first corner missed by {} m",
        closest(6.0, 0.0)
    );
    assert!(
        closest(6.0, 6.0) < 0.03,
        "second corner missed by {} m",
        closest(6.0, 6.0)
    );
    for v in r.after("Y", 52.0) {
        assert!((v - 6.0).abs() < 0.05, "off the last leg: Y = {v}");
    }
    let psi = r.col("psi");
    let heading = psi[psi.len() - 1].to_degrees().rem_euclid(360.0);
    assert!((heading - 180.0).abs() < 3.0, "final heading {heading}°");
    assert!(
        x[x.len() - 1] < 3.0,
        "moving along the last leg: X = {}",
        x[x.len() - 1]
    );
    // The summary's deviation from the path: on it at the end, half a
    // metre out at the corners' overshoot.
    let dev = r.summary.path_deviation.expect("a path is followed");
    assert!(
        dev.final_m < 0.05 && dev.max_m > 0.3 && dev.rms_m < dev.max_m,
        "{dev:?}"
    );
}

/// The integral states' rates are their integrands (speed error, heading
/// error, line offset), zero while settling, and frozen by anti-windup
/// once their own term saturates in the direction the error pushes.
#[test]
fn heading_hold_integrals_integrate_and_stop_winding_up() {
    use rover_runtime::control::{Controller, ControllerConfig, LINE_INTEGRAL_CAP};
    let m = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4")
        .unwrap()
        .model;
    let n = m.dof();
    let config: ControllerConfig = toml::from_str(
        "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 5.0\nki = 2.0\n\
         cross_track = 1.0\ncross_track_integral = 0.5\n",
    )
    .unwrap();
    let control = Controller::new(config, &m, 1.0).unwrap();
    assert_eq!(control.states(), 3);
    let w = vec![0.0; n];
    // G `y` m left of the line Y = 0 at heading ψ.
    let rates = |t: f64, (y, psi): (f64, f64), z: [f64; 3]| {
        let mut x = vec![0.0; n];
        (x[1], x[5]) = (y, psi);
        let mut out = [f64::NAN; 3];
        control.integral_rates(t, &x, &w, &z, &mut out);
        out
    };
    let settled = rates(2.0, (0.3, 0.1), [0.0; 3]);
    let e = -(0.3f64).atan() - 0.1;
    assert!(
        (settled[0] - 0.1).abs() < 1e-15,
        "speed error {}",
        settled[0]
    );
    assert!(
        (settled[1] - e).abs() < 1e-15,
        "heading error {}",
        settled[1]
    );
    assert!(
        (settled[2] - 0.3).abs() < 1e-15,
        "line offset {}",
        settled[2]
    );
    assert_eq!(
        rates(0.5, (0.3, 0.1), [0.0; 3])[1..],
        [0.0, 0.0],
        "settling"
    );
    // The line integral at its cap: it stops growing with e_y > 0 …
    let cap = LINE_INTEGRAL_CAP / 0.5;
    assert_eq!(rates(2.0, (0.3, 0.1), [0.0, 0.0, cap])[2], 0.0);
    // … and unwinds when e_y turns negative.
    assert!((rates(2.0, (-0.3, 0.1), [0.0, 0.0, cap])[2] + 0.3).abs() < 1e-15);
    // The heading integral at the largest motor torque likewise.
    let tau = m.wheels.iter().map(|w| w.max_torque).fold(0.0, f64::max);
    let wound = [0.0, -tau / 2.0, 0.0];
    assert_eq!(rates(2.0, (0.0, 0.1), wound)[1], 0.0, "e < 0 at −cap");
    assert!(rates(2.0, (0.0, -0.1), wound)[1] > 0.0, "unwinds");
}

/// A command that jumps (here the end of settling, on an output instant)
/// under tight BDF tolerances: the step that ends on the jump takes the
/// commands' left limit and the integrator restarts there, so the run goes
/// through. It used to stop at t = 1 s with the step below its minimum
/// (the implicit step evaluated the post-jump command at its end, an error
/// estimate of jump × step that only a 1e-11 s step could pass).
#[test]
fn a_command_jump_at_tight_tolerances_does_not_stall_the_integrator() {
    let r = run(
        "exomars",
        "duration = 3.0\nsettle = 1.0\noutput_rate = 10.0\n\
         [integrator.bdf]\nrtol = 1e-9\natol = 1e-11\n\
         [control.speed]\nspeed = 0.1\nki = 5.0\n\
         [control.steering]\nkind = \"ackermann\"\nradius = 2.0\n",
    );
    let t = r.col("t");
    assert!(
        (t[t.len() - 1] - 3.0).abs() < 1e-12,
        "ends at {}",
        t[t.len() - 1]
    );
    assert!(r.col("delta1").iter().any(|d| d.abs() > 0.05), "it steers");
}
