//! Every kind of the suspension library: the fitted polynomials match exact
//! kinematics written independently here, within the reported bound, at
//! seeded random points of the travel box; S_j (the polynomial's
//! derivative) matches central differences of the exact u_j.

use rover_spec::Spec;

const LIBRARY: &str = r#"name = "library"
gravity = 1.62

[body]
mass = 50.0
inertia = [2.0, 3.0, 4.0]

[wheel_defaults]
mass = 1.0
radius = 0.1
stiffness = 5000.0
damping = 100.0
mu_x = 0.5
mu_y = 0.5
cornering_stiffness = 50.0
max_torque = 2.0

[[suspension]]
name = "lsa"
kind = "longitudinal_swing_arm"
pivot = [0.4, 0.3, 0.0]
length = 0.25
coordinate = { rest_deg = 30.0, min_deg = -10.0, max_deg = 70.0, stiffness = 10.0 }
bodies = [{ name = "lsa_arm", mass = 0.4, member = "arm", position = [0.35, 0.3, -0.1] }]

[[suspension]]
name = "tsa"
kind = "transversal_swing_arm"
pivot = [0.0, 0.1, 0.0]
length = 0.3
camber_reference_deg = 5.0
coordinate = { rest_deg = 10.0, min_deg = -20.0, max_deg = 40.0 }
fit = { method = "taylor", terms = 7 }

[[suspension]]
name = "dw_left"
kind = "double_wishbone"
x = 1.0
lower_pivot = [0.45, -0.25]
lower_length = 0.36
upper_pivot = [0.45, -0.05]
upper_length = 0.32
upright_length = 0.22
wheel_offset = [0.075, 0.121]
coordinate = { min_deg = -20.0, max_deg = 20.0 }
bodies = [{ name = "dw_upright", mass = 2.0, member = "upright", position = [1.0, 0.8, -0.15] }]

[[suspension]]
name = "dw_right"
kind = "double_wishbone"
x = -1.0
lower_pivot = [-0.45, -0.25]
lower_length = 0.36
upper_pivot = [-0.45, -0.05]
upper_length = 0.32
upright_length = 0.22
wheel_offset = [0.075, 0.121]
coordinate = { rest_deg = 5.0, min_deg = -15.0, max_deg = 25.0 }
fit = { method = "taylor", terms = 9 }

[[suspension]]
name = "lr"
kind = "longitudinal_rocker"
pivot = [0.2, -0.3, 0.0]
arms = [{ name = "f", length = 0.25, angle_deg = -45.0 }, { name = "m", length = 0.3, angle_deg = 40.0 }]
coordinate = { min_deg = -30.0, max_deg = 30.0 }
fit = { method = "taylor", terms = 5 }

[[suspension]]
name = "tr"
kind = "transversal_rocker"
pivot = [-0.3, 0.0, -0.01]
arms = [{ name = "l", length = 0.267, angle_deg = 48.5 }, { name = "r", length = 0.267, angle_deg = -48.5 }]
coordinate = { rest_deg = 3.0, min_deg = -25.0, max_deg = 25.0 }

[[suspension]]
name = "rb"
kind = "rocker_bogie"
pivot = [0.15, 0.50, -0.05]
front_wheel = [0.70, 0.60, -0.32]
bogie_pivot = [-0.30, 0.55, -0.15]
middle_wheel = [0.00, 0.60, -0.32]
rear_wheel = [-0.65, 0.60, -0.32]
rocker = { rest_deg = 5.0, min_deg = -25.0, max_deg = 25.0 }
bogie_left = { rest_deg = -3.0, min_deg = -35.0, max_deg = 35.0 }
bogie_right = { rest_deg = 4.0, min_deg = -35.0, max_deg = 35.0 }
bodies = [{ name = "rb_bogie", mass = 3.0, member = "bogie_left", position = [-0.3, 0.58, -0.25] }]

