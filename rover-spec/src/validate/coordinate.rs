//! A suspension coordinate: rest, travel, spring, damper, bump stops.

use rover_dynamics::model::Spring;

use crate::checks::{Ctx, coord_value, num};
use crate::description::CoordinateDesc;
use crate::linkage::CoordRange;

/// A checked coordinate, before the bump-stop defaults (they need the
/// carried masses).
#[derive(Clone, Debug)]
pub struct CheckedCoord {
    /// Name.
    pub name: String,
    /// Field path of its table.
    pub path: String,
    /// Length \[m\] rather than angle \[rad\].
    pub linear: bool,
    /// Rest and travel.
    pub range: CoordRange,
    /// Spring neutral y_0.
    pub neutral: f64,
    /// Spring.
    pub spring: Spring,
    /// Damping.
    pub damping: f64,
    /// Bump-stop stiffness, if given.
    pub stop_stiffness: Option<f64>,
    /// Bump-stop damping, if given.
    pub stop_damping: Option<f64>,
}

/// Check one coordinate table at `path`; `default_name` if it has none.
pub fn check_coordinate(
    ctx: &mut Ctx,
    path: &str,
    c: &CoordinateDesc,
    default_name: &str,
    may_be_linear: bool,
) -> Option<CheckedCoord> {
    let linear = c.linear.unwrap_or(false);
    if linear && !may_be_linear {
        ctx.error(
            format!("{path}.linear"),
            "only a raw polynomial suspension may have a linear coordinate",
            "library suspensions turn about pivots: remove `linear`",
        );
        return None;
    }
    let rest = ctx.angle(path, "rest", c.rest, c.rest_deg, linear);
    let neutral = ctx.angle(path, "neutral", c.neutral, c.neutral_deg, linear);
    let min = ctx.angle(path, "min", c.min, c.min_deg, linear);
    let max = ctx.angle(path, "max", c.max, c.max_deg, linear);
    let unit = if linear { "" } else { "_deg" };
    let (min, max) = match (min, max) {
        (Ok(Some(a)), Ok(Some(b))) => (a, b),
        (Ok(None), _) | (_, Ok(None)) => {
            let missing = if matches!(min, Ok(None)) {
                "min"
            } else {
                "max"
            };
            ctx.error(
                path,
                format!("the travel limit `{missing}` is missing"),
                format!(
                    "every coordinate needs its travel: add `{missing}{unit} = …` (the fit covers [min, max])"
                ),
            );
            return None;
        }
        _ => return None,
    };
    let rest = rest.ok()?.unwrap_or(0.0);
    if min >= max {
        ctx.error(
            Ctx::angle_path(path, "max", c.max_deg.is_some()),
            format!(
                "the travel range is empty: max = {} is not above min = {}",
                coord_value(max, linear),
                coord_value(min, linear)
            ),
            "give min < max",
        );
        return None;
    }
    if !linear && max - min > 2.0 * std::f64::consts::PI {
        ctx.error(
            Ctx::angle_path(path, "max", c.max_deg.is_some()),
            format!(
                "the travel [{}, {}] spans more than a full turn",
                coord_value(min, linear),
                coord_value(max, linear)
            ),
            "angles without `_deg` are in radians: check the unit, and give the range the suspension can really travel",
        );
        return None;
    }
    if rest < min || rest > max {
        let rest_path = if c.rest.is_some() || c.rest_deg.is_some() {
            Ctx::angle_path(path, "rest", c.rest_deg.is_some())
        } else {
            path.to_string()
        };
        ctx.error(
            rest_path,
            format!(
                "the rest value {} is outside the travel range [{}, {}]",
                coord_value(rest, linear),
                coord_value(min, linear),
                coord_value(max, linear)
            ),
            "the rover starts at rest and the fit is centred there: move the rest value into the range or widen the range",
        );
        return None;
    }
    let neutral = neutral.ok()?.unwrap_or(rest);
    if neutral < min || neutral > max {
        ctx.error(
            Ctx::angle_path(path, "neutral", c.neutral_deg.is_some()),
            format!(
                "the spring neutral {} is outside the travel range [{}, {}]",
                coord_value(neutral, linear),
                coord_value(min, linear),
                coord_value(max, linear)
            ),
            "the neutral is where the spring force is zero, a position the suspension can take (the active suspension moves it within the travel): give a value in [min, max]",
        );
        return None;
    }
    let spring = check_spring(ctx, path, c, linear)?;
    let damping = match c.damping {
        Some(d) => ctx.non_negative(
            &format!("{path}.damping"),
            d,
            "damping is in N·m·s/rad (or N·s/m) and cannot be negative",
        )?,
        None => 0.0,
    };
    let stop_stiffness = match c.stop_stiffness {
        Some(k) => Some(ctx.positive(
            &format!("{path}.stop_stiffness"),
            k,
            "a bump stop must push back: give a positive stiffness, or omit it for the default (100·k)",
        )?),
        None => None,
    };
    let stop_damping = match c.stop_damping {
        Some(d) => Some(ctx.non_negative(
            &format!("{path}.stop_damping"),
            d,
            "omit it for the default (critical damping)",
        )?),
        None => None,
    };
    let name = c.name.clone().unwrap_or_else(|| default_name.to_string());
    Some(CheckedCoord {
        name,
        path: path.to_string(),
        linear,
        range: CoordRange { rest, min, max },
        neutral,
        spring,
        damping,
        stop_stiffness,
        stop_damping,
    })
}

