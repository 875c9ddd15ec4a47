//! A scenario's `[sensors]`: the table's checks, the sensor log a run
//! writes (its columns, its rows at the sensors' rate, its readings read
//! back bit for bit), a run whose rows do not depend on whether the log is
//! written, and every error of the log's reader.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use rover_estimate::SensorConfig;
use rover_estimate::sensors::STANDARD_GRAVITY;
use rover_scenario::prepare::Prepared;
use rover_scenario::scenario::Scenario;
use rover_scenario::sensor_log::{SensorLogError, parse_sensor_log};

/// swing4 on flat ground driving at 0.05 m/s after 0.5 s of settling,
/// with `sensors` (TOML tables) appended.
fn scenario(duration: f64, sensors: &str) -> String {
    format!(
        "rover = \"swing4\"\nduration = {duration}\nsettle = 0.5\noutput_rate = 20.0\n\
         [control.speed]\nspeed = 0.05\n{sensors}"
    )
}

const IMU_AND_ENCODERS: &str = "[sensors]\nseed = 3\nrate = 100.0\n\
    [sensors.imu]\ngyro_noise_deg_per_sqrt_h = 0.2\ngyro_bias_deg_per_h = 10.0\n\
    accel_noise_ug_per_sqrt_hz = 100.0\naccel_bias_mg = 0.1\n\
    [sensors.wheel_encoders]\nresolution = 0.001\n\
    [sensors.suspension_encoders]\nresolution = 0.0017453292519943296\n\
    [sensors.position_fix]\nrate = 2.0\nsigma = 0.05\n\
    [sensors.heading_fix]\nrate = 1.0\nsigma = 0.01\n";

