//! The controllers built from their settings and evaluated directly: the
//! static-load torque distribution, the heading law, the integral states'
//! rates, and the settings refused with the field and the fix.

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
        (&vec![0.0; n], &w, &[0.0], &[]),
        (&[1.0, 0.0, 0.0, 0.0], &[]),
        &[0.0; 4],
        &[],
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
        control.integral_rates(t, (&x, &w, &z, &[]), &mut out);
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

/// A set-point that cannot be used is refused with the field, the point
/// and what is wrong.
#[test]
fn bad_set_points_are_refused_with_the_point() {
    let m = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4")
        .unwrap()
        .model;
    let error = |speed: &str| {
        let config: rover_runtime::control::ControllerConfig =
            toml::from_str(&format!("[speed]\nspeed = {speed}\n")).unwrap();
        rover_runtime::control::Controller::new(config, &m, 0.0)
            .unwrap_err()
            .to_string()
    };
    let cases = [
        ("nan", "value NaN is not a finite number"),
        (
            "{ points = [] }",
            "the table has no points; give at least one [t, value]",
        ),
        (
            "{ points = [[0.0, 0.1], [1.0, nan]] }",
            "point 2 = [1, NaN] is not finite",
        ),
        (
            "{ points = [[0.0, 0.1], [2.0, 0.2], [1.5, 0.3]] }",
            "times must increase: point 3 has t = 1.5 s after t = 2 s",
        ),
    ];
    for (speed, want) in cases {
        assert_eq!(error(speed), format!("control.speed.speed: {want}"));
    }
}

/// Ackermann commands a steering geometry can take: an angle strictly
/// between −90° and 90°, a turn centre off the rover's centre line (R ≠ 0),
/// at construction and as a set-point later.
#[test]
fn ackermann_commands_out_of_range_are_refused() {
    let m = rover_spec::load_str(rover_models::builtin("lrv").unwrap(), "lrv")
        .unwrap()
        .model;
    let build = |steering: &str| {
        let config: rover_runtime::control::ControllerConfig =
            toml::from_str(&format!("[steering]\nkind = \"ackermann\"\n{steering}\n")).unwrap();
        rover_runtime::control::Controller::new(config, &m, 0.0)
    };
    let error = |steering: &str| build(steering).unwrap_err().to_string();
    for angle in [
        "1e12",
        "90.0",
        "-90.0",
        "{ points = [[0.0, 5.0], [1.0, 100.0]] }",
    ] {
        let e = error(&format!("front_left_deg = {angle}"));
        assert!(
            e.starts_with("control.steering.front_left_deg: ")
                && e.contains("between -90° and 90°"),
            "{angle}: {e}"
        );
    }
    for radius in ["0.0", "{ points = [[0.0, 5.0], [1.0, 0.0]] }"] {
        let e = error(&format!("radius = {radius}"));
        assert!(
            e.starts_with("control.steering.radius: ") && e.contains("0 m is no turn"),
            "{radius}: {e}"
        );
    }
    let through_zero =
        error("radius = { points = [[0.0, -5.0], [1.0, 5.0]], interpolation = \"linear\" }");
    assert!(through_zero.contains("through R = 0"), "{through_zero}");
    // Either sign turns, and a step from one to the other never passes 0.
    build("radius = -5.0").unwrap();
    build("front_left_deg = 89.9").unwrap();
    build("radius = { points = [[0.0, -5.0], [1.0, 5.0]] }").unwrap();
    // A set-point is held to the same ranges.
    let mut by_angle = build("front_left_deg = 5.0").unwrap();
    let e = by_angle
        .set_steering_setpoint(1e12)
        .unwrap_err()
        .to_string();
    assert!(e.contains("between -90° and 90°"), "{e}");
    by_angle.set_steering_setpoint(-30.0).unwrap();
    let mut by_radius = build("radius = 5.0").unwrap();
    let e = by_radius
        .set_steering_setpoint(0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("0 m is no turn"), "{e}");
}