[[suspension]]
name = "poly"
kind = "polynomial"
coordinates = [{ name = "s", linear = true, rest = 0.01, min = -0.05, max = 0.05 }]
[[suspension.points]]
name = "hub"
position = [-0.5, 0.0, -0.3]
terms = [{ coordinate = "s", coeffs = [[0.0, 0.0, 0.0], [0.1, 0.0, 1.0], [0.0, 0.0, -2.0]] }]
member = [{ coordinate = "s", axis = [0.0, 2.0, 0.0], angle = [0.0, 3.0] }]
camber = { terms = [{ coordinate = "s", coeffs = [0.0, 0.5] }] }
toe = { constant = 0.02, terms = [{ coordinate = "s", coeffs = [0.0, -0.4] }] }

[[wheel]]
name = "lsa"
suspension = "lsa"
[[wheel]]
name = "tsa"
suspension = "tsa"
[[wheel]]
name = "dw_left"
suspension = "dw_left"
[[wheel]]
name = "dw_right"
suspension = "dw_right"
[[wheel]]
name = "lr_f"
suspension = "lr"
point = "f"
[[wheel]]
name = "lr_m"
suspension = "lr"
point = "m"
[[wheel]]
name = "tr_l"
suspension = "tr"
point = "l"
[[wheel]]
name = "tr_r"
suspension = "tr"
point = "r"
[[wheel]]
name = "rb_fl"
suspension = "rb"
point = "front_left"
[[wheel]]
name = "rb_ml"
suspension = "rb"
point = "middle_left"
[[wheel]]
name = "rb_rl"
suspension = "rb"
point = "rear_left"
[[wheel]]
name = "rb_fr"
suspension = "rb"
point = "front_right"
[[wheel]]
name = "rb_mr"
suspension = "rb"
point = "middle_right"
[[wheel]]
name = "rb_rr"
suspension = "rb"
point = "rear_right"
[[wheel]]
name = "poly"
suspension = "poly"
"#;

type V = [f64; 3];

fn ry(a: f64, v: V) -> V {
    [
        a.cos() * v[0] + a.sin() * v[2],
        v[1],
        -a.sin() * v[0] + a.cos() * v[2],
    ]
}
fn rx(a: f64, v: V) -> V {
    [
        v[0],
        a.cos() * v[1] - a.sin() * v[2],
        a.sin() * v[1] + a.cos() * v[2],
    ]
}
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn norm(a: V) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
fn deg(d: f64) -> f64 {
    d.to_radians()
}

/// Double wishbone, solved by the law of cosines at the upper pivot:
/// the upper arm's angle is the angle of U→B plus (left) or minus (right)
/// the triangle angle at U. Returns (wheel centre, lower joint, upright angle).
fn wishbone(side: f64, x: f64, y: f64) -> (V, [f64; 2], f64) {
    let (l, ll, u, lu, h) = ([0.45 * side, -0.25], 0.36, [0.45 * side, -0.05], 0.32, 0.22);
    let b = [l[0] + side * ll * y.cos(), l[1] + side * ll * y.sin()];
    let d = ((b[0] - u[0]).powi(2) + (b[1] - u[1]).powi(2)).sqrt();
    let alpha = ((lu * lu + d * d - h * h) / (2.0 * lu * d)).acos();
    let psi = (b[1] - u[1]).atan2(b[0] - u[0]) + side * alpha;
    let c = [u[0] + lu * psi.cos(), u[1] + lu * psi.sin()];
    let e = [(c[0] - b[0]) / h, (c[1] - b[1]) / h];
    let n = [side * e[1], -side * e[0]];
    let w = [
        x,
        b[0] + 0.075 * e[0] + 0.121 * n[0],
        b[1] + 0.075 * e[1] + 0.121 * n[1],
    ];
    (w, b, e[1].atan2(e[0]))
}

