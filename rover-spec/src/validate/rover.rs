//! The whole description: every field, then the relations between them
//! (names, references, fits), then the numeric model.

use std::collections::BTreeMap;

use rover_dynamics::Model;
use rover_dynamics::model::{CarriedBody, Coordinate, RigidBody, Spring};

use super::body::check_inertia;
use super::names::{check_strings, check_unique};
use super::suspension::{Built, Source, build};
use super::wheel::{CheckedWheel, check_wheel};
use crate::checks::{Ctx, coord_value, non_finite, num};
use crate::description::{Description, MassDesc};
use crate::diagnostic::Diagnostic;
use crate::fit::FitFailure;
use crate::linkage::{FitMethod, FittedPoint, LinkEnd, Linkage};
use crate::point_fit::fit_point;
use crate::sketch::{Sketch, SketchJoint, SketchLink};
use crate::spec::{BodyFit, Spec, SuspensionInfo};

/// Effective inertia used for the critical bump-stop damping of a
/// coordinate that moves no mass at rest [kg·m² or kg]: small, so the stop
/// damping stays small, but not zero.
pub const MIN_STOP_INERTIA: f64 = 1e-3;
/// Bump-stop stiffness of a coordinate without spring [N·m/rad or N/m].
pub const FREE_STOP_STIFFNESS: f64 = 100.0;
/// Bump-stop stiffness as a multiple of the spring's stiffness.
pub const STOP_STIFFNESS_FACTOR: f64 = 100.0;

/// Where a carried body sits.
#[derive(Clone, Debug, PartialEq)]
enum Place {
    /// A named point.
    Point(String),
    /// A member, at a rest position.
    Member(usize, [f64; 3]),
}

/// A carried body before fitting.
struct Carried {
    name: String,
    suspension: usize,
    place: Place,
    at: String,
    mass: f64,
    inertia: Option<([[f64; 3]; 3], String)>,
}

/// Check a description and build its [`Spec`], or return every problem.
///
/// In three stages, each reporting every problem it finds before the next
/// would trip over them: the fields one by one; the relations between them
/// (names, references, the fits of the suspensions); the numeric model and
/// what it implies (finite derived numbers, a rover that can run).
pub fn validate(desc: &Description) -> Result<Spec, Vec<Diagnostic>> {
    let mut ctx = Ctx::default();
    if let Ok(value) = toml::Value::try_from(desc) {
        if check_strings(&mut ctx, &value) {
            return Err(ctx.diags);
        }
        non_finite(&mut ctx, &value, "");
        super::runnable::magnitudes(&mut ctx, &value, "");
    }
    super::runnable::fields(&mut ctx, desc);
    let gravity = ctx.positive(
        "gravity",
        desc.gravity,
        "g is in m/s² and acts along −Z: Moon 1.62, Mars 3.71, Earth 9.81",
    );
    let body_mass = ctx.positive(
        "body.mass",
        desc.body.mass,
        "the body mass is in kg and positive",
    );
    let body_inertia = check_inertia(&mut ctx, "body.inertia", &desc.body.inertia);
    check_names(&mut ctx, desc);
    let built = build_suspensions(&mut ctx, desc);
    let (carried, wheels) = place_bodies(&mut ctx, desc, &built);
    let fitted = fit_bodies(&mut ctx, &built, &carried);

    if ctx.diags.is_empty() && fitted.iter().any(Option::is_none) {
        ctx.error(
            "",
            "a carried body could not be placed on its suspension",
            "this is a bug in rover-spec: please report it with the file",
        );
    }
    if !ctx.diags.is_empty() {
        return Err(ctx.diags);
    }
    let built: Vec<Built> = built.into_iter().flatten().collect();
    let fitted: Vec<FittedPoint> = fitted.into_iter().flatten().collect();
    let (Some(gravity), Some(body_mass), Some(body_inertia)) = (gravity, body_mass, body_inertia)
    else {
        return Err(vec![Diagnostic::at(
            "",
            "the description is invalid",
            "see the other messages",
        )]);
    };

    let bodies: Vec<CarriedBody> = carried
        .iter()
        .zip(&fitted)
        .map(|(c, p)| CarriedBody {
            mass: c.mass,
            inertia: c.inertia.as_ref().map(|i| i.0),
            position: p.position.clone(),
            member: p.member.clone(),
        })
        .collect();
    let model_wheels: Vec<_> = wheels
        .into_iter()
        .enumerate()
        .map(|(j, w)| {
            let mut wheel = w.wheel;
            wheel.body = j;
            wheel.camber = fitted[j].camber.clone();
            wheel.toe = fitted[j].toe.clone();
            wheel
        })
        .collect();
    let coordinates = model_coordinates(&built, &bodies);
    check_derived_numbers(&coordinates, &built, &carried, &bodies)?;
    let model = Model {
        gravity,
        body: RigidBody {
            mass: body_mass,
            inertia: body_inertia,
        },
        coordinates,
        bodies,
        wheels: model_wheels,
    };
    let rest_wheel_centres = model.rest_wheel_centres();
    let radius_paths: Vec<String> = desc
        .wheels
        .iter()
        .enumerate()
        .map(|(i, w)| match w.radius {
            Some(_) => format!("wheel[{i}].radius"),
            None => "wheel_defaults.radius".to_string(),
        })
        .collect();
    check_runnable(&model, &built, &rest_wheel_centres, &radius_paths)?;
    let sketch = sketch(&built, &carried, &model);
    Ok(Spec {
        name: desc.name.clone(),
        model,
        coordinate_names: coords_of(&built).map(|c| c.name.clone()).collect(),
        coordinate_linear: coords_of(&built).map(|c| c.linear).collect(),
        body_names: carried.iter().map(|c| c.name.clone()).collect(),
        wheel_names: desc.wheels.iter().map(|w| w.name.clone()).collect(),
        suspensions: suspension_infos(&built),
        fits: body_fits(desc, &built, &carried, &fitted),
        rest_wheel_centres,
        sketch,
        description: desc.clone(),
    })
}

