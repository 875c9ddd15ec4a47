//! Tracing the equations of `rover-dynamics` for one rover: the functions a
//! generated plant offers, each as an expression graph with named inputs
//! and outputs.
//!
//! The very code the generic plant runs with `f64` (kinematics, M, bias,
//! forces, the LDLᵀ solve of `rover_dynamics::eom::derivatives`) runs here
//! with [`Sym`]; the model's numbers enter as constants and fold, the
//! state, loads, spring neutrals and steering angles enter as inputs.

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::bias::add_bias;
use rover_dynamics::fidelity::{Fidelity, Frozen, linear_wheel_kinematics, reduced_derivatives};
use rover_dynamics::forces::{Load, add_gravity, add_suspension, add_wheel_loads};
use rover_dynamics::kinematics::{body_kinematics, position_rates, wheel_kinematics};
use rover_dynamics::mass::mass_matrix;
use rover_dynamics::workspace::Workspace;
use rover_dynamics::{Scalar, model::Spring};
use rover_spec::Spec;

use crate::diff::derivative;
use crate::graph::{Graph, Id};
use crate::ordered_solve::{block_solve, suspension_first};
use crate::sym::{Sym, trace};

/// An input of a traced function: its name in the generated code and the
/// Rust expression that reads it from the function's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct InputVar {
    /// Identifier of the local it is unpacked into (`phi`, `yd_y1`).
    pub name: String,
    /// Where it is read (`x[3]`, `loads[0].force[2]`, `self.neutral[1]`).
    pub access: String,
    /// The per-wheel or per-coordinate quantity it is one of, and whose:
    /// (`"yd"`, 2) for `yd_y3`, (`"f_z"`, 0) for the first wheel's vertical
    /// force. Inputs of one quantity, one per wheel, can share a vector
    /// ([`crate::lanes`]).
    pub lane: Option<(String, usize)>,
}

/// An output of a traced function.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputVar {
    /// Its node.
    pub id: Id,
    /// The statement head that receives it (`xdot[0] =`, `let pivot_3 =`).
    pub place: String,
    /// Index of its block (a wheel), see [`Function::groups`].
    pub group: usize,
}

/// One traced function.
#[derive(Clone, Debug)]
pub struct Function {
    /// The graph (values, and derivatives when asked for).
    pub graph: Graph,
    /// Inputs; input k of the graph is `inputs[k]`.
    pub inputs: Vec<InputVar>,
    /// Outputs, in writing order.
    pub outputs: Vec<OutputVar>,
    /// Block titles; outputs of group g are written in block g.
    pub groups: Vec<String>,
}

#[cfg(test)]
impl Function {
    /// A one-block function for unit tests: inputs `names[k]` read from
    /// `x[k]`, the outputs of `build` written to `out[k]`.
    pub(crate) fn for_test(names: &[&str], build: impl FnOnce(&mut Graph) -> Vec<Id>) -> Function {
        let mut graph = Graph::new();
        let outs = build(&mut graph);
        Function {
            graph,
            inputs: names
                .iter()
                .enumerate()
                .map(|(k, n)| InputVar {
                    name: n.to_string(),
                    access: format!("x[{k}]"),
                    lane: None,
                })
                .collect(),
            outputs: outs
                .into_iter()
                .enumerate()
                .map(|(k, id)| OutputVar {
                    id,
                    place: format!("out[{k}] ="),
                    group: 0,
                })
                .collect(),
            groups: vec!["all".into()],
        }
    }
}

/// Every function of a generated plant.
#[derive(Clone, Debug)]
pub struct Traced {
    /// ẋ, ẇ and the LDLᵀ pivots from x, w, the wheel loads and the spring neutrals.
    pub derivatives: Function,
    /// The row of M of each pivot, in elimination order.
    pub pivot_rows: Vec<usize>,
    /// The upper triangle of M(y).
    pub mass_matrix: Function,
    /// Wheel-centre kinematics from x, w and the steering angles, one block per wheel.
    pub wheels: Function,
    /// ∂(ẋ, ẇ)/∂(x, w) at fixed loads, when asked for.
    pub jacobian: Option<Function>,
    /// Local names of the coordinates (sanitized `coordinate_names`).
    pub coordinate_idents: Vec<String>,
    /// Local names of the wheels (sanitized `wheel_names`).
    pub wheel_idents: Vec<String>,
}

/// A Rust identifier from a description name: lower case, `_` for anything
/// else, never starting with a digit.
pub fn ident(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "n_");
    }
    s
}

