//! The output row: every column a run writes, each defined once — its
//! name, its unit, what it means and how it is computed from the state and
//! the run's parts. The CSV of a run, the live loop's state messages and
//! the Python package's arrays are all filled from [`Columns`], so they
//! cannot disagree, and a new column is one entry of the table below.
//!
//! The order (docs/CLI.md, "Output"): time, the coordinates x, the
//! pseudo-velocities w, the wheel centres, the contact of each wheel, on a
//! soil each wheel's spin, slip and sinkage, the motor torques, the steering angles, the springs' neutrals and the speed
//! set-point.

use rover_dynamics::HeightField;
use rover_dynamics::plant::{Plant, WheelState};

use crate::sim::RoverSystem;
use rover_dynamics::wheel_ground::WheelReport;

/// What a row is computed from: the state and the run's parts at one
/// instant.
#[derive(Clone, Copy, Debug)]
pub struct RowInputs<'a> {
    /// Time \[s\].
    pub t: f64,
    /// The coordinates x = \[X, Y, Z, φ, θ, ψ, y1 … ym\].
    pub x: &'a [f64],
    /// The pseudo-velocities w = \[vx, vy, vz, Ωx, Ωy, Ωz, ẏ1 … ẏm\].
    pub w: &'a [f64],
    /// Each wheel's centre and motion.
    pub wheels: &'a [WheelState],
    /// What the contact did on each wheel.
    pub reports: &'a [WheelReport],
    /// Each wheel's spin rate on a soil \[rad/s\] (empty on rigid ground).
    pub spins: &'a [f64],
    /// Motor torques per wheel [N·m].
    pub torques: &'a [f64],
    /// Steering angles per wheel \[rad\].
    pub steering: &'a [f64],
    /// The springs' neutrals y0, moved by an active suspension.
    pub neutrals: &'a [f64],
    /// The speed set-point in force [m/s].
    pub speed_setpoint: f64,
}

impl<'a> RowInputs<'a> {
    /// The row of `sys` evaluated at (t, y) (its last right-hand side must
    /// have been at that state), with the speed set-point in force.
    pub fn of_system<P: Plant, H: HeightField>(
        sys: &'a RoverSystem<P, H>,
        t: f64,
        y: &'a [f64],
        speed_setpoint: f64,
    ) -> Self {
        let n = sys.dof();
        RowInputs {
            t,
            x: &y[..n],
            w: &y[n..2 * n],
            wheels: sys.wheel_states(),
            reports: sys.reports(),
            spins: &y[sys.spin_range()],
            torques: sys.torques(),
            steering: sys.steering(),
            neutrals: sys.control.neutrals(),
            speed_setpoint,
        }
    }
}

/// A column's unit. A suspension coordinate is an angle or a length,
/// as the rover's description says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// s
    Second,
    /// m
    Metre,
    /// rad
    Radian,
    /// m/s
    MetrePerSecond,
    /// rad/s
    RadianPerSecond,
    /// N
    Newton,
    /// N·m
    NewtonMetre,
    /// A ratio, without unit.
    Ratio,
    /// rad or m: the coordinate's own.
    Coordinate,
    /// rad/s or m/s: the coordinate's own, per second.
    CoordinateRate,
}

impl Unit {
    /// The unit's symbol; `linear` tells a suspension coordinate's.
    pub fn symbol(self, linear: bool) -> &'static str {
        match self {
            Unit::Second => "s",
            Unit::Metre => "m",
            Unit::Radian => "rad",
            Unit::MetrePerSecond => "m/s",
            Unit::RadianPerSecond => "rad/s",
            Unit::Newton => "N",
            Unit::NewtonMetre => "N·m",
            Unit::Ratio => "1",
            Unit::Coordinate if linear => "m",
            Unit::Coordinate => "rad",
            Unit::CoordinateRate if linear => "m/s",
            Unit::CoordinateRate => "rad/s",
        }
    }
}

/// What a column's index counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Over {
    /// One column.
    Once,
    /// One per suspension coordinate, `{i}` in the name (1-based).
    Coordinate,
    /// One per wheel, `{j}` in the name (1-based, the description's order).
    Wheel,
    /// One per wheel on a soil only (a rigid ground's law has no spin,
    /// slip or sinkage), `{j}` in the name.
    SoilWheel,
}

