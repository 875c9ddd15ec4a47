//! Wheels: their fields (from the wheel or `[wheel_defaults]`) and ranges.

use rover_dynamics::model::{MotorCurve, MotorMount, Wheel};
use rover_dynamics::poly::ScalarPoly;

use super::body::check_inertia;
use crate::checks::Ctx;
use crate::description::{MotorMountDesc, WheelDesc, WheelFields};

/// A checked wheel, before it is tied to its suspension point.
pub struct CheckedWheel {
    /// Mass \[kg\].
    pub mass: f64,
    /// Inertia, if given, with the path it came from.
    pub inertia: Option<([[f64; 3]; 3], String)>,
    /// The model's wheel (body index, camber and toe filled in later).
    pub wheel: Wheel,
}

/// Take a field from the wheel, else from the defaults; its path.
fn pick<T: Copy>(
    index: usize,
    field: &str,
    own: Option<T>,
    default: Option<T>,
) -> Option<(T, String)> {
    match (own, default) {
        (Some(v), _) => Some((v, format!("wheel[{index}].{field}"))),
        (None, Some(v)) => Some((v, format!("wheel_defaults.{field}"))),
        (None, None) => None,
    }
}

/// Check wheel number `index`.
pub fn check_wheel(
    ctx: &mut Ctx,
    index: usize,
    w: &WheelDesc,
    d: &WheelFields,
) -> Option<CheckedWheel> {
    let mut missing = Vec::new();
    let mut num = |field: &'static str,
                   own: Option<f64>,
                   def: Option<f64>,
                   positive: bool,
                   help: &str|
     -> Option<f64> {
        let Some((v, path)) = pick(index, field, own, def) else {
            missing.push(field);
            return None;
        };
        if positive {
            ctx.positive(&path, v, help)
        } else {
            ctx.non_negative(&path, v, help)
        }
    };
    let mass = num(
        "mass",
        w.mass,
        d.mass,
        false,
        "the wheel mass is in kg (0 for a massless wheel)",
    );
    let radius = num(
        "radius",
        w.radius,
        d.radius,
        true,
        "the radius is in metres and positive",
    );
    let stiffness = num(
        "stiffness",
        w.stiffness,
        d.stiffness,
        true,
        "the radial tyre stiffness k_w is in N/m and positive",
    );
    let damping = num(
        "damping",
        w.damping,
        d.damping,
        false,
        "the radial tyre damping c_w is in N·s/m, ≥ 0",
    );
    let mu_x = num(
        "mu_x",
        w.mu_x,
        d.mu_x,
        true,
        "μx_max is a friction coefficient, > 0",
    );
    let mu_y = num(
        "mu_y",
        w.mu_y,
        d.mu_y,
        true,
        "μy_max is a friction coefficient, > 0",
    );
    let cornering = num(
        "cornering_stiffness",
        w.cornering_stiffness,
        d.cornering_stiffness,
        true,
        "the cornering stiffness C is in N/rad and positive",
    );
    let max_torque = num(
        "max_torque",
        w.max_torque,
        d.max_torque,
        false,
        "the maximum motor torque is in N·m, ≥ 0",
    );
    if !missing.is_empty() {
        let list: Vec<String> = missing.iter().map(|f| format!("`{f}`")).collect();
        ctx.error(
            format!("wheel[{index}]"),
            format!(
                "wheel `{}` has no {} (and `[wheel_defaults]` gives none)",
                w.name,
                list.join(", ")
            ),
            format!(
                "add {} to this wheel or to `[wheel_defaults]`",
                list.join(", ")
            ),
        );
        return None;
    }
    let inertia = match pick(index, "inertia", w.inertia, d.inertia) {
        Some((i, path)) => Some((check_inertia(ctx, &path, &i)?, path)),
        None => None,
    };
    // Optional, positive when given.
    let mut optional = |field: &str, own: Option<f64>, def: Option<f64>, help: &str| match pick(
        index, field, own, def,
    ) {
        Some((v, path)) => ctx.positive(&path, v, help).map(Some),
        None => Some(None),
    };
    let width = optional(
        "width",
        w.width,
        d.width,
        "the wheel's width is in metres and positive (what the soil law presses on)",
    )?;
    let spin_inertia = optional(
        "spin_inertia",
        w.spin_inertia,
        d.spin_inertia,
        "the moment of inertia about the axle is in kg·m² and positive (leave it out for ½·mass·radius²)",
    )?;
    let no_load_speed = optional(
        "no_load_speed",
        w.no_load_speed,
        d.no_load_speed,
        "the motor's no-load speed is the wheel's spin rate at zero torque, in rad/s and positive (leave it out for a motor without a speed limit)",
    )?;
    let stall_torque = optional(
        "stall_torque",
        w.stall_torque,
        d.stall_torque,
        "the motor's stall torque is in N·m and positive (leave it out to take max_torque)",
    )?;
    let motor_curve = match (no_load_speed, stall_torque) {
        (Some(no_load_speed), stall) => match (stall, max_torque) {
            (Some(stall_torque), _) => Some(MotorCurve {
                stall_torque,
                no_load_speed,
            }),
            (None, Some(m)) if m > 0.0 => Some(MotorCurve {
                stall_torque: m,
                no_load_speed,
            }),
            // max_torque 0: no torque at any speed, the line is moot.
            (None, _) => None,
        },
        (None, Some(_)) => {
            let path = pick(index, "stall_torque", w.stall_torque, d.stall_torque)
                .map_or_else(|| format!("wheel[{index}].stall_torque"), |p| p.1);
            ctx.error(
                path,
                format!(
                    "wheel `{}` has a motor stall torque but no `no_load_speed`: the torque–speed line needs both",
                    w.name
                ),
                "add `no_load_speed` [rad/s] (the wheel's spin rate at which the motor gives no torque), or remove `stall_torque`",
            );
            return None;
        }
        (None, None) => None,
    };
    let motor = match pick(index, "motor", w.motor, d.motor).map(|p| p.0) {
        Some(MotorMountDesc::Hub) => MotorMount::Hub,
        Some(MotorMountDesc::Body) | None => MotorMount::Body,
    };
    let steerable = pick(index, "steerable", w.steerable, d.steerable).is_some_and(|p| p.0);
    let (mass, radius) = (mass?, radius?);
    Some(CheckedWheel {
        mass,
        inertia,
        wheel: Wheel {
            body: 0,
            radius,
            width,
            spin_inertia: spin_inertia.unwrap_or(0.5 * mass * radius * radius),
            stiffness: stiffness?,
            damping: damping?,
            mu_x: mu_x?,
            mu_y: mu_y?,
            cornering_stiffness: cornering?,
            max_torque: max_torque?,
            motor_curve,
            motor,
            steerable,
            camber: ScalarPoly::constant(0.0),
            toe: ScalarPoly::constant(0.0),
        },
    })
}
