//! One terrain for every roughness claim of the paper: the runs each claim
//! reads, over several seeds; the claims judged on their mean; the search
//! over a small grid of fields, stored as a CSV of every run's numbers.

use std::fmt::Write as _;
use std::path::Path;

use rayon::prelude::*;
use rover_scenario::output::Status;

use super::claims::Judged;
use super::runs::{ACTIVE, Case, Field, ackermann, deviations, other, rough_ratio, run_case, slip};
use crate::error::CliError;

/// Seeds of every roughness figure.
pub const SEEDS: [u64; 5] = [1, 2, 3, 4, 5];

/// The grid searched: node amplitudes × node spacings.
pub const AMPLITUDES: [f64; 3] = [0.25, 0.35, 0.5];
/// Node spacings of the grid \[m\].
pub const SPACINGS: [f64; 4] = [0.3, 0.4, 0.5, 0.7];

/// The field of the whole report: the grid's best compromise (the report's
/// search table; `rover reproduce` fails when the search ranks another
/// setting above it).
pub const CHOSEN: Field = Field {
    amplitude: 0.25,
    spacing: 0.7,
};

/// Roughness values of Fig. 6 (the paper's, without the flat case).
pub const FIG6_ROUGHNESS: [f64; 4] = [0.1, 0.2, 0.5, 1.0];
/// Speeds of Fig. 7 \[m/s\], at Z_R = [`FIG7_ROUGHNESS`].
pub const FIG7_SPEEDS: [f64; 5] = [0.05, 0.1, 0.2, 0.5, 1.0];
/// The roughness of Fig. 7.
pub const FIG7_ROUGHNESS: f64 = 0.3;
/// Front-left steering angle of the searched Figs. 6–7 runs \[deg\].
pub const SEARCH_DELTA: f64 = 20.0;
/// Duration of the Examples 1 runs \[s\]: 6 s settling and 40 s moving
/// (about 2 m at 0.05 m/s, the paper's "travelled distance of about 2 m").
pub const EXAMPLE1_DURATION: f64 = 46.0;
/// Duration of the Fig. 15 runs \[s\] (the paper's 150 s).
pub const FIG15_DURATION: f64 = 150.0;
/// Duration of the Figs. 11–12 runs \[s\]: 6 s settling and 34 s moving.
pub const FIG11_DURATION: f64 = 40.0;
/// The roughness of the paper's Fig. 11 figures (Z_R = 0.3, V = 0.1 m/s,
/// Δτ = 0.2 N·m), at which the search runs the four levels.
pub const FIG11_CLAIM_ROUGHNESS: f64 = 0.3;
/// Speed of the Figs. 11–12 runs \[m/s\].
pub const FIG11_SPEED: f64 = 0.1;
/// Differential torque of the Figs. 11–12 runs \[N·m\].
pub const FIG11_DELTA_TAU: f64 = 0.2;
/// The fidelity levels of Figs. 11–12, the full model first.
pub const LEVELS: [&str; 4] = ["full", "simplified", "linearized", "quasi_static"];
/// "Quite close" (Fig. 12): a reduced level's largest deviation from the
/// full model in X and in Y \[m\] ...
pub const CLOSE_M: f64 = 0.1;
/// ... and in roll, pitch and yaw \[deg\].
pub const CLOSE_DEG: f64 = 3.0;

/// How long, and over which seeds, the claims' runs go: the report's
/// ([`FULL`]) or the quick form's ([`QUICK`]).
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    pub seeds: &'static [u64],
    /// Example 1's Figs. 5–7 runs \[s\].
    pub example1: f64,
    /// Fig. 15's runs \[s\].
    pub fig15: f64,
    /// The Figs. 11–12 runs \[s\].
    pub fig11: f64,
}

/// The report's runs.
pub const FULL: Plan = Plan {
    seeds: &SEEDS,
    example1: EXAMPLE1_DURATION,
    fig15: FIG15_DURATION,
    fig11: FIG11_DURATION,
};

