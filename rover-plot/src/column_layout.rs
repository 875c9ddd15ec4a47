//! Where the plotted quantities are in a run CSV: columns are found by name,
//! the number of suspension coordinates `m` and of wheels `n` are deduced from
//! the names (`y1..ym`, `W1X..WnX`), so added columns do not break plotting.

use std::collections::BTreeMap;
use std::path::Path;

use crate::PlotError;

/// Column positions (0-based) of one wheel's quantities.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct WheelColumns {
    /// `W{j}X, W{j}Y, W{j}Z`: wheel centre, inertial.
    pub centre: [usize; 3],
    /// `H{j}X, H{j}Y, H{j}Z`: contact point, inertial.
    pub contact: [usize; 3],
    /// `Fn{j}`: normal force.
    pub normal_force: usize,
    /// `tau{j}`: motor torque.
    pub torque: usize,
}

/// Column positions (0-based) of everything the plots draw.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct ColumnLayout {
    /// `t`.
    pub t: usize,
    /// `X, Y, Z`: position of G.
    pub g: [usize; 3],
    /// `phi, theta, psi`: roll, pitch, yaw.
    pub attitude: [usize; 3],
    /// `y1..ym`: suspension coordinates.
    pub y: Vec<usize>,
    /// `vx`: forward speed (body frame).
    pub vx: usize,
    /// `V_set`: speed set-point.
    pub v_set: usize,
    /// One entry per wheel, `W1..Wn`.
    pub wheels: Vec<WheelColumns>,
}

impl ColumnLayout {
    /// Finds every plotted column in `header` (the names, trimmed).
    ///
    /// Errors name the file, the missing or repeated column, and the plot
    /// that needs it.
    pub(crate) fn from_header(path: &Path, header: &[&str]) -> Result<Self, PlotError> {
        let mut by_name: BTreeMap<&str, usize> = BTreeMap::new();
        for (index, name) in header.iter().enumerate().filter(|(_, n)| !n.is_empty()) {
            if let Some(first) = by_name.insert(name, index) {
                return Err(PlotError::DuplicateColumn {
                    path: path.to_path_buf(),
                    column: (*name).to_string(),
                    first: first + 1,
                    second: index + 1,
                });
            }
        }
        let find = |column: &str, needed_for: &'static str| {
            by_name
                .get(column)
                .copied()
                .ok_or_else(|| PlotError::MissingColumn {
                    path: path.to_path_buf(),
                    column: column.to_string(),
                    needed_for,
                })
        };
        let three = |prefix: &str, needed_for: &'static str| -> Result<[usize; 3], PlotError> {
            Ok([
                find(&format!("{prefix}X"), needed_for)?,
                find(&format!("{prefix}Y"), needed_for)?,
                find(&format!("{prefix}Z"), needed_for)?,
            ])
        };

        let t = find("t", "every time history")?;
        let g = [
            find("X", "the trajectories and coordinates")?,
            find("Y", "the trajectories and coordinates")?,
            find("Z", "the trajectories and coordinates")?,
        ];
        let attitude = [
            find("phi", "the coordinates plot")?,
            find("theta", "the coordinates plot")?,
            find("psi", "the coordinates plot")?,
        ];
        let y = (1..)
            .map_while(|k| by_name.get(format!("y{k}").as_str()).copied())
            .collect();
        let vx = find("vx", "the speed plot")?;
        let v_set = find("V_set", "the speed plot")?;

        let wheel_count = (1..)
            .take_while(|j| by_name.contains_key(format!("W{j}X").as_str()))
            .count();
        if wheel_count == 0 {
            // Report the first wheel column as missing: a rover has wheels.
            find("W1X", "the trajectories (wheel centres)")?;
        }
        let wheels = (1..=wheel_count)
            .map(|j| {
                Ok(WheelColumns {
                    centre: three(&format!("W{j}"), "the trajectories (wheel centres)")?,
                    contact: three(&format!("H{j}"), "the trajectories (contact points)")?,
                    normal_force: find(&format!("Fn{j}"), "the forces plot")?,
                    torque: find(&format!("tau{j}"), "the torques plot")?,
                })
            })
            .collect::<Result<Vec<_>, PlotError>>()?;

        Ok(Self {
            t,
            g,
            attitude,
            y,
            vx,
            v_set,
            wheels,
        })
    }

    /// Every column this layout reads, each once, in ascending order.
    pub(crate) fn used_columns(&self) -> Vec<usize> {
        let mut used = vec![self.t, self.vx, self.v_set];
        used.extend(self.g);
        used.extend(self.attitude);
        used.extend(&self.y);
        for wheel in &self.wheels {
            used.extend(wheel.centre);
            used.extend(wheel.contact);
            used.push(wheel.normal_force);
            used.push(wheel.torque);
        }
        used.sort_unstable();
        used.dedup();
        used
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The header a run writes, for `m` coordinates and `n` wheels.
    fn header(m: usize, n: usize) -> Vec<String> {
        rover_runtime::row::Columns::new(m, n).names().to_vec()
    }

    fn layout(names: &[String]) -> Result<ColumnLayout, PlotError> {
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        ColumnLayout::from_header(Path::new("run.csv"), &refs)
    }

    #[test]
    fn counts_coordinates_and_wheels_from_the_names() {
        let l = layout(&header(3, 6)).unwrap();
        assert_eq!(l.y, vec![7, 8, 9]);
        assert_eq!(l.wheels.len(), 6);
        // t,X,Y,Z,phi,theta,psi (7) + y (3) + v,O (6) + dy (3) = 19: W1X.
        assert_eq!(l.wheels[0].centre, [19, 20, 21]);
        assert_eq!(l.vx, 10);
    }

    #[test]
    fn finds_columns_by_name_whatever_their_order() {
        let mut names = header(2, 4);
        names.reverse();
        names.insert(0, "extra".into());
        let l = layout(&names).unwrap();
        assert_eq!(names[l.t], "t");
        assert_eq!(names[l.wheels[3].torque], "tau4");
        assert_eq!(names[l.y[1]], "y2");
    }

    #[test]
    fn a_rover_without_suspension_coordinates_has_m_zero() {
        let l = layout(&header(0, 4)).unwrap();
        assert!(l.y.is_empty());
    }

    #[test]
    fn missing_and_duplicate_columns_are_named() {
        let mut names = header(2, 4);
        names.retain(|n| n != "H3Z");
        let e = layout(&names).unwrap_err().to_string();
        assert_eq!(
            e,
            "run.csv:1: no column `H3Z` in the header (needed for the trajectories (contact points)); \
             write the CSV with `rover simulate` or add the column"
        );
        let mut names = header(2, 4);
        names.push("vx".into());
        let e = layout(&names).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "run.csv:1: column `vx` appears twice (columns 10 and {}); rename or remove one of them",
                names.len()
            )
        );
        let mut names = header(2, 4);
        names.retain(|n| !n.starts_with('W'));
        let e = layout(&names).unwrap_err().to_string();
        assert!(e.contains("no column `W1X`"), "{e}");
    }
}