/// A rover whose static equilibrium would rest on a bump stop has no
/// equilibrium a reduced level can be frozen at.
#[test]
fn an_equilibrium_outside_the_travel_is_refused() {
    // One swing arm whose wheel must come under G: at 64° it would, but
    // the travel ends at −2°.
    let text = rover_models::builtin("swing4").unwrap();
    let head = &text[..text.find("[[suspension]]").unwrap()];
    let one = format!(
        "{head}[[suspension]]\nname = \"only\"\nkind = \"longitudinal_swing_arm\"\npivot = [0.18, 0.0, -0.01]\nlength = 0.2\n\
         coordinate = {{ rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 }}\n\n\
         [[wheel]]\nname = \"only\"\nsuspension = \"only\"\n"
    );
    let spec = rover_spec::load_str(&one, "one.toml").unwrap();
    let e = rover_runtime::quasi_static::flat_ground_equilibrium(&spec.model).unwrap_err();
    assert!(
        matches!(
            e,
            rover_runtime::quasi_static::QuasiStaticError::OutsideTravel { coordinate: 0, .. }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("outside its travel"), "{e}");
    // The built-in rovers rest inside their travel.
    for name in rover_models::NAMES {
        let spec = rover_spec::load_str(rover_models::builtin(name).unwrap(), name).unwrap();
        rover_runtime::quasi_static::flat_ground_equilibrium(&spec.model).unwrap();
    }
}

/// A motor with a torque–speed line, saturated by a large speed error:
/// full stall torque at rest, the line in between, nothing at the no-load
/// speed, while braking keeps the full torque.
#[test]
fn a_motor_line_limits_the_drive_torque_by_the_wheel_spin() {
    use rover_dynamics::model::MotorCurve;
    use rover_runtime::control::{Controller, ControllerConfig};
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let mut model = spec.model;
    let (stall, w0) = (1.0, 5.0);
    for w in &mut model.wheels {
        w.motor_curve = Some(MotorCurve {
            stall_torque: stall,
            no_load_speed: w0,
        });
    }
    let n = model.dof();
    let k = model.wheels.len();
    let torques = |speed: f64, rate: f64| {
        let config: ControllerConfig =
            toml::from_str(&format!("[speed]\nspeed = {speed:?}\nkp = 100.0")).unwrap();
        let control = Controller::new(config, &model, 0.0).unwrap();
        let mut tau = vec![0.0; k];
        control.torques(
            1.0,
            (&vec![0.0; n], &vec![0.0; n], &[0.0], &[]),
            (&vec![1.0; k], &[]),
            &vec![0.0; k],
            &vec![rate; k],
            &mut tau,
        );
        tau
    };
    // Below max_torque (1.29 N·m): the stall torque caps it at rest.
    assert_eq!(torques(1.0, 0.0), vec![stall; k]);
    assert_eq!(torques(1.0, 0.5 * w0), vec![0.5 * stall; k]);
    assert_eq!(torques(1.0, w0), vec![0.0; k]);
    assert_eq!(torques(1.0, 2.0 * w0), vec![0.0; k]);
    // Braking a wheel spinning at its no-load speed: the full torque.
    assert_eq!(torques(-1.0, w0), vec![-stall; k]);
}

/// The active suspension's laws take their own settings only: the paper's
/// law needs its gains, the leveling law refuses them and gains outside
/// their range, each named with the fix; the leveling law's defaults come
/// from the rover (Example 2: the arm's lag c/k = 0.7 s).
#[test]
fn active_suspension_settings_are_checked_per_law() {
    use rover_runtime::control::{Controller, ControllerConfig};
    let m = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4")
        .unwrap()
        .model;
    let build = |table: &str| {
        let config: ControllerConfig =
            toml::from_str(&format!("[active_suspension]\n{table}")).unwrap();
        Controller::new(config, &m, 0.0).map(|_| ())
    };
    let error = |table: &str| build(table).unwrap_err().to_string();
    assert!(build("kp_pitch = 0.6\nkp_roll = 0.6\n").is_ok());
    assert!(build("law = \"leveling\"\n").is_ok());
    assert!(build("law = \"leveling\"\nattitude_gain = 0.2\nrate_gain = 0.1\n").is_ok());
    let cases = [
        (
            "kp_roll = 0.6\n",
            "control.active_suspension.kp_pitch: the paper's law (eq. 42) gives no gains",
        ),
        (
            "law = \"leveling\"\nkp_pitch = 0.6\n",
            "control.active_suspension.kp_pitch: belongs to law = \"eq42\", not to law = \"leveling\"",
        ),
        (
            "kp_pitch = 0.6\nkp_roll = 0.6\nwarp_gain = 0.5\n",
            "control.active_suspension.warp_gain: belongs to law = \"leveling\", not to law = \"eq42\"",
        ),
        (
            "law = \"leveling\"\nattitude_gain = 1.5\n",
            "control.active_suspension.attitude_gain: is the fraction of the error removed per update and must lie in (0, 1], got 1.5",
        ),
        (
            "law = \"leveling\"\nattitude_gain = 0.0\n",
            "control.active_suspension.attitude_gain: is the fraction of the error removed per update and must lie in (0, 1], got 0",
        ),
        (
            "law = \"leveling\"\nrate_gain = -0.1\n",
            "control.active_suspension.rate_gain: must be ≥ 0 s, got -0.1",
        ),
    ];
    for (table, want) in cases {
        let got = error(table);
        assert!(got.starts_with(want), "{table}: {got}");
    }
    assert!(toml::from_str::<ControllerConfig>("[active_suspension]\nlaw = \"lqr\"\n").is_err());
    // The defaults, from the rover: b = a·c/k, c_h = Δt_c·k/(2c).
    let y_eq = rover_runtime::quasi_static::flat_ground_equilibrium(&m).unwrap();
    let config = toml::from_str("law = \"leveling\"\n").unwrap();
    let law = rover_runtime::control::ActiveSuspension::leveling(config, &m, &y_eq).unwrap();
    let l = law.leveling.unwrap();
    let lag = 3.5 / 5.0;
    assert!((l.lag - lag).abs() < 1e-6, "lag {}", l.lag);
    let want = [0.3, 0.3 * lag, 0.1 / (2.0 * lag), 0.5];
    for (g, w) in l.gains.iter().zip(want) {
        assert!((g - w).abs() < 1e-6, "gains {:?} vs {want:?}", l.gains);
    }
    // The neutral's range: the travel shifted by the static deflection on
    // the loaded side (front arms sag towards −60°, rear towards +60°).
    for i in 0..4 {
        let c = &m.coordinates[i];
        let d = c.neutral - y_eq[i];
        assert!(
            (law.lo[i] - (c.min + d.min(0.0))).abs() < 1e-12
                && (law.hi[i] - (c.max + d.max(0.0))).abs() < 1e-12,
            "y{}: [{}, {}], deflection {d}",
            i + 1,
            law.lo[i],
            law.hi[i]
        );
        assert!(d.abs() > 0.2, "y{}: static deflection {d} rad", i + 1);
    }
}