fn prepared(text: &str) -> Prepared {
    Prepared::from_text(None, text, Path::new("sensors.toml"), Path::new("."))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The whole run: run.csv's text, and the sensor log's when asked for.
fn run(p: &Prepared, with_log: bool) -> (String, Option<String>) {
    let mut csv = Vec::new();
    let mut log = Vec::new();
    let summary = p
        .run_with_sensors(
            false,
            &mut csv,
            with_log.then_some(&mut log),
            &AtomicBool::new(false),
            |_| {},
        )
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(summary.complete, "{:?}", summary.error);
    let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
    (text(csv), with_log.then(|| text(log)))
}

fn config(p: &Prepared) -> &SensorConfig {
    p.scenario.sensors.as_ref().unwrap()
}

#[test]
fn a_run_writes_a_row_of_readings_at_every_sensor_instant() {
    let p = prepared(&scenario(2.0, IMU_AND_ENCODERS));
    let (_, log) = run(&p, true);
    let log = log.unwrap();
    let header = log.lines().next().unwrap();
    assert_eq!(
        header,
        "t,gx,gy,gz,ax,ay,az,enc1,enc2,enc3,enc4,susp1,susp2,susp3,susp4,\
         fix_X,fix_Y,fix_Z,fix_psi,tau1,tau2,tau3,tau4,delta1,delta2,delta3,delta4"
    );
    // Rows at t = 0, 0.01, …, 2.0.
    let samples = parse_sensor_log(&log, Path::new("sensors.csv"), config(&p), 4, 4)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(samples.len(), 201);
    for (k, s) in samples.iter().enumerate() {
        assert!(
            (s.t - k as f64 * 0.01).abs() < 1e-12,
            "row {k}: t = {}",
            s.t
        );
        // Fixes at 2 Hz and 1 Hz, from t = 0.
        assert_eq!(s.position.is_some(), k % 50 == 0, "row {k}");
        assert_eq!(s.heading.is_some(), k % 100 == 0, "row {k}");
    }
    // What was written reads back bit for bit: the log of the same seed
    // written again is the same text.
    let (_, again) = run(&p, true);
    assert_eq!(again.unwrap(), log);
    // Settled on flat ground before the drive (t = 0.3 … 0.5 s), the
    // accelerometers read g up, within the noise (100 µg/√Hz at 100 Hz:
    // σ = 9.8 mg) and the bias (0.1 mg) times 6, and the wheels do not
    // turn; driving, the encoders count the rolled distance over the
    // radius.
    let g = 1.62;
    let sigma = 100e-6 * STANDARD_GRAVITY * 10.0;
    for s in &samples[30..50] {
        let a = s.accel.unwrap();
        assert!((a[2] - g).abs() < 6.0 * sigma, "t = {}: {a:?}", s.t);
        assert!(
            a[0].abs() < 6.0 * sigma && a[1].abs() < 6.0 * sigma,
            "{a:?}"
        );
    }
    // The encoders count whole milliradians, and their mean, times the
    // radius (0.09 m), is the distance G rolled (X, straight ahead on flat
    // ground) within 10 %: the swing arms, still sagging after a short
    // settling, move the front wheels forwards and the rear ones backwards
    // against G, so that each wheel alone rolls more or less than G.
    let last = samples.last().unwrap();
    for a in &last.wheel_angles {
        assert!((a / 1e-3 - (a / 1e-3).round()).abs() < 1e-6, "{a}");
    }
    let rolled = 0.09 * last.wheel_angles.iter().sum::<f64>() / 4.0;
    let x_end: f64 = run(&p, false)
        .0
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert!(x_end > 0.05, "{x_end}");
    assert!(
        (rolled / x_end - 1.0).abs() < 0.1,
        "rolled {rolled} m, G went {x_end} m"
    );
}

#[test]
fn the_runs_rows_do_not_depend_on_whether_the_readings_are_written() {
    let p = prepared(&scenario(2.0, IMU_AND_ENCODERS));
    let (with, _) = run(&p, true);
    let (without, _) = run(&p, false);
    assert_eq!(with, without);
    // And a stepped run gives them too (it lands on the sensor instants
    // without reading them).
    let whole: Vec<&str> = with.lines().skip(1).collect();
    let mut s = p.stepper(false).unwrap_or_else(|e| panic!("{e}"));
    let mut row = vec![0.0; s.columns().len()];
    for (k, want) in whole.iter().enumerate() {
        if k > 0 {
            s.step(1).unwrap();
        }
        s.row_into(&mut row);
        let want: Vec<f64> = want.split(',').map(|v| v.parse().unwrap()).collect();
        let same = row
            .iter()
            .zip(&want)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(same, "row {k}: stepped {row:?}, whole {want:?}");
    }
}

/// The scenario error of `sensors`, with the file's name.
fn bad(sensors: &str) -> String {
    Scenario::parse(&scenario(2.0, sensors), Path::new("s.toml"))
        .expect_err("refused")
        .to_string()
}

#[test]
fn a_sensors_table_that_cannot_be_read_is_refused_naming_the_field_and_its_line() {
    let imu = "[sensors.imu]\ngyro_noise_deg_per_sqrt_h = 0.2\ngyro_bias_deg_per_h = 10.0\naccel_noise_ug_per_sqrt_hz = 100.0\naccel_bias_mg = 0.1\n";
    assert_eq!(
        bad("[sensors]\nrate = 0.0\n"),
        "s.toml:8: sensors.rate must be > 0, got 0\n  = help: readings per second of the IMU and the encoders [Hz], e.g. rate = 100.0"
    );
    assert_eq!(
        bad(&imu.replace("= 10.0", "= -10.0")),
        "s.toml:9: sensors.imu.gyro_bias_deg_per_h must be ≥ 0, got -10\n  = help: the gyros' bias instability [°/h], e.g. 10.0; a datasheet's figure, 0 for a perfect sensor"
    );
    assert_eq!(
        bad(&format!("{imu}bias_time = 0.0\n")),
        "s.toml:12: sensors.imu.bias_time must be > 0, got 0\n  = help: the biases' correlation time [s], e.g. bias_time = 300.0"
    );
    assert_eq!(
        bad("[sensors.wheel_encoders]\nresolution = 0.0\n"),
        "s.toml:8: sensors.wheel_encoders.resolution must be > 0, got 0\n  = help: one count of the encoder [rad], e.g. resolution = 0.001 (2π/6283 counts a turn)"
    );
    assert_eq!(
        bad("[sensors.suspension_encoders]\nresolution = 0.001\nnoise = -1e-3\n"),
        "s.toml:9: sensors.suspension_encoders.noise must be ≥ 0, got -0.001\n  = help: the reading's white noise, a standard deviation [rad or m]; 0 for none"
    );
    assert_eq!(
        bad("[sensors.position_fix]\nrate = 0.0\nsigma = 0.1\n"),
        "s.toml:8: sensors.position_fix.rate must be > 0, got 0\n  = help: fixes per second [Hz], e.g. rate = 0.1"
    );
    assert_eq!(
        bad("[sensors.heading_fix]\nrate = 1.0\nsigma = 0.0\n"),
        "s.toml:9: sensors.heading_fix.sigma must be > 0, got 0\n  = help: the yaw's standard deviation [rad], e.g. sigma = 0.01 (a fix without error would be a truth no filter could weigh)"
    );
    assert_eq!(
        bad("[sensors]\nrate = 10.0\n[sensors.position_fix]\nrate = 20.0\nsigma = 0.1\n"),
        "s.toml:10: sensors.position_fix.rate = 20 Hz is faster than sensors.rate = 10 Hz: a fix is read at a sensor instant\n  = help: give the fix a rate of at most 10 Hz, or raise sensors.rate"
    );
    assert_eq!(
        bad("[sensors]\nrate = 1e6\n"),
        "s.toml:8: duration × sensors.rate = 2 s × 1000000 Hz asks for 2.000e6 rows of readings; at most 1000000 are written\n  = help: lower sensors.rate or shorten duration"
    );
    let quasi_static = format!(
        "fidelity = \"quasi_static\"\n{}",
        scenario(2.0, "[sensors]\n")
    );
    assert_eq!(
        Scenario::parse(&quasi_static, Path::new("s.toml"))
            .expect_err("refused")
            .to_string(),
        "s.toml:8: [sensors] needs the rover's accelerations and wheel spins, which the quasi-static level (a static equilibrium at each instant) does not have\n  = help: run the sensors at the \"full\", \"simplified\" or \"linearized\" level, or remove [sensors]"
    );
    // A key the table does not have: the parser's message, listing the keys.
    let typo = bad("[sensors.wheel_encoders]\nresolutoin = 0.001\n");
    assert!(
        typo.contains("unknown field `resolutoin`, expected `resolution`"),
        "{typo}"
    );
}

// The reader's errors, on the log of a declaration with an IMU, wheel
// encoders and a position fix, on a rover of 2 wheels and 1 coordinate.

fn declared() -> SensorConfig {
    let text = "rate = 10.0\n[imu]\ngyro_noise_deg_per_sqrt_h = 0.2\ngyro_bias_deg_per_h = 10.0\n\
                accel_noise_ug_per_sqrt_hz = 100.0\naccel_bias_mg = 0.1\n\
                [wheel_encoders]\nresolution = 0.001\n[position_fix]\nrate = 5.0\nsigma = 0.1\n";
    toml::from_str(text).unwrap()
}

const HEADER: &str = "t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2";

fn row(t: &str, fix: bool) -> String {
    let fix = if fix { "1.5,-2,0.25" } else { ",," };
    format!("{t},0.001,0,-0.002,0.01,0,1.62,0.5,0.501,{fix},0.1,-0.1,0,0")
}

fn log(rows: &[String]) -> String {
    let mut text = format!("{HEADER}\n");
    for r in rows {
        text.push_str(r);
        text.push('\n');
    }
    text
}

fn good_rows() -> Vec<String> {
    vec![row("0", true), row("0.1", false), row("0.2", true)]
}

/// The reader's error for `text`, rendered.
fn reader_error(text: &str) -> String {
    let e: SensorLogError =
        parse_sensor_log(text, Path::new("sensors.csv"), &declared(), 2, 1).expect_err("refused");
    e.to_string()
}

#[test]
fn a_log_that_fits_its_declaration_reads_back_whole() {
    let samples = parse_sensor_log(&log(&good_rows()), Path::new("x"), &declared(), 2, 1).unwrap();
    assert_eq!(samples.len(), 3);
    assert_eq!(samples[1].t, 0.1);
    assert_eq!(samples[0].position, Some([1.5, -2.0, 0.25]));
    assert_eq!(samples[1].position, None);
    assert_eq!(samples[2].gyro, Some([0.001, 0.0, -0.002]));
    assert_eq!(samples[2].wheel_angles, [0.5, 0.501]);
    assert_eq!(samples[2].torques, [0.1, -0.1]);
    assert!(samples[0].suspension.is_empty() && samples[0].heading.is_none());
    // Columns in another order read the same.
    let swapped = log(&good_rows())
        .lines()
        .map(|l| {
            let mut c: Vec<&str> = l.split(',').collect();
            c.swap(0, 15);
            c.join(",")
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_eq!(
        parse_sensor_log(&swapped, Path::new("x"), &declared(), 2, 1).unwrap(),
        samples
    );
}

#[test]
fn the_reader_names_the_column_that_does_not_fit_the_declaration() {
    let with_header = |h: &str| format!("{h}\n{}\n", row("0", true));
    assert_eq!(
        reader_error(&with_header(&HEADER.replace(",gz", ""))),
        "sensors.csv:1: no column `gz`, which [sensors.imu] declares (an IMU reads it)\n  = help: the columns of this declaration are t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    assert_eq!(
        reader_error(&with_header(&HEADER.replace(",delta2", ""))),
        "sensors.csv:1: no column `delta2`, which every sensor log has (the time and the commands)\n  = help: the columns of this declaration are t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    assert_eq!(
        reader_error(&with_header(&format!("{HEADER},fix_psi"))),
        "sensors.csv:1: column 17 (`fix_psi`): the column is read by a heading fix, which [sensors] does not declare\n  = help: declare [sensors.heading_fix] (the declaration the log was written with), or read the log without that column: t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    assert_eq!(
        reader_error(&with_header(&format!("{HEADER},enc3"))),
        "sensors.csv:1: column 17 (`enc3`): the rover has 2 wheels: there is no wheel 3\n  = help: the columns of this declaration are t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    assert_eq!(
        reader_error(&with_header(&HEADER.replace("gy", "gyro_y"))),
        "sensors.csv:1: column 3 (`gyro_y`): `gyro_y` is no sensor column\n  = help: the columns of this declaration are t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    assert_eq!(
        reader_error(&with_header(&HEADER.replace("ax", "gx"))),
        "sensors.csv:1: column 5 (`gx`): the column is named twice\n  = help: name each column once: t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
    let mut zero_rate = declared();
    zero_rate.rate = 0.0;
    let e = parse_sensor_log(
        &log(&good_rows()),
        Path::new("sensors.csv"),
        &zero_rate,
        2,
        1,
    )
    .expect_err("refused");
    assert_eq!(
        e.to_string(),
        "sensors.csv: the declaration to read it with cannot be used: sensors.rate must be > 0, got 0\n  = help: readings per second of the IMU and the encoders [Hz], e.g. rate = 100.0"
    );
    assert_eq!(
        reader_error(""),
        "sensors.csv: the file is empty: it has no header\n  = help: a sensor log starts with the header t,gx,gy,gz,ax,ay,az,enc1,enc2,fix_X,fix_Y,fix_Z,tau1,tau2,delta1,delta2"
    );
}

#[test]
fn the_reader_names_the_line_and_cell_of_a_reading_it_cannot_take() {
    let mut rows = good_rows();
    rows[1] = rows[1].replace(",0.501,", ",0.5.1,");
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:3: column 9 (`enc2`): `0.5.1` is not a number\n  = help: a decimal number in rad, e.g. 0.25 or -1.5e-3"
    );
    let mut rows = good_rows();
    rows[2] = rows[2].replace(",1.62,", ",NaN,");
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:4: column 7 (`az`): the reading is NaN\n  = help: a reading is a finite number: the row of a sensor that failed is left out, not written as NaN"
    );
    let mut rows = good_rows();
    rows[0] = rows[0].replace(",1.62,", ",inf,");
    assert!(
        reader_error(&log(&rows)).starts_with("sensors.csv:2: column 7 (`az`): the reading is inf")
    );
    let mut rows = good_rows();
    rows[1] = rows[1].replace("0.001,", ",");
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:3: column 2 (`gx`): the cell is empty\n  = help: every row reads `gx` (rad/s); only the fixes' cells may be empty"
    );
    let mut rows = good_rows();
    rows[2] = rows[2].replace("1.5,-2,", ",-2,");
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:4: column 10 (`fix_X`): a position fix has some of fix_X, fix_Y, fix_Z and not the others\n  = help: a position fix gives all three coordinates, or none (three empty cells)"
    );
    // A log cut off while it was written.
    let mut text = log(&good_rows());
    text.truncate(text.len() - 12);
    assert_eq!(
        reader_error(&text),
        "sensors.csv:4: the row has 13 cells, the header 16\n  = help: one cell per column in every row (a shorter last row is a log cut off while it was written)"
    );
}

