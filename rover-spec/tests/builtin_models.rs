//! The built-in models load, with the geometry MODEL.md §10 fixes.

use rover_dynamics::model::{MotorMount, Spring};
use rover_spec::Spec;
use rover_spec::report::check_report;

fn load(name: &str) -> Spec {
    let text = rover_models::builtin(name).unwrap();
    rover_spec::load_str(text, rover_models::builtin_path(name).unwrap())
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_model_loads_from_its_file() {
    for name in rover_models::NAMES {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("..")
            .join(rover_models::builtin_path(name).unwrap());
        let spec = rover_spec::load_file(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&spec.name, name);
        // Every fit holds its default or declared tolerance.
        for f in &spec.fits {
            let o = spec.suspensions[f.suspension].fit.unwrap();
            assert!(
                f.shares
                    .iter()
                    .all(|s| s.position <= o.tolerance && s.angle <= o.angle_tolerance)
            );
        }
    }
}

#[test]
fn exomars_is_example_1() {
    let s = load("exomars");
    let m = &s.model;
    assert_eq!(m.dof(), 9);
    assert_eq!((m.gravity, m.body.mass), (1.62, 30.0));
    assert_eq!(
        m.body.inertia,
        [[0.7, 0.0, 0.0], [0.0, 0.9, 0.0], [0.0, 0.0, 1.5]]
    );
    assert!((m.total_mass() - 33.6).abs() < 1e-12);
    assert_eq!(
        s.wheel_names,
        [
            "front_left",
            "front_right",
            "middle_left",
            "middle_right",
            "rear_left",
            "rear_right"
        ]
    );
    assert_eq!(s.coordinate_names, ["y1", "y2", "y3"]);
    // All wheel centres at z = −0.187 m at rest (the paper's rounding).
    for p in &s.rest_wheel_centres {
        assert!((p[2] + 0.187).abs() < 3e-4, "{p:?}");
    }
    // Front–middle a = 0.354 m, middle–rear b = 0.273 m (MODEL.md §8).
    let x: Vec<f64> = s.rest_wheel_centres.iter().map(|p| p[0]).collect();
    assert!(
        (x[0] - x[2] - 0.354).abs() < 1e-3 && (x[2] - x[4] - 0.273).abs() < 1e-3,
        "{x:?}"
    );
    for (c, w) in m.coordinates.iter().zip(&m.wheels) {
        assert_eq!(
            (c.rest, c.spring.clone(), c.damping),
            (0.0, Spring::None, 0.0)
        );
        assert!((c.max - 30f64.to_radians()).abs() < 1e-15);
        assert_eq!(w.motor, MotorMount::Body);
    }
    let steer: Vec<bool> = m.wheels.iter().map(|w| w.steerable).collect();
    assert_eq!(steer, [true, true, false, false, true, true]);
    for w in &m.wheels {
        assert_eq!(
            (w.radius, w.stiffness, w.damping, w.mu_x, w.mu_y),
            (0.09, 4000.0, 300.0, 0.5, 0.5)
        );
        assert_eq!((w.cornering_stiffness, w.max_torque), (50.0, 1.29));
    }
    // The rear wheels camber with the transversal rocker: γ = y3.
    let y = [0.0, 0.0, 0.2];
    assert!((m.wheels[4].camber.value(&y) - 0.2).abs() < 1e-12);
    assert_eq!(m.wheels[0].camber.value(&y), 0.0);
    // Taylor k = 5 about 0 over ±30°: about 3e-4·l (MODEL.md §10).
    assert!(s.fits[0].max_position_error / 0.25 < 3.5e-4);
}

#[test]
fn swing4_is_example_2() {
    let s = load("swing4");
    let m = &s.model;
    assert_eq!(m.dof(), 10);
    let y0 = 17.2f64.to_radians();
    for (i, c) in m.coordinates.iter().enumerate() {
        let sign = if i < 2 { -1.0 } else { 1.0 };
        assert!((c.neutral - sign * y0).abs() < 1e-15 && c.rest == c.neutral);
        assert_eq!(c.spring, Spring::Linear { stiffness: 5.0 });
        assert_eq!(c.damping, 3.5);
        let (lo, hi) = if i < 2 { (-60.0, -2.0) } else { (2.0, 60.0) };
        assert!(
            (c.min - f64::to_radians(lo)).abs() < 1e-15
                && (c.max - f64::to_radians(hi)).abs() < 1e-15
        );
    }
    // Table 2 pivots, arms of 0.2 m: the wheel of arm i at rest.
    let pivots = [[0.18, 0.2], [0.18, -0.2], [-0.22, 0.2], [-0.22, -0.2]];
    for (i, p) in pivots.iter().enumerate() {
        let y = m.coordinates[i].rest;
        let u = s.rest_wheel_centres[i];
        assert!((u[0] - (p[0] - 0.2 * y.sin())).abs() < 1e-12);
        assert!((u[1] - p[1]).abs() < 1e-15);
        assert!((u[2] - (-0.01 - 0.2 * y.cos())).abs() < 1e-12);
        // Taylor k = 5 about y0: the terms are eq. 33's.
        let t = &m.bodies[i].position.terms[0];
        assert_eq!((t.coeffs.len(), t.center), (5, y));
        assert!((t.coeffs[1][0] + 0.2 * y.cos()).abs() < 1e-15);
        assert!((t.coeffs[4][2] + 0.2 * y.cos() / 24.0).abs() < 1e-15);
        // Below 2e-3·l over the travel (MODEL.md §10).
        assert!(s.fits[i].max_position_error < 2e-3 * 0.2);
    }
}

#[test]
fn mer_is_a_rocker_bogie_with_differential() {
    let s = load("mer");
    let m = &s.model;
    assert_eq!((m.dof(), m.bodies.len(), m.wheels.len()), (9, 10, 6));
    assert!((m.total_mass() - 174.0).abs() < 1e-9);
    assert_eq!(m.gravity, 3.71);
    // Left and right rockers turn opposite ways with y1.
    let y = [0.1, 0.0, 0.0];
    assert!((m.bodies[0].member[0].angle.value(&y) - 0.1).abs() < 1e-12);
    assert!((m.bodies[1].member[0].angle.value(&y) + 0.1).abs() < 1e-12);
    assert!(
        m.wheels
            .iter()
            .all(|w| w.motor == MotorMount::Hub && w.radius == 0.13)
    );
}

#[test]
fn lrv_is_on_four_double_wishbones() {
    let s = load("lrv");
    let m = &s.model;
    assert_eq!(m.dof(), 10);
    assert!((m.total_mass() - 700.0).abs() < 1e-9);
    for (k, p) in s.rest_wheel_centres.iter().enumerate() {
        // Wheelbase 2.286 m, tread 1.829 m.
        assert!(
            (p[0].abs() - 1.143).abs() < 1e-12 && (p[1].abs() - 0.9145).abs() < 2e-3,
            "{k}: {p:?}"
        );
        // The wheel's camber follows the upright.
        assert_eq!(m.bodies[k].member[0].axis, [1.0, 0.0, 0.0]);
    }
    assert!(s.suspensions.iter().all(|x| x.kind == "double_wishbone"));
}

#[test]
fn check_report_of_exomars() {
    insta::assert_snapshot!(check_report(&load("exomars")));
}
