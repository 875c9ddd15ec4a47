//! The figure of a state estimate (`rover estimate`): the estimate with
//! its ±1σ band, dead reckoning and, when known, the truth, for roll,
//! pitch, yaw, the first suspension coordinate and the forward speed, and
//! each estimator's horizontal position error.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::PlotError;
use crate::csv_columns::read_columns;
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::render::{Drawing, write_drawing};
use crate::style::TITLE_SIZE;
use crate::time_panel::{Line, TimePanel, draw_time_panel};

const STEM: &str = "estimate";
const SIZE: (u32, u32) = (1500, 900);
const TRUTH: RGBColor = RGBColor(0, 0, 0);
const FILTER: RGBColor = RGBColor(31, 119, 180);
const BAND: RGBColor = RGBColor(150, 190, 225);
const BASELINE: RGBColor = RGBColor(230, 120, 20);

/// The quantities drawn, as the CSVs name them.
const DRAWN: [&str; 7] = ["phi", "theta", "psi", "y1", "vx", "X", "Y"];

/// One file's columns: `t` and [`DRAWN`], with the 1σ of each when asked.
struct Histories {
    t: Vec<f64>,
    values: Vec<Vec<f64>>,
    sigma: Vec<Vec<f64>>,
}

impl Histories {
    fn read(path: &Path, with_sigma: bool) -> Result<Self, PlotError> {
        let mut wanted: Vec<String> = std::iter::once("t".to_string())
            .chain(DRAWN.iter().map(|s| s.to_string()))
            .collect();
        if with_sigma {
            wanted.extend(DRAWN.iter().map(|s| format!("sigma_{s}")));
        }
        let mut at = Vec::new();
        let mut columns =
            read_columns(path, |names| {
                for w in &wanted {
                    let k = names.iter().position(|n| n == w).ok_or_else(|| {
                        PlotError::MissingColumn {
                            path: path.to_path_buf(),
                            column: w.clone(),
                            needed_for: "the estimate's figure",
                        }
                    })?;
                    at.push(k);
                }
                Ok((at[0], at.clone()))
            })?;
        let mut take = |k: usize| std::mem::take(&mut columns[at[k]]);
        let t = take(0);
        let values = (1..=DRAWN.len()).map(&mut take).collect();
        let sigma = if with_sigma {
            (DRAWN.len() + 1..=2 * DRAWN.len()).map(&mut take).collect()
        } else {
            Vec::new()
        };
        Ok(Self { t, values, sigma })
    }

    /// The horizontal distance from `truth` at each of the truth's times
    /// that this history also has.
    fn drift(&self, truth: &Histories) -> (Vec<f64>, Vec<f64>) {
        let (mut t, mut d) = (Vec::new(), Vec::new());
        for (k, &tt) in truth.t.iter().enumerate() {
            let i = self.t.partition_point(|s| *s < tt - 1e-9 * (1.0 + tt));
            if i < self.t.len() && (self.t[i] - tt).abs() <= 1e-9 * (1.0 + tt) {
                t.push(tt);
                let dx = self.values[5][i] - truth.values[5][k];
                let dy = self.values[6][i] - truth.values[6][k];
                d.push(dx.hypot(dy));
            }
        }
        (t, d)
    }
}

/// Draws `estimate.png` and `estimate.svg` into `out_dir` from the
/// filter's `estimate.csv`, dead reckoning's `dead_reckoning.csv` and,
/// when given, the truth's `run.csv`; `angular` says whether the first
/// suspension coordinate is an angle (drawn in degrees). The paths written.
pub fn plot_estimate(
    estimate: &Path,
    baseline: &Path,
    truth: Option<&Path>,
    out_dir: &Path,
    title: &str,
    angular: bool,
) -> Result<Vec<PathBuf>, PlotError> {
    crate::font::register_embedded_font();
    let drawing = EstimateDrawing {
        filter: Histories::read(estimate, true)?,
        baseline: Histories::read(baseline, false)?,
        truth: truth.map(|p| Histories::read(p, false)).transpose()?,
        title: title.to_string(),
        angular,
    };
    write_drawing(&drawing, STEM, SIZE, out_dir)
}

