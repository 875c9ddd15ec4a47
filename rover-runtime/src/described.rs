//! A rover declared with `#[derive(Rover)]` as the runtime sees it: its
//! description parsed into the model the terrain, contact and controllers
//! read, its `rover check` report, and the check that a plant and a model
//! given separately describe the same rover.
//!
//! The derive validated the description at compile time and generated the
//! plant from it; [`RoverDescription`] parses the same text again with the
//! same `rover-spec`, so [`RoverDescription::model`] is the model the plant
//! was generated from.

use rover_dynamics::Model;
use rover_dynamics::described::Described;
use rover_dynamics::model::{CarriedBody, Coordinate, Wheel};
use rover_dynamics::plant::Plant;
use rover_spec::{Spec, SpecError};

/// What a rover declared with `#[derive(Rover)]` offers beyond its plant,
/// for the struct and for its plant type alike (implemented for every
/// [`Described`] type; bring it into scope with `use
/// rover_runtime::RoverDescription`).
///
/// Each call parses the description (a fraction of a millisecond for the
/// built-in rovers): call it once and keep the result.
pub trait RoverDescription: Described {
    /// The validated description: the model, the names, the fits, the rest
    /// geometry. An error only if the `rover-spec` this runs with rejects
    /// what the derive's accepted (two versions of it in one build).
    fn spec() -> Result<Spec, SpecError> {
        rover_spec::load_str(Self::DESCRIPTION, Self::ORIGIN)
    }

    /// The numeric model the plant was generated from.
    fn model() -> Result<Model, SpecError> {
        Self::spec().map(|s| s.model)
    }

    /// What `rover check` prints for this rover: the fitted polynomials and
    /// their errors, masses, inertias, the rest geometry; and, for a plant
    /// generated at a reduced level, the level and where it is frozen.
    fn report() -> Result<String, SpecError> {
        let mut text = rover_spec::report::check_report(&Self::spec()?);
        if Self::FIDELITY != "full" {
            text.push_str(&format!(
                "\nplant generated at the {} level, frozen at y = {:?}\n",
                Self::FIDELITY,
                Self::Y_REF
            ));
        }
        Ok(text)
    }
}

impl<T: Described> RoverDescription for T {}

/// A plant and a model that do not describe the same rover: what differs,
/// one line per field (`body.mass: 100 in the plant, 60 in the model`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error(
    "the plant and the model describe different rovers:\n{}\n  = help: build both from one description: `Simulation::new(MyRover::plant())` takes the model from the plant's own description",
    differences.iter().map(|d| format!("  - {d}")).collect::<Vec<_>>().join("\n")
)]
pub struct Mismatch {
    /// The fields that differ, with both values.
    pub differences: Vec<String>,
}

/// The differences between the model of a plant's description (`plant`,
/// its names from `names`) and a model loaded separately, field by field;
/// empty when they are the same rover.
pub fn model_differences(plant: &Model, names: &Spec, model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    push_num(&mut out, "gravity".into(), plant.gravity, model.gravity);
    push_num(
        &mut out,
        "body.mass".into(),
        plant.body.mass,
        model.body.mass,
    );
    for (i, (ra, rb)) in plant
        .body
        .inertia
        .iter()
        .zip(&model.body.inertia)
        .enumerate()
    {
        for (j, (a, b)) in ra.iter().zip(rb).enumerate() {
            push_num(&mut out, format!("body.inertia[{i}][{j}]"), *a, *b);
        }
    }
    let mut counts = Vec::new();
    let mut count = |what: &str, a: usize, b: usize| {
        if a != b {
            counts.push(format!("{what}: {a} in the plant, {b} in the model"));
        }
    };
    count(
        "suspension coordinates",
        plant.coordinates.len(),
        model.coordinates.len(),
    );
    count("carried bodies", plant.bodies.len(), model.bodies.len());
    count("wheels", plant.wheels.len(), model.wheels.len());
    let name = |list: &[String], i: usize, kind: &str| match list.get(i) {
        Some(n) => format!("{kind} `{n}`"),
        None => format!("{kind} {}", i + 1),
    };
    for (i, (a, b)) in plant.coordinates.iter().zip(&model.coordinates).enumerate() {
        out.extend(coordinate_differences(
            &name(&names.coordinate_names, i, "coordinate"),
            a,
            b,
        ));
    }
    for (j, (a, b)) in plant.bodies.iter().zip(&model.bodies).enumerate() {
        out.extend(body_differences(&name(&names.body_names, j, "body"), a, b));
    }
    for (k, (a, b)) in plant.wheels.iter().zip(&model.wheels).enumerate() {
        out.extend(wheel_differences(
            &name(&names.wheel_names, k, "wheel"),
            a,
            b,
        ));
    }
    counts.extend(out);
    counts
}

