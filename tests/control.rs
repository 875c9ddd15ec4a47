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

/// A command that jumps (here the end of settling, on an output instant)
/// under tight BDF tolerances: the step that ends on the jump takes the
/// commands' left limit and the integrator restarts there, so the run goes
/// through. An implicit step that evaluated the post-jump command at its
/// end would carry an error estimate of jump × step that only a 1e-11 s
/// step could pass, and stop at t = 1 s with the step below its minimum.
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
