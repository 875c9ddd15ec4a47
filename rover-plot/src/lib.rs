//! Plots of a rover simulation run, as a rover engineer reads them after the
//! run: [`plot_run`] reads the run CSV and writes each [`Figure`] as PNG and
//! SVG.
//!
//! # Input
//!
//! The run CSV has a header row; columns are found by name, so their order
//! does not matter and added columns are ignored. The plots read `t`, `X, Y,
//! Z` (G), `phi, theta, psi`, `y1..ym`, `vx`, `V_set`, and per wheel `j`
//! `W{j}X, W{j}Y, W{j}Z` (centre), `H{j}X, H{j}Y, H{j}Z` (contact point),
//! `Fn{j}` and `tau{j}`. The number of suspension coordinates `m` and of
//! wheels `n` are the longest runs `y1, y2, …` and `W1X, W2X, …` in the
//! header. SI units: m, rad, s, N, N·m. Only these cells are parsed: each
//! must be a finite number, and `t` must not decrease. A run cut short plots
//! what it has; a single row still plots.
//!
//! [`PlotMeta`] adds what the CSV does not say: the title, the names of the
//! suspension coordinates and which are angles, the wheel names, the end of
//! settling and the number of body outlines.
//!
//! # The figures
//!
//! - `trajectory_xz` (side view) and `trajectory_xy` (top view), as in the
//!   paper's Figs. 8, 13 and 16: the path of the centre of mass G (black), of
//!   each wheel centre (thick, one colour per wheel) and of its contact point
//!   (thin, a lighter shade of the same colour; it joins the centre while the
//!   wheel is airborne),
//!   projected on the plane, with **equal scales** on both axes so that
//!   heights and lateral offsets are seen in true proportion. Grey sketches
//!   show the body at a few instants (the convex hull of the wheel centres
//!   and a cross at G), evenly spaced from the end of settling to the end of
//!   the run; a dot marks the start and a grey circle G at the end of
//!   settling.
//! - `coordinates`, as in Figs. 9, 14 and 15: one small panel per
//!   generalized coordinate — X, Y, Z of G in m; roll φ, pitch θ and yaw ψ in
//!   degrees; each suspension coordinate in degrees if [`PlotMeta::angular`]
//!   says it is an angle, else in m — three panels a row (four past twelve
//!   panels).
//! - `torques`: the motor torque `tau{j}` of each wheel, N·m.
//! - `speed`: the body's forward speed `vx` (solid) against the set-point
//!   `V_set` (dashed), m/s.
//! - `forces`: the normal force `Fn{j}` of each wheel, N (zero when the wheel
//!   is off the ground).
//!
//! - `ruts_map` ([`plot_ruts`], for a run on ground that keeps ruts): the
//!   rut depth seen from above as a colour scale (pale: shallow, dark
//!   brown: the deepest; a colour bar in mm), and G's path over it.
//!
//! Legends sit in their own column right of the chart and never hide data.
//! Every time history shows a dashed vertical marker labelled "settled" at
//! [`PlotMeta::settle_time`] when it falls inside the run. Runs longer than
//! 4000 samples are thinned for drawing: time histories keep each bucket's
//! minimum and maximum of 4000 (no peak is lost), trajectories an even
//! stride of 2000 points.
//!
//! # Deterministic, and no system libraries
//!
//! The same CSV and metadata give byte-identical SVG and PNG files. plotters
//! is built **without** its default `ttf` feature, which loads fonts through
//! the system's fontconfig and freetype: text is drawn with DejaVu Sans
//! embedded in the binary (the `dejavu` crate) and registered with plotters'
//! `ab_glyph` back end, PNGs are encoded by the `png` crate. So a fresh
//! machine needs no font or system library; `cargo tree -p rover-plot | grep
//! -i -E "font-kit|fontconfig|freetype"` prints nothing. SVG text names the
//! `sans-serif` family and is rendered by the viewer.
#![warn(missing_docs)]

mod axis_range;
mod chart;
mod column_layout;
mod convex_hull;
mod coordinates;
mod csv_columns;
mod decimate;
mod draw_result;
mod error;
mod estimate_plot;
mod figure;
mod font;
mod labels;
mod legend;
mod meta;
mod plot_run;
mod render;
mod run_data;
mod rut_map;
mod speed;
mod style;
mod tick_label;
mod time_panel;
mod trajectory;
mod wheel_histories;

pub use chart::{Series, line_chart};
pub use error::PlotError;
pub use estimate_plot::plot_estimate;
pub use figure::Figure;
pub use meta::PlotMeta;
pub use plot_run::plot_run;
pub use rut_map::{MAX_BLOCKS, RutImage, plot_ruts};