struct EstimateDrawing {
    filter: Histories,
    baseline: Histories,
    truth: Option<Histories>,
    title: String,
    angular: bool,
}

impl EstimateDrawing {
    /// The panel of quantity `q` (an index into [`DRAWN`]) scaled by `scale`.
    fn panel(&self, q: usize, caption: &str, unit: &str, scale: f64) -> TimePanel<'_> {
        let f = &self.filter;
        let scaled = |v: &[f64]| v.iter().map(|x| x * scale).collect::<Vec<_>>();
        let band = |sign: f64| {
            f.values[q]
                .iter()
                .zip(&f.sigma[q])
                .map(|(v, s)| (v + sign * s) * scale)
                .collect::<Vec<_>>()
        };
        let mut lines = Vec::new();
        if let Some(t) = &self.truth {
            lines.push(line("truth", TRUTH, false, &t.t, scaled(&t.values[q])));
        }
        lines.push(line(
            "model-based EKF",
            FILTER,
            false,
            &f.t,
            scaled(&f.values[q]),
        ));
        lines.push(line("EKF ± 1σ", BAND, true, &f.t, band(1.0)));
        lines.push(Line {
            label: None,
            ..line("", BAND, true, &f.t, band(-1.0))
        });
        let b = &self.baseline;
        lines.push(line(
            "dead reckoning",
            BASELINE,
            false,
            &b.t,
            scaled(&b.values[q]),
        ));
        TimePanel {
            caption: caption.to_string(),
            y_desc: format!("{} [{unit}]", DRAWN[q]),
            lines,
        }
    }

    /// Each estimator's horizontal position error, with the truth.
    fn drift_panel(&self, truth: &Histories) -> (TimePanel<'_>, [Vec<f64>; 2]) {
        let (tf, df) = self.filter.drift(truth);
        let (tb, db) = self.baseline.drift(truth);
        let panel = TimePanel {
            caption: "horizontal position error".into(),
            y_desc: "|Δ(X, Y)| [m]".into(),
            lines: vec![
                line("model-based EKF", FILTER, false, &[], df),
                line("dead reckoning", BASELINE, false, &[], db),
            ],
        };
        (panel, [tf, tb])
    }
}

fn line<'a>(
    label: &str,
    colour: RGBColor,
    dashed: bool,
    t: &'a [f64],
    values: Vec<f64>,
) -> Line<'a> {
    Line {
        label: Some(label.to_string()),
        colour,
        dashed,
        t,
        values,
    }
}

impl Drawing for EstimateDrawing {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        root.fill(&WHITE).map_err(failed)?;
        let area = root
            .titled(
                &format!("{} — state estimate", self.title),
                (FAMILY, TITLE_SIZE),
            )
            .map_err(failed)?;
        let panels = area.split_evenly((2, 3));
        let end = self.filter.t.last().copied().unwrap_or(0.0);
        let span = self.filter.t.first().copied().unwrap_or(0.0)..end.max(1e-9);
        let deg = 180.0 / std::f64::consts::PI;
        let (unit, scale) = if self.angular {
            ("°", deg)
        } else {
            ("m", 1.0)
        };
        let quantities = [
            self.panel(0, "roll", "°", deg),
            self.panel(1, "pitch", "°", deg),
            self.panel(2, "yaw", "°", deg),
            self.panel(3, "first suspension coordinate", unit, scale),
            self.panel(4, "forward speed", "m/s", 1.0),
        ];
        for (panel, area) in quantities.iter().zip(&panels) {
            draw_time_panel(area, panel, span.clone(), None)?;
        }
        if let Some(truth) = &self.truth {
            let (mut panel, times) = self.drift_panel(truth);
            for (l, t) in panel.lines.iter_mut().zip(&times) {
                l.t = t;
            }
            draw_time_panel(&panels[5], &panel, span, None)?;
        }
        Ok(())
    }
}