/// The checked coordinates of every suspension, in the model's order.
fn coords_of(built: &[Built]) -> impl Iterator<Item = &super::coordinate::CheckedCoord> {
    built.iter().flat_map(|b| b.coords.iter())
}

/// Suspension names, and wheel and carried-body names, each unique.
fn check_names(ctx: &mut Ctx, desc: &Description) {
    let suspension_names: Vec<(String, String, &str)> = desc
        .suspensions
        .iter()
        .enumerate()
        .map(|(i, s)| {
            (
                s.name().to_string(),
                format!("suspension[{i}].name"),
                "suspension",
            )
        })
        .collect();
    check_unique(ctx, &suspension_names);
    let mut body_names: Vec<(String, String, &str)> = desc
        .wheels
        .iter()
        .enumerate()
        .map(|(i, w)| (w.name.clone(), format!("wheel[{i}].name"), "wheel"))
        .collect();
    for (i, s) in desc.suspensions.iter().enumerate() {
        for (k, b) in s.bodies().iter().enumerate() {
            body_names.push((
                b.name.clone(),
                format!("suspension[{i}].bodies[{k}].name"),
                "carried body",
            ));
        }
    }
    check_unique(ctx, &body_names);
}

/// Each suspension built (`None` where it has errors), its coordinates
/// numbered in order; coordinate names unique across the rover.
fn build_suspensions(ctx: &mut Ctx, desc: &Description) -> Vec<Option<Built>> {
    let mut built: Vec<Option<Built>> = Vec::new();
    let mut first = 0;
    for (i, s) in desc.suspensions.iter().enumerate() {
        let b = build(ctx, i, s, first);
        if let Some(b) = &b {
            first += b.coords.len();
        }
        built.push(b);
    }
    let coord_names: Vec<(String, String, &str)> = built
        .iter()
        .flatten()
        .flat_map(|b| b.coords.iter())
        .map(|c| (c.name.clone(), format!("{}.name", c.path), "coordinate"))
        .collect();
    check_unique(ctx, &coord_names);
    built
}

