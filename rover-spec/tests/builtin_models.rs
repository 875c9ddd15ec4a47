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

/// The sketch of each built-in rover draws every library member rigid: at
/// coordinates spread over the travel box, each link keeps its rest length
/// (to the fits' tolerance), every wheel is the end of a link, and a joint
/// shared by two members (a bogie's pivot on its rocker, a wishbone's ball
/// joints) is at one place on both.
#[test]
fn the_sketch_draws_rigid_members_that_carry_every_wheel() {
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let mut kinds = std::collections::BTreeSet::new();
    for name in rover_models::NAMES {
        let s = load(name);
        let sketch = &s.sketch;
        let m = &s.model;
        for w in 0..m.wheels.len() {
            assert!(
                sketch
                    .links
                    .iter()
                    .any(|l| l.joints.iter().any(|&j| sketch.joints[j].wheel == Some(w))),
                "{name}: wheel {w} is on no link"
            );
        }
        for su in &s.suspensions {
            assert!(
                sketch.links.iter().any(|l| l.suspension == su.name),
                "{name}: suspension {} has no link",
                su.name
            );
            kinds.insert(su.kind);
        }
        let rest = sketch.positions(&m.rest());
        // Joints at one place at rest on different members stay together.
        let mut pairs = Vec::new();
        for a in 0..rest.len() {
            for b in 0..a {
                if dist(rest[a], rest[b]) < 1e-9 {
                    pairs.push((a, b));
                }
            }
        }
        for k in 0..=8 {
            // Corners and the middle of the travel box, and points between.
            let y: Vec<f64> = m
                .coordinates
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let f = ((k * (i + 3)) % 9) as f64 / 8.0;
                    c.min + f * (c.max - c.min)
                })
                .collect();
            let now = sketch.positions(&y);
            for l in &sketch.links {
                let [a, b] = l.joints;
                let (r, d) = (dist(rest[a], rest[b]), dist(now[a], now[b]));
                assert!(
                    (r - d).abs() < 3e-3,
                    "{name}: {}.{} is {r} m long at rest and {d} m at y = {y:?}",
                    l.suspension,
                    l.member
                );
            }
            for &(a, b) in &pairs {
                assert!(
                    dist(now[a], now[b]) < 3e-3,
                    "{name}: joints {a} and {b} part at y = {y:?}"
                );
            }
            // A wheel's joint is where the model puts the wheel.
            for (j, joint) in sketch.joints.iter().enumerate() {
                if let Some(w) = joint.wheel {
                    let u = m.bodies[m.wheels[w].body].position.value(&y);
                    assert!(dist(u, now[j]) < 1e-12);
                }
            }
        }
        // Something moves: the sketch is not the rest pose drawn forever.
        let y: Vec<f64> = m.coordinates.iter().map(|c| c.max).collect();
        let moved = sketch.positions(&y);
        assert!(
            rest.iter().zip(&moved).any(|(a, b)| dist(*a, *b) > 1e-3),
            "{name}: no joint moves"
        );
    }
    for kind in [
        "longitudinal_swing_arm",
        "double_wishbone",
        "longitudinal_rocker",
        "transversal_rocker",
        "rocker_bogie",
    ] {
        assert!(kinds.contains(kind), "no built-in rover has a {kind}");
    }
}
