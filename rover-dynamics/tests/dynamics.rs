//! Invariants of the equations of motion: M symmetric positive
//! definite and equal to the Hessian of T; ∂M/∂y against finite differences;
//! the momentum form of Ṁ·w and f2 against the explicit one; an independent
//! Lagrangian route; invariance in X, Y, ψ; virtual work of applied loads.

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::dual::Dual;
use rover_dynamics::kinematics::body_kinematics;
use rover_dynamics::linalg::{axis_angle, m3, mat_mul, transpose};
use rover_dynamics::mass::{mass_matrix, mass_matrix_derivative};
use rover_dynamics::plant::{Plant, WheelLoad};
use rover_dynamics::workspace::Workspace;
use rover_runtime::GenericPlant;
use rover_test_support::hand_models::{exomars, swing4, swing4_rich};
use rover_test_support::rng::Rng;

use crate::lagrange;

fn models() -> Vec<(&'static str, Model)> {
    vec![
        ("exomars", exomars()),
        ("swing4", swing4()),
        ("swing4_rich", swing4_rich()),
    ]
}

/// A random state inside the travel range, with every velocity non-zero.
fn random_state(model: &Model, rng: &mut Rng) -> (Vec<f64>, Vec<f64>) {
    let n = model.dof();
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for k in 0..3 {
        x[k] = rng.uniform(-2.0, 2.0);
    }
    x[3] = rng.uniform(-0.5, 0.5);
    x[4] = rng.uniform(-0.5, 0.5);
    x[5] = rng.uniform(-3.0, 3.0);
    for (i, c) in model.coordinates.iter().enumerate() {
        x[6 + i] = rng.uniform(c.min, c.max);
    }
    for v in w.iter_mut() {
        let mag = rng.uniform(0.05, 0.5);
        *v = if rng.uniform(0.0, 1.0) < 0.5 {
            -mag
        } else {
            mag
        };
    }
    (x, w)
}

fn random_loads(model: &Model, rng: &mut Rng) -> Vec<WheelLoad> {
    let mut v3r = |s: f64| [rng.uniform(-s, s), rng.uniform(-s, s), rng.uniform(-s, s)];
    (0..model.wheels.len())
        .map(|_| WheelLoad {
            force: v3r(20.0),
            moment: v3r(2.0),
            stator_torque: v3r(1.0),
        })
        .collect()
}

/// Kinetic energy from the bodies' velocities, with S_j and the member rates
/// taken by dual numbers from the position polynomials (not from the plant's
/// Horner derivatives).
fn kinetic_energy(model: &Model, y: &[f64], w: &[f64]) -> f64 {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mul = |m: &[[f64; 3]; 3], v: [f64; 3]| [dot(m[0], v), dot(m[1], v), dot(m[2], v)];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let v = [w[0], w[1], w[2]];
    let om = [w[3], w[4], w[5]];
    let mut t = 0.5 * model.body.mass * dot(v, v) + 0.5 * dot(om, mul(&model.body.inertia, om));
    // y moving along ẏ: dual parts give S_j·ẏ and α'·ẏ.
    let yt: Vec<Dual<f64>> = y
        .iter()
        .zip(&w[6..])
        .map(|(&a, &b)| Dual { re: a, eps: b })
        .collect();
    for body in &model.bodies {
        let u = body.position.value(&yt);
        let ur = u.map(|d| d.re);
        let ud = u.map(|d| d.eps);
        let vj = [
            v[0] + cross(om, ur)[0] + ud[0],
            v[1] + cross(om, ur)[1] + ud[1],
            v[2] + cross(om, ur)[2] + ud[2],
        ];
        t += 0.5 * body.mass * dot(vj, vj);
        if let Some(j0) = body.inertia {
            let mut oj = om;
            let mut jm = j0;
            for mr in &body.member {
                let a = mr.angle.value(&yt);
                for k in 0..3 {
                    oj[k] += mr.axis[k] * a.eps;
                }
                let rm = axis_angle(mr.axis, a.re);
                jm = mat_mul(&mat_mul(&rm, &m3(&jm)), &transpose(&rm));
            }
            t += 0.5 * dot(oj, mul(&jm, oj));
        }
    }
    t
}

