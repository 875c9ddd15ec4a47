//! Files that are not what they claim, end to end through the binary:
//! devices, FIFOs and links where a file is named, files on the machine
//! that a scenario names (located in errors, never quoted), outputs that
//! would escape their folder or destroy an input, and Ctrl-C at any time.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::hostile::{expect, rover, scratch, write};

/// `rover simulate --scenario scenario --out out` in `dir` succeeds.
fn runs(dir: &Path, scenario: &str, out: &str) {
    let args = [
        "simulate",
        "--scenario",
        scenario,
        "--out",
        out,
        "--no-plots",
        "--quiet",
    ];
    let done = rover(dir, &args);
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
}

fn mkfifo(path: &Path) {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
}

fn symlink(target: impl AsRef<Path>, link: &Path) {
    std::os::unix::fs::symlink(target, link).unwrap();
}

/// The same scenario around a `[terrain]`, `[control.commands]` or rover
/// naming `name`.
fn naming(what: &str, name: &str) -> String {
    match what {
        "rover" => format!("rover = \"{name}\"\nduration = 1.0\n"),
        "terrain" => format!(
            "rover = \"swing4\"\nduration = 1.0\n[terrain]\nkind = \"file\"\npath = \"{name}\"\nscale = 0.001\norigin = [-1.0, -1.0]\nspacing = [0.05, 0.05]\n"
        ),
        "soil" => format!(
            "rover = \"mer\"\nduration = 1.0\n[terrain]\nkind = \"flat\"\nsoil = \"{name}\"\n"
        ),
        "commands" => {
            format!("rover = \"swing4\"\nduration = 1.0\n[control.commands]\nfile = \"{name}\"\n")
        }
        _ => unreachable!(),
    }
}

#[test]
fn devices_fifos_and_links_to_them_are_refused_wherever_a_file_is_named() {
    let dir = scratch("special-files");
    symlink("/dev/zero", &dir.join("zero.toml"));
    symlink("/dev/urandom", &dir.join("random.png"));
    mkfifo(&dir.join("pipe.csv"));
    // Given directly.
    for (args, what) in [
        (&["check", "/dev/zero"][..], "character device"),
        (&["check", "zero.toml"], "character device"),
        (&["check", "pipe.csv"], "FIFO"),
        (
            &["simulate", "--scenario", "/dev/urandom", "--out", "o"],
            "character device",
        ),
        (
            &["simulate", "--scenario", "pipe.csv", "--out", "o"],
            "FIFO",
        ),
    ] {
        let started = Instant::now();
        expect(&dir, args, 2, &[what, "not a regular file"]);
        assert!(started.elapsed() < Duration::from_secs(10), "{args:?}");
    }
    // Named by a scenario.
    for (kind, name, what) in [
        ("rover", "zero.toml", "character device"),
        ("terrain", "random.png", "character device"),
        ("terrain", "pipe.csv", "FIFO"),
        ("soil", "zero.toml", "character device"),
        ("commands", "pipe.csv", "FIFO"),
        ("commands", "/dev/zero", "character device"),
    ] {
        let file = format!("{kind}-{}.toml", name.replace(['/', '.'], "_"));
        write(&dir, &file, naming(kind, name));
        let started = Instant::now();
        expect(
            &dir,
            &["simulate", "--scenario", &file, "--out", "o"],
            2,
            &[what],
        );
        assert!(started.elapsed() < Duration::from_secs(10), "{kind} {name}");
    }
}