/// The quick form's: one seed; Example 1 drives 30 s instead of 40 s,
/// Fig. 15 runs 60 s instead of 150 s, Figs. 11–12 drive 20 s instead of
/// 34 s.
pub const QUICK: Plan = Plan {
    seeds: &[1],
    example1: 36.0,
    fig15: 60.0,
    fig11: 26.0,
};

/// What one run gives the claims.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    pub field: Field,
    pub seed: u64,
    /// `fig6_zr<Z_R>`, `fig7_v<V>`, `fig15_passive`, `fig15_active`,
    /// `fig11_<level>`.
    pub case: String,
    pub completed: bool,
    /// Where the run ended \[s\].
    pub t_end: f64,
    /// R/R_k on the rough part (Ackermann runs that completed).
    pub ratio: Option<f64>,
    pub max_roll_deg: f64,
    pub max_pitch_deg: f64,
    /// Largest yaw change beyond the usual turning in 2 s \[deg\].
    pub max_yaw_change_deg: f64,
    /// The first sudden slide: path length from the end of settling \[m\].
    pub slide_distance_m: Option<f64>,
    /// ... its time \[s\].
    pub slide_t: Option<f64>,
    /// A reduced level's largest deviation from the full model of the same
    /// seed (Fig. 12): X, Y, Z \[m\], roll, pitch, yaw \[deg\]; `None` for
    /// the other cases, or when the full run stopped.
    pub deviation: Option<[f64; 6]>,
}

impl Record {
    fn of(field: Field, seed: u64, case: &str, c: &Case) -> Result<Self, CliError> {
        let s = &c.summary;
        let slide = s.slide.as_ref();
        let sudden = slide.and_then(|sl| sl.sudden.as_ref());
        Ok(Self {
            field,
            seed,
            case: case.into(),
            completed: s.status == Status::Completed,
            t_end: s.t_end,
            ratio: rough_ratio(c)?,
            max_roll_deg: s.max_roll_deg,
            max_pitch_deg: s.max_pitch_deg,
            max_yaw_change_deg: slide.map_or(0.0, |sl| sl.max_yaw_change_deg),
            slide_distance_m: sudden.map(|x| x.distance_m),
            slide_t: sudden.map(|x| x.t),
            deviation: None,
        })
    }

    /// The largest deviation in X or Y \[m\].
    pub fn position_deviation(&self) -> Option<f64> {
        self.deviation.map(|d| d[0].max(d[1]))
    }

    /// The largest deviation in roll, pitch or yaw \[deg\].
    pub fn attitude_deviation(&self) -> Option<f64> {
        self.deviation.map(|d| d[3].max(d[4]).max(d[5]))
    }
}

/// The cases of one seed: (name, rover, scenario text). The quasi-static
/// case follows the full case's path (`fig11_full.csv` beside it).
pub fn cases(field: Field, seed: u64, plan: &Plan) -> Vec<(String, &'static str, String)> {
    let mut out = Vec::new();
    for z in FIG6_ROUGHNESS {
        out.push((
            format!("fig6_zr{z}"),
            "exomars",
            ackermann(&field.terrain(z, seed), 0.05, SEARCH_DELTA, plan.example1),
        ));
    }
    for v in FIG7_SPEEDS {
        out.push((
            format!("fig7_v{v}"),
            "exomars",
            ackermann(
                &field.terrain(FIG7_ROUGHNESS, seed),
                v,
                SEARCH_DELTA,
                plan.example1,
            ),
        ));
    }
    for (name, extra) in [("fig15_passive", ""), ("fig15_active", ACTIVE)] {
        out.push((
            name.into(),
            "swing4",
            slip(&field.terrain(0.2, seed), 0.05, 0.2, plan.fig15, "") + extra,
        ));
    }
    let rough = field.terrain(FIG11_CLAIM_ROUGHNESS, seed);
    for level in LEVELS {
        let mut extra = format!("fidelity = \"{level}\"\n");
        if level == "quasi_static" {
            extra.push_str("path_from = \"fig11_full.csv\"\n");
        }
        out.push((
            format!("fig11_{level}"),
            "swing4",
            slip(&rough, FIG11_SPEED, FIG11_DELTA_TAU, plan.fig11, &extra),
        ));
    }
    out
}

