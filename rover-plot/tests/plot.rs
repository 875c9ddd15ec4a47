//! End-to-end tests of `plot_run` on a synthetic run: a 4-wheel rover with
//! four swing-arm coordinates driving a circle after settling.

use std::collections::BTreeSet;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use rover_dynamics::plant::WheelState;
use rover_dynamics::wheel_ground::WheelReport;
use rover_plot::{Figure, PlotMeta, plot_run};
use rover_runtime::row::{Columns, RowInputs};

/// A fresh, empty directory for one test.
fn test_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("rover-plot")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const M: usize = 4;
const N: usize = 4;

/// The header of the run CSV, as a run writes it.
fn header() -> Vec<String> {
    Columns::new(M, N).names().to_vec()
}

/// One row at time `t`: still until 2 s, then a circle of radius 2 m at
/// 0.1 m/s, the body bobbing and rolling a little.
fn row(t: f64) -> Vec<f64> {
    let (radius, speed, settle) = (2.0, 0.1, 2.0);
    let s = (t - settle).max(0.0);
    let psi = speed * s / radius;
    let (x, y) = (radius * psi.sin(), radius * (1.0 - psi.cos()));
    let z = 0.30 + 0.01 * (2.0 * PI * 0.5 * t).sin();
    let phi = 0.02 * (0.7 * t).sin();
    let theta = 0.01 * (1.3 * t).cos();
    let ys: Vec<f64> = (0..M).map(|k| 0.05 * (0.5 * t + k as f64).sin()).collect();
    let vx = if t < settle {
        0.0
    } else {
        speed + 0.005 * (3.0 * t).sin()
    };
    let mut x_state = vec![x, y, z, phi, theta, psi];
    x_state.extend(&ys);
    let mut w = vec![
        vx,
        0.0,
        0.0,
        0.0,
        0.0,
        if t < settle { 0.0 } else { speed / radius },
    ];
    w.extend(ys.iter().map(|_| 0.0));
    let offsets = [(0.5, 0.4), (0.5, -0.4), (-0.5, 0.4), (-0.5, -0.4)];
    let wheels: Vec<WheelState> = offsets
        .iter()
        .enumerate()
        .map(|(j, &(bx, by))| WheelState {
            centre: [
                x + bx * psi.cos() - by * psi.sin(),
                y + bx * psi.sin() + by * psi.cos(),
                0.15 + 0.02 * ys[j],
            ],
            ..Default::default()
        })
        .collect();
    let reports: Vec<WheelReport> = wheels
        .iter()
        .enumerate()
        .map(|(j, w)| WheelReport {
            point: [w.centre[0], w.centre[1], 0.0],
            normal: 60.0 + 5.0 * (t + j as f64).sin(),
            drawbar: 0.5,
            lateral: 0.1,
            ..Default::default()
        })
        .collect();
    let torques: Vec<f64> = (0..N)
        .map(|j| {
            if t < settle {
                0.0
            } else {
                0.8 + 0.1 * (t + j as f64).cos()
            }
        })
        .collect();
    let columns = Columns::new(M, N);
    let mut r = vec![0.0; columns.len()];
    let inputs = RowInputs {
        t,
        x: &x_state,
        w: &w,
        wheels: &wheels,
        reports: &reports,
        spins: &[],
        torques: &torques,
        steering: &[0.0; N],
        neutrals: &[0.0; M],
        speed_setpoint: if t < settle { 0.0 } else { speed },
    };
    columns.fill(&inputs, &mut r);
    r
}

/// The run CSV text with `rows` samples every 0.1 s.
fn run_csv(rows: usize) -> String {
    let mut text = header().join(",");
    text.push('\n');
    for i in 0..rows {
        let values: Vec<String> = row(i as f64 * 0.1).iter().map(|v| v.to_string()).collect();
        text.push_str(&values.join(","));
        text.push('\n');
    }
    text
}

fn meta() -> PlotMeta {
    PlotMeta {
        title: "Synthetic circle & test".into(),
        coordinate_names: ["swing FL", "swing FR", "swing RL", "swing RR"]
            .map(String::from)
            .to_vec(),
        angular: vec![true; M],
        wheel_names: ["FL", "FR", "RL", "RR"].map(String::from).to_vec(),
        settle_time: 2.0,
        ..PlotMeta::default()
    }
}