#[test]
fn the_reader_wants_one_row_per_sensor_instant_in_order() {
    let mut rows = good_rows();
    rows[2] = row("0.1", false);
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:4: column 1 (`t`): t = 0.1 does not follow the previous row's t = 0.1\n  = help: the rows' times increase, one row per sensor instant"
    );
    // A row missing: 0.3 after 0.1.
    let mut rows = good_rows();
    rows[2] = row("0.3", false);
    assert_eq!(
        reader_error(&log(&rows)),
        "sensors.csv:4: column 1 (`t`): t = 0.3 is not the sensor instant of row 3 at rate = 10 Hz: t = 0.2\n  = help: row k of a sensor log is at t = (k − 1) / rate from t = 0, every 0.1 s with none missing; check that [sensors] rate is the one the log was written with"
    );
    // Another rate's log.
    let rows = [row("0", true), row("0.01", false)];
    assert!(
        reader_error(&log(&rows)).starts_with(
            "sensors.csv:3: column 1 (`t`): t = 0.01 is not the sensor instant of row 2 at rate = 10 Hz: t = 0.1"
        )
    );
}

#[test]
fn a_log_read_from_a_file_names_the_file() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sensor_log");
    std::fs::create_dir_all(&dir).unwrap();
    let missing = dir.join("missing.csv");
    let _ = std::fs::remove_file(&missing);
    let e = rover_scenario::read_sensor_log(&missing, &declared(), 2, 1).unwrap_err();
    assert_eq!(e.file, missing);
    assert!(
        e.to_string().contains(": cannot read it: ")
            && e.to_string().ends_with("= help: give the sensors.csv that `rover simulate` wrote for a scenario with [sensors]"),
        "{e}"
    );
    let path = dir.join("sensors.csv");
    std::fs::write(&path, log(&good_rows())).unwrap();
    let samples = rover_scenario::read_sensor_log(&path, &declared(), 2, 1).unwrap();
    assert_eq!(samples.len(), 3);
}