#[test]
fn mass_matrix_is_spd_and_the_hessian_of_kinetic_energy() {
    let mut rng = Rng::new(1);
    for (name, model) in models() {
        let n = model.dof();
        let mut plant = GenericPlant::new(model.clone()).unwrap();
        for _ in 0..50 {
            let (x, _) = random_state(&model, &mut rng);
            let mut mm = vec![0.0; n * n];
            plant.mass_matrix(&x, &mut mm);
            for a in 0..n {
                for b in 0..n {
                    assert_eq!(mm[a * n + b], mm[b * n + a], "{name}: M not symmetric");
                }
            }
            // Cholesky: every pivot positive.
            let mut l = mm.clone();
            for j in 0..n {
                let mut d = l[j * n + j];
                for k in 0..j {
                    d -= l[j * n + k] * l[j * n + k];
                }
                assert!(d > 0.0, "{name}: M not positive definite (pivot {j} = {d})");
                let d = d.sqrt();
                l[j * n + j] = d;
                for i in j + 1..n {
                    let mut v = l[i * n + j];
                    for k in 0..j {
                        v -= l[i * n + k] * l[j * n + k];
                    }
                    l[i * n + j] = v / d;
                }
            }
            // Hessian of T by polarization (exact for a quadratic form).
            let y = &x[6..];
            let unit = |a: usize| {
                let mut e = vec![0.0; n];
                e[a] = 1.0;
                e
            };
            let scale = mm.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for a in 0..n {
                for b in a..n {
                    let h = if a == b {
                        2.0 * kinetic_energy(&model, y, &unit(a))
                    } else {
                        let mut e = unit(a);
                        e[b] = 1.0;
                        kinetic_energy(&model, y, &e)
                            - kinetic_energy(&model, y, &unit(a))
                            - kinetic_energy(&model, y, &unit(b))
                    };
                    assert!(
                        (h - mm[a * n + b]).abs() <= 1e-12 * scale,
                        "{name}: M[{a}][{b}] = {} but the Hessian of T gives {h}",
                        mm[a * n + b]
                    );
                }
            }
        }
    }
}

#[test]
fn mass_matrix_derivative_matches_finite_differences() {
    let mut rng = Rng::new(2);
    for (name, model) in models() {
        let n = model.dof();
        let mut ws = Workspace::<f64>::new(&model);
        let mut dm = vec![0.0; n * n];
        for _ in 0..10 {
            let (x, _) = random_state(&model, &mut rng);
            let y = x[6..].to_vec();
            body_kinematics(&model, &y, &mut ws);
            for i in 0..model.m() {
                mass_matrix_derivative(&model, &ws, i, &mut dm);
                let h = 1e-6;
                let at = |d: f64| {
                    let mut yy = y.clone();
                    yy[i] += d;
                    let mut w2 = Workspace::<f64>::new(&model);
                    body_kinematics(&model, &yy, &mut w2);
                    mass_matrix(&model, &mut w2);
                    w2.mass
                };
                let (p, m) = (at(h), at(-h));
                for k in 0..n * n {
                    let fd = (p[k] - m[k]) / (2.0 * h);
                    assert!(
                        (fd - dm[k]).abs() < 1e-7,
                        "{name}: ∂M/∂y{i}[{k}] = {} vs FD {fd}",
                        dm[k]
                    );
                }
                body_kinematics(&model, &y, &mut ws);
            }
        }
    }
}