/// A linear spring, a table, or none.
fn check_spring(ctx: &mut Ctx, path: &str, c: &CoordinateDesc, linear: bool) -> Option<Spring> {
    match (&c.stiffness, &c.spring_table) {
        (Some(_), Some(_)) => {
            ctx.error(
                format!("{path}.spring_table"),
                "both `stiffness` and `spring_table` are given",
                "keep `stiffness` for a linear spring or `spring_table` for a nonlinear one",
            );
            None
        }
        (Some(k), None) => {
            let k = ctx.non_negative(
                &format!("{path}.stiffness"),
                *k,
                "spring stiffness is in N·m/rad (or N/m) and cannot be negative",
            )?;
            Some(Spring::Linear { stiffness: k })
        }
        (None, None) => Some(Spring::None),
        (None, Some(t)) => {
            let tpath = format!("{path}.spring_table");
            let deflection: Vec<f64> = match (&t.deflection, &t.deflection_deg) {
                (Some(_), Some(_)) => {
                    ctx.error(
                        format!("{tpath}.deflection_deg"),
                        "`deflection` and `deflection_deg` are both given",
                        "keep one of them",
                    );
                    return None;
                }
                (Some(d), None) => d.clone(),
                (None, Some(d)) if !linear => d.iter().map(|v| v.to_radians()).collect(),
                (None, Some(_)) => {
                    ctx.error(
                        format!("{tpath}.deflection_deg"),
                        "a linear coordinate has no degrees",
                        "give `deflection` in metres",
                    );
                    return None;
                }
                (None, None) => {
                    ctx.error(
                        &tpath,
                        "the spring table has no `deflection`",
                        "add `deflection = […]` (or `deflection_deg`)",
                    );
                    return None;
                }
            };
            let dpath = if t.deflection_deg.is_some() {
                format!("{tpath}.deflection_deg")
            } else {
                format!("{tpath}.deflection")
            };
            if deflection.iter().chain(&t.force).any(|v| !v.is_finite()) {
                return None;
            }
            if deflection.len() < 2 || deflection.len() != t.force.len() {
                ctx.error(
                    format!("{tpath}.force"),
                    format!(
                        "the spring table needs at least 2 points and as many forces as deflections, got {} deflections and {} forces",
                        deflection.len(),
                        t.force.len()
                    ),
                    "give one force per deflection",
                );
                return None;
            }
            if let Some(i) = deflection.windows(2).position(|w| w[1] <= w[0]) {
                ctx.error(
                    dpath,
                    format!(
                        "deflections must increase strictly, but entry {} ({}) is not above entry {} ({})",
                        i + 2,
                        num(deflection[i + 1]),
                        i + 1,
                        num(deflection[i])
                    ),
                    "sort the table by deflection and remove repeated points",
                );
                return None;
            }
            match deflection.iter().position(|&d| d == 0.0) {
                Some(i) if t.force[i] == 0.0 => {}
                _ => {
                    ctx.error(
                        &tpath,
                        "the spring table must pass through (0, 0): at the neutral value the spring force is zero",
                        "add a point with deflection 0 and force 0, and put the spring's free position in `neutral`",
                    );
                    return None;
                }
            }
            Some(Spring::Table {
                deflection,
                force: t.force.clone(),
            })
        }
    }
}