/// Names made unique by a numeric suffix, in order.
fn unique(names: Vec<String>, taken: &mut Vec<String>) -> Vec<String> {
    names
        .into_iter()
        .map(|n| {
            let mut candidate = n.clone();
            let mut k = 2;
            while taken.contains(&candidate) {
                candidate = format!("{n}_{k}");
                k += 1;
            }
            taken.push(candidate.clone());
            candidate
        })
        .collect()
}

const POSE: [&str; 6] = ["pos_x", "pos_y", "pos_z", "phi", "theta", "psi"];
const TWIST: [&str; 6] = ["vx", "vy", "vz", "omega_x", "omega_y", "omega_z"];
const AXES: [&str; 3] = ["x", "y", "z"];

/// Inputs x and w, in order, with their names.
fn state_inputs(coords: &[String], inputs: &mut Vec<InputVar>) {
    for (k, n) in POSE.iter().enumerate() {
        inputs.push(InputVar {
            name: n.to_string(),
            access: format!("x[{k}]"),
            lane: None,
        });
    }
    for (i, c) in coords.iter().enumerate() {
        inputs.push(InputVar {
            name: c.clone(),
            access: format!("x[{}]", 6 + i),
            lane: Some(("y".into(), i)),
        });
    }
    for (k, n) in TWIST.iter().enumerate() {
        inputs.push(InputVar {
            name: n.to_string(),
            access: format!("w[{k}]"),
            lane: None,
        });
    }
    for (i, c) in coords.iter().enumerate() {
        inputs.push(InputVar {
            name: format!("yd_{c}"),
            access: format!("w[{}]", 6 + i),
            lane: Some(("yd".into(), i)),
        });
    }
}

/// A reduced fidelity level (MODEL.md §9) and the configuration y_ref its
/// kinematics are frozen at (docs/FIDELITY.md).
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Simplified or linearized (`Full` traces the full model).
    pub fidelity: Fidelity,
    /// The frozen configuration, one value per suspension coordinate.
    pub y_ref: Vec<f64>,
}

/// The level's frozen configuration fits the rover: one value per
/// suspension coordinate, each inside its travel (the fitted kinematics
/// reach no farther); otherwise a message naming the coordinate, its
/// suspension and its travel.
pub fn check_level(spec: &Spec, level: &Level) -> Result<(), String> {
    let m = spec.model.coordinates.len();
    if level.y_ref.len() != m {
        return Err(format!(
            "the frozen configuration y_ref has {} values but the rover has {m} suspension coordinates: give one per coordinate, in order",
            level.y_ref.len()
        ));
    }
    match spec.outside_travel(&level.y_ref, "in the frozen configuration y_ref") {
        Some(m) => Err(format!(
            "{m}: a reduced level is frozen inside the travel, where the kinematics are fitted; give y_ref values inside it"
        )),
        None => Ok(()),
    }
}

/// Trace every function of the plant of `spec` (full fidelity).
pub fn trace_spec(spec: &Spec, with_jacobian: bool) -> Traced {
    trace_spec_at(spec, with_jacobian, None)
}

/// Trace every function of the plant of `spec` at a fidelity level.
pub fn trace_spec_at(spec: &Spec, with_jacobian: bool, level: Option<&Level>) -> Traced {
    let level = level.filter(|l| l.fidelity != Fidelity::Full);
    let model = &spec.model;
    let mut taken: Vec<String> = POSE.iter().chain(&TWIST).map(|s| s.to_string()).collect();
    let coords = unique(
        spec.coordinate_names.iter().map(|n| ident(n)).collect(),
        &mut taken,
    );
    let wheels = unique(
        spec.wheel_names.iter().map(|n| ident(n)).collect(),
        &mut taken,
    );
    let derivatives = trace_derivatives(model, &coords, &wheels, level);
    let jacobian = with_jacobian.then(|| jacobian_of(&derivatives, model.dof()));
    Traced {
        derivatives,
        pivot_rows: suspension_first(model.dof()),
        mass_matrix: trace_mass(model, &coords, level),
        wheels: trace_wheels(model, &coords, &wheels, &spec.wheel_names, level),
        jacobian,
        coordinate_idents: coords,
        wheel_idents: wheels,
    }
}