#[test]
fn a_file_that_a_scenario_names_is_located_but_never_quoted() {
    let dir = scratch("unquoted");
    write(
        &dir,
        "secrets",
        "root:SECRET-ONE:0:0\naws_secret = \"SECRET-TWO\"\n",
    );
    for kind in ["rover", "soil", "commands"] {
        let file = format!("{kind}.toml");
        write(&dir, &file, naming(kind, "secrets"));
        let err = expect(
            &dir,
            &["simulate", "--scenario", &file, "--out", "o"],
            2,
            &["secrets"],
        );
        assert!(!err.contains("SECRET"), "{kind}: {err}");
    }
    // Located: the rover's and the soil's errors say where.
    let err = expect(
        &dir,
        &["simulate", "--scenario", "rover.toml", "--out", "o"],
        2,
        &[],
    );
    assert!(err.contains("secrets:1:5"), "{err}");
    let err = expect(
        &dir,
        &["simulate", "--scenario", "soil.toml", "--out", "o"],
        2,
        &[],
    );
    assert!(err.contains("secrets:1:"), "{err}");
    // A description given on the command line is the user's own: quoted.
    let err = expect(&dir, &["check", "secrets"], 2, &[]);
    assert!(err.contains("root:SECRET-ONE"), "{err}");
}

#[test]
fn outputs_never_escape_their_folder_nor_replace_anything_but_a_regular_file() {
    let dir = scratch("outputs");
    write(&dir, "s.toml", "rover = \"swing4\"\nduration = 0.2\n");
    write(&dir, "precious", "keep");
    let precious = || std::fs::read_to_string(dir.join("precious")).unwrap();
    // Each output, a link to a file outside the folder.
    for (folder, name) in [("linked", "run.csv"), ("summary", "summary.json")] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
        symlink(dir.join("precious"), &dir.join(folder).join(name));
        let args = [
            "simulate",
            "--scenario",
            "s.toml",
            "--out",
            folder,
            "--no-plots",
        ];
        expect(&dir, &args, 2, &[name, "symbolic link"]);
    }
    assert_eq!(precious(), "keep");
    // `--out` that is a file, a device or an input.
    expect(
        &dir,
        &["simulate", "--scenario", "s.toml", "--out", "precious"],
        2,
        &["--out precious", "is a file, not a folder"],
    );
    expect(
        &dir,
        &["simulate", "--scenario", "s.toml", "--out", "/dev/null"],
        2,
        &["--out /dev/null", "character device"],
    );
    write(&dir, "r.toml", rover_models::builtin("swing4").unwrap());
    for args in [
        &["codegen", "r.toml", "--out", "r.toml"][..],
        &[
            "linearize",
            "swing4",
            "--scenario",
            "s.toml",
            "--out",
            "s.toml",
        ],
    ] {
        expect(&dir, args, 2, &["is the input", "another path"]);
    }
    mkfifo(&dir.join("fifo"));
    for out in [".", "/dev/null", "fifo", "linked/run.csv"] {
        expect(&dir, &["codegen", "swing4", "--out", out], 2, &["--out"]);
    }
    assert_eq!(precious(), "keep");
    assert_eq!(
        std::fs::read_to_string(dir.join("r.toml")).unwrap(),
        rover_models::builtin("swing4").unwrap()
    );
    // And a good run writes regular files only.
    runs(&dir, "s.toml", "good");
    for name in ["run.csv", "summary.json"] {
        assert!(
            std::fs::symlink_metadata(dir.join("good").join(name))
                .unwrap()
                .is_file()
        );
    }
}

#[test]
fn scenarios_with_absurd_numbers_are_refused_naming_the_field() {
    let dir = scratch("absurd");
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "nan_gain",
            "rover = \"swing4\"\nduration = 1.0\n[control.active_suspension]\nsample_time = 0.1\nkp_pitch = nan\nkd_pitch = 0.0\nkp_roll = 0.5\nkd_roll = 0.0\n",
            &[
                "nan_gain.toml:5",
                "control.active_suspension.kp_pitch = NaN",
                "finite",
            ],
        ),
        (
            "inf_speed",
            "rover = \"swing4\"\nduration = 1.0\n[control.speed]\nspeed = inf\nkp = 10.0\n",
            &["inf_speed.toml:4", "control.speed.speed", "finite"],
        ),
        (
            "tiny_sample",
            "rover = \"swing4\"\nduration = 1.0\n[control.active_suspension]\nsample_time = 1e-9\nkp_pitch = 0.5\nkd_pitch = 0.0\nkp_roll = 0.5\nkd_roll = 0.0\n",
            &["tiny_sample.toml:4", "sample_time", "updates"],
        ),
        (
            "high_start",
            "rover = \"swing4\"\nduration = 10.0\n[initial]\nz = 1e6\n",
            &["initial.z", "fall", "whole run"],
        ),
        (
            "fine_waves",
            "rover = \"swing4\"\nduration = 1.0\n[terrain]\nkind = \"sinusoid\"\namplitude = 0.01\nwavelength = 1e-6\n",
            &["terrain.wavelength", "shorter than 0.001 m"],
        ),
    ];
    for (name, text, parts) in cases {
        let file = format!("{name}.toml");
        write(&dir, &file, text);
        let started = Instant::now();
        expect(
            &dir,
            &["simulate", "--scenario", &file, "--out", "o"],
            2,
            parts,
        );
        assert!(started.elapsed() < Duration::from_secs(20), "{name}");
    }
    // A drop the run can land from is still a valid start.
    write(
        &dir,
        "drop.toml",
        "rover = \"swing4\"\nduration = 1.0\n[initial]\nz = 0.5\n",
    );
    runs(&dir, "drop.toml", "d");
}

