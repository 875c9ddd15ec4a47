//! The exported variables: the run's row as outputs (named as the CSV's
//! columns, with their units and meanings), and, when the plant takes its
//! inputs from outside, the wheels' motor torques, the steerable wheels'
//! angles and the springs' neutrals. One list serves the model
//! description, the FMI getters and setters and the C library, so that a
//! value reference means one thing everywhere.

use rover_runtime::row::Columns;
use rover_spec::Spec;

/// What the plant takes from outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Inputs {
    /// Nothing: the scenario's own controllers drive it, as `rover simulate` runs it.
    #[default]
    None,
    /// Motor torques, steering angles and spring neutrals, added to the
    /// scenario's own loops (a scenario for a rig's controller has none).
    Torques,
}

/// An exported variable's role.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// The time, FMI's independent variable (column `t`).
    Time,
    /// A column of the row (its index in the row).
    Output(usize),
    /// Wheel `j`'s motor torque command (0-based) [N·m].
    Torque(usize),
    /// Wheel `j`'s steering command (0-based) \[rad\].
    Steering(usize),
    /// Coordinate `i`'s spring neutral (0-based) \[rad or m\].
    Neutral(usize),
}

/// One exported variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    /// Its name: the CSV column's, or `tau{j}_cmd`, `delta{j}_cmd`, `y0_{i}_cmd`.
    pub name: String,
    /// Its value reference: its position in [`Variables::list`].
    pub value_reference: u32,
    /// Its unit's symbol (`""` for a ratio).
    pub unit: &'static str,
    /// What it is.
    pub description: String,
    /// Its role.
    pub role: Role,
    /// The start value of an input.
    pub start: f64,
}

/// Every exported variable of one rover and scenario, value reference k at
/// position k: the time, the row's other columns, then the inputs.
#[derive(Clone, Debug, PartialEq)]
pub struct Variables {
    /// The variables in value-reference order.
    pub list: Vec<Variable>,
    /// The number of wheels.
    pub wheels: usize,
    /// The number of suspension coordinates.
    pub coordinates: usize,
}

/// A unit's symbol as the model description writes it (ASCII: `N.m`).
fn ascii_unit(symbol: &'static str) -> &'static str {
    match symbol {
        "N·m" => "N.m",
        "1" => "",
        s => s,
    }
}

impl Variables {
    /// The variables of `spec`'s rover with the run's `columns`.
    pub fn new(spec: &Spec, columns: &Columns, inputs: Inputs) -> Self {
        let units = columns.units(&spec.coordinate_linear);
        let meanings = columns.meanings();
        let mut list: Vec<Variable> = Vec::new();
        for (k, name) in columns.names().iter().enumerate() {
            let (name, role) = if k == 0 {
                ("time".to_string(), Role::Time)
            } else {
                (name.clone(), Role::Output(k))
            };
            list.push(Variable {
                name,
                value_reference: k as u32,
                unit: ascii_unit(units[k]),
                // A meaning repeated over coordinates or wheels says which.
                description: if meanings.iter().filter(|m| **m == meanings[k]).count() > 1 {
                    format!("{} ({})", meanings[k], columns.names()[k])
                } else {
                    meanings[k].to_string()
                },
                role,
                start: 0.0,
            });
        }
        let model = &spec.model;
        if inputs == Inputs::Torques {
            let mut push = |name: String, unit, description: String, role, start| {
                let value_reference = list.len() as u32;
                list.push(Variable {
                    name,
                    value_reference,
                    unit,
                    description,
                    role,
                    start,
                });
            };
            for j in 0..model.wheels.len() {
                push(
                    format!("tau{}_cmd", j + 1),
                    "N.m",
                    format!(
                        "wheel {}'s motor torque command, added to the scenario's own (positive drives forward)",
                        j + 1
                    ),
                    Role::Torque(j),
                    0.0,
                );
            }
            for (j, w) in model.wheels.iter().enumerate() {
                if w.steerable {
                    push(
                        format!("delta{}_cmd", j + 1),
                        "rad",
                        format!(
                            "wheel {}'s steering command, added to the scenario's own (positive turns left)",
                            j + 1
                        ),
                        Role::Steering(j),
                        0.0,
                    );
                }
            }
            for (i, c) in model.coordinates.iter().enumerate() {
                if c.spring != rover_dynamics::model::Spring::None {
                    let linear = spec.coordinate_linear.get(i).copied().unwrap_or(false);
                    push(
                        format!("y0_{}_cmd", i + 1),
                        if linear { "m" } else { "rad" },
                        format!(
                            "suspension coordinate y{}'s spring neutral: the active suspension's set-point",
                            i + 1
                        ),
                        Role::Neutral(i),
                        c.neutral,
                    );
                }
            }
        }
        Variables {
            list,
            wheels: model.wheels.len(),
            coordinates: model.coordinates.len(),
        }
    }

    /// The variable of value reference `vr`.
    pub fn get(&self, vr: u32) -> Option<&Variable> {
        self.list.get(vr as usize)
    }

    /// Whether any variable is an input.
    pub fn has_inputs(&self) -> bool {
        self.list.iter().any(Variable::is_input)
    }

    /// The valid value references, for messages.
    pub fn range(&self) -> String {
        format!("0 to {}", self.list.len().saturating_sub(1))
    }
}

impl Variable {
    /// Whether the importer sets it.
    pub fn is_input(&self) -> bool {
        matches!(
            self.role,
            Role::Torque(_) | Role::Steering(_) | Role::Neutral(_)
        )
    }
}