fn trace_derivatives(
    model: &Model,
    coords: &[String],
    wheels: &[String],
    level: Option<&Level>,
) -> Function {
    let n = model.dof();
    let m = model.m();
    let mut inputs = Vec::new();
    state_inputs(coords, &mut inputs);
    for (j, wname) in wheels.iter().enumerate() {
        for (field, short) in [("force", "f"), ("moment", "mu"), ("stator_torque", "tau")] {
            for (c, axis) in AXES.iter().enumerate() {
                inputs.push(InputVar {
                    name: format!("{short}_{wname}_{axis}"),
                    access: format!("loads[{j}].{field}[{c}]"),
                    lane: Some((format!("{short}_{axis}"), j)),
                });
            }
        }
    }
    let neutral_base = inputs.len();
    for (i, c) in coords.iter().enumerate() {
        inputs.push(InputVar {
            name: format!("y0_{c}"),
            access: format!("self.neutral[{i}]"),
            lane: Some(("y0".into(), i)),
        });
    }
    let k = model.wheels.len();
    let order = suspension_first(n);
    let ((xdot, wdot, pivots, cos_roll), graph) = trace(|| {
        let x: Vec<Sym> = (0..n).map(Sym::input).collect();
        let w: Vec<Sym> = (n..2 * n).map(Sym::input).collect();
        let loads: Vec<Load<Sym>> = (0..k)
            .map(|j| {
                let base = 2 * n + 9 * j;
                let v = |o: usize| [0, 1, 2].map(|c| Sym::input(base + o + c));
                Load {
                    force: v(0),
                    moment: v(3),
                    stator_torque: v(6),
                }
            })
            .collect();
        // A coordinate without a spring never reads its neutral: keep it a
        // constant so that no unused input is unpacked.
        let neutral: Vec<Sym> = (0..m)
            .map(|i| match model.coordinates[i].spring {
                Spring::None => Sym::cst(model.coordinates[i].neutral),
                _ => Sym::input(neutral_base + i),
            })
            .collect();
        if let Some(level) = level {
            // rover_dynamics::fidelity::reduced_derivatives: M constant,
            // factored at generation time; the pivots are constants.
            let mut frozen = Frozen::<Sym>::at(model, &level.y_ref);
            let mut xdot = vec![Sym::zero(); n];
            let mut wdot = vec![Sym::zero(); n];
            reduced_derivatives(
                model,
                level.fidelity,
                &mut frozen,
                &neutral,
                &x,
                &w,
                &loads,
                &mut xdot,
                &mut wdot,
            );
            let pivots: Vec<(Sym, Sym)> = order
                .iter()
                .map(|&r| (frozen.factor[r * n + r], Sym::one()))
                .collect();
            let cos_roll = if level.fidelity.is_linearized() {
                // The linearized attitude has no cos φ: never singular.
                Sym::one()
            } else {
                x[3].cos()
            };
            return (xdot, wdot, pivots, cos_roll);
        }
        // rover_dynamics::eom::derivatives, with the solve eliminating the
        // suspension coordinates first (see `ordered_solve`).
        let mut ws = Workspace::<Sym>::new(model);
        let y = &x[6..];
        body_kinematics(model, y, &mut ws);
        mass_matrix(model, &mut ws);
        let att = Attitude::new(x[3], x[4], x[5]);
        let mut rhs = vec![Sym::zero(); n];
        add_bias(model, &mut ws, &w, &mut rhs);
        add_gravity(model, &ws, &att, &mut rhs);
        add_suspension(model, &neutral, y, &w[6..], &mut rhs);
        add_wheel_loads(model, &ws, &att, &loads, &mut rhs);
        let (wdot, pivots) = block_solve(&ws.mass, &rhs);
        let mut xdot = vec![Sym::zero(); n];
        position_rates(&x, &w, &mut xdot);
        (xdot, wdot, pivots, x[3].cos())
    });
    let mut outputs = vec![OutputVar {
        id: cos_roll.0,
        place: "let cos_roll =".into(),
        group: 0,
    }];
    for (&r, (num, den)) in order.iter().zip(&pivots) {
        outputs.push(OutputVar {
            id: num.0,
            place: format!("let pivot_{r} ="),
            group: 0,
        });
        outputs.push(OutputVar {
            id: den.0,
            place: format!("let pivot_den_{r} ="),
            group: 0,
        });
    }
    for (r, v) in xdot.iter().enumerate() {
        outputs.push(OutputVar {
            id: v.0,
            place: format!("xdot[{r}] ="),
            group: 0,
        });
    }
    for (r, v) in wdot.iter().enumerate() {
        outputs.push(OutputVar {
            id: v.0,
            place: format!("wdot[{r}] ="),
            group: 0,
        });
    }
    Function {
        graph,
        inputs,
        outputs,
        groups: vec!["ẋ = B·w, M·ẇ = −Ṁ·w − f1 + f2 + Q (MODEL.md §5, eq. 24–25)".into()],
    }
}

