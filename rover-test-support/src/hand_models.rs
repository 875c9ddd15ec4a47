//! The paper's two rovers built by hand from MODEL.md §10 with exact Taylor
//! coefficients, independent of the description parser: the dynamics tests
//! use them, and a test holds the parsed model files equal to them.

use rover_dynamics::Model;
use rover_dynamics::model::{
    CarriedBody, Coordinate, MemberRotation, MotorMount, RigidBody, Spring, Wheel,
};
use rover_dynamics::poly::{PolyVec, ScalarPoly, Term};

const K: usize = 5;

fn factorial(p: usize) -> f64 {
    (1..=p).map(|v| v as f64).product()
}

/// Taylor coefficients of sin(ξ + β) and cos(ξ + β) in ξ.
fn sin_cos_taylor(beta: f64) -> (Vec<f64>, Vec<f64>) {
    let s = (0..K)
        .map(|p| (beta + p as f64 * std::f64::consts::FRAC_PI_2).sin() / factorial(p))
        .collect();
    let c = (0..K)
        .map(|p| (beta + p as f64 * std::f64::consts::FRAC_PI_2).cos() / factorial(p))
        .collect();
    (s, c)
}

/// A point on an arm of length l at angle (y + β) about e_y (longitudinal,
/// `u = A + Ry(y+β)·[0,0,−l]`) or e_x (transversal, `u = A + Rx(y+β)·[0,0,−l]`),
/// expanded about y = center with ξ = y − center and β absorbing the centre.
fn arm(
    coord: usize,
    pivot: [f64; 3],
    l: f64,
    beta: f64,
    center: f64,
    transversal: bool,
) -> PolyVec {
    let (s, c) = sin_cos_taylor(beta + center);
    let coeffs = (0..K)
        .map(|p| {
            if transversal {
                [0.0, l * s[p], -l * c[p]]
            } else {
                [-l * s[p], 0.0, -l * c[p]]
            }
        })
        .collect();
    PolyVec {
        constant: pivot,
        terms: vec![Term {
            coord,
            center,
            coeffs,
        }],
    }
}

fn member(coord: usize, axis: [f64; 3], center: f64) -> Vec<MemberRotation> {
    vec![MemberRotation {
        coord,
        axis,
        angle: ScalarPoly {
            constant: 0.0,
            terms: vec![Term {
                coord,
                center,
                coeffs: vec![0.0, 1.0],
            }],
        },
    }]
}

fn wheel(body: usize, steerable: bool) -> Wheel {
    Wheel {
        body,
        radius: 0.090,
        width: None,
        spin_inertia: 0.5 * 0.6 * 0.090 * 0.090,
        stiffness: 4000.0,
        damping: 300.0,
        mu_x: 0.5,
        mu_y: 0.5,
        cornering_stiffness: 50.0,
        max_torque: 1.29,
        motor_curve: None,
        motor: MotorMount::Body,
        steerable,
        camber: ScalarPoly::default(),
        toe: ScalarPoly::default(),
    }
}

fn coordinate(rest: f64, neutral: f64, k: f64, c: f64, min: f64, max: f64) -> Coordinate {
    Coordinate {
        rest,
        neutral,
        spring: if k > 0.0 {
            Spring::Linear { stiffness: k }
        } else {
            Spring::None
        },
        damping: c,
        min,
        max,
        stop_stiffness: if k > 0.0 { 100.0 * k } else { 100.0 },
        stop_damping: 0.0,
    }
}

fn body() -> RigidBody {
    RigidBody {
        mass: 30.0,
        inertia: [[0.7, 0.0, 0.0], [0.0, 0.9, 0.0], [0.0, 0.0, 1.5]],
    }
}

