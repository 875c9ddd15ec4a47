//! Rovers on a soil: the whole chain (contact depth, the soil law, the
//! loads, the wheels' spins, the speed loop on the rim) at rest and
//! climbing, the embedded stop, and the errors a soil or a wheel without a
//! width gives.

use std::sync::atomic::AtomicBool;

use rover_dynamics::soil::{Shear, SoilContact, SoilWheel, soil_forces_sheared};
use rover_runtime::soil::SoilConfig;
use rover_scenario::output::Status;
use rover_scenario::scenario::Scenario;

use crate::support::run::{Run, run};

/// MER on flat dry sand, parked (its wheels held at rest by the speed loop).
const PARKED: &str = r#"
rover = "mer"
duration = 12.0
output_rate = 10.0
[terrain]
soil = "dry_sand"
[control.speed]
speed = 0.0
kp = 500.0
"#;

/// At rest on flat sand the rover stands on its wheels' soil pressure:
/// each wheel's normal force is the soil's vertical force at the depth it
/// sank to (no shear at rest), and together they carry the rover's weight.
#[test]
fn a_rover_parked_on_soil_stands_on_the_soils_pressure() {
    let r = run("mer", PARKED);
    assert_eq!(r.summary.status, Status::Completed);
    let spec = rover_spec::load_str(rover_models::builtin("mer").unwrap(), "mer").unwrap();
    let model = &spec.model;
    let sand = SoilConfig::builtin("dry_sand").unwrap().soil().unwrap();
    let last = |name: &str| *r.col(name).last().unwrap();
    let mut total = 0.0;
    for (j, w) in model.wheels.iter().enumerate() {
        let (normal, z) = (
            last(&format!("Fn{}", j + 1)),
            last(&format!("sinkage{}", j + 1)),
        );
        let wheel = SoilWheel::new(&sand, w.radius, w.width.unwrap());
        let contact = SoilContact {
            entry_angle: (1.0 - z / w.radius).acos(),
            slip: 0.0,
            slip_angle: 0.0,
        };
        let rest = Shear {
            rim: 0.0,
            travel: 0.0,
        };
        let rule = rover_dynamics::wheel_soil::RunRule::new();
        let pressure = soil_forces_sheared(&wheel, contact, rest, &rule).vertical;
        assert!(
            (normal - pressure).abs() < 1e-6 * pressure,
            "wheel {}: {normal} N on a soil pressing {pressure} N at {z} m",
            j + 1
        );
        assert!(z > 0.005 && z < 0.05, "wheel {}: sinks {z} m", j + 1);
        assert!(last(&format!("slip{}", j + 1)).abs() < 1e-3);
        total += normal;
    }
    let weight =
        model.gravity * (model.body.mass + model.bodies.iter().map(|b| b.mass).sum::<f64>());
    assert!(
        (total - weight).abs() < 1e-6 * weight,
        "the wheels carry {total} N of a {weight} N rover"
    );
}

/// A soil run's rows carry each wheel's spin, slip, slip angle, sinkage
/// and the soil's torque; a rigid run's do not.
#[test]
fn soil_runs_carry_slip_and_sinkage_columns() {
    let soft = run("mer", &PARKED.replace("duration = 12.0", "duration = 0.5"));
    let rigid = run(
        "mer",
        &PARKED
            .replace("duration = 12.0", "duration = 0.5")
            .replace("soil = \"dry_sand\"", ""),
    );
    for name in ["spin1", "slip6", "slip_angle3", "sinkage2", "T4"] {
        assert!(soft.header.iter().any(|h| h == name), "{name}");
        assert!(
            !rigid.header.iter().any(|h| h == name),
            "{name} on rigid ground"
        );
    }
    assert!(soft.summary.soil.is_some() && rigid.summary.soil.is_none());
}

/// MER on dry sand at 5 cm/s: the steeper the slope, the more its wheels
/// slip, and up to 12.5° it climbs.
fn climb(angle: f64) -> Run {
    let scenario = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/soil_slope.toml"),
    )
    .unwrap()
    .replace("angle_deg = 10.0", &format!("angle_deg = {angle}"))
    .replace("[0.0, -10.0, 0.0]", &format!("[0.0, {}, 0.0]", -angle))
    .replace("duration = 40.0", "duration = 15.0");
    run("mer", &scenario)
}

fn mean_slip(r: &Run) -> f64 {
    let soil = r.summary.soil.as_ref().unwrap();
    soil.iter().map(|w| w.mean_slip).sum::<f64>() / soil.len() as f64
}