fn write_csv(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("run.csv");
    std::fs::write(&path, text).unwrap();
    path
}

/// Decodes a PNG: its size and its pixels as RGB triples.
fn decode_png(path: &Path) -> ((u32, u32), Vec<[u8; 3]>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", path.display());
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    let pixels = buf[..info.buffer_size()]
        .chunks_exact(3)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    ((info.width, info.height), pixels)
}

#[test]
fn plots_every_figure_as_png_and_svg() {
    let dir = test_dir("every_figure");
    let csv = write_csv(&dir, &run_csv(201));
    let out = dir.join("plots");
    let written = plot_run(&csv, &out, &meta()).unwrap();

    let stems = [
        "trajectory_xz",
        "trajectory_xy",
        "coordinates",
        "torques",
        "speed",
        "forces",
    ];
    let expected: Vec<PathBuf> = stems
        .iter()
        .flat_map(|s| [out.join(format!("{s}.png")), out.join(format!("{s}.svg"))])
        .collect();
    assert_eq!(written, expected);
    assert_eq!(Figure::ALL.map(Figure::stem), stems);

    let sizes = [
        (1200, 600),
        (1100, 850),
        (1400, 1000),
        (1000, 500),
        (1000, 500),
        (1000, 500),
    ];
    for (figure, size) in Figure::ALL.iter().zip(sizes) {
        assert_eq!(figure.size(), size);
        let png_path = out.join(format!("{}.png", figure.stem()));
        let (decoded_size, pixels) = decode_png(&png_path);
        assert_eq!(decoded_size, size, "{}", png_path.display());
        // Not blank: many colours (lines, anti-aliased text), and ink on
        // more than 1 % of the pixels.
        let colours: BTreeSet<[u8; 3]> = pixels.iter().copied().collect();
        assert!(
            colours.len() >= 20,
            "{}: {} colours",
            png_path.display(),
            colours.len()
        );
        let ink = pixels.iter().filter(|&&p| p != [255, 255, 255]).count();
        assert!(
            ink * 100 > pixels.len(),
            "{}: {ink} non-white pixels",
            png_path.display()
        );
    }

    let svg = |stem: &str| std::fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
    let title = "Synthetic circle &amp; test";
    let must_contain: [(&str, &[&str]); 6] = [
        (
            "trajectory_xz",
            &[
                "side view (xz plane)",
                "X [m]",
                "Z [m]",
                "FL wheel centre",
                "RR contact point",
                "G (centre of mass)",
                "settled, t = 2 s",
            ],
        ),
        (
            "trajectory_xy",
            &[
                "top view (xy plane)",
                "X [m]",
                "Y [m]",
                "body at 4 instants",
            ],
        ),
        (
            "coordinates",
            &[
                "generalized coordinates",
                "t [s]",
                "X [m]",
                "Y [m]",
                "Z [m]",
                "φ [deg]",
                "θ [deg]",
                "ψ [deg]",
                "swing FL [deg]",
                "swing RR [deg]",
                "settled",
            ],
        ),
        (
            "torques",
            &["motor torques", "t [s]", "τ [N·m]", "FL", "RR", "settled"],
        ),
        (
            "speed",
            &[
                "forward speed",
                "t [s]",
                "speed [m/s]",
                "vx (body)",
                "V_set (set-point)",
            ],
        ),
        ("forces", &["normal forces", "t [s]", "Fn [N]", "FR", "RL"]),
    ];
    for (stem, texts) in must_contain {
        let text = svg(stem);
        assert!(text.starts_with("<svg"), "{stem}");
        assert!(text.contains(title), "{stem}: no title");
        for t in texts {
            assert!(text.contains(t), "{stem}.svg lacks {t:?}");
        }
    }
}

