//! Checks of the assembled model that a run, a linearization and the code
//! generator all rely on: each names the field to change.
//!
//! Limits (docs/DESCRIPTION.md, "Limits"): at most [`MAX_DOF`] degrees of
//! freedom, at least one wheel, every number within ±[`MAX_MAGNITUDE`],
//! gravity up to [`MAX_GRAVITY`], a body mass of at least [`MIN_BODY_MASS`],
//! tyres that carry the rover's weight, wheels at distinct places and a mass
//! matrix that is positive definite at rest.

use rover_dynamics::Model;
use rover_dynamics::mass::mass_matrix;
use rover_dynamics::workspace::Workspace;

use crate::checks::{Ctx, num};

/// Most degrees of freedom (6 + suspension coordinates) a rover may have:
/// the dense buffers of the plant and of the generated code hold this many.
pub const MAX_DOF: usize = rover_dynamics::mass::MAX_DOF;
/// Largest magnitude of any number of a description, in SI units.
pub const MAX_MAGNITUDE: f64 = 1e12;
/// Largest gravity \[m/s²\] (ten times Jupiter's).
pub const MAX_GRAVITY: f64 = 250.0;
/// Smallest body mass \[kg\].
pub const MIN_BODY_MASS: f64 = 1e-3;

/// Numbers too large to be a rover quantity in SI units.
pub fn magnitudes(ctx: &mut Ctx, value: &toml::Value, path: &str) {
    crate::checks::each_leaf(value, path, &mut |v, path| {
        let too_large = match v {
            toml::Value::Float(f) if f.is_finite() && f.abs() > MAX_MAGNITUDE => Some(num(*f)),
            toml::Value::Integer(i) if (*i as f64).abs() > MAX_MAGNITUDE => Some(i.to_string()),
            _ => None,
        };
        if let Some(value) = too_large {
            ctx.error(
                path,
                format!(
                    "{value} is too large: no rover quantity in SI units exceeds ±{}",
                    num(MAX_MAGNITUDE)
                ),
                "give the value in SI units (kg, m, N/m, kg·m²)",
            );
        }
    });
}

/// Checks of single fields that need no model: the name, gravity, the
/// body mass, the number of wheels.
pub fn fields(ctx: &mut Ctx, desc: &crate::description::Description) {
    if desc.name.trim().is_empty() {
        ctx.error(
            "name",
            "the rover's name is empty",
            "name the rover, e.g. name = \"my_rover\": it heads reports, plots and generated code",
        );
    }
    if desc.gravity.is_finite() && desc.gravity > MAX_GRAVITY {
        ctx.error(
            "gravity",
            format!(
                "gravity {} m/s² is beyond any planet (at most {})",
                num(desc.gravity),
                num(MAX_GRAVITY)
            ),
            "g is in m/s²: Moon 1.62, Mars 3.71, Earth 9.81",
        );
    }
    if desc.body.mass.is_finite() && desc.body.mass > 0.0 && desc.body.mass < MIN_BODY_MASS {
        ctx.error(
            "body.mass",
            format!(
                "body mass {} kg is below {} kg",
                num(desc.body.mass),
                num(MIN_BODY_MASS)
            ),
            "the body mass is in kg",
        );
    }
    if desc.wheels.is_empty() {
        ctx.error(
            "",
            "the rover has no wheel: it cannot stand on the ground nor be driven",
            "add at least one `[[wheel]]` table, each on a `[[suspension]]`",
        );
    }
}

