//! A sensor log estimated: the paper's Fig. 13 drive read by a MEMS IMU,
//! wheel and suspension encoders (scenarios/fig13_observer.toml), the
//! model-based filter against the truth and against dead reckoning on the
//! same log; what the outputs hold; a failure mid-log; the tuning file.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rover_estimate::{FilterConfig, InitialSigma, SensorSample};
use rover_scenario::estimate::{
    EstimateOptions, EstimateSummary, Preset, estimate_columns, read_tuning,
};
use rover_scenario::prepare::Prepared;
use rover_scenario::sensor_log::parse_sensor_log;
use rover_scenario::truth_log::{TruthLog, parse_truth};

fn scenario_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(name)
}

/// The scenario's run: its log and its truth.
fn run(p: &Prepared) -> (Vec<SensorSample>, TruthLog) {
    let (mut csv, mut log) = (Vec::new(), Vec::new());
    let summary = p
        .run_with_sensors(
            false,
            &mut csv,
            Some(&mut log),
            &AtomicBool::new(false),
            |_| {},
        )
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(summary.complete, "{:?}", summary.error);
    let model = &p.spec.model;
    let (m, wheels) = (model.m(), model.wheels.len());
    let config = p.scenario.sensors.as_ref().unwrap();
    let log = String::from_utf8(log).unwrap();
    let samples = parse_sensor_log(&log, Path::new("sensors.csv"), config, wheels, m).unwrap();
    let csv = String::from_utf8(csv).unwrap();
    let truth = parse_truth(&csv, Path::new("run.csv"), m, wheels).unwrap();
    (samples, truth)
}

/// The estimate of `samples`: its summary and estimate.csv's text.
fn estimate(
    p: &Prepared,
    samples: &[SensorSample],
    truth: Option<&TruthLog>,
) -> (EstimateSummary, String) {
    let (mut est, mut dr) = (Vec::new(), Vec::new());
    let summary = p
        .estimate(
            false,
            samples,
            truth,
            &EstimateOptions::default(),
            &mut est,
            &mut dr,
        )
        .unwrap_or_else(|e| panic!("{e}"));
    (summary, String::from_utf8(est).unwrap())
}

/// The targets on the Fig. 13 run (swing4 slip-steered on the paper's
/// rough terrain, 1.7 m in 34 s; the true map; no fixes): roll and pitch
/// within 0.2° RMS, the suspension within 0.3°, G's velocity within
/// 1 cm/s, the position drift within 1 % of the distance; never worse than
/// dead reckoning on the same log, and at least twice less drift where
/// the wheels skid. Consistency: the NEES within its 95 % χ² interval
/// at most instants (0.73 on this log; the 0.9 sought is not reached,
/// docs/ESTIMATE.md says what binds it).
#[test]
fn the_fig13_drive_is_estimated_within_its_targets_and_beats_dead_reckoning() {
    let p = Prepared::from_file(None, &scenario_path("fig13_observer.toml")).unwrap();
    let (samples, truth) = run(&p);
    let (s, _) = estimate(&p, &samples, Some(&truth));
    assert_eq!(s.status, "completed", "{:?}", s.error);
    let (f, d) = (
        s.filter.as_ref().unwrap(),
        s.dead_reckoning.as_ref().unwrap(),
    );
    let distance = s.distance.unwrap();
    assert!(distance > 1.6, "{distance}");
    assert!(f.roll_deg <= 0.2 && f.pitch_deg <= 0.2, "{f:?}");
    assert!(f.suspension_deg_max.unwrap() <= 0.3, "{f:?}");
    assert!(f.velocity <= 0.01, "{f:?}");
    assert!(f.drift_fraction <= 0.01, "{f:?}");
    assert!(d.final_drift >= 2.0 * f.final_drift, "{d:?} against {f:?}");
    assert!(
        f.roll_deg <= d.roll_deg && f.pitch_deg <= d.pitch_deg && f.yaw_deg <= d.yaw_deg,
        "{f:?} {d:?}"
    );
    assert!(f.suspension_deg_max <= d.suspension_deg_max && f.velocity <= d.velocity);
    let c = s.consistency.as_ref().unwrap();
    assert_eq!(c.dof, 20);
    assert!(c.fraction_inside >= 0.6, "{c:?}");
    assert_eq!(s.preset, "exact model");
}