/// Directory of a field's runs under `work`.
pub fn field_dir(work: &Path, field: Field) -> std::path::PathBuf {
    work.join(format!("a{}_L{}", field.amplitude, field.spacing))
}

/// Run every case of `field` over the plan's seeds (in parallel; the
/// quasi-static cases after the full ones whose path they follow): the
/// records and the cases (for plotting), keyed by (seed, case name).
pub fn evaluate(field: Field, work: &Path, plan: &Plan) -> Result<Vec<(Record, Case)>, CliError> {
    let dir = field_dir(work, field);
    let jobs: Vec<(u64, String, &'static str, String)> = plan
        .seeds
        .iter()
        .flat_map(|&seed| {
            cases(field, seed, plan)
                .into_iter()
                .map(move |(name, rover, text)| (seed, name, rover, text))
        })
        .collect();
    let (later, first): (Vec<_>, Vec<_>) =
        jobs.into_iter().partition(|j| j.1 == "fig11_quasi_static");
    let run = |(seed, name, rover, text): &(u64, String, &'static str, String)| {
        let case = run_case(rover, text, &dir.join(format!("seed{seed}/{name}.csv")))?;
        Ok((Record::of(field, *seed, name, &case)?, case))
    };
    let mut done: Vec<(Record, Case)> =
        first.par_iter().map(run).collect::<Result<_, CliError>>()?;
    let more: Vec<(Record, Case)> = later.par_iter().map(run).collect::<Result<_, CliError>>()?;
    done.extend(more);
    // Fig. 12: each reduced level against the full model of its seed.
    let full: Vec<(u64, bool, std::path::PathBuf)> = done
        .iter()
        .filter(|(r, _)| r.case == "fig11_full")
        .map(|(r, c)| (r.seed, r.completed, c.csv.clone()))
        .collect();
    for (r, c) in &mut done {
        if !r.case.starts_with("fig11_") || r.case == "fig11_full" {
            continue;
        }
        if let Some((_, true, csv)) = full.iter().find(|f| f.0 == r.seed) {
            r.deviation = Some(deviations(csv, &c.csv)?);
        }
    }
    Ok(done)
}

/// Mean and spread of a quantity over seeds; runs that stopped are counted
/// apart.
#[derive(Clone, Debug, Default)]
pub struct Sample {
    pub values: Vec<f64>,
    pub stopped: usize,
}

impl Sample {
    pub fn mean(&self) -> Option<f64> {
        (!self.values.is_empty())
            .then(|| self.values.iter().sum::<f64>() / self.values.len() as f64)
    }

    /// Sample standard deviation (0 for one value).
    pub fn sd(&self) -> Option<f64> {
        let m = self.mean()?;
        let n = self.values.len();
        Some(if n < 2 {
            0.0
        } else {
            (self.values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        })
    }

    /// `mean ± sd` with `digits` decimals, and how many runs stopped.
    pub fn show(&self, digits: usize) -> String {
        let mut s = match (self.mean(), self.sd()) {
            (Some(m), Some(sd)) => format!("{m:.digits$} ± {sd:.digits$}"),
            _ => "—".into(),
        };
        if self.stopped > 0 {
            let _ = write!(
                s,
                " ({} of {} stopped)",
                self.stopped,
                self.stopped + self.values.len()
            );
        }
        s
    }
}

/// A field's records gathered per quantity.
pub struct Outcome {
    pub field: Field,
    pub records: Vec<Record>,
}

impl Outcome {
    pub fn new(field: Field, records: Vec<Record>) -> Self {
        Self { field, records }
    }

    pub fn of_case(&self, case: &str) -> impl Iterator<Item = &Record> {
        self.records.iter().filter(move |r| r.case == case)
    }

    /// R/R_k of a case over the seeds.
    pub fn ratio(&self, case: &str) -> Sample {
        let mut s = Sample::default();
        for r in self.of_case(case) {
            match r.ratio {
                Some(v) => s.values.push(v),
                None => s.stopped += 1,
            }
        }
        s
    }

    /// A quantity of a case over the seeds (runs that stopped included:
    /// their largest angles up to the stop).
    pub fn quantity(&self, case: &str, f: impl Fn(&Record) -> f64) -> Sample {
        let mut s = Sample::default();
        for r in self.of_case(case) {
            s.values.push(f(r));
        }
        s
    }

    /// A reduced level's deviation from the full model over the seeds
    /// (`f` picks it from a record); runs that stopped, or whose full run
    /// stopped, are counted apart.
    pub fn deviation_of(&self, case: &str, f: impl Fn(&Record) -> Option<f64>) -> Sample {
        let mut s = Sample::default();
        for r in self.of_case(case) {
            match f(r).filter(|_| r.completed) {
                Some(v) => s.values.push(v),
                None => s.stopped += 1,
            }
        }
        s
    }

    /// Seeds (and the distance after settling) of the case's sudden slides.
    pub fn slides(&self, case: &str) -> Vec<(u64, f64)> {
        self.of_case(case)
            .filter_map(|r| r.slide_distance_m.map(|d| (r.seed, d)))
            .collect()
    }

    /// How many seeds ran the case.
    pub fn seeds(&self, case: &str) -> usize {
        self.of_case(case).count()
    }

    /// |R/R_k − 1| averaged over the given cases' seeds, a stopped run
    /// counting as [`BREAKDOWN`] (kinematic steering has failed there).
    fn deviation(&self, cases: &[String]) -> f64 {
        let mut v = Vec::new();
        for c in cases {
            for r in self.of_case(c) {
                v.push(r.ratio.map_or(BREAKDOWN, |x| (x - 1.0).abs()));
            }
        }
        if v.is_empty() {
            return 0.0;
        }
        v.iter().sum::<f64>() / v.len() as f64
    }

    /// Every claim judged on this field.
    pub fn claims(&self) -> Vec<Claim> {
        CLAIMS.iter().map(|c| (c.judge)(self, c)).collect()
    }

    /// Claims that hold, and the summed shortfall of those that do not.
    pub fn score(&self) -> (usize, f64) {
        let c = self.claims();
        (
            c.iter().filter(|c| c.holds).count(),
            c.iter().map(|c| c.shortfall).sum(),
        )
    }
}

/// |R/R_k − 1| from which kinematic steering counts as unacceptable.
pub const BREAKDOWN: f64 = 0.1;
/// The paper's band of R/R_k on moderate ground, to its two decimals.
pub const BAND: (f64, f64) = (0.945, 0.995);
/// Its width: the band holds when the mean over the seeds is in it and
/// the seeds scatter by no more than this (standard deviation), so that a
/// mean does not land in the band by seeds far above and below cancelling.
pub const BAND_WIDTH: f64 = 0.05;

/// A claim of the paper judged on one field.
#[derive(Clone, Debug)]
pub struct Claim {
    pub id: &'static str,
    pub figure: &'static str,
    pub paper: &'static str,
    pub threshold: &'static str,
    pub holds: bool,
    /// Our numbers.
    pub ours: String,
    /// How far from holding, in units of the claim's own scale (0 when it
    /// holds).
    pub shortfall: f64,
}

impl Claim {
    /// The claim in the report's list of every claim.
    pub fn judged(&self) -> Judged {
        Judged {
            id: self.id.into(),
            figure: self.figure.into(),
            paper: self.paper.into(),
            threshold: self.threshold.into(),
            ours: self.ours.clone(),
            holds: self.holds,
            gate: true,
        }
    }
}

/// A claim's text and its judge.
pub struct ClaimSpec {
    /// Its key in the stored record of which claims hold.
    pub id: &'static str,
    pub figure: &'static str,
    pub paper: &'static str,
    /// How we judge it.
    pub threshold: &'static str,
    judge: fn(&Outcome, &ClaimSpec) -> Claim,
}

impl ClaimSpec {
    fn verdict(&self, holds: bool, ours: String, shortfall: f64) -> Claim {
        Claim {
            id: self.id,
            figure: self.figure,
            paper: self.paper,
            threshold: self.threshold,
            holds,
            ours,
            shortfall: if holds { 0.0 } else { shortfall.max(1e-3) },
        }
    }
}

/// The paper's roughness claims (section 7), each judged on the mean over
/// the seeds.
pub const CLAIMS: [ClaimSpec; 9] = [
    ClaimSpec {
        id: "fig6_band",
        figure: "Fig. 6",
        paper: "R ≈ 0.95–0.99·R_k on moderate ground (Z_R = 0.1, 0.2)",
        threshold: "at δ₁ = 20°, at both Z_R: mean over the seeds in 0.945–0.995, spread (sd) ≤ 0.05, no run stopped",
        judge: |o, c| {
            let mut ours = Vec::new();
            let mut miss = 0.0f64;
            for z in [0.1, 0.2] {
                let s = o.ratio(&format!("fig6_zr{z}"));
                ours.push(format!("{}: {}", z, s.show(3)));
                miss += match (s.mean(), s.sd()) {
                    (Some(m), Some(sd)) if s.stopped == 0 => {
                        ((BAND.0 - m).max(m - BAND.1)).max(0.0) / BAND_WIDTH
                            + (sd - BAND_WIDTH).max(0.0) / BAND_WIDTH
                    }
                    _ => 1.0,
                };
            }
            c.verdict(miss == 0.0, ours.join("; "), miss)
        },
    },
    ClaimSpec {
        id: "fig6_breakdown",
        figure: "Fig. 6",
        paper: "kinematic steering unacceptable at Z_R = 0.5 and 1",
        threshold: "at δ₁ = 20°, at each Z_R: mean |R/R_k − 1| ≥ 0.1 over the seeds (a stopped run counts 0.1)",
        judge: |o, c| {
            let mut ours = Vec::new();
            let mut miss = 0.0f64;
            for z in [0.5, 1.0] {
                let name = format!("fig6_zr{z}");
                let d = o.deviation(std::slice::from_ref(&name));
                ours.push(format!("{z}: {}", o.ratio(&name).show(3)));
                miss += (BREAKDOWN - d).max(0.0) / BREAKDOWN;
            }
            c.verdict(miss == 0.0, ours.join("; "), miss)
        },
    },
    ClaimSpec {
        id: "fig7_speed",
        figure: "Fig. 7",
        paper: "at Z_R = 0.3 the agreement worsens with speed",
        threshold: "mean |R/R_k − 1| at 0.5–1 m/s above that at 0.05–0.1 m/s (δ₁ = 20°; a stopped run counts 0.1)",
        judge: |o, c| {
            let names =
                |vs: &[f64]| -> Vec<String> { vs.iter().map(|v| format!("fig7_v{v}")).collect() };
            let slow = o.deviation(&names(&[0.05, 0.1]));
            let fast = o.deviation(&names(&[0.5, 1.0]));
            c.verdict(
                fast > slow,
                format!("mean |R/R_k − 1| {slow:.3} at 0.05–0.1 m/s, {fast:.3} at 0.5–1 m/s"),
                (slow - fast) / BREAKDOWN,
            )
        },
    },
    ClaimSpec {
        id: "fig15_passive_pitch",
        figure: "Fig. 15",
        paper: "passive pitch in excess of 10° (Z_R = 0.2)",
        threshold: "mean over the seeds of the largest pitch > 10°",
        judge: |o, c| {
            let s = o.quantity("fig15_passive", |r| r.max_pitch_deg);
            let m = s.mean().unwrap_or(0.0);
            c.verdict(m > 10.0, format!("{}°", s.show(1)), (10.0 - m) / 10.0)
        },
    },
    ClaimSpec {
        id: "fig15_passive_slide",
        figure: "Figs. 15–16",
        paper: "the passive rover's rear wheels slide suddenly after about 1 m",
        threshold: "a sudden slide (yaw change ≥ 5° beyond the usual turning within 2 s) on at least one seed",
        judge: |o, c| {
            let slides = o.slides("fig15_passive");
            let n = o.seeds("fig15_passive");
            let change = o.quantity("fig15_passive", |r| r.max_yaw_change_deg);
            c.verdict(
                !slides.is_empty(),
                format!(
                    "{} of {n} seeds{}; largest yaw change in 2 s {}°",
                    slides.len(),
                    if slides.is_empty() {
                        String::new()
                    } else {
                        format!(
                            " ({})",
                            slides
                                .iter()
                                .map(|(s, d)| format!("seed {s} at {d:.2} m"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        )
                    },
                    change.show(1)
                ),
                1.0,
            )
        },
    },
    ClaimSpec {
        id: "fig15_active_attitude",
        figure: "Fig. 15",
        paper: "active suspension: roll and pitch always much smaller than 1°",
        threshold: "mean over the seeds of the largest roll and of the largest pitch < 1°",
        judge: |o, c| {
            let roll = o.quantity("fig15_active", |r| r.max_roll_deg);
            let pitch = o.quantity("fig15_active", |r| r.max_pitch_deg);
            let worst = roll
                .mean()
                .unwrap_or(90.0)
                .max(pitch.mean().unwrap_or(90.0));
            c.verdict(
                worst < 1.0,
                format!("roll {}°, pitch {}°", roll.show(2), pitch.show(2)),
                worst - 1.0,
            )
        },
    },
    ClaimSpec {
        id: "fig15_active_no_slide",
        figure: "Figs. 15–16",
        paper: "active suspension prevents the slide",
        threshold: "no sudden slide on any seed",
        judge: |o, c| {
            let slides = o.slides("fig15_active");
            let n = o.seeds("fig15_active");
            let change = o.quantity("fig15_active", |r| r.max_yaw_change_deg);
            c.verdict(
                slides.is_empty(),
                format!(
                    "{} of {n} seeds slide; largest yaw change in 2 s {}°",
                    slides.len(),
                    change.show(1)
                ),
                slides.len() as f64 / n.max(1) as f64,
            )
        },
    },
    ClaimSpec {
        id: "fig11_quasi_static_converges",
        figure: "Fig. 11",
        paper: "the quasi-static level runs the Z_R = 0.3, V = 0.1 m/s case (in 15 % of the full model's time)",
        threshold: "Example 2, Δτ = 0.2 N·m, the full model's path imposed: the run completes on every seed",
        judge: |o, c| {
            let runs: Vec<&Record> = o.of_case("fig11_quasi_static").collect();
            let stopped: Vec<String> = runs
                .iter()
                .filter(|r| !r.completed)
                .map(|r| format!("seed {} at t = {:.1} s", r.seed, r.t_end))
                .collect();
            let n = runs.len();
            let mut ours = format!("{} of {n} seeds complete", n - stopped.len());
            if !stopped.is_empty() {
                let _ = write!(ours, " (stopped: {})", stopped.join(", "));
            }
            c.verdict(
                n > 0 && stopped.is_empty(),
                ours,
                stopped.len() as f64 / n.max(1) as f64,
            )
        },
    },
    ClaimSpec {
        id: "fig12_close_zr0.3",
        figure: "Fig. 12",
        paper: "the simplified and linearized levels' results are quite close to the full model's (shown at Z_R = 0.1; judged here on Fig. 11's case, Z_R = 0.3)",
        threshold: "Example 2, V = 0.1 m/s, Δτ = 0.2 N·m: each level completes, and the mean over the seeds of its largest deviation from the full model is within 0.1 m in X and Y and within 3° in roll, pitch and yaw",
        judge: |o, c| {
            let mut ours = Vec::new();
            let mut miss = 0.0f64;
            for level in ["simplified", "linearized"] {
                let case = format!("fig11_{level}");
                let pos = o.deviation_of(&case, Record::position_deviation);
                let att = o.deviation_of(&case, Record::attitude_deviation);
                ours.push(format!(
                    "{level}: X/Y {} m, roll/pitch/yaw {}°",
                    pos.show(2),
                    att.show(1)
                ));
                let n = (pos.values.len() + pos.stopped).max(1) as f64;
                miss += pos.stopped as f64 / n;
                match (pos.mean(), att.mean()) {
                    (Some(p), Some(a)) => {
                        miss += (p / CLOSE_M - 1.0).max(0.0) + (a / CLOSE_DEG - 1.0).max(0.0);
                    }
                    _ => miss += 1.0,
                }
            }
            c.verdict(miss == 0.0, ours.join("; "), miss)
        },
    },
];

/// The grid of the search.
pub fn grid() -> Vec<Field> {
    AMPLITUDES
        .iter()
        .flat_map(|&amplitude| {
            SPACINGS
                .iter()
                .map(move |&spacing| Field { amplitude, spacing })
        })
        .collect()
}

const HEADER: &str = "amplitude,spacing,seed,case,completed,t_end,ratio,max_roll_deg,max_pitch_deg,max_yaw_change_deg,slide_distance_m,slide_t,dev_x_m,dev_y_m,dev_z_m,dev_roll_deg,dev_pitch_deg,dev_yaw_deg";

/// Columns of the search's CSV.
const COLUMNS: usize = 18;

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x:.6}"))
}

/// The records as the search's CSV (every field's runs, one per row).
pub fn to_csv(records: &[Record]) -> String {
    let mut s = String::from(HEADER);
    s.push('\n');
    for r in records {
        let dev = match r.deviation {
            Some(d) => d.map(|x| format!("{x:.6}")).join(","),
            None => ",,,,,".into(),
        };
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:.3},{},{:.4},{:.4},{:.4},{},{},{dev}",
            r.field.amplitude,
            r.field.spacing,
            r.seed,
            r.case,
            r.completed,
            r.t_end,
            opt(r.ratio),
            r.max_roll_deg,
            r.max_pitch_deg,
            r.max_yaw_change_deg,
            opt(r.slide_distance_m),
            opt(r.slide_t)
        );
    }
    s
}

