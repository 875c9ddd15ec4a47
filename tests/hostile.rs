//! Hostile input, end to end through the binary: every case ends in
//! bounded time and memory, without a panic, with the expected exit code
//! and an error naming the file, the field and the fix; a run that cannot
//! start leaves no output that passes for a result.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Wall time any case may take.
const TIME_LIMIT: Duration = Duration::from_secs(60);
/// Address space any case may use (kB, `ulimit -v`): a memory bomb aborts.
const MEMORY_LIMIT_KB: u64 = 4_000_000;

pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("hostile")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run `rover args…` in `dir` under the time and memory limits.
pub(crate) fn rover(dir: &Path, args: &[&str]) -> Output {
    let mut script = format!("ulimit -v {MEMORY_LIMIT_KB}; exec \"$0\"");
    for i in 1..=args.len() {
        script.push_str(&format!(" \"${{{i}}}\""));
    }
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_rover"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if started.elapsed() > TIME_LIMIT {
            let _ = child.kill();
            panic!("rover {args:?} still running after {TIME_LIMIT:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// `rover args…` exits with `code`, without a panic, its standard error
/// holding every one of `parts`.
pub(crate) fn expect(dir: &Path, args: &[&str], code: i32, parts: &[&str]) -> String {
    let out = rover(dir, args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!err.contains("panicked"), "rover {args:?} panicked: {err}");
    assert!(!err.contains("memory allocation"), "rover {args:?}: {err}");
    assert_eq!(out.status.code(), Some(code), "rover {args:?}: {err}");
    for p in parts {
        assert!(err.contains(p), "rover {args:?}: no `{p}` in: {err}");
    }
    err
}

fn swing4() -> String {
    rover_models::builtin("swing4").unwrap().to_string()
}

/// swing4's body and wheel defaults with `n` swing arms, each with a wheel.
fn many_wheels(n: usize) -> String {
    let base = swing4();
    let head = &base[..base.find("[[suspension]]").unwrap()];
    let mut s = head.replace("name = \"swing4\"", "name = \"many\"");
    for i in 0..n {
        s.push_str(&format!(
            "[[suspension]]\nname = \"s{i}\"\nkind = \"longitudinal_swing_arm\"\npivot = [{}, 0.2, -0.01]\nlength = 0.2\n\
             coordinate = {{ name = \"y{i}\", rest_deg = -17.2, neutral_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 }}\n\
             fit = {{ method = \"taylor\", terms = 5 }}\n\n[[wheel]]\nname = \"w{i}\"\nsuspension = \"s{i}\"\n\n",
            0.5 * i as f64
        ));
    }
    s
}

pub(crate) fn write(dir: &Path, name: &str, text: impl AsRef<[u8]>) {
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn rovers_that_cannot_run_are_refused_by_every_command_naming_the_field() {
    let dir = scratch("rovers");
    let base = swing4();
    let last_wheel = base.find("[[wheel]]\nname = \"rear_right\"").unwrap();
    let cases: Vec<(&str, String, &[&str])> = vec![
        (
            "dof27.toml",
            many_wheels(27),
            &["suspension[26]", "at most 26"],
        ),
        ("dof50.toml", many_wheels(50), &["at most 26"]),
        (
            "no_wheel.toml",
            base[..base.find("[[suspension]]").unwrap()].to_string(),
            &["no wheel", "[[wheel]]"],
        ),
        (
            "heavy.toml",
            base.replace("mass = 30.0", "mass = 1e308"),
            &["body.mass", "too large"],
        ),
        (
            "sinks.toml",
            base.replace("mass = 30.0", "mass = 1e6"),
            &["body.mass", "cannot carry", "stiffness"],
        ),
        (
            "tiny.toml",
            base.replace("mass = 30.0", "mass = 1e-9"),
            &["body.mass", "below"],
        ),
        (
            "radius.toml",
            base.replace("radius = 0.090", "radius = 1e308"),
            &["wheel_defaults.radius", "too large"],
        ),
        (
            "inertia.toml",
            base.replace(
                "inertia = [0.7, 0.9, 1.5]",
                "inertia = [1e308, 1e308, 1e308]",
            ),
            &["body.inertia", "too large"],
        ),
        (
            "k_w.toml",
            base.replace("stiffness = 4000.0", "stiffness = 1e308"),
            &["wheel_defaults.stiffness", "too large"],
        ),
        (
            "gravity.toml",
            base.replace("gravity = 1.62", "gravity = 1e308"),
            &["gravity", "too large"],
        ),
        (
            "gravity_300.toml",
            base.replace("gravity = 1.62", "gravity = 300.0"),
            &["gravity", "Mars 3.71"],
        ),
        (
            "no_name.toml",
            base.replace("name = \"swing4\"", "name = \"\""),
            &["name", "empty"],
        ),
        (
            "same_place.toml",
            base.replace(
                "pivot = [0.180, -0.200, -0.010]",
                "pivot = [0.180, 0.200, -0.010]",
            ),
            &["wheel[1]", "same place as wheel 1"],
        ),
        (
            "arm_without_wheel.toml",
            base[..last_wheel].to_string(),
            &["suspension[3].coordinate", "moves no mass", "help:"],
        ),
    ];
    for (file, text, parts) in cases {
        write(&dir, file, text);
        expect(&dir, &["check", file], 2, parts);
        expect(&dir, &["codegen", file], 2, parts);
        expect(&dir, &["linearize", file], 2, parts);
    }
    // Not UTF-8: the byte, its line and column.
    let mut bytes = base.into_bytes();
    bytes.insert(300, 0xff);
    write(&dir, "latin1.toml", &bytes);
    expect(
        &dir,
        &["check", "latin1.toml"],
        2,
        &["byte 301", "line 5", "UTF-8"],
    );
    std::fs::create_dir_all(dir.join("folder.toml")).unwrap();
    expect(&dir, &["check", "folder.toml"], 2, &["is a directory"]);
}

/// `rover simulate swing4` on `scenario`; its error and summary.
fn simulate(
    dir: &Path,
    name: &str,
    scenario: &str,
    code: i32,
    parts: &[&str],
) -> serde_json::Value {
    let file = format!("{name}.toml");
    write(dir, &file, scenario);
    let out = format!("out_{name}");
    expect(
        dir,
        &[
            "simulate",
            "swing4",
            "--scenario",
            &file,
            "--out",
            &out,
            "--quiet",
            "--no-plots",
        ],
        code,
        parts,
    );
    let summary = std::fs::read_to_string(dir.join(&out).join("summary.json")).unwrap_or_default();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap_or_default();
    assert_ne!(summary["status"], "running", "{name}: {summary}");
    summary
}

#[test]
fn scenarios_that_would_hang_or_flood_are_refused_naming_the_field() {
    let dir = scratch("limits");
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "rk4_tiny",
            "duration = 1.0\n[integrator.rk4]\nstep = 1e-12\n",
            &["rk4_tiny.toml:3", "integrator.rk4.step", "steps", "help:"],
        ),
        (
            "rk4_denormal",
            "duration = 1.0\n[integrator.rk4]\nstep = 5e-324\n",
            &["integrator.rk4.step"],
        ),
        (
            "euler_tiny",
            "duration = 1.0\n[integrator.semi_implicit_euler]\nstep = 1e-15\n",
            &["integrator.semi_implicit_euler.step"],
        ),
        (
            "dopri_max_step",
            "duration = 1.0\n[integrator.dopri5]\nmax_step = 1e-9\n",
            &["integrator.dopri5.max_step"],
        ),
        (
            "samples",
            "duration = 1.0\n[contact]\nsamples = 10000000\n",
            &["samples.toml:3", "contact.samples", "10000", "help:"],
        ),
        (
            "path_twice",
            "duration = 1.0\nfidelity = \"quasi_static\"\npath_from = \"path.csv\"\n",
            &["path.csv:3", "t = 0", "must increase"],
        ),
        (
            "long",
            "duration = 1e12\n",
            &["long.toml:1", "output rows", "1000000", "help:"],
        ),
        (
            "dense",
            "duration = 2.0\noutput_rate = 1e9\n",
            &["dense.toml:2", "output_rate"],
        ),
        (
            "below",
            "duration = 1.0\n[initial]\nz = -1.0\n",
            &[
                "below.toml:3",
                "initial.z",
                "into the ground",
                "leave z out",
            ],
        ),
        (
            "far",
            "duration = 1.0\n[initial]\nxy = [1e300, 0.0]\n",
            &["far.toml:3", "initial.xy", "help:"],
        ),
        (
            "tipped",
            "duration = 1.0\n[initial]\nattitude_deg = [85.0, 0.0, 0.0]\n",
            &["initial.attitude_deg", "roll-over limit"],
        ),
        (
            "nan",
            "duration = 1.0\n[initial]\nvelocity = [nan, 0.0, 0.0]\n",
            &["nan.toml:3", "initial.velocity", "finite"],
        ),
        (
            "two_integrators",
            "duration = 1.0\n[integrator.rk4]\nstep = 1e-3\n[integrator.bdf]\nrtol = 1e-3\n",
            &["line 2", "help: give exactly one method table"],
        ),
        (
            "scale0",
            "duration = 1.0\n[terrain]\nkind = \"file\"\npath = \"m.asc\"\nscale = 0.0\n",
            &["scale0.toml:5", "terrain.scale"],
        ),
        (
            "folder",
            "duration = 1.0\n[terrain]\nkind = \"file\"\npath = \"maps\"\n",
            &["terrain.path", "is a directory"],
        ),
        (
            "huge_height",
            "duration = 1.0\n[terrain]\nkind = \"file\"\npath = \"huge.asc\"\n",
            &["huge.asc", "column 2, row 2", "1e308"],
        ),
        (
            "huge_png",
            "duration = 1.0\n[terrain]\nkind = \"file\"\npath = \"huge.png\"\norigin = [-5.0, -5.0]\nspacing = [0.01, 0.01]\nscale = 0.001\n",
            &["huge.png", "20000 × 20000", "at most 50000000", "crop"],
        ),
    ];
    write(&dir, "path.csv", "t,X,Y,psi\n0,0,0,0\n0,1,0,0\n1,2,0,0\n");
    write(
        &dir,
        "m.asc",
        "ncols 3\nnrows 3\nxllcorner -5\nyllcorner -5\ncellsize 5\n0 0 0\n0 0 0\n0 0 0\n",
    );
    write(
        &dir,
        "huge.asc",
        "ncols 3\nnrows 3\nxllcorner -5\nyllcorner -5\ncellsize 5\n0 0 0\n0 1e308 0\n0 0 0\n",
    );
    write(&dir, "huge.png", huge_png(20_000, 20_000));
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    for (name, scenario, parts) in cases {
        // Refused when read (nothing written) or when set up (a summary
        // that says so, no CSV).
        let summary = simulate(&dir, name, scenario, 2, parts);
        assert!(
            summary.is_null() || summary["status"] == "failed",
            "{name}: {summary}"
        );
        assert!(!dir.join(format!("out_{name}/run.csv")).exists(), "{name}");
    }
    // A 200 kB line is not echoed whole.
    let long_line = format!("duration = 1.0\nrover = \"{}\" = 1\n", "x".repeat(200_000));
    write(&dir, "wide.toml", &long_line);
    let err = expect(
        &dir,
        &["simulate", "swing4", "--scenario", "wide.toml", "--quiet"],
        2,
        &["wide.toml", "help:"],
    );
    assert!(err.len() < 2_000, "{} bytes", err.len());
    // Not UTF-8.
    write(&dir, "latin1.toml", b"duration = 1.0 # \xe9t\xe9\n");
    expect(
        &dir,
        &["simulate", "swing4", "--scenario", "latin1.toml", "--quiet"],
        2,
        &["latin1.toml:1", "column 18", "UTF-8"],
    );
}

#[test]
fn output_rates_that_miss_the_end_still_end_with_its_row() {
    let dir = scratch("rates");
    for (name, rate) in [("slow", "0.7"), ("once", "1e-9")] {
        let summary = simulate(
            &dir,
            name,
            &format!("duration = 2.0\noutput_rate = {rate}\n"),
            0,
            &[],
        );
        assert_eq!(summary["status"], "completed", "{name}");
        assert_eq!(summary["final_state"]["t"], 2.0, "{name}: {summary}");
        let csv = std::fs::read_to_string(dir.join(format!("out_{name}/run.csv"))).unwrap();
        let last = csv.lines().last().unwrap();
        assert!(
            last.starts_with("2,") || last.starts_with("2.0,"),
            "{name}: {last}"
        );
    }
}

#[test]
fn a_diverging_fixed_step_is_reported_as_divergence_not_a_roll_over() {
    let dir = scratch("diverge");
    let summary = simulate(
        &dir,
        "big_step",
        "duration = 1.0\n[integrator.rk4]\nstep = 10.0\n",
        1,
        &["diverged", "step"],
    );
    assert_eq!(summary["status"], "failed");
}

#[test]
fn a_rejected_scenario_leaves_no_earlier_result_behind() {
    let dir = scratch("stale");
    simulate(&dir, "run", "duration = 0.5\n", 0, &[]);
    std::fs::rename(dir.join("out_run"), dir.join("out_bad")).unwrap();
    let summary = simulate(
        &dir,
        "bad",
        "duration = 0.5\n[contact]\nsamples = 1\n",
        2,
        &["contact.samples"],
    );
    assert_eq!(summary["status"], "failed");
    assert!(!dir.join("out_bad/run.csv").exists());
}

#[test]
fn linearize_refuses_a_speed_beyond_any_rover() {
    let dir = scratch("linearize");
    expect(
        &dir,
        &["linearize", "swing4", "--speed", "1e9"],
        2,
        &["1000000000 m/s", "±100 m/s"],
    );
}

#[cfg(unix)]
#[test]
fn sigterm_ends_a_run_like_ctrl_c() {
    let dir = scratch("sigterm");
    write(
        &dir,
        "long.toml",
        "duration = 500.0\noutput_rate = 10.0\n[terrain]\nkind = \"random\"\nz_r = 0.2\n",
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_rover"))
        .args([
            "simulate",
            "swing4",
            "--scenario",
            "long.toml",
            "--out",
            "out",
            "--quiet",
            "--no-plots",
            "--generic",
        ])
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait for the first rows, then terminate.
    let started = Instant::now();
    while std::fs::metadata(dir.join("out/run.csv")).map_or(0, |m| m.len()) < 2_000 {
        assert!(started.elapsed() < TIME_LIMIT, "no rows");
        std::thread::sleep(Duration::from_millis(50));
    }
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        assert!(
            started.elapsed() < TIME_LIMIT,
            "still running after SIGTERM"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["status"], "interrupted", "{summary}");
}

/// A 16-bit grayscale PNG that declares `width × height` pixels and holds
/// one byte of image data: its header alone asks for gigabytes.
fn huge_png(width: u32, height: u32) -> Vec<u8> {
    fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let start = out.len();
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
        let crc = crc32(&out[start..]);
        out.extend_from_slice(&crc.to_be_bytes());
    }
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = 0xffff_ffffu32;
        for &b in bytes {
            crc ^= u32::from(b);
            for _ in 0..8 {
                crc = if crc & 1 != 0 {
                    (crc >> 1) ^ 0xedb8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&width.to_be_bytes());
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[16, 0, 0, 0, 0]);
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(
        &mut out,
        b"IDAT",
        &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01],
    );
    chunk(&mut out, b"IEND", &[]);
    out
}

/// Descriptions that are absurd, end to end: names that would drive the
/// terminal are refused escaped (nothing reaches the terminal raw), a type
/// name that is a keyword is refused as such, an equilibrium on a bump stop
/// is refused naming the suspension, and Ackermann commands beyond any
/// steering geometry name their field; a bad value inside `[terrain]` is
/// reported at its own line and column.
#[test]
fn absurd_descriptions_and_commands_are_refused_naming_the_field() {
    let dir = scratch("absurd");
    let base = swing4();
    let escape = base.replacen(
        "name = \"front_left\"\nsuspension",
        "name = \"\\u001b[2J\\u001b]0;pwned\\u0007\"\nsuspension",
        1,
    );
    assert_ne!(escape, base);
    write(&dir, "escape.toml", &escape);
    for command in ["check", "codegen", "linearize"] {
        let out = rover(&dir, &[command, "escape.toml"]);
        let (stdout, stderr) = (
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
        );
        assert_eq!(out.status.code(), Some(2), "{command}: {stderr}");
        assert!(
            !stdout.contains('\u{1b}') && !stderr.contains('\u{1b}') && !stderr.contains('\u{7}'),
            "{command} printed a control character: {stderr:?}"
        );
        assert!(
            stderr.contains("wheel[0].name") && stderr.contains(r#""\u{1b}[2J"#),
            "{command}: {stderr}"
        );
    }
    let out = rover(&dir, &["codegen", "swing4", "--type-name", "Self"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_ne!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("keyword") && !err.contains("internal error"),
        "{err}"
    );

    // One wheel on an arm ahead of G: it would come under G at 64°, beyond
    // the travel's end at -2°.
    let head = &base[..base.find("[[suspension]]").unwrap()];
    let one = format!(
        "{head}[[suspension]]\nname = \"only\"\nkind = \"longitudinal_swing_arm\"\npivot = [0.18, 0.0, -0.01]\nlength = 0.2\n\
         coordinate = {{ rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 }}\n\n\
         [[wheel]]\nname = \"only\"\nsuspension = \"only\"\n"
    );
    write(&dir, "one.toml", &one);
    expect(&dir, &["check", "one.toml"], 0, &[]);
    let err = expect(
        &dir,
        &["codegen", "one.toml", "--fidelity", "simplified"],
        2,
        &[
            "suspension `only`",
            "outside its travel [-60°, -2°]",
            "help:",
        ],
    );
    assert!(!err.contains("internal error"), "{err}");

    let scenario = |name: &str, text: &str, parts: &[&str]| {
        write(&dir, &format!("{name}.toml"), text);
        let out = format!("out_{name}");
        let scenario = format!("{name}.toml");
        let args = [
            "simulate",
            "lrv",
            "--scenario",
            &scenario,
            "--out",
            &out,
            "--quiet",
            "--no-plots",
        ];
        let run = rover(&dir, &args);
        let err = String::from_utf8_lossy(&run.stderr).to_string();
        assert_ne!(run.status.code(), Some(0), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        for p in parts {
            assert!(err.contains(p), "{name}: no `{p}` in: {err}");
        }
    };
    scenario(
        "angle",
        "duration = 1.0\n[control.steering]\nkind = \"ackermann\"\nfront_left_deg = 1e12\n",
        &["control.steering.front_left_deg", "between -90° and 90°"],
    );
    scenario(
        "radius",
        "duration = 1.0\n[control.steering]\nkind = \"ackermann\"\nradius = 0.0\n",
        &["control.steering.radius", "0 m is no turn"],
    );
    scenario(
        "seed",
        "duration = 1.0\nsettle = 0.5\noutput_rate = 20.0\n\n# rough ground\n\n\n[terrain]\nseed = -3\nkind = \"random\"\nz_r = 0.1\n",
        &["line 9, column 8", "seed = -3"],
    );
}
