//! What `rover check` prints: the validated rover, its fitted polynomials
//! with their errors, masses and rest geometry.

use std::fmt::Write;

use rover_dynamics::model::{MotorMount, Spring};

use crate::checks::{coord_value, num};
use crate::linkage::FitMethod;
use crate::spec::Spec;

/// The report of a validated rover (deterministic text, SI units, angles
/// also in degrees).
pub fn check_report(spec: &Spec) -> String {
    let mut out = String::new();
    let m = &spec.model;
    let _ = writeln!(
        out,
        "rover `{}`: {} DOF (6 + {} suspension coordinates), {} carried bodies, {} wheels",
        spec.name,
        m.dof(),
        m.m(),
        m.bodies.len(),
        m.wheels.len()
    );
    let _ = writeln!(
        out,
        "total mass {} kg, g = {} m/s²",
        num(m.total_mass()),
        num(m.gravity)
    );
    let j = m.body.inertia;
    let _ = writeln!(
        out,
        "\nbody: mass {} kg, inertia about G [kg·m²]:",
        num(m.body.mass)
    );
    for row in j {
        let _ = writeln!(
            out,
            "  [{:>10}, {:>10}, {:>10}]",
            num(row[0]),
            num(row[1]),
            num(row[2])
        );
    }

    let _ = writeln!(out, "\ncoordinates:");
    for (i, c) in m.coordinates.iter().enumerate() {
        let lin = spec.coordinate_linear[i];
        let (ku, cu) = if lin {
            ("N/m", "N·s/m")
        } else {
            ("N·m/rad", "N·m·s/rad")
        };
        let susp = spec.suspensions.iter().find(|s| s.coordinates.contains(&i));
        let spring = match &c.spring {
            Spring::None => "none".to_string(),
            Spring::Linear { stiffness } => format!("{} {ku}", num(*stiffness)),
            Spring::Table { deflection, .. } => format!("table of {} points", deflection.len()),
        };
        let _ = writeln!(
            out,
            "  y{} `{}` ({}): rest {}, neutral {}, travel [{}, {}]",
            i + 1,
            spec.coordinate_names[i],
            susp.map_or(String::new(), |s| format!("{} `{}`", s.kind, s.name)),
            coord_value(c.rest, lin),
            coord_value(c.neutral, lin),
            coord_value(c.min, lin),
            coord_value(c.max, lin)
        );
        let _ = writeln!(
            out,
            "      spring {spring}, damper {} {cu}, bump stops {} {ku}, {} {cu}",
            num(c.damping),
            num(c.stop_stiffness),
            num(c.stop_damping)
        );
    }

    let rest = m.rest();
    let _ = writeln!(out, "\ncarried bodies (rest position in body axes [m]):");
    for (j, b) in m.bodies.iter().enumerate() {
        let p = b.position.value(&rest);
        let f = &spec.fits[j];
        let kind = if j < m.wheels.len() { "wheel" } else { "body" };
        let _ = writeln!(
            out,
            "  {} `{}` ({kind} on `{}`.{}): mass {} kg, at ({}, {}, {}){}",
            j + 1,
            spec.body_names[j],
            spec.suspensions[f.suspension].name,
            f.at,
            num(b.mass),
            num(p[0]),
            num(p[1]),
            num(p[2]),
            if b.inertia.is_some() {
                ", with inertia"
            } else {
                ""
            }
        );
    }

    let _ = writeln!(out, "\nwheels:");
    for (k, w) in m.wheels.iter().enumerate() {
        let _ = writeln!(
            out,
            "  {} `{}`: R_w {} m, k_w {} N/m, c_w {} N·s/m, μx {}, μy {}, C {} N/rad, M_sat {} N·m{}, motor on {}, {}",
            k + 1,
            spec.wheel_names[k],
            num(w.radius),
            num(w.stiffness),
            num(w.damping),
            num(w.mu_x),
            num(w.mu_y),
            num(w.cornering_stiffness),
            num(w.max_torque),
            match &w.motor_curve {
                Some(c) => format!(
                    " (DC line: stall {} N·m, no load at {} rad/s)",
                    num(c.stall_torque),
                    num(c.no_load_speed)
                ),
                None => String::new(),
            },
            match w.motor {
                MotorMount::Hub => "the hub",
                MotorMount::Body => "the body",
            },
            if w.steerable {
                "steerable"
            } else {
                "not steered"
            }
        );
    }

    let _ = writeln!(
        out,
        "\nfitted polynomials u_j = c_j + Σ_i Z_ij·[1, ξ, ξ², …]ᵀ, ξ = y_i − y_ic:"
    );
    for (j, b) in m.bodies.iter().enumerate() {
        let f = &spec.fits[j];
        let s = &spec.suspensions[f.suspension];
        let method = match s.fit {
            Some(o) => format!(
                "{}, k = {}",
                match o.method {
                    FitMethod::Taylor => "Taylor",
                    FitMethod::LeastSquares => "least squares",
                },
                o.terms
            ),
            None => "given".to_string(),
        };
        let _ = writeln!(
            out,
            "  {} `{}` ({method}): c = ({}, {}, {}) m, max error {} m, {} rad",
            j + 1,
            spec.body_names[j],
            num(b.position.constant[0]),
            num(b.position.constant[1]),
            num(b.position.constant[2]),
            num(f.max_position_error),
            num(f.max_angle_error)
        );
        for t in &b.position.terms {
            let lin = spec.coordinate_linear[t.coord];
            let share = f.shares.iter().find(|e| e.coord == t.coord);
            let _ = write!(
                out,
                "    Z for y{} `{}`, centre {}",
                t.coord + 1,
                spec.coordinate_names[t.coord],
                coord_value(t.center, lin)
            );
            if let Some(e) = share {
                let _ = write!(
                    out,
                    ": error {} m at {}, {} rad at {}",
                    num(e.position),
                    coord_value(e.position_at, lin),
                    num(e.angle),
                    coord_value(e.angle_at, lin)
                );
            }
            let _ = writeln!(out);
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                let row: Vec<String> = t.coeffs.iter().map(|c| coefficient(c[k])).collect();
                let _ = writeln!(out, "      {axis}: [{}]", row.join(", "));
            }
        }
        for r in &b.member {
            let coeffs: Vec<String> = r
                .angle
                .terms
                .iter()
                .flat_map(|t| t.coeffs.iter())
                .map(|c| coefficient(*c))
                .collect();
            let _ = writeln!(
                out,
                "    member turns about ({}, {}, {}) with y{}: angle [{}]",
                num(r.axis[0]),
                num(r.axis[1]),
                num(r.axis[2]),
                r.coord + 1,
                coeffs.join(", ")
            );
        }
    }

    let _ = writeln!(out, "\nrest geometry: wheel centres in body axes [m]");
    for (k, p) in spec.rest_wheel_centres.iter().enumerate() {
        let w = &m.wheels[k];
        let _ = writeln!(
            out,
            "  {:<14} x {:>9}  y {:>9}  z {:>9}   camber {}°, toe {}°",
            spec.wheel_names[k],
            num(p[0]),
            num(p[1]),
            num(p[2]),
            num(w.camber.value(&rest).to_degrees()),
            num(w.toe.value(&rest).to_degrees())
        );
    }
    out
}

/// A polynomial coefficient, signed, 7 significant digits (−0 shown as +0).
fn coefficient(c: f64) -> String {
    format!("{:+.6e}", c + 0.0)
}