#[test]
fn ctrl_c_while_a_run_is_prepared_ends_it_within_a_second() {
    let dir = scratch("ctrl-c-preparing");
    // A fine random terrain: seconds of generation before the first step.
    write(
        &dir,
        "fine.toml",
        "rover = \"swing4\"\nduration = 1.0\n[terrain]\nkind = \"random\"\nz_r = 0.2\ngrid_spacing = 0.008\n",
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_rover"))
        .args([
            "simulate",
            "--scenario",
            "fine.toml",
            "--out",
            "out",
            "--quiet",
            "--no-plots",
        ])
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(300));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the preparation ended too soon to test"
    );
    let sent = Instant::now();
    assert!(
        Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status()
            .unwrap()
            .success()
    );
    while child.try_wait().unwrap().is_none() {
        assert!(
            sent.elapsed() < Duration::from_secs(1),
            "still running 1 s after Ctrl-C"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("interrupted while preparing the run"), "{err}");
    assert!(!dir.join("out/run.csv").exists());
    let summary = std::fs::read_to_string(dir.join("out/summary.json")).unwrap();
    assert!(
        summary.contains("\"interrupted\"") && summary.contains("\"complete\": false"),
        "{summary}"
    );
}

#[test]
fn escape_sequences_in_a_file_reach_the_terminal_as_text() {
    let dir = scratch("escapes");
    write(
        &dir,
        "esc.toml",
        "rover = \"ab\u{1b}[2J\u{1b}[31mred\"\nduration = 1.0\n",
    );
    let err = expect(
        &dir,
        &["simulate", "--scenario", "esc.toml", "--out", "o"],
        2,
        &["esc.toml", "\\u{1b}[2J"],
    );
    assert!(!err.contains('\u{1b}'), "{err:?}");
}

#[cfg(feature = "drive")]
#[test]
fn view_serves_only_what_the_run_folder_holds() {
    let dir = scratch("view-link");
    write(
        &dir,
        "elsewhere.csv",
        "t,X,Y,Z,phi,theta,psi,W1X,Fn1\n0,0,0,0,0,0,0,0,0\n",
    );
    std::fs::create_dir_all(dir.join("run")).unwrap();
    symlink(dir.join("elsewhere.csv"), &dir.join("run/run.csv"));
    expect(
        &dir,
        &["view", "run", "--port", "0"],
        2,
        &["run.csv", "symbolic link"],
    );
}

#[test]
fn a_negative_number_is_a_value_refused_by_its_own_range() {
    let dir = scratch("negative");
    let err = expect(
        &dir,
        &["linearize", "exomars", "--speed", "-1e9"],
        2,
        &["speed"],
    );
    assert!(!err.contains("-- -1e9"), "{err}");
    let err = expect(
        &dir,
        &[
            "wheel-test",
            "--soil",
            "dry_sand",
            "--radius",
            "-1",
            "--width",
            "0.1",
            "--load",
            "10",
            "--slip",
            "0.1",
        ],
        2,
        &["--radius -1"],
    );
    assert!(!err.contains("tip:"), "{err}");
}
