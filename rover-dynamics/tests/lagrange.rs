//! An independent route to the accelerations: Lagrange's equations in the
//! ordinary coordinates q = x, with every derivative of the Lagrangian taken
//! exactly by nested dual numbers, and the bodies' velocities obtained by
//! differentiating their positions in time (not from T_j, S_j or E).
//!
//! ```text
//! Σ_b ∂²L/∂q̇_a∂q̇_b·q̈_b = Q_a − Σ_b ∂²L/∂q̇_a∂q_b·q̇_b + ∂L/∂q_a
//! Q_a = ∂P/∂q̇_a,  P = Σ_wheels F·V_j + μ·ω_member + τ·ω_stator   (virtual power)
//! ```
//! then ẇ = d/dt w(q, q̇) with w = [Rᵀ·ṙ; vee(Rᵀ·Ṙ); ẏ].

use rover_dynamics::attitude::Attitude;
use rover_dynamics::dual::Dual;
use rover_dynamics::forces::coordinate_force;
use rover_dynamics::linalg::{axis_angle, m3, mat_mul, transpose, v3};
use rover_dynamics::model::MotorMount;
use rover_dynamics::plant::WheelLoad;
use rover_dynamics::solve::ldlt_solve;
use rover_dynamics::{Model, Scalar};

type D1 = Dual<f64>;
type D2 = Dual<D1>;

/// R(q) and Ṙ along q̇, at any scalar level.
fn rotation_and_rate<S: Scalar + PartialOrd>(q: &[S], qd: &[S]) -> ([[S; 3]; 3], [[S; 3]; 3]) {
    let t = |a: usize| Dual {
        re: q[a],
        eps: qd[a],
    };
    let r = Attitude::new(t(3), t(4), t(5)).rotation();
    let re = r.map(|row| row.map(|v| v.re));
    let eps = r.map(|row| row.map(|v| v.eps));
    (re, eps)
}

/// Body angular velocity from Ω̃ = Rᵀ·Ṙ.
fn body_omega<S: Scalar>(r: &[[S; 3]; 3], rd: &[[S; 3]; 3]) -> [S; 3] {
    let w = mat_mul(&transpose(r), rd);
    [w[2][1], w[0][2], w[1][0]]
}