/// Records from the search's CSV.
pub fn from_csv(path: &Path) -> Result<Vec<Record>, CliError> {
    let text = rover_files::read_text(path, rover_files::Limit::Data).map_err(|e| {
        other(format!(
            "{}: {e} (run `rover reproduce --search` to make it)",
            path.display()
        ))
    })?;
    parse_csv(&text, path)
}

/// Records from the search CSV's text; `path` names it in errors.
pub fn parse_csv(text: &str, path: &Path) -> Result<Vec<Record>, CliError> {
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        return Err(other(format!(
            "{}: not the search's header, which has the columns {HEADER} \
             (run `rover reproduce --search` again)",
            path.display()
        )));
    }
    lines
        .enumerate()
        .map(|(i, l)| {
            let bad = || other(format!("{}:{}: unreadable row", path.display(), i + 2));
            let v: Vec<&str> = l.split(',').collect();
            if v.len() != COLUMNS {
                return Err(bad());
            }
            let num = |s: &str| s.parse::<f64>().map_err(|_| bad());
            let maybe = |s: &str| -> Result<Option<f64>, CliError> {
                if s.is_empty() {
                    Ok(None)
                } else {
                    num(s).map(Some)
                }
            };
            Ok(Record {
                field: Field {
                    amplitude: num(v[0])?,
                    spacing: num(v[1])?,
                },
                seed: v[2].parse().map_err(|_| bad())?,
                case: v[3].into(),
                completed: v[4] == "true",
                t_end: num(v[5])?,
                ratio: maybe(v[6])?,
                max_roll_deg: num(v[7])?,
                max_pitch_deg: num(v[8])?,
                max_yaw_change_deg: num(v[9])?,
                slide_distance_m: maybe(v[10])?,
                slide_t: maybe(v[11])?,
                deviation: {
                    let d: Vec<Option<f64>> =
                        v[12..].iter().map(|s| maybe(s)).collect::<Result<_, _>>()?;
                    match d.iter().flatten().count() {
                        0 => None,
                        6 => Some(std::array::from_fn(|k| d[k].unwrap_or(0.0))),
                        _ => return Err(bad()),
                    }
                },
            })
        })
        .collect()
}