// The same log held as columns (as the Python module passes it): read by
// the same checks, located at the column and the element.

/// The columns of a log's text: each header name and its values, an
/// empty cell as NaN.
fn columns_of(text: &str) -> Vec<(String, Vec<f64>)> {
    let mut lines = text.lines();
    let mut cols: Vec<(String, Vec<f64>)> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|n| (n.to_string(), Vec::new()))
        .collect();
    for line in lines {
        for (cell, (_, values)) in line.split(',').zip(cols.iter_mut()) {
            values.push(if cell.is_empty() {
                f64::NAN
            } else {
                cell.parse().unwrap()
            });
        }
    }
    cols
}

fn from_columns(
    cols: &[(String, Vec<f64>)],
) -> Result<Vec<rover_estimate::SensorSample>, rover_scenario::columns::ColumnsError> {
    let borrowed: Vec<(&str, &[f64])> = cols
        .iter()
        .map(|(n, v)| (n.as_str(), v.as_slice()))
        .collect();
    rover_scenario::sensor_log::samples_from_columns(&borrowed, &declared(), 2, 1)
}

fn columns_error(cols: &[(String, Vec<f64>)]) -> String {
    from_columns(cols).expect_err("refused").to_string()
}

fn set(cols: &mut [(String, Vec<f64>)], name: &str, i: usize, v: f64) {
    cols.iter_mut().find(|(n, _)| n == name).unwrap().1[i] = v;
}