/// The carried bodies, wheels first (in the description's order, each on
/// its suspension's point), then each suspension's other masses; and the
/// checked wheels.
fn place_bodies(
    ctx: &mut Ctx,
    desc: &Description,
    built: &[Option<Built>],
) -> (Vec<Carried>, Vec<CheckedWheel>) {
    let defaults = desc.wheel_defaults.clone().unwrap_or_default();
    let mut carried = Vec::new();
    let mut wheels = Vec::new();
    for (i, w) in desc.wheels.iter().enumerate() {
        let checked = check_wheel(ctx, i, w, &defaults);
        let place = find_suspension(
            ctx,
            &format!("wheel[{i}].suspension"),
            &w.suspension,
            desc,
            built,
        )
        .and_then(|s| {
            wheel_point(ctx, i, w.point.as_deref(), s, built[s].as_ref()?).map(|p| (s, p))
        });
        if let (Some(c), Some((s, point))) = (checked, place) {
            carried.push(Carried {
                name: w.name.clone(),
                suspension: s,
                place: Place::Point(point.clone()),
                at: point,
                mass: c.mass,
                inertia: c.inertia.clone(),
            });
            wheels.push(c);
        }
    }
    check_points_used_once(ctx, &carried, desc);
    for (i, s) in desc.suspensions.iter().enumerate() {
        let Some(b) = built[i].as_ref() else { continue };
        for (k, m) in s.bodies().iter().enumerate() {
            if let Some(c) = mass_place(ctx, &format!("suspension[{i}].bodies[{k}]"), m, i, b) {
                carried.push(c);
            }
        }
    }
    (carried, wheels)
}

/// Every carried body's fitted position, one per body (`None` where the
/// fit failed). Every named point is fitted, used or not: a linkage that
/// cannot cover its travel is an error even before a wheel sits on it.
fn fit_bodies(
    ctx: &mut Ctx,
    built: &[Option<Built>],
    carried: &[Carried],
) -> Vec<Option<FittedPoint>> {
    let mut cache: BTreeMap<(usize, String), FittedPoint> = BTreeMap::new();
    for (s, b) in built.iter().enumerate() {
        let Some(b) = b else { continue };
        for name in point_names(b) {
            let place = Place::Point(name);
            if let Some(p) = fit_carried(ctx, b, &place, global_of(built, s)) {
                cache.insert((s, format!("{place:?}")), p);
            }
        }
    }
    let mut fitted = Vec::new();
    for c in carried {
        let Some(b) = built[c.suspension].as_ref() else {
            continue;
        };
        let key = (c.suspension, format!("{:?}", c.place));
        let point = match cache.get(&key) {
            Some(p) => Some(p.clone()),
            None => {
                let p = fit_carried(ctx, b, &c.place, global_of(built, c.suspension));
                if let Some(p) = &p {
                    cache.insert(key, p.clone());
                }
                p
            }
        };
        if let (Some(p), Some((_, path))) = (&point, &c.inertia)
            && p.member.len() > 1
        {
            ctx.error(
                path.clone(),
                format!("`{}` turns with {} coordinates, so its inertia cannot be carried", c.name, p.member.len()),
                "give inertia only to bodies on a member that turns with one coordinate, or omit it",
            );
        }
        fitted.push(point);
    }
    fitted
}