/// The bias as computed (Newton–Euler: each body's acceleration at ẇ = 0
/// pulled back by its partial velocities) against the paper's eq. 25–28
/// built literally from p = M·w and ∂M/∂y_i.
#[test]
fn newton_euler_form_of_the_bias_equals_the_papers_form() {
    let mut rng = Rng::new(3);
    for (name, model) in models() {
        let n = model.dof();
        let mut ws = Workspace::<f64>::new(&model);
        let mut dm = vec![0.0; n * n];
        for _ in 0..20 {
            let (x, w) = random_state(&model, &mut rng);
            body_kinematics(&model, &x[6..], &mut ws);
            mass_matrix(&model, &mut ws);
            let mut fast = vec![0.0; n];
            rover_dynamics::bias::add_bias(&model, &mut ws, &w, &mut fast);
            // Explicit: −Σ_i ẏ_i·∂M/∂y_i·w − f1 + [0; ½·wᵀ·∂M/∂y_i·w]
            let mut slow = vec![0.0; n];
            let p: Vec<f64> = (0..n)
                .map(|a| (0..n).map(|b| ws.mass[a * n + b] * w[b]).sum())
                .collect();
            let cross = |a: [f64; 3], b: [f64; 3]| {
                [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ]
            };
            let (v, om) = ([w[0], w[1], w[2]], [w[3], w[4], w[5]]);
            let (pv, pw) = ([p[0], p[1], p[2]], [p[3], p[4], p[5]]);
            let f1v = cross(om, pv);
            let f1w = [
                cross(v, pv)[0] + cross(om, pw)[0],
                cross(v, pv)[1] + cross(om, pw)[1],
                cross(v, pv)[2] + cross(om, pw)[2],
            ];
            for k in 0..3 {
                slow[k] -= f1v[k];
                slow[3 + k] -= f1w[k];
            }
            for i in 0..model.m() {
                mass_matrix_derivative(&model, &ws, i, &mut dm);
                let dmw: Vec<f64> = (0..n)
                    .map(|a| (0..n).map(|b| dm[a * n + b] * w[b]).sum())
                    .collect();
                for a in 0..n {
                    slow[a] -= w[6 + i] * dmw[a];
                }
                slow[6 + i] += 0.5 * (0..n).map(|a| w[a] * dmw[a]).sum::<f64>();
            }
            for a in 0..n {
                assert!(
                    (fast[a] - slow[a]).abs() < 1e-12 * (1.0 + slow[a].abs()),
                    "{name}: row {a}: {} vs {}",
                    fast[a],
                    slow[a]
                );
            }
        }
    }
}

#[test]
fn accelerations_equal_lagranges_equations_in_ordinary_coordinates() {
    let mut rng = Rng::new(4);
    for (name, model) in models() {
        let n = model.dof();
        let mut plant = GenericPlant::new(model.clone()).unwrap();
        let neutral: Vec<f64> = model.coordinates.iter().map(|c| c.neutral).collect();
        for _ in 0..8 {
            let (x, w) = random_state(&model, &mut rng);
            let loads = random_loads(&model, &mut rng);
            let (mut xd, mut wd) = (vec![0.0; n], vec![0.0; n]);
            plant.derivatives(&x, &w, &loads, &mut xd, &mut wd).unwrap();
            let reference = lagrange::accelerations(&model, &x, &w, &loads, &neutral);
            for a in 0..n {
                assert!(
                    (wd[a] - reference[a]).abs() < 1e-9 * (1.0 + reference[a].abs()),
                    "{name}: ẇ[{a}] = {} but Lagrange gives {}",
                    wd[a],
                    reference[a]
                );
            }
        }
    }
}

