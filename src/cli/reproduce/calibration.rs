//! One terrain for every roughness claim of the paper: the runs each claim
//! reads, over several seeds; the claims judged on their mean; the search
//! over a small grid of fields, stored as a CSV of every run's numbers.

use std::fmt::Write as _;
use std::path::Path;

use rayon::prelude::*;
use rover_scenario::output::Status;

use super::runs::{ACTIVE, Case, Field, ackermann, other, rough_ratio, run_case, slip};
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
    amplitude: 0.5,
    spacing: 0.5,
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

/// What one run gives the claims.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    pub field: Field,
    pub seed: u64,
    /// `fig6_zr<Z_R>`, `fig7_v<V>`, `fig15_passive`, `fig15_active`.
    pub case: String,
    pub completed: bool,
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
            ratio: rough_ratio(c)?,
            max_roll_deg: s.max_roll_deg,
            max_pitch_deg: s.max_pitch_deg,
            max_yaw_change_deg: slide.map_or(0.0, |sl| sl.max_yaw_change_deg),
            slide_distance_m: sudden.map(|x| x.distance_m),
            slide_t: sudden.map(|x| x.t),
        })
    }
}

/// The cases of one seed: (name, rover, scenario text).
pub fn cases(field: Field, seed: u64) -> Vec<(String, &'static str, String)> {
    let mut out = Vec::new();
    for z in FIG6_ROUGHNESS {
        out.push((
            format!("fig6_zr{z}"),
            "exomars",
            ackermann(
                &field.terrain(z, seed),
                0.05,
                SEARCH_DELTA,
                EXAMPLE1_DURATION,
            ),
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
                EXAMPLE1_DURATION,
            ),
        ));
    }
    for (name, extra) in [("fig15_passive", ""), ("fig15_active", ACTIVE)] {
        out.push((
            name.into(),
            "swing4",
            slip(&field.terrain(0.2, seed), 0.05, 0.2, FIG15_DURATION, "") + extra,
        ));
    }
    out
}

/// Directory of a field's runs under `work`.
pub fn field_dir(work: &Path, field: Field) -> std::path::PathBuf {
    work.join(format!("a{}_L{}", field.amplitude, field.spacing))
}

/// Run every case of `field` over [`SEEDS`] (in parallel): the records
/// and the cases (for plotting), keyed by (seed, case name).
pub fn evaluate(field: Field, work: &Path) -> Result<Vec<(Record, Case)>, CliError> {
    let dir = field_dir(work, field);
    let jobs: Vec<(u64, String, &'static str, String)> = SEEDS
        .iter()
        .flat_map(|&seed| {
            cases(field, seed)
                .into_iter()
                .map(move |(name, rover, text)| (seed, name, rover, text))
        })
        .collect();
    jobs.par_iter()
        .map(|(seed, name, rover, text)| {
            let case = run_case(rover, text, &dir.join(format!("seed{seed}/{name}.csv")))?;
            Ok((Record::of(field, *seed, name, &case)?, case))
        })
        .collect()
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

    fn of_case(&self, case: &str) -> impl Iterator<Item = &Record> {
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
    pub figure: &'static str,
    pub paper: &'static str,
    pub holds: bool,
    /// Our numbers.
    pub ours: String,
    /// How far from holding, in units of the claim's own scale (0 when it
    /// holds).
    pub shortfall: f64,
}

/// A claim's text and its judge.
pub struct ClaimSpec {
    pub figure: &'static str,
    pub paper: &'static str,
    judge: fn(&Outcome, &ClaimSpec) -> Claim,
}

impl ClaimSpec {
    fn verdict(&self, holds: bool, ours: String, shortfall: f64) -> Claim {
        Claim {
            figure: self.figure,
            paper: self.paper,
            holds,
            ours,
            shortfall: if holds { 0.0 } else { shortfall.max(1e-3) },
        }
    }
}

/// The paper's roughness claims (section 7), each judged on the mean over
/// [`SEEDS`].
pub const CLAIMS: [ClaimSpec; 7] = [
    ClaimSpec {
        figure: "Fig. 6",
        paper: "R ≈ 0.95–0.99·R_k on moderate ground (Z_R = 0.1, 0.2): mean in the band, spread (sd) ≤ 0.05",
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
        figure: "Fig. 6",
        paper: "kinematic steering unacceptable at Z_R = 0.5 and 1",
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
        figure: "Fig. 7",
        paper: "at Z_R = 0.3 the agreement worsens with speed",
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
        figure: "Fig. 15",
        paper: "passive pitch in excess of 10° (Z_R = 0.2)",
        judge: |o, c| {
            let s = o.quantity("fig15_passive", |r| r.max_pitch_deg);
            let m = s.mean().unwrap_or(0.0);
            c.verdict(m > 10.0, format!("{}°", s.show(1)), (10.0 - m) / 10.0)
        },
    },
    ClaimSpec {
        figure: "Figs. 15–16",
        paper: "the passive rover's rear wheels slide suddenly after about 1 m",
        judge: |o, c| {
            let slides = o.slides("fig15_passive");
            let n = o.seeds("fig15_passive");
            let change = o.quantity("fig15_passive", |r| r.max_yaw_change_deg);
            c.verdict(
                !slides.is_empty(),
                format!(
                    "{} of {n} seeds ({}); largest yaw change in 2 s {}°",
                    slides.len(),
                    slides
                        .iter()
                        .map(|(s, d)| format!("seed {s} at {d:.2} m"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    change.show(1)
                ),
                1.0,
            )
        },
    },
    ClaimSpec {
        figure: "Fig. 15",
        paper: "active suspension: roll and pitch always much smaller than 1°",
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
        figure: "Figs. 15–16",
        paper: "active suspension prevents the slide",
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

const HEADER: &str = "amplitude,spacing,seed,case,completed,ratio,max_roll_deg,max_pitch_deg,max_yaw_change_deg,slide_distance_m,slide_t";

fn opt(v: Option<f64>) -> String {
    v.map_or(String::new(), |x| format!("{x:.6}"))
}

/// The records as the search's CSV (every field's runs, one per row).
pub fn to_csv(records: &[Record]) -> String {
    let mut s = String::from(HEADER);
    s.push('\n');
    for r in records {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{:.4},{:.4},{:.4},{},{}",
            r.field.amplitude,
            r.field.spacing,
            r.seed,
            r.case,
            r.completed,
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
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        return Err(other(format!(
            "{}: not the search's header (run `rover reproduce --search` again)",
            path.display()
        )));
    }
    lines
        .enumerate()
        .map(|(i, l)| {
            let bad = || other(format!("{}:{}: unreadable row", path.display(), i + 2));
            let v: Vec<&str> = l.split(',').collect();
            if v.len() != 11 {
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
                ratio: maybe(v[5])?,
                max_roll_deg: num(v[6])?,
                max_pitch_deg: num(v[7])?,
                max_yaw_change_deg: num(v[8])?,
                slide_distance_m: maybe(v[9])?,
                slide_t: maybe(v[10])?,
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