/// estimate.csv: its columns, one row per sample, every value finite,
/// each 1σ positive; the first row the scenario's start.
#[test]
fn the_estimate_rows_hold_the_state_its_sigma_loads_and_biases() {
    let text = std::fs::read_to_string(scenario_path("fig13_observer.toml"))
        .unwrap()
        .replace("duration = 40.0", "duration = 2.0")
        .replace("settle = 6.0", "settle = 0.5");
    let p = Prepared::from_text(None, &text, Path::new("short.toml"), &scenario_path("")).unwrap();
    let (samples, truth) = run(&p);
    let (s, csv) = estimate(&p, &samples, Some(&truth));
    assert_eq!(s.samples, samples.len());
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, estimate_columns(4, 4, false, true));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), samples.len());
    let sigma = header.iter().position(|h| *h == "sigma_X").unwrap();
    for r in &rows {
        assert!(r.iter().all(|v| v.is_finite()));
        assert!(r[sigma..sigma + 20].iter().all(|v| *v > 0.0), "{r:?}");
    }
    // The start is the truth's, moved by the first readings within the
    // initial σ (1 µm, 3 µrad: the start is known) and the velocities'
    // (1 cm/s).
    for (k, v) in truth.y[0].iter().enumerate() {
        let d = (rows[0][1 + k] - v).abs();
        assert!(d < 3.0 * rows[0][sigma + k].max(1e-3), "{k}: {d}");
    }
}

/// A log the filter cannot take to its end (a steering command to a
/// wheel that does not steer, at t = 0.5 s): the summary says where and
/// why, and the rows before are kept.
#[test]
fn a_failure_mid_log_keeps_the_rows_before_it() {
    let text = std::fs::read_to_string(scenario_path("fig13_observer.toml"))
        .unwrap()
        .replace("duration = 40.0", "duration = 1.0")
        .replace("settle = 6.0", "settle = 0.5");
    let p = Prepared::from_text(None, &text, Path::new("short.toml"), &scenario_path("")).unwrap();
    let (mut samples, _) = run(&p);
    samples[50].steering[0] = 0.1;
    let (s, csv) = estimate(&p, &samples, None);
    assert_eq!(s.status, "failed");
    let error = s.error.unwrap();
    assert!(
        error.contains("t = 0.51") && error.contains("steer"),
        "{error}"
    );
    assert_eq!(s.samples, 51);
    assert_eq!(csv.lines().count(), 1 + 51);
}

#[test]
fn a_tuning_file_names_a_field_it_does_not_know() {
    let dir = std::env::temp_dir().join(format!("rover-tuning-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tuning.toml");
    std::fs::write(
        &path,
        "[filter]\nsubsteps = 2\n\n[initial]\nattitude = 0.002\nheading = 1\n",
    )
    .unwrap();
    let e = read_tuning(&path).unwrap_err();
    assert!(e.contains("tuning.toml:6") && e.contains("heading"), "{e}");
    std::fs::write(&path, "[filter]\nsubsteps = 2\n").unwrap();
    let t = read_tuning(&path).unwrap();
    // The file's field over either preset; the rest is the preset's.
    let (exact, exact_initial) = t.resolve(Preset::ExactModel);
    let (approximate, _) = t.resolve(Preset::ApproximateModel);
    assert_eq!((exact.substeps, approximate.substeps), (2, 2));
    assert_eq!(exact.velocity_noise, FilterConfig::default().velocity_noise);
    assert_eq!(
        approximate.velocity_noise,
        FilterConfig::approximate_model().velocity_noise
    );
    assert_eq!(exact_initial, InitialSigma::default());
    let _ = std::fs::remove_dir_all(&dir);
}