#[test]
fn a_log_as_columns_reads_as_its_file() {
    let text = log(&good_rows());
    let from_file = parse_sensor_log(&text, Path::new("x"), &declared(), 2, 1).unwrap();
    let mut cols = columns_of(&text);
    assert_eq!(from_columns(&cols).unwrap(), from_file);
    // In any order.
    cols.reverse();
    assert_eq!(from_columns(&cols).unwrap(), from_file);
}

#[test]
fn a_log_as_columns_is_refused_at_the_column_and_element() {
    let good = columns_of(&log(&good_rows()));
    let listing = HEADER;

    let mut cols = good.clone();
    cols.retain(|(n, _)| n != "gz");
    assert_eq!(
        columns_error(&cols),
        format!(
            "sensors: no column `gz`, which [sensors.imu] declares (an IMU reads it)\n  = help: the columns of this declaration are {listing}"
        )
    );
    let mut cols = good.clone();
    cols.push(("fix_psi".into(), vec![0.0; 3]));
    assert_eq!(
        columns_error(&cols),
        format!(
            "sensors[\"fix_psi\"]: the column is read by a heading fix, which [sensors] does not declare\n  = help: declare [sensors.heading_fix] (the declaration the log was written with), or read the log without that column: {listing}"
        )
    );
    let mut cols = good.clone();
    cols[4].1.pop();
    assert_eq!(
        columns_error(&cols),
        "sensors[\"ax\"]: 2 values, where `t` has 3\n  = help: one value per sensor instant in every column (NaN in a fix's columns where no fix is due)"
    );
    let mut cols = good.clone();
    set(&mut cols, "az", 2, f64::NAN);
    assert_eq!(
        columns_error(&cols),
        "sensors[\"az\"][2]: the reading is NaN\n  = help: a reading is a finite number: NaN stands for no fix, in a fix's columns only"
    );
    let mut cols = good.clone();
    set(&mut cols, "enc1", 0, f64::INFINITY);
    assert!(columns_error(&cols).starts_with("sensors[\"enc1\"][0]: the reading is inf\n"));
    let mut cols = good.clone();
    set(&mut cols, "fix_Y", 0, f64::NAN);
    assert_eq!(
        columns_error(&cols),
        "sensors[\"fix_X\"][0]: a position fix has some of fix_X, fix_Y, fix_Z and not the others\n  = help: a position fix gives all three coordinates, or none (NaN in all three)"
    );
    let mut cols = good.clone();
    set(&mut cols, "t", 2, 0.1);
    assert_eq!(
        columns_error(&cols),
        "sensors[\"t\"][2]: t = 0.1 does not follow the previous instant's t = 0.1\n  = help: the times increase, one element per sensor instant"
    );
    let mut cols = good.clone();
    set(&mut cols, "t", 2, 0.3);
    assert_eq!(
        columns_error(&cols),
        "sensors[\"t\"][2]: t = 0.3 is not sensor instant 2 at rate = 10 Hz: t = 0.2\n  = help: element k of `t` is at t = k / rate from t = 0, every 0.1 s with none missing; check that [sensors] rate is the one the log was written with"
    );
}