#[test]
fn the_same_csv_gives_byte_identical_files() {
    let dir = test_dir("deterministic");
    let csv = write_csv(&dir, &run_csv(120));
    let first = plot_run(&csv, &dir.join("a"), &meta()).unwrap();
    let second = plot_run(&csv, &dir.join("b"), &meta()).unwrap();
    for (a, b) in first.iter().zip(&second) {
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{}",
            a.display()
        );
    }
}

#[test]
fn a_run_cut_short_still_plots() {
    for rows in [1, 3] {
        let dir = test_dir(&format!("short_{rows}"));
        let csv = write_csv(&dir, &run_csv(rows));
        let written = plot_run(&csv, &dir.join("plots"), &PlotMeta::default()).unwrap();
        assert_eq!(written.len(), 12);
        // Default names: the title is the file stem, wheels W1..Wn.
        let torques = std::fs::read_to_string(dir.join("plots/torques.svg")).unwrap();
        assert!(torques.contains("run — motor torques"));
        assert!(torques.contains("W4"));
        let coordinates = std::fs::read_to_string(dir.join("plots/coordinates.svg")).unwrap();
        assert!(coordinates.contains("y4 [m]"));
    }
}

#[test]
fn columns_are_found_by_name_and_extra_columns_are_ignored() {
    let dir = test_dir("reordered");
    let text = run_csv(30);
    // Move `t` to the end and add a text column: the plots do not change.
    let mut lines = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut cells: Vec<&str> = line.split(',').collect();
        let t = cells.remove(0);
        cells.push(t);
        cells.push(if i == 0 { "status" } else { "ok" });
        lines.push(cells.join(","));
    }
    let csv = write_csv(&dir, &(lines.join("\n") + "\n"));
    let reordered = plot_run(&csv, &dir.join("reordered"), &meta()).unwrap();
    let plain_csv = dir.join("plain.csv");
    std::fs::write(&plain_csv, &text).unwrap();
    // meta() sets the title, so the differing file names do not show.
    let plain = plot_run(&plain_csv, &dir.join("plain"), &meta()).unwrap();
    for (a, b) in reordered.iter().zip(&plain) {
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{}",
            a.display()
        );
    }
}

#[test]
fn windows_line_ends_a_byte_order_mark_and_spaces_are_accepted() {
    let dir = test_dir("crlf_bom");
    let text = run_csv(20);
    let unix = write_csv(&dir, &text);
    let windows = dir.join("windows.csv");
    let spaced = text.replacen("t,X,", " t ,X,", 1).replace("\n", "\r\n");
    std::fs::write(&windows, format!("\u{feff}{spaced}")).unwrap();
    let a = plot_run(&unix, &dir.join("unix"), &meta()).unwrap();
    let b = plot_run(&windows, &dir.join("windows"), &meta()).unwrap();
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(
            std::fs::read(a).unwrap(),
            std::fs::read(b).unwrap(),
            "{}",
            a.display()
        );
    }
}

/// Plots `text` and returns the error message, with the directory replaced by `DIR`.
fn error_for(name: &str, text: &str, meta: &PlotMeta) -> String {
    let dir = test_dir(name);
    let csv = write_csv(&dir, text);
    let out = dir.join("plots");
    let message = plot_run(&csv, &out, meta).unwrap_err().to_string();
    assert!(!out.exists(), "{name}: no file is written on error");
    message.replace(&dir.display().to_string(), "DIR")
}