/// The model's coordinates: each checked coordinate with its bump stop,
/// stiff against its spring and critically damped against the inertia it
/// moves at rest.
fn model_coordinates(built: &[Built], bodies: &[CarriedBody]) -> Vec<Coordinate> {
    coords_of(built)
        .enumerate()
        .map(|(i, c)| {
            let k_ref = match &c.spring {
                Spring::Linear { stiffness } => *stiffness,
                Spring::Table { deflection, force } => deflection
                    .windows(2)
                    .zip(force.windows(2))
                    .map(|(d, f)| ((f[1] - f[0]) / (d[1] - d[0])).abs())
                    .fold(0.0, f64::max),
                Spring::None => 0.0,
            };
            let stop_stiffness = c.stop_stiffness.unwrap_or(if k_ref > 0.0 {
                STOP_STIFFNESS_FACTOR * k_ref
            } else {
                FREE_STOP_STIFFNESS
            });
            let inertia = effective_inertia(bodies, i);
            let inertia = if inertia > 0.0 {
                inertia
            } else {
                MIN_STOP_INERTIA
            };
            Coordinate {
                rest: c.range.rest,
                neutral: c.neutral,
                spring: c.spring.clone(),
                damping: c.damping,
                min: c.range.min,
                max: c.range.max,
                stop_stiffness,
                stop_damping: c
                    .stop_damping
                    .unwrap_or(2.0 * (stop_stiffness * inertia).sqrt()),
            }
        })
        .collect()
}

/// Huge inputs can overflow what is derived from them (1e308 kg times a
/// slope): nothing non-finite leaves [`validate`].
fn check_derived_numbers(
    coordinates: &[Coordinate],
    built: &[Built],
    carried: &[Carried],
    bodies: &[CarriedBody],
) -> Result<(), Vec<Diagnostic>> {
    let mut ctx = Ctx::default();
    for (c, checked) in coordinates.iter().zip(coords_of(built)) {
        let numbers = [
            c.stop_stiffness,
            c.stop_damping,
            c.rest,
            c.min,
            c.max,
            c.neutral,
        ];
        if numbers.iter().any(|v| !v.is_finite()) {
            ctx.error(
                checked.path.clone(),
                "a number derived from this coordinate (its bump stop) is not finite: an input is too large",
                "check the magnitudes of the coordinate, its spring and the masses it moves (SI units)",
            );
        }
    }
    for (c, b) in carried.iter().zip(bodies) {
        let poly = b
            .position
            .terms
            .iter()
            .flat_map(|t| t.coeffs.iter().flatten())
            .chain(&b.position.constant);
        if !b.mass.is_finite() || poly.clone().any(|v| !v.is_finite()) {
            ctx.error(
                format!("suspension[{}]", c.suspension),
                format!("the polynomials of `{}` are not finite: an input is too large", c.name),
                "check the magnitudes of this suspension's lengths and positions (SI units: metres)",
            );
        }
    }
    if ctx.diags.is_empty() {
        Ok(())
    } else {
        Err(ctx.diags)
    }
}

/// The checks of a rover that `check` accepts and a run must be able to
/// use (see the `runnable` module), located at its coordinates.
fn check_runnable(
    model: &Model,
    built: &[Built],
    rest_wheel_centres: &[[f64; 3]],
    radius_paths: &[String],
) -> Result<(), Vec<Diagnostic>> {
    let mut ctx = Ctx::default();
    let coordinate_paths: Vec<String> = coords_of(built).map(|c| c.path.clone()).collect();
    let suspension_of: Vec<String> = built
        .iter()
        .enumerate()
        .flat_map(|(i, b)| b.coords.iter().map(move |_| format!("suspension[{i}]")))
        .collect();
    super::runnable::model(
        &mut ctx,
        model,
        &coordinate_paths,
        &suspension_of,
        rest_wheel_centres,
        radius_paths,
    );
    if ctx.diags.is_empty() {
        Ok(())
    } else {
        Err(ctx.diags)
    }
}

/// Each suspension's name, kind, coordinate indices and fit options.
fn suspension_infos(built: &[Built]) -> Vec<SuspensionInfo> {
    let mut first = 0;
    built
        .iter()
        .map(|b| {
            let info = SuspensionInfo {
                name: b.name.clone(),
                kind: b.kind,
                coordinates: (first..first + b.coords.len()).collect(),
                fit: match &b.source {
                    Source::Library { options, .. } => Some(*options),
                    Source::Polynomial { .. } => None,
                },
            };
            first += b.coords.len();
            info
        })
        .collect()
}