/// The records split by field, in grid order.
pub fn outcomes(records: &[Record]) -> Vec<Outcome> {
    let mut out: Vec<Outcome> = Vec::new();
    for r in records {
        match out.iter_mut().find(|o| o.field == r.field) {
            Some(o) => o.records.push(r.clone()),
            None => out.push(Outcome::new(r.field, vec![r.clone()])),
        }
    }
    out
}

/// The best of the outcomes: most claims holding, then the smallest
/// summed shortfall.
pub fn best(outcomes: &[Outcome]) -> Option<&Outcome> {
    outcomes.iter().min_by(|a, b| {
        let (sa, sb) = (a.score(), b.score());
        sb.0.cmp(&sa.0).then(sa.1.total_cmp(&sb.1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(case: &str, deviation: Option<[f64; 6]>) -> Record {
        Record {
            field: CHOSEN,
            seed: 3,
            case: case.into(),
            completed: deviation.is_some(),
            t_end: 17.3,
            ratio: None,
            max_roll_deg: 30.125,
            max_pitch_deg: 4.5,
            max_yaw_change_deg: 2.25,
            slide_distance_m: Some(1.5),
            slide_t: None,
            deviation,
        }
    }

    #[test]
    fn the_search_csv_round_trips_the_fig11_and_fig12_fields() {
        let records = vec![
            record(
                "fig11_simplified",
                Some([0.85, 0.5, 0.01, 30.0, 2.5, 189.0]),
            ),
            record("fig11_quasi_static", None),
        ];
        let text = to_csv(&records);
        let back = parse_csv(&text, Path::new("calibration.csv")).unwrap();
        assert_eq!(back, records);
        assert_eq!(back[0].position_deviation(), Some(0.85));
        assert_eq!(back[0].attitude_deviation(), Some(189.0));
        // A row with only some of the deviations is refused, with its line.
        let broken = text.replacen("0.850000,", ",", 1);
        let err = parse_csv(&broken, Path::new("calibration.csv"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("calibration.csv:2"), "{err}");
        // The older header, without the new columns, asks for a new search.
        let old = "amplitude,spacing,seed,case,completed,ratio\n";
        let err = parse_csv(old, Path::new("c.csv")).unwrap_err().to_string();
        assert!(err.contains("--search"), "{err}");
    }

    #[test]
    fn the_fig12_claim_holds_within_the_thresholds_and_fails_beyond_or_stopped() {
        let judge = |sim: Option<[f64; 6]>, lin: Option<[f64; 6]>| {
            let o = Outcome::new(
                CHOSEN,
                vec![
                    record("fig11_simplified", sim),
                    record("fig11_linearized", lin),
                ],
            );
            o.claims()
                .into_iter()
                .find(|c| c.id == "fig12_close_zr0.3")
                .unwrap()
        };
        let close = [0.03, 0.04, 0.01, 2.0, 0.7, 1.2];
        assert!(judge(Some(close), Some(close)).holds);
        let far = [0.85, 0.9, 0.02, 30.0, 5.0, 189.0];
        let c = judge(Some(close), Some(far));
        assert!(!c.holds);
        // (0.9 / 0.1 − 1) + (189 / 3 − 1) in the claim's units.
        assert!((c.shortfall - (8.0 + 62.0)).abs() < 1e-9, "{}", c.shortfall);
        let c = judge(Some(close), None);
        assert!(!c.holds && c.ours.contains("1 of 1 stopped"), "{}", c.ours);
    }

    #[test]
    fn the_quasi_static_claim_fails_when_a_seed_stops() {
        let mut done = record("fig11_quasi_static", Some([0.0; 6]));
        let stopped = record("fig11_quasi_static", None);
        let o = Outcome::new(CHOSEN, vec![done.clone(), stopped]);
        let c = o
            .claims()
            .into_iter()
            .find(|c| c.id == "fig11_quasi_static_converges")
            .unwrap();
        assert!(!c.holds && c.ours.contains("at t = 17.3"), "{}", c.ours);
        done.seed = 4;
        let o = Outcome::new(CHOSEN, vec![done]);
        assert!(
            o.claims()
                .iter()
                .any(|c| c.id == "fig11_quasi_static_converges" && c.holds)
        );
    }
}
