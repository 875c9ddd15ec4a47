//! A suspension table → its coordinates and exact kinematics (library
//! kinds) or its polynomials (raw kind).

use rover_dynamics::model::MemberRotation;
use rover_dynamics::poly::{PolyVec, ScalarPoly, Term};

use super::coordinate::{CheckedCoord, check_coordinate};
use crate::checks::{Ctx, num};
use crate::description::{
    CoordinateDesc, DoubleWishboneDesc, FitDesc, FitMethodDesc, PolynomialDesc, RockerBogieDesc,
    RockerDesc, ScalarPolyDesc, SuspensionDesc, SwingArmDesc, TransversalSwingArmDesc,
};
use crate::jet::MAX_TERMS;
use crate::linkage::{FitMethod, FitOptions, FittedPoint, Linkage, Member, PointDef};
use crate::suspension::{DoubleWishbone, Kinematics, Rocker, RockerBogie, SwingArm};

/// A checked suspension.
pub struct Built {
    /// Name.
    pub name: String,
    /// `kind` keyword.
    pub kind: &'static str,
    /// Its coordinates, local order, with the path of each coordinate table.
    pub coords: Vec<CheckedCoord>,
    /// Exact kinematics or given polynomials.
    pub source: Source,
}

/// Where the polynomials of a suspension come from.
#[allow(clippy::large_enum_variant)] // one per suspension
pub enum Source {
    /// A library kind, fitted with these options.
    Library {
        /// The kinematics.
        kin: Kinematics,
        /// Its members.
        members: Vec<Member>,
        /// Its points.
        points: Vec<PointDef>,
        /// Fit options.
        options: FitOptions,
        /// Path of the fit table (or of the suspension).
        fit_path: String,
    },
    /// Raw polynomials, already in global coordinates.
    Polynomial {
        /// Named points.
        points: Vec<(String, FittedPoint)>,
    },
}