fn push_num(out: &mut Vec<String>, field: String, a: f64, b: f64) {
    if a != b {
        out.push(format!("{field}: {a} in the plant, {b} in the model"));
    }
}

fn push_other<T: PartialEq + std::fmt::Debug>(out: &mut Vec<String>, field: String, a: &T, b: &T) {
    if a != b {
        out.push(format!("{field}: {a:?} in the plant, {b:?} in the model"));
    }
}

fn coordinate_differences(who: &str, a: &Coordinate, b: &Coordinate) -> Vec<String> {
    let mut out = Vec::new();
    for (field, x, y) in [
        ("rest", a.rest, b.rest),
        ("neutral", a.neutral, b.neutral),
        ("damping", a.damping, b.damping),
        ("min", a.min, b.min),
        ("max", a.max, b.max),
        ("stop_stiffness", a.stop_stiffness, b.stop_stiffness),
        ("stop_damping", a.stop_damping, b.stop_damping),
    ] {
        push_num(&mut out, format!("{who}.{field}"), x, y);
    }
    push_other(&mut out, format!("{who}.spring"), &a.spring, &b.spring);
    out
}

fn body_differences(who: &str, a: &CarriedBody, b: &CarriedBody) -> Vec<String> {
    let mut out = Vec::new();
    push_num(&mut out, format!("{who}.mass"), a.mass, b.mass);
    push_other(&mut out, format!("{who}.inertia"), &a.inertia, &b.inertia);
    if a.position != b.position {
        out.push(format!(
            "{who}: its position u_j(y) differs (the suspension's geometry or fit)"
        ));
    }
    if a.member != b.member {
        out.push(format!(
            "{who}: the member carrying it turns differently (the suspension's geometry or fit)"
        ));
    }
    out
}

fn wheel_differences(who: &str, a: &Wheel, b: &Wheel) -> Vec<String> {
    let mut out = Vec::new();
    push_other(&mut out, format!("{who}.body"), &a.body, &b.body);
    for (field, x, y) in [
        ("radius", a.radius, b.radius),
        ("stiffness", a.stiffness, b.stiffness),
        ("damping", a.damping, b.damping),
        ("mu_x", a.mu_x, b.mu_x),
        ("mu_y", a.mu_y, b.mu_y),
        (
            "cornering_stiffness",
            a.cornering_stiffness,
            b.cornering_stiffness,
        ),
        ("max_torque", a.max_torque, b.max_torque),
    ] {
        push_num(&mut out, format!("{who}.{field}"), x, y);
    }
    push_other(&mut out, format!("{who}.motor"), &a.motor, &b.motor);
    push_other(
        &mut out,
        format!("{who}.steerable"),
        &a.steerable,
        &b.steerable,
    );
    if a.camber != b.camber {
        out.push(format!("{who}.camber: differs"));
    }
    if a.toe != b.toe {
        out.push(format!("{who}.toe: differs"));
    }
    out
}

/// What any plant can be checked for against a model: its sizes, and the
/// total mass, which is the translational block of its mass matrix at any
/// configuration and any fidelity level (MODEL.md §4). A plant whose
/// description is at hand is compared field by field instead
/// ([`model_differences`]); this catches the rest, such as a plant of one
/// rover run with the terrain contact and controllers of another.
pub fn plant_differences<P: Plant + ?Sized>(plant: &mut P, model: &Model) -> Vec<String> {
    let mut out = Vec::new();
    let (n, k) = (model.dof(), model.wheels.len());
    if plant.dof() != n {
        out.push(format!(
            "degrees of freedom: {} in the plant, {n} in the model",
            plant.dof()
        ));
    }
    if plant.wheel_count() != k {
        out.push(format!(
            "wheels: {} in the plant, {k} in the model",
            plant.wheel_count()
        ));
    }
    if !out.is_empty() {
        return out;
    }
    let mut x = vec![0.0; n];
    x[6..].copy_from_slice(&model.rest());
    let mut m = vec![0.0; n * n];
    plant.mass_matrix(&x, &mut m);
    let (mass, expected) = (m[0], model.total_mass());
    // The sums of the same masses in another order differ in the last bits.
    // A NaN mass differs too.
    let same = (mass - expected).abs() <= 1e-9 * expected;
    if !same {
        // To the gram's millionth: the sums' last bits say nothing.
        let kg = |m: f64| (m * 1e9).round() / 1e9;
        out.push(format!(
            "total mass: {} kg in the plant, {} kg in the model",
            kg(mass),
            kg(expected)
        ));
    }
    out
}