/// Example 1 (ExoMars-like, 6 wheels, 9 DOF), MODEL.md §10.
pub fn exomars() -> Model {
    let d = std::f64::consts::PI / 180.0;
    let ey = [0.0, 1.0, 0.0];
    let ex = [1.0, 0.0, 0.0];
    let left = [0.150, 0.200, -0.010];
    let right = [0.150, -0.200, -0.010];
    let rear = [-0.300, 0.0, -0.010];
    let point = |coord, pivot, l, beta: f64, transversal| CarriedBody {
        mass: 0.6,
        inertia: None,
        position: arm(coord, pivot, l, beta * d, 0.0, transversal),
        member: member(coord, if transversal { ex } else { ey }, 0.0),
    };
    let bodies = vec![
        point(0, left, 0.250, -45.0, false),
        point(1, right, 0.250, -45.0, false),
        point(0, left, 0.250, 45.0, false),
        point(1, right, 0.250, 45.0, false),
        point(2, rear, 0.267, 48.5, true),
        point(2, rear, 0.267, -48.5, true),
    ];
    let mut wheels: Vec<Wheel> = (0..6).map(|j| wheel(j, true)).collect();
    let camber = ScalarPoly {
        constant: 0.0,
        terms: vec![Term {
            coord: 2,
            center: 0.0,
            coeffs: vec![0.0, 1.0],
        }],
    };
    wheels[4].camber = camber.clone();
    wheels[5].camber = camber;
    let r = 30.0 * d;
    Model {
        gravity: 1.62,
        body: body(),
        coordinates: (0..3)
            .map(|_| coordinate(0.0, 0.0, 0.0, 0.0, -r, r))
            .collect(),
        bodies,
        wheels,
    }
}

/// Example 2 (4 wheels on longitudinal swing arms, 10 DOF), MODEL.md §10.
pub fn swing4() -> Model {
    let d = std::f64::consts::PI / 180.0;
    let x = [0.180, 0.180, -0.220, -0.220];
    let y = [0.200, -0.200, 0.200, -0.200];
    let y0 = [-17.2 * d, -17.2 * d, 17.2 * d, 17.2 * d];
    let bodies = (0..4)
        .map(|i| CarriedBody {
            mass: 0.6,
            inertia: None,
            position: arm(i, [x[i], y[i], -0.010], 0.200, 0.0, y0[i], false),
            member: member(i, [0.0, 1.0, 0.0], y0[i]),
        })
        .collect();
    let coordinates = (0..4)
        .map(|i| {
            let (lo, hi) = if i < 2 {
                (-60.0 * d, -2.0 * d)
            } else {
                (2.0 * d, 60.0 * d)
            };
            coordinate(y0[i], y0[i], 5.0, 3.5, lo, hi)
        })
        .collect();
    Model {
        gravity: 1.62,
        body: body(),
        coordinates,
        bodies,
        wheels: (0..4).map(|j| wheel(j, false)).collect(),
    }
}

/// A variant exercising what the paper's rovers leave out: rotational
/// inertia of every carried body (turning with its member), an extra massive
/// arm body, a tabulated spring and a hub motor. Built on `swing4`.
pub fn swing4_rich() -> Model {
    let mut m = swing4();
    for (j, b) in m.bodies.iter_mut().enumerate() {
        let a = 0.002 + 0.0005 * j as f64;
        b.inertia = Some([
            [a, 0.0002, 0.0],
            [0.0002, 1.5 * a, 0.0001],
            [0.0, 0.0001, a],
        ]);
    }
    // Massive arm midpoint of the front-left arm.
    let d = std::f64::consts::PI / 180.0;
    m.bodies.push(CarriedBody {
        mass: 0.3,
        inertia: Some([[0.001, 0.0, 0.0], [0.0, 0.002, 0.0], [0.0, 0.0, 0.0015]]),
        position: arm(0, [0.180, 0.200, -0.010], 0.100, 0.0, -17.2 * d, false),
        member: member(0, [0.0, 1.0, 0.0], -17.2 * d),
    });
    m.coordinates[2].spring = Spring::Table {
        deflection: vec![-0.5, -0.1, 0.0, 0.1, 0.5],
        force: vec![4.0, 0.45, 0.0, -0.45, -4.0],
    };
    m.wheels[1].motor = MotorMount::Hub;
    m
}
