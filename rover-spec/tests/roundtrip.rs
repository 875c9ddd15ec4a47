//! TOML → Description → TOML → Description gives the same value, and the
//! same validated rover.

use rover_spec::Description;
use rover_spec::description::{
    BodyDesc, CoordinateDesc, FitDesc, FitMethodDesc, Inertia, MassDesc, MemberDesc,
    MotorMountDesc, PolyPointDesc, PolyTermDesc, PolynomialDesc, ScalarPolyDesc, ScalarTermDesc,
    SpringTableDesc, SuspensionDesc, SwingArmDesc, WheelDesc, WheelFields,
};

fn round_trip(desc: &Description) {
    let text = desc.to_toml_string().expect("serializes");
    let back =
        rover_spec::parse_str(&text, "<round trip>").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(&back, desc, "{text}");
    assert_eq!(back.to_toml_string().unwrap(), text);
}

#[test]
fn every_model_round_trips() {
    for name in rover_models::NAMES {
        let text = rover_models::builtin(name).unwrap();
        let desc = rover_spec::parse_str(text, name).unwrap();
        round_trip(&desc);
        let again = desc.to_toml_string().unwrap();
        let a = rover_spec::load_str(text, name).unwrap();
        let b = rover_spec::load_str(&again, name).unwrap();
        assert_eq!(a.model, b.model, "{name}");
    }
}

/// A description built in Rust, using the forms the model files do not:
/// a full inertia, a spring table, a carried mass, a raw polynomial point.
fn rust_built() -> Description {
    let coordinate = CoordinateDesc {
        name: Some("y1".into()),
        rest_deg: Some(-20.0),
        min_deg: Some(-50.0),
        max_deg: Some(10.0),
        spring_table: Some(SpringTableDesc {
            deflection: None,
            deflection_deg: Some(vec![-20.0, 0.0, 30.0]),
            force: vec![4.0, 0.0, -9.0],
        }),
        damping: Some(2.0),
        ..CoordinateDesc::default()
    };
    Description {
        name: "built".into(),
        gravity: 3.71,
        body: BodyDesc {
            mass: 20.0,
            inertia: Inertia::Full([[1.0, 0.1, 0.0], [0.1, 1.2, 0.0], [0.0, 0.0, 1.5]]),
        },
        wheel_defaults: Some(WheelFields {
            mass: Some(1.0),
            radius: Some(0.1),
            stiffness: Some(5000.0),
            damping: Some(100.0),
            mu_x: Some(0.6),
            mu_y: Some(0.5),
            cornering_stiffness: Some(80.0),
            max_torque: Some(3.0),
            no_load_speed: Some(40.0),
            motor: Some(MotorMountDesc::Hub),
            ..WheelFields::default()
        }),
        suspensions: vec![
            SuspensionDesc::LongitudinalSwingArm(SwingArmDesc {
                name: "arm".into(),
                pivot: [0.3, 0.2, 0.0],
                length: 0.25,
                coordinate,
                fit: Some(FitDesc {
                    method: Some(FitMethodDesc::LeastSquares),
                    terms: Some(6),
                    ..FitDesc::default()
                }),
                bodies: vec![MassDesc {
                    name: "arm_mass".into(),
                    mass: 0.5,
                    inertia: Some(Inertia::Diagonal([0.01, 0.01, 0.001])),
                    member: Some("arm".into()),
                    position: Some([0.35, 0.2, -0.1]),
                    point: None,
                }],
            }),
            SuspensionDesc::Polynomial(PolynomialDesc {
                name: "slider".into(),
                coordinates: vec![CoordinateDesc {
                    name: Some("s".into()),
                    linear: Some(true),
                    min: Some(-0.05),
                    max: Some(0.05),
                    stiffness: Some(2000.0),
                    ..CoordinateDesc::default()
                }],
                points: vec![PolyPointDesc {
                    name: "hub".into(),
                    position: [-0.3, 0.0, -0.2],
                    terms: vec![PolyTermDesc {
                        coordinate: "s".into(),
                        coeffs: vec![[0.0; 3], [0.0, 0.0, 1.0]],
                    }],
                    member: vec![MemberDesc {
                        coordinate: "s".into(),
                        axis: [0.0, 1.0, 0.0],
                        angle: vec![0.0, 0.5],
                    }],
                    camber: Some(ScalarPolyDesc {
                        constant: Some(0.01),
                        terms: vec![ScalarTermDesc {
                            coordinate: "s".into(),
                            coeffs: vec![0.0, 0.2],
                        }],
                    }),
                    toe: None,
                }],
                bodies: Vec::new(),
            }),
        ],
        wheels: vec![
            WheelDesc {
                name: "a".into(),
                suspension: "arm".into(),
                point: None,
                mass: None,
                inertia: None,
                radius: None,
                width: None,
                spin_inertia: None,
                stiffness: None,
                damping: None,
                mu_x: None,
                mu_y: None,
                cornering_stiffness: None,
                max_torque: None,
                no_load_speed: None,
                stall_torque: None,
                motor: None,
                steerable: Some(true),
            },
            WheelDesc {
                name: "b".into(),
                suspension: "slider".into(),
                point: Some("hub".into()),
                mass: Some(2.0),
                inertia: None,
                radius: Some(0.12),
                width: Some(0.08),
                spin_inertia: Some(0.02),
                stiffness: None,
                damping: None,
                mu_x: None,
                mu_y: None,
                cornering_stiffness: None,
                max_torque: None,
                no_load_speed: None,
                stall_torque: None,
                motor: Some(MotorMountDesc::Body),
                steerable: None,
            },
        ],
    }
}

#[test]
fn rust_built_description_round_trips_and_validates() {
    let desc = rust_built();
    round_trip(&desc);
    let spec = rover_spec::from_description(&desc, "<rust>").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec.coordinate_names, ["y1", "s"]);
    assert_eq!(spec.body_names, ["a", "b", "arm_mass"]);
    assert_eq!(spec.coordinate_linear, [false, true]);
    let m = &spec.model;
    assert_eq!(m.total_mass(), 20.0 + 1.0 + 2.0 + 0.5);
    // Table spring: the stop stiffness is 100 × the steepest slope.
    let steepest = 9.0 / 30f64.to_radians();
    assert!((m.coordinates[0].stop_stiffness - 100.0 * steepest).abs() < 1e-9);
    // Linear coordinate without a stop override: 100 × k.
    assert_eq!(m.coordinates[1].stop_stiffness, 100.0 * 2000.0);
    // The slider's stop damping is critical for the mass it moves: 2 kg at unit slope.
    assert!((m.coordinates[1].stop_damping - 2.0 * (200_000.0f64 * 2.0).sqrt()).abs() < 1e-9);
    // The raw polynomial passes through unchanged, centred at the rest value.
    let hub = &m.bodies[1];
    assert_eq!(hub.position.terms[0].coord, 1);
    assert_eq!(hub.position.terms[0].center, 0.0);
    assert_eq!(hub.member[0].angle.terms[0].coeffs, [0.0, 0.5]);
    assert_eq!(m.wheels[1].camber.constant, 0.01);
    // The arm's mass turns with the arm: at rest it is where it was put.
    let rest = m.rest();
    let p = m.bodies[2].position.value(&rest);
    assert!(
        (p[0] - 0.35).abs() < 1e-12 && (p[2] + 0.1).abs() < 1e-12,
        "{p:?}"
    );
    assert_eq!(m.bodies[2].member.len(), 1);
}