/// Exact position, camber and toe of carried body `name` at y (all
/// coordinates, in the file's order: lsa, tsa, dw_left, dw_right, lr, tr,
/// rb rocker, rb bogie left, rb bogie right, s).
fn exact(name: &str, y: &[f64]) -> (V, f64, f64) {
    let mirror = |v: V| [v[0], -v[1], v[2]];
    let (a_rb, f, p, m, r) = (
        [0.15, 0.50, -0.05],
        [0.70, 0.60, -0.32],
        [-0.30, 0.55, -0.15],
        [0.00, 0.60, -0.32],
        [-0.65, 0.60, -0.32],
    );
    let yr = y[6] - deg(5.0);
    let on_bogie = |side: f64, q: V| {
        let (a, pp, qq) = if side > 0.0 {
            (a_rb, p, q)
        } else {
            (mirror(a_rb), mirror(p), mirror(q))
        };
        let angle = if side > 0.0 {
            y[7] + deg(3.0)
        } else {
            y[8] - deg(4.0)
        };
        add(add(a, ry(side * yr, sub(pp, a))), ry(angle, sub(qq, pp)))
    };
    match name {
        "lsa" => (add([0.4, 0.3, 0.0], ry(y[0], [0.0, 0.0, -0.25])), 0.0, 0.0),
        "lsa_arm" => {
            let a = [0.4, 0.3, 0.0];
            (
                add(a, ry(y[0] - deg(30.0), sub([0.35, 0.3, -0.1], a))),
                0.0,
                0.0,
            )
        }
        "tsa" => (
            add([0.0, 0.1, 0.0], rx(y[1], [0.0, 0.0, -0.3])),
            y[1] - deg(5.0),
            0.0,
        ),
        "dw_left" | "dw_upright" => {
            let (w, b, phi) = wishbone(1.0, 1.0, y[2]);
            let (_, b0, phi0) = wishbone(1.0, 1.0, 0.0);
            if name == "dw_left" {
                return (w, phi - phi0, 0.0);
            }
            let q = [0.8 - b0[0], -0.15 - b0[1]];
            let t = phi - phi0;
            let (c, s) = (t.cos(), t.sin());
            (
                [1.0, b[0] + c * q[0] - s * q[1], b[1] + s * q[0] + c * q[1]],
                t,
                0.0,
            )
        }
        "dw_right" => {
            let (w, _, phi) = wishbone(-1.0, -1.0, y[3]);
            let (_, _, phi0) = wishbone(-1.0, -1.0, deg(5.0));
            (w, phi - phi0, 0.0)
        }
        "lr_f" => (
            add([0.2, -0.3, 0.0], ry(y[4] + deg(-45.0), [0.0, 0.0, -0.25])),
            0.0,
            0.0,
        ),
        "lr_m" => (
            add([0.2, -0.3, 0.0], ry(y[4] + deg(40.0), [0.0, 0.0, -0.3])),
            0.0,
            0.0,
        ),
        "tr_l" => (
            add([-0.3, 0.0, -0.01], rx(y[5] + deg(48.5), [0.0, 0.0, -0.267])),
            y[5],
            0.0,
        ),
        "tr_r" => (
            add(
                [-0.3, 0.0, -0.01],
                rx(y[5] + deg(-48.5), [0.0, 0.0, -0.267]),
            ),
            y[5],
            0.0,
        ),
        "rb_fl" => (add(a_rb, ry(yr, sub(f, a_rb))), 0.0, 0.0),
        "rb_fr" => (
            add(mirror(a_rb), ry(-yr, sub(mirror(f), mirror(a_rb)))),
            0.0,
            0.0,
        ),
        "rb_ml" => (on_bogie(1.0, m), 0.0, 0.0),
        "rb_rl" => (on_bogie(1.0, r), 0.0, 0.0),
        "rb_mr" => (on_bogie(-1.0, m), 0.0, 0.0),
        "rb_rr" => (on_bogie(-1.0, r), 0.0, 0.0),
        "rb_bogie" => (on_bogie(1.0, [-0.3, 0.58, -0.25]), 0.0, 0.0),
        "poly" => {
            let s = y[9] - 0.01;
            (
                [-0.5 + 0.1 * s, 0.0, -0.3 + s - 2.0 * s * s],
                0.5 * s,
                0.02 - 0.4 * s,
            )
        }
        other => panic!("no exact kinematics for {other}"),
    }
}