#[test]
fn accelerations_do_not_depend_on_x_y_or_yaw() {
    let mut rng = Rng::new(5);
    for (name, model) in models() {
        let n = model.dof();
        let mut plant = GenericPlant::new(model.clone()).unwrap();
        let loads = vec![WheelLoad::default(); model.wheels.len()];
        for _ in 0..10 {
            let (mut x, w) = random_state(&model, &mut rng);
            let (mut xd, mut wd0, mut wd1) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            plant
                .derivatives(&x, &w, &loads, &mut xd, &mut wd0)
                .unwrap();
            x[0] += 100.0;
            x[1] -= 37.0;
            x[5] += 2.1;
            plant
                .derivatives(&x, &w, &loads, &mut xd, &mut wd1)
                .unwrap();
            for a in 0..n {
                assert!(
                    (wd0[a] - wd1[a]).abs() < 1e-12 * (1.0 + wd0[a].abs()),
                    "{name}: ẇ[{a}] changed with X, Y, ψ"
                );
            }
        }
    }
}

#[test]
fn generalized_forces_match_virtual_work_by_finite_differences() {
    // Q·w must equal the power of the loads, F·V_j + μ·ω_member + τ·ω_stator,
    // with V_j taken by finite differences of the wheel-centre positions.
    let mut rng = Rng::new(6);
    for (name, model) in models() {
        let n = model.dof();
        let mut ws = Workspace::<f64>::new(&model);
        for _ in 0..10 {
            let (x, w) = random_state(&model, &mut rng);
            let loads = random_loads(&model, &mut rng);
            body_kinematics(&model, &x[6..], &mut ws);
            let att = Attitude::new(x[3], x[4], x[5]);
            let gl: Vec<_> = loads
                .iter()
                .map(|l| rover_dynamics::forces::Load {
                    force: l.force,
                    moment: l.moment,
                    stator_torque: l.stator_torque,
                })
                .collect();
            let mut q = vec![0.0; n];
            rover_dynamics::forces::add_wheel_loads(&model, &ws, &att, &gl, &mut q);
            let power_q: f64 = (0..n).map(|a| q[a] * w[a]).sum();
            // Positions at x ± h·ẋ.
            let mut xd = vec![0.0; n];
            rover_dynamics::kinematics::position_rates(&x, &w, &mut xd);
            let centre = |s: f64, j: usize| {
                let xx: Vec<f64> = x.iter().zip(&xd).map(|(a, b)| a + s * b).collect();
                let mut w2 = Workspace::<f64>::new(&model);
                body_kinematics(&model, &xx[6..], &mut w2);
                let r = Attitude::new(xx[3], xx[4], xx[5]).rotation();
                let u = w2.u[j];
                [0, 1, 2].map(|k| xx[k] + r[k][0] * u[0] + r[k][1] * u[1] + r[k][2] * u[2])
            };
            let r = att.rotation();
            let to_world =
                |v: [f64; 3]| [0, 1, 2].map(|k| r[k][0] * v[0] + r[k][1] * v[1] + r[k][2] * v[2]);
            let h = 1e-6;
            let mut power = 0.0;
            for (wheel, l) in model.wheels.iter().zip(&loads) {
                let j = wheel.body;
                let (p, m) = (centre(h, j), centre(-h, j));
                let vel = [0, 1, 2].map(|k| (p[k] - m[k]) / (2.0 * h));
                let mut om_m = [w[3], w[4], w[5]];
                for i in 0..model.m() {
                    for k in 0..3 {
                        om_m[k] += ws.a[j * model.m() + i][k] * w[6 + i];
                    }
                }
                let om_m = to_world(om_m);
                let om_b = to_world([w[3], w[4], w[5]]);
                let dotp = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                power += dotp(l.force, vel) + dotp(l.moment, om_m);
                power += dotp(
                    l.stator_torque,
                    match wheel.motor {
                        rover_dynamics::model::MotorMount::Hub => om_m,
                        rover_dynamics::model::MotorMount::Body => om_b,
                    },
                );
            }
            assert!(
                (power - power_q).abs() < 1e-6 * (1.0 + power.abs()),
                "{name}: Q·w = {power_q} but the loads' power is {power}"
            );
        }
    }
}