/// Check `[[suspension]]` number `index`, whose first coordinate is y_`first`.
pub fn build(ctx: &mut Ctx, index: usize, desc: &SuspensionDesc, first: usize) -> Option<Built> {
    let path = format!("suspension[{index}]");
    let name = desc.name().to_string();
    let (coords, kin, fit) = match desc {
        SuspensionDesc::LongitudinalSwingArm(s) => {
            let (c, k) = longitudinal_swing_arm(ctx, &path, &name, s)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::TransversalSwingArm(s) => {
            let (c, k) = transversal_swing_arm(ctx, &path, &name, s)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::LongitudinalRocker(s) => {
            let (c, k) = rocker(ctx, &path, &name, s, 1)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::TransversalRocker(s) => {
            let (c, k) = rocker(ctx, &path, &name, s, 0)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::RockerBogie(s) => {
            let (c, k) = rocker_bogie(ctx, &path, &name, s)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::DoubleWishbone(s) => {
            let (c, k) = double_wishbone(ctx, &path, &name, s)?;
            (c, k, &s.fit)
        }
        SuspensionDesc::Polynomial(p) => return polynomial(ctx, &path, name, desc, p, first),
    };
    let options = fit_options(ctx, &path, fit.as_ref())?;
    let fit_path = if fit.is_some() {
        format!("{path}.fit")
    } else {
        path.clone()
    };
    let members = kin.members();
    let points = kin.points();
    Some(Built {
        name,
        kind: desc.kind(),
        coords,
        source: Source::Library {
            kin,
            members,
            points,
            options,
            fit_path,
        },
    })
}

/// A library kind's coordinates and exact kinematics (`None` where a
/// field has errors, all of them reported).
type Checked = Option<(Vec<CheckedCoord>, Kinematics)>;

/// The coordinate table `field` of the suspension at `path`, named
/// `default` unless it names itself.
fn coord(
    ctx: &mut Ctx,
    path: &str,
    field: &str,
    c: &CoordinateDesc,
    default: &str,
) -> Option<CheckedCoord> {
    check_coordinate(ctx, &format!("{path}.{field}"), c, default, false)
}

/// A swing arm turning about the body's y axis.
fn longitudinal_swing_arm(ctx: &mut Ctx, path: &str, name: &str, s: &SwingArmDesc) -> Checked {
    let c = coord(ctx, path, "coordinate", &s.coordinate, name);
    let pivot = point3(ctx, &format!("{path}.pivot"), s.pivot);
    let length = ctx.positive(
        &format!("{path}.length"),
        s.length,
        "the arm length is in metres, pivot to wheel centre",
    );
    let c = c?;
    let kin = Kinematics::SwingArm(SwingArm {
        pivot: pivot?,
        length: length?,
        axis: 1,
        rest: c.range.rest,
        camber_rest: 0.0,
    });
    Some((vec![c], kin))
}

/// A swing arm turning about the body's x axis, the wheel cambering with it.
fn transversal_swing_arm(
    ctx: &mut Ctx,
    path: &str,
    name: &str,
    s: &TransversalSwingArmDesc,
) -> Checked {
    let c = coord(ctx, path, "coordinate", &s.coordinate, name);
    let pivot = point3(ctx, &format!("{path}.pivot"), s.pivot);
    let length = ctx.positive(
        &format!("{path}.length"),
        s.length,
        "the arm length is in metres, pivot to wheel centre",
    );
    let reference = ctx.angle(
        path,
        "camber_reference",
        s.camber_reference,
        s.camber_reference_deg,
        false,
    );
    let c = c?;
    let reference = reference.ok()?.unwrap_or(c.range.rest);
    let kin = Kinematics::SwingArm(SwingArm {
        pivot: pivot?,
        length: length?,
        axis: 0,
        rest: c.range.rest,
        camber_rest: c.range.rest - reference,
    });
    Some((vec![c], kin))
}

/// A rocker turning about body axis `axis` (1: y, longitudinal; 0: x,
/// transversal), with a wheel at the end of each arm.
fn rocker(ctx: &mut Ctx, path: &str, name: &str, s: &RockerDesc, axis: usize) -> Checked {
    let c = coord(ctx, path, "coordinate", &s.coordinate, name);
    let pivot = point3(ctx, &format!("{path}.pivot"), s.pivot);
    if s.arms.is_empty() {
        ctx.error(
            format!("{path}.arms"),
            "a rocker needs at least one arm",
            "add `arms = [{ name = \"front\", length = …, angle_deg = … }]`",
        );
    }
    let mut arms = Vec::new();
    let mut ok = true;
    for (k, arm) in s.arms.iter().enumerate() {
        let apath = format!("{path}.arms[{k}]");
        if s.arms[..k].iter().any(|a| a.name == arm.name) {
            ctx.error(
                format!("{apath}.name"),
                format!("the point name `{}` is used twice in this rocker", arm.name),
                "give each arm its own name",
            );
            ok = false;
        }
        let l = ctx.positive(
            &format!("{apath}.length"),
            arm.length,
            "the arm length is in metres, pivot to wheel centre",
        );
        let beta = ctx.angle(&apath, "angle", arm.angle, arm.angle_deg, false);
        match (l, beta) {
            (Some(l), Ok(b)) => arms.push((arm.name.clone(), l, b.unwrap_or(0.0))),
            _ => ok = false,
        }
    }
    let c = c?;
    if !ok || arms.is_empty() {
        return None;
    }
    let kin = Kinematics::Rocker(Rocker {
        pivot: pivot?,
        arms,
        axis,
        rest: c.range.rest,
    });
    Some((vec![c], kin))
}

/// The rocker-bogie pair: a rocker on each side, a bogie on each rocker.
fn rocker_bogie(ctx: &mut Ctx, path: &str, name: &str, s: &RockerBogieDesc) -> Checked {
    let r = coord(ctx, path, "rocker", &s.rocker, &format!("{name}_rocker"));
    let bl = coord(
        ctx,
        path,
        "bogie_left",
        &s.bogie_left,
        &format!("{name}_bogie_left"),
    );
    let br = coord(
        ctx,
        path,
        "bogie_right",
        &s.bogie_right,
        &format!("{name}_bogie_right"),
    );
    let pts: Vec<Option<[f64; 3]>> = [
        ("pivot", s.pivot),
        ("front_wheel", s.front_wheel),
        ("bogie_pivot", s.bogie_pivot),
        ("middle_wheel", s.middle_wheel),
        ("rear_wheel", s.rear_wheel),
    ]
    .iter()
    .map(|(f, p)| point3(ctx, &format!("{path}.{f}"), *p))
    .collect();
    if let Some(p) = pts[0]
        && p[1] <= 0.0
    {
        ctx.error(
            format!("{path}.pivot"),
            format!(
                "the rocker pivot must be on the left side (y > 0), got y = {} m",
                num(p[1])
            ),
            "give the left side's geometry; the right side mirrors it in y",
        );
        return None;
    }
    let (r, bl, br) = (r?, bl?, br?);
    let pts: Option<Vec<[f64; 3]>> = pts.into_iter().collect();
    let pts = pts?;
    let kin = Kinematics::RockerBogie(RockerBogie {
        pivot: pts[0],
        front: pts[1],
        bogie_pivot: pts[2],
        middle: pts[3],
        rear: pts[4],
        rest: [r.range.rest, bl.range.rest, br.range.rest],
    });
    Some((vec![r, bl, br], kin))
}

/// A double wishbone, assembled at its rest angle.
fn double_wishbone(ctx: &mut Ctx, path: &str, name: &str, s: &DoubleWishboneDesc) -> Checked {
    let c = coord(ctx, path, "coordinate", &s.coordinate, name);
    let help = "lengths are in metres and positive";
    let lengths = [
        ctx.positive(&format!("{path}.lower_length"), s.lower_length, help),
        ctx.positive(&format!("{path}.upper_length"), s.upper_length, help),
        ctx.positive(&format!("{path}.upright_length"), s.upright_length, help),
    ];
    let finite = [
        s.x,
        s.lower_pivot[0],
        s.lower_pivot[1],
        s.upper_pivot[0],
        s.upper_pivot[1],
        s.wheel_offset[0],
        s.wheel_offset[1],
    ]
    .iter()
    .all(|v| v.is_finite());
    if s.lower_pivot[0] == 0.0 {
        ctx.error(
            format!("{path}.lower_pivot"),
            "the lower pivot is on the centre plane (y = 0), so the side is unknown",
            "give the inner pivot's y: positive on the left, negative on the right",
        );
        return None;
    }
    let c = c?;
    let [Some(ll), Some(lu), Some(h)] = lengths else {
        return None;
    };
    if !finite {
        return None;
    }
    let Some(w) = (DoubleWishbone {
        x: s.x,
        lower_pivot: s.lower_pivot,
        lower_length: ll,
        upper_pivot: s.upper_pivot,
        upper_length: lu,
        upright_length: h,
        wheel_offset: s.wheel_offset,
        rest: c.range.rest,
        branch: 1.0,
    })
    .assembled() else {
        ctx.error(
            path,
            format!(
                "the double wishbone cannot assemble with the upper ball joint above the lower at the rest angle {}°",
                num(c.range.rest.to_degrees())
            ),
            "check the pivots and lengths: the upper arm and the upright must reach each other",
        );
        return None;
    };
    Some((vec![c], Kinematics::DoubleWishbone(w)))
}

/// A raw polynomial suspension: its named coordinates and its points'
/// polynomials, already global.
fn polynomial(
    ctx: &mut Ctx,
    path: &str,
    name: String,
    desc: &SuspensionDesc,
    p: &PolynomialDesc,
    first: usize,
) -> Option<Built> {
    let mut coords = Vec::new();
    for (k, c) in p.coordinates.iter().enumerate() {
        let cpath = format!("{path}.coordinates[{k}]");
        if c.name.is_none() {
            ctx.error(
                &cpath,
                "a polynomial suspension's coordinate needs a `name`",
                "add `name = \"…\"`: the polynomials refer to it",
            );
        }
        coords.push(check_coordinate(ctx, &cpath, c, "", true));
    }
    if p.coordinates.is_empty() {
        ctx.error(
            format!("{path}.coordinates"),
            "a polynomial suspension needs at least one coordinate",
            "add `coordinates = [{ name = \"…\", min = …, max = … }]`",
        );
    }
    let coords: Option<Vec<CheckedCoord>> = coords.into_iter().collect();
    let coords = coords?;
    let points = polynomial_points(ctx, path, p, &coords, first)?;
    Some(Built {
        name,
        kind: desc.kind(),
        coords,
        source: Source::Polynomial { points },
    })
}

/// A finite 3-vector (non-finite entries are already reported).
fn point3(_ctx: &mut Ctx, _path: &str, p: [f64; 3]) -> Option<[f64; 3]> {
    p.iter().all(|v| v.is_finite()).then_some(p)
}

/// The `fit` table, with defaults.
fn fit_options(ctx: &mut Ctx, path: &str, fit: Option<&FitDesc>) -> Option<FitOptions> {
    let mut o = FitOptions::default();
    let Some(f) = fit else { return Some(o) };
    if let Some(m) = f.method {
        o.method = match m {
            FitMethodDesc::Taylor => FitMethod::Taylor,
            FitMethodDesc::LeastSquares => FitMethod::LeastSquares,
        };
    }
    if let Some(k) = f.terms {
        if !(2..=MAX_TERMS).contains(&k) {
            ctx.error(
                format!("{path}.fit.terms"),
                format!("the number of terms must be between 2 and {MAX_TERMS}, got {k}"),
                "k = 5 (powers ξ⁰ … ξ⁴) is the paper's choice; more terms fit a wider travel",
            );
            return None;
        }
        o.terms = k;
    }
    if let Some(t) = f.tolerance {
        o.tolerance = ctx.positive(
            &format!("{path}.fit.tolerance"),
            t,
            "the tolerance is the largest accepted position error, in metres",
        )?;
    }
    if let Some(t) = f.angle_tolerance {
        o.angle_tolerance = ctx.positive(
            &format!("{path}.fit.angle_tolerance"),
            t,
            "the angle tolerance is the largest accepted angle error, in radians",
        )?;
    }
    Some(o)
}

/// The points of a raw polynomial suspension, in global coordinates.
fn polynomial_points(
    ctx: &mut Ctx,
    path: &str,
    p: &crate::description::PolynomialDesc,
    coords: &[CheckedCoord],
    first: usize,
) -> Option<Vec<(String, FittedPoint)>> {
    let find = |ctx: &mut Ctx, fpath: String, name: &str| -> Option<usize> {
        let k = coords.iter().position(|c| c.name == name);
        if k.is_none() {
            let names: Vec<&str> = coords.iter().map(|c| c.name.as_str()).collect();
            ctx.error(
                fpath,
                format!("this suspension has no coordinate named `{name}`"),
                format!("its coordinates are: {}", names.join(", ")),
            );
        }
        k
    };
    let check_len = |ctx: &mut Ctx, fpath: String, n: usize| -> bool {
        if (1..=MAX_TERMS).contains(&n) {
            true
        } else {
            ctx.error(
                fpath,
                format!("a polynomial has 1 to {MAX_TERMS} coefficients, got {n}"),
                "give the coefficients of ξ⁰, ξ¹, …",
            );
            false
        }
    };
    let mut out = Vec::new();
    let mut ok = true;
    if p.points.is_empty() {
        ctx.error(
            format!("{path}.points"),
            "a polynomial suspension needs at least one point",
            "add a `[[suspension.points]]` table",
        );
        return None;
    }
    for (k, pt) in p.points.iter().enumerate() {
        let ppath = format!("{path}.points[{k}]");
        if p.points[..k].iter().any(|q| q.name == pt.name) {
            ctx.error(
                format!("{ppath}.name"),
                format!(
                    "the point name `{}` is used twice in this suspension",
                    pt.name
                ),
                "give each point its own name",
            );
            ok = false;
        }
        let mut position = PolyVec::constant(pt.position);
        for (t, term) in pt.terms.iter().enumerate() {
            let tpath = format!("{ppath}.terms[{t}]");
            let Some(c) = find(ctx, format!("{tpath}.coordinate"), &term.coordinate) else {
                ok = false;
                continue;
            };
            if pt.terms[..t]
                .iter()
                .any(|o| o.coordinate == term.coordinate)
            {
                ctx.error(
                    format!("{tpath}.coordinate"),
                    format!(
                        "coordinate `{}` has two terms in this point",
                        term.coordinate
                    ),
                    "merge them into one list of coefficients",
                );
                ok = false;
            }
            ok &= check_len(ctx, format!("{tpath}.coeffs"), term.coeffs.len());
            position.terms.push(Term {
                coord: first + c,
                center: coords[c].range.rest,
                coeffs: term.coeffs.clone(),
            });
        }
        let mut member = Vec::new();
        for (t, m) in pt.member.iter().enumerate() {
            let mpath = format!("{ppath}.member[{t}]");
            let Some(c) = find(ctx, format!("{mpath}.coordinate"), &m.coordinate) else {
                ok = false;
                continue;
            };
            let norm =
                (m.axis[0] * m.axis[0] + m.axis[1] * m.axis[1] + m.axis[2] * m.axis[2]).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                if norm == 0.0 {
                    ctx.error(
                        format!("{mpath}.axis"),
                        "the member axis is the zero vector",
                        "give the axis the member turns about, e.g. [0, 1, 0]",
                    );
                }
                ok = false;
                continue;
            }
            ok &= check_len(ctx, format!("{mpath}.angle"), m.angle.len());
            if m.angle.first().is_some_and(|a| *a != 0.0) {
                ctx.error(
                    format!("{mpath}.angle"),
                    format!("the member angle must be 0 at rest, but its constant coefficient is {}", num(m.angle[0])),
                    "the angle is measured from the rest configuration: make the first coefficient 0",
                );
                ok = false;
            }
            member.push(MemberRotation {
                coord: first + c,
                axis: [m.axis[0] / norm, m.axis[1] / norm, m.axis[2] / norm],
                angle: ScalarPoly {
                    constant: 0.0,
                    terms: vec![Term {
                        coord: first + c,
                        center: coords[c].range.rest,
                        coeffs: m.angle.clone(),
                    }],
                },
            });
        }
        let mut scalar = |ctx: &mut Ctx, field: &str, s: &Option<ScalarPolyDesc>| -> ScalarPoly {
            let mut out = ScalarPoly::constant(s.as_ref().and_then(|s| s.constant).unwrap_or(0.0));
            for (t, term) in s.iter().flat_map(|s| s.terms.iter()).enumerate() {
                let tpath = format!("{ppath}.{field}.terms[{t}]");
                let Some(c) = find(ctx, format!("{tpath}.coordinate"), &term.coordinate) else {
                    ok = false;
                    continue;
                };
                ok &= check_len(ctx, format!("{tpath}.coeffs"), term.coeffs.len());
                out.terms.push(Term {
                    coord: first + c,
                    center: coords[c].range.rest,
                    coeffs: term.coeffs.clone(),
                });
            }
            out
        };
        let camber = scalar(ctx, "camber", &pt.camber);
        let toe = scalar(ctx, "toe", &pt.toe);
        out.push((
            pt.name.clone(),
            FittedPoint {
                position,
                member,
                camber,
                toe,
                max_position_error: 0.0,
                max_angle_error: 0.0,
                shares: Vec::new(),
            },
        ));
    }
    ok.then_some(out)
}