/// splitmix64: a seeded, dependency-free generator.
struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn spec() -> Spec {
    rover_spec::load_str(LIBRARY, "library.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn random_state(spec: &Spec, rng: &mut Rng) -> Vec<f64> {
    spec.model
        .coordinates
        .iter()
        .map(|c| c.min + (c.max - c.min) * rng.unit())
        .collect()
}

#[test]
fn rest_geometry_is_exact() {
    let spec = spec();
    let rest = spec.model.rest();
    for (j, b) in spec.model.bodies.iter().enumerate() {
        let (u, camber, toe) = exact(&spec.body_names[j], &rest);
        let p = b.position.value(&rest);
        assert!(
            norm(sub(p, u)) < 1e-12,
            "{}: {p:?} vs {u:?}",
            spec.body_names[j]
        );
        if let Some(w) = spec.model.wheels.iter().find(|w| w.body == j) {
            assert!(
                (w.camber.value(&rest) - camber).abs() < 1e-12,
                "{}",
                spec.body_names[j]
            );
            assert!((w.toe.value(&rest) - toe).abs() < 1e-12);
        }
        for r in &b.member {
            assert_eq!(r.angle.value(&rest), 0.0, "member angles vanish at rest");
        }
    }
    // Wheel centres at rest, as reported.
    for (k, w) in spec.model.wheels.iter().enumerate() {
        assert_eq!(
            spec.rest_wheel_centres[k],
            spec.model.bodies[w.body].position.value(&rest)
        );
    }
}

#[test]
fn positions_and_angles_within_reported_bound() {
    let spec = spec();
    let mut rng = Rng(20120288);
    let mut worst = 0.0f64;
    for _ in 0..300 {
        let y = random_state(&spec, &mut rng);
        for (j, b) in spec.model.bodies.iter().enumerate() {
            let name = &spec.body_names[j];
            let fit = &spec.fits[j];
            let (u, camber, toe) = exact(name, &y);
            let err = norm(sub(b.position.value(&y), u));
            assert!(
                err <= fit.max_position_error + 1e-12,
                "{name}: {err} > {}",
                fit.max_position_error
            );
            worst = worst.max(err / fit.max_position_error.max(1e-300));
            if let Some(w) = spec.model.wheels.iter().find(|w| w.body == j) {
                let e = (w.camber.value(&y) - camber).abs();
                assert!(
                    e <= fit.max_angle_error + 1e-12,
                    "{name} camber: {e} > {}",
                    fit.max_angle_error
                );
                assert!((w.toe.value(&y) - toe).abs() <= fit.max_angle_error + 1e-12);
            }
        }
    }
    // The bound is not loose by orders of magnitude somewhere.
    assert!(worst > 0.05, "{worst}");
}

#[test]
fn member_rotations_match_the_kinematics() {
    let spec = spec();
    let rest = spec.model.rest();
    let names = &spec.body_names;
    let find = |n: &str| names.iter().position(|x| x == n).unwrap();
    // Arms, rockers, bogies: a unit rate about their axis.
    for (n, axis, coord, sign) in [
        ("lsa", 1, 0, 1.0),
        ("tsa", 0, 1, 1.0),
        ("lr_f", 1, 4, 1.0),
        ("tr_l", 0, 5, 1.0),
        ("rb_fl", 1, 6, 1.0),
        ("rb_fr", 1, 6, -1.0),
        ("rb_ml", 1, 7, 1.0),
        ("rb_mr", 1, 8, 1.0),
    ] {
        let member = &spec.model.bodies[find(n)].member;
        assert_eq!(member.len(), 1, "{n}");
        let r = &member[0];
        assert_eq!(r.coord, coord, "{n}");
        assert_eq!(r.axis[axis], 1.0, "{n}");
        let mut y = rest.clone();
        y[coord] += 0.2;
        assert!(
            (r.angle.value(&y) - sign * 0.2).abs() < 1e-9,
            "{n}: {}",
            r.angle.value(&y)
        );
    }
    // The bogie moves with the rocker but turns only with its own angle.
    let bogie = &spec.model.bodies[find("rb_ml")];
    let coords: Vec<usize> = bogie.position.terms.iter().map(|t| t.coord).collect();
    assert_eq!(coords, [6, 7]);
    // The wishbone upright turns by its camber change; the polynomial
    // suspension keeps its (normalised) axis.
    let up = &spec.model.bodies[find("dw_left")].member[0];
    assert_eq!(up.axis, [1.0, 0.0, 0.0]);
    let poly = &spec.model.bodies[find("poly")].member[0];
    assert_eq!(poly.axis, [0.0, 1.0, 0.0]);
}

#[test]
fn s_j_matches_finite_differences_of_the_exact_u_j() {
    let spec = spec();
    let mut rng = Rng(7);
    let h = 1e-6;
    for _ in 0..100 {
        let y = random_state(&spec, &mut rng);
        for (j, b) in spec.model.bodies.iter().enumerate() {
            let name = &spec.body_names[j];
            let mut slopes = Vec::new();
            b.position.eval(&y, |coord, d1, _| slopes.push((coord, d1)));
            for (coord, d1) in slopes {
                let (mut yp, mut ym) = (y.clone(), y.clone());
                yp[coord] += h;
                ym[coord] -= h;
                let fd: Vec<f64> = (0..3)
                    .map(|k| (exact(name, &yp).0[k] - exact(name, &ym).0[k]) / (2.0 * h))
                    .collect();
                // Markov's inequality for a degree-k error of size E on a
                // half-range r: |e'| ≤ k²·E/r; plus the difference's own error.
                let c = &spec.model.coordinates[coord];
                let r = (c.rest - c.min).max(c.max - c.rest);
                let share = spec.fits[j]
                    .shares
                    .iter()
                    .find(|s| s.coord == coord)
                    .map_or(0.0, |s| s.position);
                let k = b
                    .position
                    .terms
                    .iter()
                    .find(|t| t.coord == coord)
                    .unwrap()
                    .coeffs
                    .len() as f64;
                let bound = k * k * share / r + 1e-7;
                let err = norm(sub(d1, [fd[0], fd[1], fd[2]]));
                assert!(
                    err <= bound,
                    "{name}, y{}: |S − FD| = {err} > {bound}",
                    coord + 1
                );
            }
        }
    }
}

#[test]
fn taylor_fits_have_exact_slopes_at_rest() {
    // A Taylor fit matches the derivatives at the rest value exactly: the
    // transversal arm (k = 7) and the right wishbone (k = 9, through the
    // four-bar's sqrt and atan2 on truncated series).
    let spec = spec();
    let rest = spec.model.rest();
    for (name, coord) in [("tsa", 1), ("dw_right", 3), ("lr_f", 4)] {
        let j = spec.body_names.iter().position(|n| n == name).unwrap();
        let mut s = [0.0; 3];
        spec.model.bodies[j].position.eval(&rest, |_, d1, _| s = d1);
        let h = 1e-5;
        let (mut yp, mut ym) = (rest.clone(), rest.clone());
        yp[coord] += h;
        ym[coord] -= h;
        for (k, sk) in s.iter().enumerate() {
            let fd = (exact(name, &yp).0[k] - exact(name, &ym).0[k]) / (2.0 * h);
            assert!((sk - fd).abs() < 1e-9, "{name}[{k}]: {sk} vs {fd}");
        }
    }
}

#[test]
fn raw_polynomials_are_taken_as_given() {
    let spec = spec();
    let j = spec.body_names.iter().position(|n| n == "poly").unwrap();
    assert_eq!(spec.fits[j].max_position_error, 0.0);
    let t = &spec.model.bodies[j].position.terms[0];
    assert_eq!((t.coord, t.center), (9, 0.01));
    assert_eq!(t.coeffs, vec![[0.0; 3], [0.1, 0.0, 1.0], [0.0, 0.0, -2.0]]);
    assert!(spec.coordinate_linear[9]);
}