#[test]
fn the_steeper_the_soft_slope_the_more_the_wheels_slip() {
    let slips: Vec<f64> = [0.0, 5.0, 10.0]
        .iter()
        .map(|&a| {
            let r = climb(a);
            assert_eq!(r.summary.status, Status::Completed, "{a}°");
            assert!(r.summary.distance_m > 0.2, "{a}°: {}", r.summary.distance_m);
            mean_slip(&r)
        })
        .collect();
    assert!(
        slips.windows(2).all(|w| w[1] > w[0] + 0.02) && slips[0] > 0.0,
        "{slips:?}"
    );
}

/// On 20° of dry sand the rover cannot climb: its wheels turn at the
/// set-point while it stays put, and 5 s after settling with every wheel
/// above 0.95 of slip the run stops `embedded`, saying when, where and
/// which wheels; the CSV keeps what was computed.
#[test]
fn a_rover_that_cannot_climb_is_embedded() {
    let r = climb(20.0);
    assert_eq!(r.summary.status, Status::Embedded);
    let error = r.summary.error.clone().unwrap();
    assert!(
        error.contains("embedded at t = ") && error.contains("X = ") && error.contains("wheel 6"),
        "{error}"
    );
    let t = r.col("t");
    assert!(
        r.summary.t_end < 15.0 && r.summary.t_end >= 8.0,
        "{}",
        r.summary.t_end
    );
    assert!((t.last().unwrap() - r.summary.t_end).abs() < 0.1 + 1e-9);
    assert!(mean_slip(&r) > 0.9);
}

/// A soil a scenario names by a wrong name, a bad key or a value outside
/// physics: an error naming `terrain.soil` and the field.
#[test]
fn bad_soils_are_refused_naming_the_field() {
    let parse = |text: &str| {
        Scenario::parse(
            &format!("duration = 1.0\n{text}"),
            std::path::Path::new("s.toml"),
        )
    };
    let e = parse("[terrain.soil]\nn = 1.0\nk_cc = 1.0\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("terrain.soil") && e.contains("k_cc"), "{e}");
    let e = parse("[terrain]\nsoil = 3\n").unwrap_err().to_string();
    assert!(
        e.contains("terrain.soil") && e.contains("lunar_nominal"),
        "{e}"
    );
    // Parsed, then refused when the run is prepared.
    let unknown = PARKED.replace("\"dry_sand\"", "\"quicksand\"");
    let e = try_run(&unknown);
    assert!(
        e.contains("terrain.soil = \"quicksand\"") && e.contains("dry_sand"),
        "{e}"
    );
    let negative = PARKED.replace(
        "soil = \"dry_sand\"",
        "[terrain.soil]\nn = -1.0\nk_c = 990.0\nk_phi = 1.5e6\ncohesion = 1040.0\nfriction_angle_deg = 28.0\nshear_modulus = 0.025\n",
    );
    let e = try_run(&negative);
    assert!(e.contains("soil.n"), "{e}");
}

/// The run's error message, or "" when it ran.
fn try_run(scenario: &str) -> String {
    let dir = std::path::Path::new(".");
    let prepared = match rover_scenario::prepare::Prepared::from_text(
        Some("mer"),
        scenario,
        &dir.join("test.toml"),
        dir,
    ) {
        Ok(p) => p,
        Err(e) => return e.to_string(),
    };
    match prepared.run(true, std::io::sink(), &AtomicBool::new(false), |_| {}) {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

/// A rover whose wheels have no width runs on rigid ground but not on a
/// soil, whose law presses on the width: the error names the field.
#[test]
fn a_wheel_without_width_is_refused_on_soil_only() {
    let text = rover_models::builtin("exomars")
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with("width"))
        .collect::<Vec<_>>()
        .join("\n");
    let spec = rover_spec::load_str(&text, "narrow.toml").unwrap();
    assert!(spec.model.wheels.iter().all(|w| w.width.is_none()));
    let scenario = |soil: &str| {
        Scenario::parse(
            &format!("duration = 0.2\n[terrain]\n{soil}\n"),
            std::path::Path::new("s.toml"),
        )
        .unwrap()
    };
    let go = |scenario: &Scenario| {
        rover_scenario::simulate::simulate(
            rover_runtime::GenericPlant::new(spec.model.clone()).unwrap(),
            &spec.model,
            "narrow",
            scenario,
            std::path::Path::new("."),
            std::io::sink(),
            &AtomicBool::new(false),
            |_| {},
        )
    };
    assert!(go(&scenario("")).is_ok());
    let e = go(&scenario("soil = \"dry_sand\""))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("wheel 1 has no width") && e.contains("width = "),
        "{e}"
    );
}

/// A width ≤ 0, or as wide as the rover's track, is refused by the
/// description's checks, naming the field.
#[test]
fn wheel_widths_outside_the_rover_are_refused() {
    let text = rover_models::builtin("exomars").unwrap();
    for (width, field) in [("0.0", "wheel_defaults.width"), ("0.5", "wheel[0].width")] {
        let bad = text.replace("width = 0.060", &format!("width = {width}"));
        let e = rover_spec::load_str(&bad, "wide.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{width}: {e}");
    }
}

/// The quasi-static level has no wheel spin: a soil there is refused,
/// naming the field.
#[test]
fn the_quasi_static_level_refuses_a_soil() {
    let e = try_run(&PARKED.replace("[terrain]", "fidelity = \"quasi_static\"\n[terrain]"));
    assert!(e.contains("fidelity") && e.contains("soil"), "{e}");
}

/// A run that ends as settling does (its last step reaching the instant
/// the speed command switches on) completes: the end is a breakpoint too.
#[test]
fn a_run_that_ends_as_settling_does_completes() {
    let scenario = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/soil_slope.toml"),
    )
    .unwrap()
    .replace("duration = 40.0", "duration = 3.0");
    let r = run("mer", &scenario);
    assert_eq!(r.summary.status, Status::Completed, "{:?}", r.summary.error);
    assert_eq!(*r.col("t").last().unwrap(), 3.0);
}