/// Checks of the assembled model. `coordinate_paths[i]`: the field path of
/// coordinate i; `suspension_of[i]`: the path of its suspension;
/// `radius_paths[j]`: the path of wheel j's radius.
pub fn model(
    ctx: &mut Ctx,
    model: &Model,
    coordinate_paths: &[String],
    suspension_of: &[String],
    rest_wheel_centres: &[[f64; 3]],
    radius_paths: &[String],
) {
    let m = model.m();
    if model.dof() > MAX_DOF {
        let path = suspension_of
            .get(MAX_DOF - 6)
            .cloned()
            .unwrap_or_else(|| "suspension".into());
        ctx.error(
            path,
            format!(
                "the rover has {m} suspension coordinates ({} degrees of freedom); at most {} are supported ({MAX_DOF} degrees of freedom)",
                model.dof(),
                MAX_DOF - 6
            ),
            "remove suspensions or wheels, or lock coordinates that do not matter",
        );
        return;
    }
    // Wheels at the same place: one of them is a copy.
    let radius = model
        .wheels
        .iter()
        .map(|w| w.radius)
        .fold(f64::INFINITY, f64::min);
    for (j, a) in rest_wheel_centres.iter().enumerate() {
        for (k, b) in rest_wheel_centres.iter().enumerate().take(j) {
            let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            if d < 1e-3 * radius {
                ctx.error(
                    format!("wheel[{j}]"),
                    format!(
                        "wheel {} sits at the same place as wheel {} at rest ({} m apart)",
                        j + 1,
                        k + 1,
                        num(d)
                    ),
                    "give each wheel its own suspension point",
                );
            }
        }
    }
    wheel_sizes(ctx, model, rest_wheel_centres, radius_paths);
    // A wheel as wide as the track would overlap its neighbour across.
    let (lo, hi) = rest_wheel_centres
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c[1]), hi.max(c[1]))
        });
    let track = hi - lo;
    for (j, w) in model.wheels.iter().enumerate() {
        if let Some(b) = w.width
            && track > 0.0
            && b >= track
        {
            ctx.error(
                format!("wheel[{j}].width"),
                format!(
                    "wheel {} is {} m wide, as wide as the rover's track ({} m between its outermost wheel centres)",
                    j + 1,
                    num(b),
                    num(track)
                ),
                "give the tyre's width in metres (a rover's wheels are a fraction of its track)",
            );
        }
    }
    // The tyres must carry the rover: static deflection below the radius.
    let total_mass = model.body.mass + model.bodies.iter().map(|b| b.mass).sum::<f64>();
    let k_sum: f64 = model.wheels.iter().map(|w| w.stiffness).sum();
    if !model.wheels.is_empty() && k_sum > 0.0 {
        let deflection = total_mass * model.gravity / k_sum;
        let mean_radius =
            model.wheels.iter().map(|w| w.radius).sum::<f64>() / model.wheels.len() as f64;
        if deflection.is_nan() || deflection >= 0.5 * mean_radius {
            ctx.error(
                "body.mass",
                format!(
                    "the tyres cannot carry the rover: {} kg at g = {} m/s² on a total tyre stiffness of {} N/m deflects them {} m, more than half their radius ({} m)",
                    num(total_mass),
                    num(model.gravity),
                    num(k_sum),
                    num(deflection),
                    num(mean_radius)
                ),
                "check the masses (kg) and the wheels' `stiffness` k_w (N/m)",
            );
        }
    }
    // The mass matrix at rest: positive definite, or a coordinate moves no mass.
    if model.wheels.is_empty() {
        return;
    }
    let mut ws = Workspace::<f64>::new(model);
    let rest = model.rest();
    rover_dynamics::kinematics::body_kinematics(model, &rest, &mut ws);
    mass_matrix(model, &mut ws);
    let n = model.dof();
    let mut a = ws.mass.clone();
    let scale = (0..n).map(|i| a[i * n + i].abs()).fold(0.0, f64::max);
    for k in 0..n {
        let pivot = a[k * n + k];
        if pivot.is_nan() || pivot <= 1e-12 * scale {
            let (path, what) = match k.checked_sub(6) {
                Some(i) => (
                    coordinate_paths.get(i).cloned().unwrap_or_default(),
                    format!(
                        "suspension coordinate {} moves no mass independently of the others",
                        i + 1
                    ),
                ),
                None => (
                    "body".to_string(),
                    "the body's mass and inertia leave a direction without inertia".to_string(),
                ),
            };
            ctx.error(
                path,
                format!("{what}: the mass matrix is singular at rest (pivot {k} = {})", num(pivot)),
                "put a wheel or a carried body with mass on the member this coordinate moves, or remove the coordinate",
            );
            return;
        }
        for i in k + 1..n {
            let f = a[i * n + k] / pivot;
            for j in k..n {
                a[i * n + j] -= f * a[k * n + j];
            }
        }
    }
}

/// Wheels that fit the rover: no two tyres overlap at rest (seen from the
/// side, two wheels whose tyres overlap across are closer than the sum of
/// their radii), and no wheel's radius exceeds the rover's size, the
/// largest distance between two wheel centres at rest. A tyre without a
/// `width` counts as a thin disc.
fn wheel_sizes(ctx: &mut Ctx, model: &Model, centres: &[[f64; 3]], radius_paths: &[String]) {
    let path = |j: usize| {
        radius_paths
            .get(j)
            .cloned()
            .unwrap_or_else(|| format!("wheel[{j}]"))
    };
    let mut span: f64 = 0.0;
    for (j, a) in centres.iter().enumerate() {
        for (k, b) in centres.iter().enumerate().take(j) {
            let (wa, wb) = (&model.wheels[j], &model.wheels[k]);
            let across = (a[1] - b[1]).abs();
            let side = ((a[0] - b[0]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            span = span.max((side * side + across * across).sqrt());
            let half_widths = 0.5 * (wa.width.unwrap_or(0.0) + wb.width.unwrap_or(0.0));
            let same_place = side.hypot(across) < 1e-3 * wa.radius.min(wb.radius);
            if across <= half_widths && side < wa.radius + wb.radius && !same_place {
                ctx.error(
                    path(j),
                    format!(
                        "wheels {} and {} overlap at rest: seen from the side their centres are {} m apart, less than the sum of their radii ({} m + {} m), and their tyres overlap across ({} m apart in y)",
                        k + 1,
                        j + 1,
                        num(side),
                        num(wb.radius),
                        num(wa.radius),
                        num(across)
                    ),
                    "two tyres cannot share space: the radius is in metres; make the wheels smaller or place them farther apart (the suspension's pivots and lengths)",
                );
            }
        }
    }
    if centres.len() < 2 || !span.is_finite() {
        return;
    }
    for (j, w) in model.wheels.iter().enumerate() {
        if w.radius > span {
            ctx.error(
                path(j),
                format!(
                    "wheel {} has a radius of {} m, more than the rover's size ({} m between its wheel centres farthest apart)",
                    j + 1,
                    num(w.radius),
                    num(span)
                ),
                "the radius is in metres (not a diameter in cm, say): a wheel is smaller than the rover it carries",
            );
        }
    }
}