/// The synthetic CSV with cell (`line` 1-based, column `name`) replaced.
fn with_cell(line: usize, name: &str, value: &str) -> String {
    let col = header().iter().position(|n| n == name).unwrap();
    run_csv(10)
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == line {
                let mut cells: Vec<&str> = l.split(',').collect();
                cells[col] = value;
                cells.join(",")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn bad_csv_files_get_located_messages() {
    let dir = test_dir("missing_file");
    let missing = dir.join("nope.csv");
    let e = plot_run(&missing, &dir.join("plots"), &meta())
        .unwrap_err()
        .to_string();
    assert_eq!(
        e.replace(&dir.display().to_string(), "DIR"),
        "cannot read run CSV DIR/nope.csv: No such file or directory (os error 2); \
         check the path and that the run wrote its CSV"
    );

    assert_eq!(
        error_for("empty", "", &meta()),
        "DIR/run.csv: empty file, no header row; a run CSV starts with a header `t,X,Y,Z,...` \
         (write it with `rover simulate`)"
    );
    assert_eq!(
        error_for("no_rows", &(header().join(",") + "\n"), &meta()),
        "DIR/run.csv: header only, no data rows; the run stopped before its first output sample: \
         rerun it and check its error message"
    );
    let no_vset = run_csv(5).replace(",V_set\n", ",V_sat\n");
    assert_eq!(
        error_for("missing_column", &no_vset, &meta()),
        "DIR/run.csv:1: no column `V_set` in the header (needed for the speed plot); \
         write the CSV with `rover simulate` or add the column"
    );
    // `Fn3` is column 7 + 4 + 6 + 4 + 12 + 2 * 6 + 4 = 49.
    assert_eq!(
        error_for("not_a_number", &with_cell(4, "Fn3", "12.5N"), &meta()),
        "DIR/run.csv:4: column `Fn3` (column 49): `12.5N` is not a number; fix or delete line 4"
    );
    assert_eq!(
        error_for("empty_cell", &with_cell(2, "Z", ""), &meta()),
        "DIR/run.csv:2: column `Z` (column 4): `` is not a number; fix or delete line 2"
    );
    assert_eq!(
        error_for("nan", &with_cell(7, "theta", "NaN"), &meta()),
        "DIR/run.csv:7: column `theta` (column 6) is `NaN`, not a finite number; the run diverged \
         there: delete line 7 and the lines after it to plot what came before"
    );
    assert_eq!(
        error_for("time_backwards", &with_cell(5, "t", "0.05"), &meta()),
        "DIR/run.csv:5: t = 0.05 is before the previous line's t = 0.2; t must not decrease \
         (are two runs appended in one file?)"
    );
    let mut cut = run_csv(4);
    cut.push_str("0.4,1.0,2.0");
    assert_eq!(
        error_for("cut_line", &cut, &meta()),
        format!(
            "DIR/run.csv:6: 3 fields, the header has {}; the line is incomplete or has extra \
             fields (a run killed while writing?): fix or delete line 6",
            header().len()
        )
    );
}

#[test]
fn bad_cells_in_columns_the_plots_do_not_read_are_no_error() {
    let dir = test_dir("unused_bad_cell");
    let csv = write_csv(&dir, &with_cell(3, "Fd2", "n/a"));
    assert_eq!(
        plot_run(&csv, &dir.join("plots"), &meta()).unwrap().len(),
        12
    );
}

#[test]
fn metadata_that_does_not_fit_the_csv_is_refused() {
    let mut m = meta();
    m.coordinate_names.pop();
    assert_eq!(
        error_for("meta_names", &run_csv(5), &m),
        "plot metadata for DIR/run.csv: 3 coordinate names given but the CSV has 4 suspension \
         coordinates (y1..y4); give one name per coordinate, or none"
    );
    let mut m = meta();
    m.wheel_names.push("extra".into());
    assert_eq!(
        error_for("meta_wheels", &run_csv(5), &m),
        "plot metadata for DIR/run.csv: 5 wheel names given but the CSV has 4 wheels (W1X..W4X); \
         give one name per wheel, or none"
    );
    let mut m = meta();
    m.settle_time = f64::NAN;
    assert_eq!(
        error_for("meta_settle", &run_csv(5), &m),
        "plot metadata for DIR/run.csv: settle_time must be a finite time >= 0 s, got NaN"
    );
}

#[test]
fn a_long_run_is_thinned_to_a_bounded_file_size() {
    // 20 000 samples: drawn whole, the trajectories and coordinates SVGs
    // would hold 9 and 10 polylines of 20 000 points (about 3 MB each).
    let dir = test_dir("long_run");
    let csv = write_csv(&dir, &run_csv(20_000));
    let written = plot_run(&csv, &dir.join("plots"), &meta()).unwrap();
    for path in written
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
    {
        let size = std::fs::metadata(path).unwrap().len();
        assert!(size < 1_000_000, "{}: {size} bytes", path.display());
    }
}
