//! What the CSV does not say: names, which coordinates are angles, the title
//! and the end of settling.

/// Labels and options for the plots of one run.
///
/// Empty vectors mean "use the defaults": suspension coordinates named
/// `y1..ym` and plotted as lengths (m), wheels named `W1..Wn`. When given,
/// each vector must have one entry per coordinate or per wheel of the CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotMeta {
    /// Figure title, e.g. the rover and scenario names. Empty: the CSV's file stem.
    pub title: String,
    /// Names of the suspension coordinates `y1..ym`, in order.
    pub coordinate_names: Vec<String>,
    /// For each suspension coordinate, whether it is an angle (rad in the CSV,
    /// plotted in degrees) rather than a length (m).
    pub angular: Vec<bool>,
    /// Names of the wheels in the description's order (e.g. `FL`, `FR`, …).
    pub wheel_names: Vec<String>,
    /// End of the settling phase, s: a dashed vertical marker on every time
    /// history, and a marker on the trajectories where G was at that time.
    /// 0 (or a time outside the run) draws no marker.
    pub settle_time: f64,
    /// How many instants (evenly spaced from the end of settling to the end of
    /// the run) get a sketch of the body outline on the trajectory plots; 0: none.
    pub outline_instants: usize,
}

impl Default for PlotMeta {
    fn default() -> Self {
        Self {
            title: String::new(),
            coordinate_names: Vec::new(),
            angular: Vec::new(),
            wheel_names: Vec::new(),
            settle_time: 0.0,
            outline_instants: 4,
        }
    }
}
