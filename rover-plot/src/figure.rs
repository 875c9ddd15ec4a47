//! The figures a run gets, their file names and sizes.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::coordinates::draw_coordinates;
use crate::draw_result::DrawResult;
use crate::labels::Labels;
use crate::run_data::RunData;
use crate::speed::draw_speed;
use crate::trajectory::{Projection, draw_trajectory};
use crate::wheel_histories::{WheelQuantity, draw_wheel_quantity};

/// One figure of a run; each is written as `<stem>.png` and `<stem>.svg`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Figure {
    /// Side view: G, wheel centres and contact points on the xz plane.
    TrajectoryXz,
    /// Top view: G, wheel centres and contact points on the xy plane.
    TrajectoryXy,
    /// Time histories of every generalized coordinate, one panel each.
    Coordinates,
    /// Motor torque of each wheel against time.
    Torques,
    /// Forward speed against its set-point.
    Speed,
    /// Normal force of each wheel against time.
    Forces,
}

impl Figure {
    /// Every figure, in the order [`crate::plot_run`] writes them.
    pub const ALL: [Figure; 6] = [
        Figure::TrajectoryXz,
        Figure::TrajectoryXy,
        Figure::Coordinates,
        Figure::Torques,
        Figure::Speed,
        Figure::Forces,
    ];

    /// File name without extension.
    pub fn stem(self) -> &'static str {
        match self {
            Figure::TrajectoryXz => "trajectory_xz",
            Figure::TrajectoryXy => "trajectory_xy",
            Figure::Coordinates => "coordinates",
            Figure::Torques => "torques",
            Figure::Speed => "speed",
            Figure::Forces => "forces",
        }
    }

    /// Width and height in pixels (PNG) or SVG user units.
    pub fn size(self) -> (u32, u32) {
        match self {
            Figure::TrajectoryXz => (1200, 600),
            Figure::TrajectoryXy => (1100, 850),
            Figure::Coordinates => (1400, 1000),
            Figure::Torques | Figure::Speed | Figure::Forces => (1000, 500),
        }
    }

    /// Draws the figure on `root` (any back end).
    pub(crate) fn draw<DB: DrawingBackend>(
        self,
        root: &DrawingArea<DB, Shift>,
        data: &RunData,
        labels: &Labels,
    ) -> DrawResult {
        match self {
            Figure::TrajectoryXz => draw_trajectory(root, data, labels, Projection::Xz),
            Figure::TrajectoryXy => draw_trajectory(root, data, labels, Projection::Xy),
            Figure::Coordinates => draw_coordinates(root, data, labels),
            Figure::Torques => draw_wheel_quantity(root, data, labels, WheelQuantity::Torque),
            Figure::Speed => draw_speed(root, data, labels),
            Figure::Forces => draw_wheel_quantity(root, data, labels, WheelQuantity::NormalForce),
        }
    }
}