/// What each carried body's fit shares and misses, for the report.
fn body_fits(
    desc: &Description,
    built: &[Built],
    carried: &[Carried],
    fitted: &[FittedPoint],
) -> Vec<BodyFit> {
    let suspension_index = |name: &str| built.iter().position(|b| b.name == name).unwrap_or(0);
    carried
        .iter()
        .zip(fitted)
        .map(|(c, p)| BodyFit {
            suspension: suspension_index(desc.suspensions[c.suspension].name()),
            at: c.at.clone(),
            shares: p.shares.clone(),
            max_position_error: p.max_position_error,
            max_angle_error: p.max_angle_error,
        })
        .collect()
}

/// The joints and links of every library suspension ([`Linkage::sketch`]):
/// a joint where a wheel sits is that wheel's centre `u_j(y)`; any other is
/// fitted like a carried body. A joint whose fit fails (it cannot, where
/// the suspension's own points fitted) leaves its link out.
fn sketch(built: &[Built], carried: &[Carried], model: &Model) -> Sketch {
    let mut out = Sketch::default();
    let mut index: BTreeMap<(usize, usize, [u64; 3]), usize> = BTreeMap::new();
    let mut first = 0;
    for (s, b) in built.iter().enumerate() {
        let global: Vec<usize> = (first..first + b.coords.len()).collect();
        first += b.coords.len();
        let Source::Library {
            kin,
            members,
            points,
            options,
            ..
        } = &b.source
        else {
            continue;
        };
        let ranges: Vec<_> = b.coords.iter().map(|c| c.range).collect();
        let wheel_at = |end: &LinkEnd| {
            carried
                .iter()
                .take(model.wheels.len())
                .position(|c| {
                    c.suspension == s
                        && matches!(&c.place, Place::Point(name) if points
                            .iter()
                            .any(|p| &p.name == name && p.member == end.member && p.rest == end.rest))
                })
        };
        for [a, z] in kin.sketch() {
            let mut ends = [0usize; 2];
            let mut placed = true;
            for (k, end) in [a, z].iter().enumerate() {
                let key = (s, end.member, end.rest.map(f64::to_bits));
                if let Some(&i) = index.get(&key) {
                    ends[k] = i;
                    continue;
                }
                let joint = match wheel_at(end) {
                    Some(w) => Some(SketchJoint {
                        position: model.bodies[model.wheels[w].body].position.clone(),
                        wheel: Some(w),
                    }),
                    None => fit_point(kin, end.member, end.rest, &ranges, &global, options)
                        .ok()
                        .map(|f| SketchJoint {
                            position: f.position,
                            wheel: None,
                        }),
                };
                match joint {
                    Some(j) => {
                        index.insert(key, out.joints.len());
                        ends[k] = out.joints.len();
                        out.joints.push(j);
                    }
                    None => placed = false,
                }
            }
            if placed {
                out.links.push(SketchLink {
                    suspension: b.name.clone(),
                    member: members[a.member].name.to_string(),
                    joints: ends,
                });
            }
        }
    }
    out
}