fn mul3<S: Scalar>(m: &[[S; 3]; 3], v: [S; 3]) -> [S; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}
fn dot3<S: Scalar>(a: [S; 3], b: [S; 3]) -> S {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Absolute velocity of carried body j (inertial) and its member's angular
/// velocity (body components), by time-differentiating positions.
fn body_motion<S: Scalar + PartialOrd>(
    model: &Model,
    q: &[S],
    qd: &[S],
    j: usize,
) -> ([S; 3], [S; 3], [[S; 3]; 3], [S; 3]) {
    let body = &model.bodies[j];
    let qt: Vec<Dual<S>> = q
        .iter()
        .zip(qd)
        .map(|(&a, &b)| Dual { re: a, eps: b })
        .collect();
    let r = Attitude::new(qt[3], qt[4], qt[5]).rotation();
    let u = body.position.value(&qt[6..]);
    let pos = [qt[0], qt[1], qt[2]];
    let ru = mul3(&r, u);
    let vel = [
        (pos[0] + ru[0]).eps,
        (pos[1] + ru[1]).eps,
        (pos[2] + ru[2]).eps,
    ];
    let (rr, rd) = rotation_and_rate(q, qd);
    let mut om = body_omega(&rr, &rd);
    let mut jm = body
        .inertia
        .map(|j| m3::<S>(&j))
        .unwrap_or([[S::zero(); 3]; 3]);
    for mr in &body.member {
        let a = mr.angle.value(&qt[6..]);
        let e: [S; 3] = v3(mr.axis);
        for k in 0..3 {
            om[k] += e[k] * a.eps;
        }
        let rm = axis_angle(mr.axis, a.re);
        jm = mat_mul(&mat_mul(&rm, &jm), &transpose(&rm));
    }
    (vel, om, jm, u.map(|v| v.re))
}

/// The Lagrangian L = T − U at (q, q̇).
fn lagrangian<S: Scalar + PartialOrd>(model: &Model, q: &[S], qd: &[S]) -> S {
    let half = S::cst(0.5);
    let (r, rd) = rotation_and_rate(q, qd);
    let om = body_omega(&r, &rd);
    let mb = S::cst(model.body.mass);
    let jb = m3::<S>(&model.body.inertia);
    let mut t = half * mb * (qd[0] * qd[0] + qd[1] * qd[1] + qd[2] * qd[2])
        + half * dot3(om, mul3(&jb, om));
    let g = S::cst(model.gravity);
    let mut u_pot = g * mb * q[2];
    for (j, body) in model.bodies.iter().enumerate() {
        let (vel, omj, jm, u) = body_motion(model, q, qd, j);
        let m = S::cst(body.mass);
        t += half * m * dot3(vel, vel);
        if body.inertia.is_some() {
            t += half * dot3(omj, mul3(&jm, omj));
        }
        let z = q[2] + r[2][0] * u[0] + r[2][1] * u[1] + r[2][2] * u[2];
        u_pot += g * m * z;
    }
    t - u_pot
}

/// Virtual power of the wheel loads at (q, q̇).
fn load_power<S: Scalar + PartialOrd>(model: &Model, q: &[S], qd: &[S], loads: &[WheelLoad]) -> S {
    let (r, rd) = rotation_and_rate(q, qd);
    let om_body = mul3(&r, body_omega(&r, &rd));
    let mut p = S::zero();
    for (wheel, load) in model.wheels.iter().zip(loads) {
        let (vel, omj, _, _) = body_motion(model, q, qd, wheel.body);
        let om_member = mul3(&r, omj);
        p += dot3(v3(load.force), vel) + dot3(v3(load.moment), om_member);
        let stator = match wheel.motor {
            MotorMount::Hub => om_member,
            MotorMount::Body => om_body,
        };
        p += dot3(v3(load.stator_torque), stator);
    }
    p
}

fn second<F: Fn(&[D2], &[D2]) -> D2>(
    f: &F,
    q: &[f64],
    qd: &[f64],
    a: (bool, usize),
    b: (bool, usize),
) -> f64 {
    let n = q.len();
    let lift = |v: &[f64], is_vel: bool| -> Vec<D2> {
        (0..n)
            .map(|k| {
                let mut d = D2::cst(v[k]);
                if a.0 == is_vel && a.1 == k {
                    d.eps.re = 1.0;
                }
                if b.0 == is_vel && b.1 == k {
                    d.re.eps = 1.0;
                }
                d
            })
            .collect()
    };
    f(&lift(q, false), &lift(qd, true)).eps.eps
}

/// ẇ by Lagrange's equations in ordinary coordinates.
pub fn accelerations(
    model: &Model,
    x: &[f64],
    w: &[f64],
    loads: &[WheelLoad],
    neutral: &[f64],
) -> Vec<f64> {
    let n = x.len();
    let mut xdot = vec![0.0; n];
    rover_dynamics::kinematics::position_rates(x, w, &mut xdot);
    let (q, qd) = (x, &xdot[..]);
    let lag = |a: &[D2], b: &[D2]| lagrangian(model, a, b);
    let mut mass = vec![0.0; n * n];
    let mut rhs = vec![0.0; n];
    for a in 0..n {
        for b in 0..n {
            mass[a * n + b] = second(&lag, q, qd, (true, a), (true, b));
            rhs[a] -= second(&lag, q, qd, (true, a), (false, b)) * qd[b];
        }
        // ∂L/∂q_a and Q_a = ∂P/∂q̇_a with a first-level dual.
        let lift1 = |v: &[f64], on: Option<usize>| -> Vec<D1> {
            (0..n)
                .map(|k| {
                    if on == Some(k) {
                        D1::var(v[k])
                    } else {
                        D1::cst(v[k])
                    }
                })
                .collect()
        };
        rhs[a] += lagrangian(model, &lift1(q, Some(a)), &lift1(qd, None)).eps;
        rhs[a] += load_power(model, &lift1(q, None), &lift1(qd, Some(a)), loads).eps;
    }
    for (i, c) in model.coordinates.iter().enumerate() {
        rhs[6 + i] += coordinate_force(c, neutral[i], q[6 + i], qd[6 + i]);
    }
    let mut qdd = rhs;
    ldlt_solve(&mut mass, &mut qdd, n);
    // ẇ = d/dt w(q, q̇), w = [Rᵀ·ṙ; vee(Rᵀ·Ṙ); ẏ]
    let qt: Vec<D1> = (0..n)
        .map(|k| Dual {
            re: q[k],
            eps: qd[k],
        })
        .collect();
    let qdt: Vec<D1> = (0..n)
        .map(|k| Dual {
            re: qd[k],
            eps: qdd[k],
        })
        .collect();
    let (r, rd) = rotation_and_rate(&qt, &qdt);
    let v = mul3(&transpose(&r), [qdt[0], qdt[1], qdt[2]]);
    let om = body_omega(&r, &rd);
    let mut out: Vec<f64> = v.iter().chain(om.iter()).map(|d| d.eps).collect();
    out.extend_from_slice(&qdd[6..]);
    out
}