/// A run's truth read from its CSV and from its columns: the same log;
/// the columns' errors name the column and the element.
#[test]
fn a_truth_as_columns_reads_as_its_file() {
    use rover_scenario::truth_log::{read_truth, truth_from_columns};
    let p = prepared(&scenario(1.0, ""));
    let (csv, _) = run(&p, false);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("truth_columns");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("run.csv");
    std::fs::write(&path, &csv).unwrap();
    let from_file = read_truth(&path, 4, 4).unwrap();
    assert_eq!(from_file.t.len(), 21);
    let mut cols = columns_of(&csv);
    let read = |cols: &[(String, Vec<f64>)]| {
        let b: Vec<(&str, &[f64])> = cols
            .iter()
            .map(|(n, v)| (n.as_str(), v.as_slice()))
            .collect();
        truth_from_columns(&b, 4, 4)
    };
    assert_eq!(read(&cols).unwrap(), from_file);

    let mut bad = cols.clone();
    set(&mut bad, "phi", 5, f64::NAN);
    assert_eq!(
        read(&bad).unwrap_err().to_string(),
        "truth[\"phi\"][5]: the value is NaN, not a finite number\n  = help: give the columns of the run that wrote the sensor log, named as in its run.csv (or no truth: no errors are then measured)"
    );
    let mut bad = cols.clone();
    bad.iter_mut().find(|(n, _)| n == "Fn3").unwrap().1.pop();
    assert!(
        read(&bad)
            .unwrap_err()
            .to_string()
            .starts_with("truth[\"Fn3\"]: 20 values, where `t` has 21\n")
    );
    cols.retain(|(n, _)| n != "dy2");
    assert!(
        read(&cols)
            .unwrap_err()
            .to_string()
            .starts_with("truth: no column `dy2`: this is not a run of this rover\n")
    );
}