/// Σ_j m_j·|∂u_j/∂y_i|² at rest: the inertia the coordinate's bump stop
/// moves (MODEL.md §3, "critically damped").
fn effective_inertia(bodies: &[CarriedBody], i: usize) -> f64 {
    bodies
        .iter()
        .map(|b| {
            let slope: f64 = b
                .position
                .terms
                .iter()
                .filter(|t| t.coord == i)
                .filter_map(|t| t.coeffs.get(1))
                .map(|c| c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
                .sum();
            b.mass * slope
        })
        .sum()
}

/// Global coordinate indices of a suspension's local coordinates.
fn global_of(built: &[Option<Built>], s: usize) -> Vec<usize> {
    let first: usize = built[..s].iter().flatten().map(|b| b.coords.len()).sum();
    let n = built[s].as_ref().map_or(0, |b| b.coords.len());
    (first..first + n).collect()
}

/// The suspension a wheel names.
fn find_suspension(
    ctx: &mut Ctx,
    path: &str,
    name: &str,
    desc: &Description,
    built: &[Option<Built>],
) -> Option<usize> {
    match desc.suspensions.iter().position(|s| s.name() == name) {
        Some(s) => built[s].is_some().then_some(s),
        None => {
            let names: Vec<String> = desc
                .suspensions
                .iter()
                .map(|s| format!("`{}`", s.name()))
                .collect();
            let help = if names.is_empty() {
                "this rover has no `[[suspension]]` yet: add one".to_string()
            } else {
                format!("the suspensions are {}", names.join(", "))
            };
            ctx.error(path, format!("there is no suspension named `{name}`"), help);
            None
        }
    }
}

/// Names of a suspension's points.
fn point_names(b: &Built) -> Vec<String> {
    match &b.source {
        Source::Library { points, .. } => points.iter().map(|p| p.name.clone()).collect(),
        Source::Polynomial { points } => points.iter().map(|p| p.0.clone()).collect(),
    }
}

/// The point a wheel sits on.
fn wheel_point(
    ctx: &mut Ctx,
    i: usize,
    point: Option<&str>,
    s: usize,
    b: &Built,
) -> Option<String> {
    let names = point_names(b);
    let list = names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let _ = s;
    match point {
        Some(p) if names.iter().any(|n| n == p) => Some(p.to_string()),
        Some(p) => {
            ctx.error(
                format!("wheel[{i}].point"),
                format!("suspension `{}` has no point named `{p}`", b.name),
                format!("its points are {list}"),
            );
            None
        }
        None if names.len() == 1 => Some(names[0].clone()),
        None => {
            ctx.error(
                format!("wheel[{i}]"),
                format!("suspension `{}` has several points, and this wheel does not say which it sits on", b.name),
                format!("add `point = …`, one of {list}"),
            );
            None
        }
    }
}

/// No two wheels on one point.
fn check_points_used_once(ctx: &mut Ctx, carried: &[Carried], desc: &Description) {
    for (k, c) in carried.iter().enumerate() {
        if let Some(first) = carried[..k]
            .iter()
            .find(|o| o.suspension == c.suspension && o.place == c.place)
        {
            let i = desc
                .wheels
                .iter()
                .position(|w| w.name == c.name)
                .unwrap_or(0);
            ctx.error(
                format!("wheel[{i}].point"),
                format!(
                    "wheel `{}` sits on point `{}` of `{}`, which wheel `{}` already uses",
                    c.name,
                    c.at,
                    desc.suspensions[c.suspension].name(),
                    first.name
                ),
                "each point carries one wheel: choose another point",
            );
        }
    }
}

/// Where a carried mass sits.
fn mass_place(
    ctx: &mut Ctx,
    path: &str,
    m: &MassDesc,
    suspension: usize,
    b: &Built,
) -> Option<Carried> {
    let mass = ctx.non_negative(&format!("{path}.mass"), m.mass, "the mass is in kg, ≥ 0");
    let inertia = match &m.inertia {
        Some(i) => Some((
            check_inertia(ctx, &format!("{path}.inertia"), i)?,
            format!("{path}.inertia"),
        )),
        None => None,
    };
    let place = match (&m.point, &m.member, &m.position) {
        (Some(p), None, None) => {
            if !point_names(b).iter().any(|n| n == p) {
                let list = point_names(b)
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ");
                ctx.error(
                    format!("{path}.point"),
                    format!("suspension `{}` has no point named `{p}`", b.name),
                    format!("its points are {list}"),
                );
                return None;
            }
            (Place::Point(p.clone()), p.clone())
        }
        (None, Some(member), Some(pos)) => {
            let Source::Library { members, .. } = &b.source else {
                ctx.error(
                    format!("{path}.member"),
                    "a raw polynomial suspension has no members",
                    "place the mass at one of its points with `point = …`",
                );
                return None;
            };
            let Some(k) = members.iter().position(|x| x.name == member) else {
                let list = members
                    .iter()
                    .map(|n| format!("`{}`", n.name))
                    .collect::<Vec<_>>()
                    .join(", ");
                ctx.error(
                    format!("{path}.member"),
                    format!("suspension `{}` has no member named `{member}`", b.name),
                    format!("its members are {list}"),
                );
                return None;
            };
            if !pos.iter().all(|v| v.is_finite()) {
                return None;
            }
            (Place::Member(k, *pos), member.clone())
        }
        _ => {
            ctx.error(
                path,
                "a carried body needs either `point`, or `member` and `position`",
                "give `point = \"…\"` to put it at a named point, or `member = \"…\"` and `position = [x, y, z]` (its centre at rest)",
            );
            return None;
        }
    };
    Some(Carried {
        name: m.name.clone(),
        suspension,
        place: place.0,
        at: place.1,
        mass: mass?,
        inertia,
    })
}

/// Fit the polynomials of a carried body, checking the tolerance.
fn fit_carried(ctx: &mut Ctx, b: &Built, place: &Place, global: Vec<usize>) -> Option<FittedPoint> {
    let (kin, members, points, options, fit_path) = match &b.source {
        Source::Polynomial { points } => {
            let Place::Point(p) = place else { return None };
            return points.iter().find(|q| &q.0 == p).map(|q| q.1.clone());
        }
        Source::Library {
            kin,
            members,
            points,
            options,
            fit_path,
        } => (kin, members, points, options, fit_path),
    };
    let (member, rest, label) = match place {
        Place::Point(p) => {
            let d = points.iter().find(|q| &q.name == p)?;
            (d.member, d.rest, format!("point `{p}`"))
        }
        Place::Member(m, pos) => (*m, *pos, format!("a body on member `{}`", members[*m].name)),
    };
    let ranges: Vec<_> = b.coords.iter().map(|c| c.range).collect();
    match fit_point(kin, member, rest, &ranges, &global, options) {
        Err((local, FitFailure::CannotAssemble { at })) => {
            let c = &b.coords[local];
            ctx.error(
                c.path.clone(),
                format!(
                    "the linkage cannot assemble beyond {} = {}, inside the travel range [{}, {}]: the fit cannot cover this range",
                    c.name,
                    coord_value(at, c.linear),
                    coord_value(c.range.min, c.linear),
                    coord_value(c.range.max, c.linear)
                ),
                "narrow the travel range (`min`/`max`) to where the linkage assembles, or check the pivots and lengths",
            );
            None
        }
        Ok(fit) => {
            let method = match options.method {
                FitMethod::Taylor => "Taylor",
                FitMethod::LeastSquares => "least-squares",
            };
            let alternative = match options.method {
                FitMethod::Taylor => ", or use `method = \"least_squares\"`",
                FitMethod::LeastSquares => "",
            };
            for s in &fit.shares {
                let local = s.coord - global[0];
                let c = &b.coords[local];
                let over = |e: f64, tol: f64| e.is_nan() || e > tol;
                let (what, error, at, tol, unit) = if over(s.position, options.tolerance) {
                    (
                        "position",
                        s.position,
                        s.position_at,
                        options.tolerance,
                        "m",
                    )
                } else if over(s.angle, options.angle_tolerance) {
                    ("angle", s.angle, s.angle_at, options.angle_tolerance, "rad")
                } else {
                    continue;
                };
                ctx.error(
                    fit_path.clone(),
                    format!(
                        "the {method} fit (k = {}) of {label} has a {what} error of {} {unit} at {} = {}, over the tolerance {} {unit}",
                        options.terms,
                        num(error),
                        c.name,
                        coord_value(at, c.linear),
                        num(tol)
                    ),
                    format!(
                        "narrow the travel range of `{}` ([{}, {}]), raise `terms`{alternative}, or raise `tolerance`",
                        c.name,
                        coord_value(c.range.min, c.linear),
                        coord_value(c.range.max, c.linear)
                    ),
                );
            }
            let _ = members;
            Some(fit)
        }
    }
}