fn trace_mass(model: &Model, coords: &[String], level: Option<&Level>) -> Function {
    let n = model.dof();
    let m = model.m();
    // A reduced level's M is constant: no coordinate is read.
    let inputs: Vec<InputVar> = if level.is_some() {
        Vec::new()
    } else {
        coords
            .iter()
            .enumerate()
            .map(|(i, c)| InputVar {
                name: c.clone(),
                access: format!("x[{}]", 6 + i),
                lane: Some(("y".into(), i)),
            })
            .collect()
    };
    let (mass, graph) = trace(|| {
        if let Some(level) = level {
            return Frozen::<Sym>::at(model, &level.y_ref).ws.mass;
        }
        let y: Vec<Sym> = (0..m).map(Sym::input).collect();
        let mut ws = Workspace::<Sym>::new(model);
        body_kinematics(model, &y, &mut ws);
        mass_matrix(model, &mut ws);
        ws.mass
    });
    let mut outputs = Vec::new();
    for a in 0..n {
        for b in a..n {
            let id = mass[a * n + b].0;
            if graph.value(id) == Some(0.0) {
                continue;
            }
            outputs.push(OutputVar {
                id,
                place: format!("m[{a}][{b}] ="),
                group: 0,
            });
            if a != b {
                outputs.push(OutputVar {
                    id,
                    place: format!("m[{b}][{a}] ="),
                    group: 0,
                });
            }
        }
    }
    Function {
        graph,
        inputs,
        outputs,
        groups: vec!["M(y), upper triangle mirrored (MODEL.md §4, eq. 11–19)".into()],
    }
}

fn trace_wheels(
    model: &Model,
    coords: &[String],
    wheels: &[String],
    titles: &[String],
    level: Option<&Level>,
) -> Function {
    let n = model.dof();
    let mut inputs = Vec::new();
    state_inputs(coords, &mut inputs);
    for (j, w) in wheels.iter().enumerate() {
        inputs.push(InputVar {
            name: format!("delta_{w}"),
            access: format!("steer[{j}]"),
            lane: Some(("delta".into(), j)),
        });
    }
    let (states, graph) = trace(|| {
        let x: Vec<Sym> = (0..n).map(Sym::input).collect();
        let w: Vec<Sym> = (n..2 * n).map(Sym::input).collect();
        let mut ws = Workspace::<Sym>::new(model);
        body_kinematics(model, &x[6..], &mut ws);
        let att = Attitude::new(x[3], x[4], x[5]);
        let linear = level
            .filter(|l| l.fidelity.is_linearized())
            .map(|l| (l.fidelity, Frozen::<Sym>::at(model, &l.y_ref)));
        (0..model.wheels.len())
            .map(|k| {
                let steer = if model.wheels[k].steerable {
                    Sym::input(2 * n + k)
                } else {
                    Sym::zero()
                };
                match &linear {
                    Some((fidelity, frozen)) => {
                        linear_wheel_kinematics(model, *fidelity, frozen, &x, &w, k, steer)
                    }
                    None => wheel_kinematics(model, &ws, &att, &x, &w, k, steer),
                }
            })
            .collect::<Vec<_>>()
    });
    let mut outputs = Vec::new();
    for (k, s) in states.iter().enumerate() {
        for (field, v) in [
            ("centre", s.centre),
            ("velocity", s.velocity),
            ("spin_axis", s.spin_axis),
        ] {
            for (c, e) in v.iter().enumerate() {
                outputs.push(OutputVar {
                    id: e.0,
                    place: format!("out[{k}].{field}[{c}] ="),
                    group: k,
                });
            }
        }
    }
    Function {
        graph,
        inputs,
        outputs,
        groups: titles
            .iter()
            .map(|t| format!("wheel `{t}`: r_G, V, a_w (MODEL.md §3, eq. 7, 12)"))
            .collect(),
    }
}

/// ∂(ẋ, ẇ)/∂(x, w) of a traced `derivatives`, row-major 2N×2N, with the
/// values in the same graph.
fn jacobian_of(f: &Function, n: usize) -> Function {
    let mut graph = f.graph.clone();
    let rates: Vec<Id> = f
        .outputs
        .iter()
        .filter(|o| o.place.starts_with("xdot") || o.place.starts_with("wdot"))
        .map(|o| o.id)
        .collect();
    let mut outputs = Vec::new();
    for col in 0..2 * n {
        let wrt = graph.input(col as u32);
        let d = derivative(&mut graph, &rates, wrt);
        for (row, id) in d.into_iter().enumerate() {
            if graph.value(id) == Some(0.0) {
                continue;
            }
            outputs.push(OutputVar {
                id,
                place: format!("jac[{row}][{col}] ="),
                group: 0,
            });
        }
    }
    Function {
        graph,
        inputs: f.inputs.clone(),
        outputs,
        groups: vec!["∂(ẋ, ẇ)/∂(x, w) at fixed wheel loads".into()],
    }
}