/// The shipped anti-spin climb against the same climb with the torque
/// shared evenly: with anti-spin the wheels slip less (the front ones, the
/// least loaded, no longer spin up), and the rover climbs further.
#[test]
fn anti_spin_climbs_a_soft_slope_further_with_less_slip_than_even_shares() {
    let anti_spin = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios/soil_slope_anti_spin.toml"),
    )
    .unwrap();
    let even = anti_spin
        .replace("distribution = \"anti_spin\"", "distribution = \"even\"")
        .lines()
        .filter(|l| !l.starts_with("slip_"))
        .collect::<Vec<_>>()
        .join("\n");
    let (a, e) = (run("mer", &anti_spin), run("mer", &even));
    for r in [&a, &e] {
        assert_eq!(r.summary.status, Status::Completed);
    }
    let peak = |r: &Run| {
        let soil = r.summary.soil.as_ref().unwrap();
        soil.iter().map(|w| w.peak_slip).fold(0.0, f64::max)
    };
    assert!(
        a.summary.distance_m > 1.2 * e.summary.distance_m,
        "anti-spin {} m, even {} m",
        a.summary.distance_m,
        e.summary.distance_m
    );
    assert!(
        mean_slip(&a) < mean_slip(&e) - 0.05,
        "{} {}",
        mean_slip(&a),
        mean_slip(&e)
    );
    assert!(
        peak(&a) < 0.8 && peak(&e) > 0.9,
        "{} {}",
        peak(&a),
        peak(&e)
    );
}

/// The anti-spin distribution reads a slip the rigid law does not have:
/// on rigid ground it is refused, naming the field; and its parameters
/// are checked.
#[test]
fn anti_spin_is_refused_on_rigid_ground_and_with_bad_parameters() {
    let soft = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenarios/soil_slope_anti_spin.toml"),
    )
    .unwrap()
    .replace("duration = 40.0", "duration = 0.5")
    .replace("settle = 3.0", "settle = 0.2");
    let rigid = soft.replace("soil = \"dry_sand\"", "");
    let e = try_run(&rigid);
    assert!(
        e.contains("control.speed.distribution") && e.contains("soil"),
        "{e}"
    );
    let e = try_run(&soft.replace("slip_threshold = 0.2", "slip_threshold = 1.5"));
    assert!(
        e.contains("control.speed.slip_threshold") && e.contains("[0, 1)"),
        "{e}"
    );
    let e = try_run(&soft.replace("slip_band = 0.2", "slip_band = 0.0"));
    assert!(
        e.contains("control.speed.slip_band") && e.contains("> 0"),
        "{e}"
    );
    let e = try_run(&soft.replace("\"anti_spin\"", "\"even\""));
    assert!(
        e.contains("control.speed.slip_threshold") && e.contains("anti_spin"),
        "{e}"
    );
    assert_eq!(try_run(&soft), "");
}