/// How a column is computed: from the inputs and its index (0-based).
type Value = fn(&RowInputs<'_>, usize) -> f64;

/// One column of the table, or one per coordinate or wheel.
#[derive(Clone, Copy, Debug)]
pub struct Field {
    /// Its name, with `{i}` or `{j}` for the index.
    pub name: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it is.
    pub meaning: &'static str,
    value: Value,
}

/// Columns repeated together over one index: all of a group's columns for
/// the first wheel, then for the second, and so on.
#[derive(Clone, Copy, Debug)]
pub struct Group {
    /// What the index counts.
    pub over: Over,
    /// The columns, in order.
    pub fields: &'static [Field],
}

const fn field(name: &'static str, unit: Unit, meaning: &'static str, value: Value) -> Field {
    Field {
        name,
        unit,
        meaning,
        value,
    }
}

/// Every column of a run, in order.
pub const ROW: &[Group] = &[
    Group {
        over: Over::Once,
        fields: &[
            field("t", Unit::Second, "time", |r, _| r.t),
            field("X", Unit::Metre, "G's position, inertial X", |r, _| r.x[0]),
            field("Y", Unit::Metre, "G's position, inertial Y", |r, _| r.x[1]),
            field("Z", Unit::Metre, "G's position, inertial Z (up)", |r, _| {
                r.x[2]
            }),
            field("phi", Unit::Radian, "roll φ", |r, _| r.x[3]),
            field("theta", Unit::Radian, "pitch θ", |r, _| r.x[4]),
            field("psi", Unit::Radian, "yaw ψ", |r, _| r.x[5]),
        ],
    },
    Group {
        over: Over::Coordinate,
        fields: &[field(
            "y{i}",
            Unit::Coordinate,
            "suspension coordinate",
            |r, i| r.x[6 + i],
        )],
    },
    Group {
        over: Over::Once,
        fields: &[
            field(
                "vx",
                Unit::MetrePerSecond,
                "G's velocity, body x",
                |r, _| r.w[0],
            ),
            field(
                "vy",
                Unit::MetrePerSecond,
                "G's velocity, body y",
                |r, _| r.w[1],
            ),
            field(
                "vz",
                Unit::MetrePerSecond,
                "G's velocity, body z",
                |r, _| r.w[2],
            ),
            field(
                "Ox",
                Unit::RadianPerSecond,
                "angular velocity, body x",
                |r, _| r.w[3],
            ),
            field(
                "Oy",
                Unit::RadianPerSecond,
                "angular velocity, body y",
                |r, _| r.w[4],
            ),
            field(
                "Oz",
                Unit::RadianPerSecond,
                "angular velocity, body z",
                |r, _| r.w[5],
            ),
        ],
    },
    Group {
        over: Over::Coordinate,
        fields: &[field(
            "dy{i}",
            Unit::CoordinateRate,
            "suspension coordinate's rate",
            |r, i| r.w[6 + i],
        )],
    },
    Group {
        over: Over::Wheel,
        fields: &[
            field("W{j}X", Unit::Metre, "wheel centre, inertial X", |r, j| {
                r.wheels[j].centre[0]
            }),
            field("W{j}Y", Unit::Metre, "wheel centre, inertial Y", |r, j| {
                r.wheels[j].centre[1]
            }),
            field("W{j}Z", Unit::Metre, "wheel centre, inertial Z", |r, j| {
                r.wheels[j].centre[2]
            }),
        ],
    },
    Group {
        over: Over::Wheel,
        fields: &[
            field(
                "H{j}X",
                Unit::Metre,
                "contact point (of the largest normal force), inertial X; the wheel centre when airborne",
                |r, j| r.reports[j].point[0],
            ),
            field("H{j}Y", Unit::Metre, "contact point, inertial Y", |r, j| {
                r.reports[j].point[1]
            }),
            field("H{j}Z", Unit::Metre, "contact point, inertial Z", |r, j| {
                r.reports[j].point[2]
            }),
            field("Fn{j}", Unit::Newton, "normal force", |r, j| {
                r.reports[j].normal
            }),
            field("Fd{j}", Unit::Newton, "drawbar pull", |r, j| {
                r.reports[j].drawbar
            }),
            field(
                "Fc{j}",
                Unit::Newton,
                "lateral (cornering) force",
                |r, j| r.reports[j].lateral,
            ),
        ],
    },
    Group {
        over: Over::SoilWheel,
        fields: &[
            field(
                "spin{j}",
                Unit::RadianPerSecond,
                "on a soil: the wheel's spin rate about its axle (positive rolling forward)",
                |r, j| r.spins[j],
            ),
            field(
                "slip{j}",
                Unit::Ratio,
                "on a soil: slip, 1 − v/(r·ω) driving (1 spinning in place), r·ω/v − 1 braking (−1 locked)",
                |r, j| r.reports[j].slip,
            ),
            field(
                "slip_angle{j}",
                Unit::Radian,
                "on a soil: angle between the wheel's heading and its centre's velocity",
                |r, j| r.reports[j].slip_angle,
            ),
            field(
                "sinkage{j}",
                Unit::Metre,
                "on a soil: the rim's depth below the soil's surface (a rut's floor where earlier passes left one)",
                |r, j| r.reports[j].sinkage,
            ),
            field(
                "rut{j}",
                Unit::Metre,
                "on a soil: the depth of the rut earlier passes left under the wheel, below the terrain",
                |r, j| r.reports[j].rut,
            ),
            field(
                "sinkage_undisturbed{j}",
                Unit::Metre,
                "on a soil: the rim's depth below the undisturbed terrain, rut{j} + sinkage{j}",
                |r, j| r.reports[j].rut + r.reports[j].sinkage,
            ),
            field(
                "T{j}",
                Unit::NewtonMetre,
                "on a soil: the soil's torque against the wheel's spin",
                |r, j| r.reports[j].torque,
            ),
        ],
    },
    Group {
        over: Over::Wheel,
        fields: &[field(
            "tau{j}",
            Unit::NewtonMetre,
            "motor torque",
            |r, j| r.torques[j],
        )],
    },
    Group {
        over: Over::Wheel,
        fields: &[field("delta{j}", Unit::Radian, "steering angle", |r, j| {
            r.steering[j]
        })],
    },
    Group {
        over: Over::Coordinate,
        fields: &[field(
            "y0_{i}",
            Unit::Coordinate,
            "spring neutral (moved by the active suspension)",
            |r, i| r.neutrals[i],
        )],
    },
    Group {
        over: Over::Once,
        fields: &[field(
            "V_set",
            Unit::MetrePerSecond,
            "speed set-point",
            |r, _| r.speed_setpoint,
        )],
    },
];

/// One column of a rover's row: its definition in [`ROW`] and the
/// coordinate or wheel it is of (0-based; `None` for a column of
/// [`Over::Once`]).
#[derive(Clone, Copy, Debug)]
struct Column {
    field: &'static Field,
    index: Option<usize>,
}

/// The columns of one rover's row (m suspension coordinates, k wheels), in
/// order: built once, then [`Columns::fill`] computes rows without
/// allocating.
#[derive(Clone, Debug)]
pub struct Columns {
    columns: Vec<Column>,
    names: Vec<String>,
    m: usize,
    wheels: usize,
}

impl Columns {
    /// The columns of a rover with `m` suspension coordinates and `wheels`
    /// wheels on rigid ground.
    pub fn new(m: usize, wheels: usize) -> Self {
        Self::on_ground(m, wheels, false)
    }

    /// The columns of a rover with `m` suspension coordinates and `wheels`
    /// wheels, on a soil when `soil` (its columns then included).
    pub fn on_ground(m: usize, wheels: usize, soil: bool) -> Self {
        let (mut columns, mut names) = (Vec::new(), Vec::new());
        for group in ROW {
            let count = match group.over {
                Over::Once => 1,
                Over::Coordinate => m,
                Over::Wheel => wheels,
                Over::SoilWheel if soil => wheels,
                Over::SoilWheel => 0,
            };
            for index in 0..count {
                for field in group.fields {
                    let name = match group.over {
                        Over::Once => field.name.to_string(),
                        Over::Coordinate => field.name.replace("{i}", &(index + 1).to_string()),
                        Over::Wheel | Over::SoilWheel => {
                            field.name.replace("{j}", &(index + 1).to_string())
                        }
                    };
                    names.push(name);
                    columns.push(Column {
                        field,
                        index: (group.over != Over::Once).then_some(index),
                    });
                }
            }
        }
        Columns {
            columns,
            names,
            m,
            wheels,
        }
    }

    /// Number of columns.
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Whether there are none (never: a row has at least `t`).
    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }

    /// The column names, in order: the CSV's header.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The position of the column named `name`.
    pub fn position(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// What each column is, in order (the meaning of docs/CLI.md's column
    /// table); the index a column is repeated over is its name's number.
    pub fn meanings(&self) -> Vec<&'static str> {
        self.columns.iter().map(|c| c.field.meaning).collect()
    }

    /// Each column's unit symbol; `coordinate_linear` tells which
    /// suspension coordinates are lengths (the others are angles).
    pub fn units(&self, coordinate_linear: &[bool]) -> Vec<&'static str> {
        self.columns
            .iter()
            .map(|c| {
                let linear = matches!(c.field.unit, Unit::Coordinate | Unit::CoordinateRate)
                    && c.index
                        .and_then(|i| coordinate_linear.get(i))
                        .copied()
                        .unwrap_or(false);
                c.field.unit.symbol(linear)
            })
            .collect()
    }

    /// Compute the row of `inputs` into `out` (one value per column).
    /// Allocates nothing.
    ///
    /// # Panics
    ///
    /// When `out` or an input is shorter than the rover's columns need: a
    /// caller's bug (the inputs of another rover), not a user's input.
    pub fn fill(&self, inputs: &RowInputs<'_>, out: &mut [f64]) {
        assert_eq!(
            out.len(),
            self.columns.len(),
            "a row of {} columns",
            self.columns.len()
        );
        debug_assert!(inputs.x.len() == 6 + self.m && inputs.wheels.len() == self.wheels);
        for (o, c) in out.iter_mut().zip(&self.columns) {
            *o = (c.field.value)(inputs, c.index.unwrap_or(0));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit as the column table of docs/CLI.md writes it.
    fn doc_unit(u: Unit) -> &'static str {
        match u {
            Unit::Coordinate => "rad or m",
            Unit::CoordinateRate => "rad/s or m/s",
            u => u.symbol(false),
        }
    }

    #[test]
    fn the_header_is_state_wheels_contact_commands_neutrals_set_point() {
        let c = Columns::new(2, 3);
        let names = c.names().join(",");
        assert_eq!(
            names,
            "t,X,Y,Z,phi,theta,psi,y1,y2,vx,vy,vz,Ox,Oy,Oz,dy1,dy2,\
             W1X,W1Y,W1Z,W2X,W2Y,W2Z,W3X,W3Y,W3Z,\
             H1X,H1Y,H1Z,Fn1,Fd1,Fc1,H2X,H2Y,H2Z,Fn2,Fd2,Fc2,H3X,H3Y,H3Z,Fn3,Fd3,Fc3,\
             tau1,tau2,tau3,delta1,delta2,delta3,y0_1,y0_2,V_set"
        );
        assert_eq!(c.position("Fn2"), Some(35));
        let units = c.units(&[false, true]);
        let unit = |n: &str| units[c.position(n).unwrap()];
        assert_eq!(
            [
                unit("y1"),
                unit("y2"),
                unit("dy1"),
                unit("dy2"),
                unit("y0_2")
            ],
            ["rad", "m", "rad/s", "m/s", "m"]
        );
        assert_eq!(
            [unit("Fc3"), unit("tau1"), unit("V_set")],
            ["N", "N·m", "m/s"]
        );
    }

    #[test]
    fn a_row_takes_each_value_from_its_input() {
        let c = Columns::new(1, 2);
        let x = [1.0, 2.0, 3.0, 0.1, 0.2, 0.3, 0.4];
        let w = [5.0, 6.0, 7.0, 0.5, 0.6, 0.7, 0.8];
        let wheels = [
            WheelState {
                centre: [10.0, 11.0, 12.0],
                ..Default::default()
            },
            WheelState {
                centre: [20.0, 21.0, 22.0],
                ..Default::default()
            },
        ];
        let reports = [
            WheelReport::default(),
            WheelReport {
                point: [30.0, 31.0, 32.0],
                normal: 33.0,
                drawbar: 34.0,
                lateral: 35.0,
                ..Default::default()
            },
        ];
        let inputs = RowInputs {
            t: 9.0,
            x: &x,
            w: &w,
            wheels: &wheels,
            reports: &reports,
            spins: &[],
            torques: &[1.5, 2.5],
            steering: &[0.0, -0.25],
            neutrals: &[0.45],
            speed_setpoint: 0.125,
        };
        let mut row = vec![f64::NAN; c.len()];
        c.fill(&inputs, &mut row);
        let at = |n: &str| row[c.position(n).unwrap()];
        assert_eq!(
            [at("t"), at("Z"), at("psi"), at("y1")],
            [9.0, 3.0, 0.3, 0.4]
        );
        assert_eq!([at("vx"), at("Oz"), at("dy1")], [5.0, 0.7, 0.8]);
        assert_eq!([at("W2X"), at("W2Z"), at("W1Y")], [20.0, 22.0, 11.0]);
        assert_eq!(
            [at("H2Y"), at("Fn2"), at("Fd2"), at("Fc2"), at("Fn1")],
            [31.0, 33.0, 34.0, 35.0, 0.0]
        );
        assert_eq!(
            [at("tau2"), at("delta2"), at("y0_1"), at("V_set")],
            [2.5, -0.25, 0.45, 0.125]
        );
    }

    /// docs/CLI.md's table of the columns is this table: a column added
    /// here and not there (or the reverse) fails.
    #[test]
    fn the_column_table_in_the_docs_lists_every_column() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/CLI.md");
        let doc = std::fs::read_to_string(path).unwrap();
        let documented: Vec<&str> = doc.lines().filter(|l| l.starts_with("| `")).collect();
        let expected: Vec<String> = ROW
            .iter()
            .flat_map(|g| g.fields)
            .map(|f| format!("| `{}` | {} | {} |", f.name, doc_unit(f.unit), f.meaning))
            .collect();
        assert_eq!(documented, expected, "docs/CLI.md, \"Output columns\"");
    }
}
