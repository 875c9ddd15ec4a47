//! The ruts a run leaves, as files (docs/CLI.md, docs/TERRAIN.md "Rut
//! maps"): `rover simulate` on a soil writes the rut depth as a CSV grid
//! and a 16-bit PNG, and the ground (terrain minus rut) as a CSV grid, all
//! read back by the terrain reader; the summary's `ruts` agrees with them;
//! the next run loads `ground.csv` as its terrain; a run without ruts
//! leaves no earlier run's rut files behind.

use std::path::{Path, PathBuf};

use rover::cli::{SimulateArgs, simulate};
use rover_dynamics::HeightField;
use rover_terrain::{Georeference, SampleScale, read_csv, read_png};
use serde_json::Value;

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("rut_outputs")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn short_drive() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/soil_pocket_short.toml")
}

#[test]
fn a_run_on_soil_writes_its_ruts_as_the_next_runs_terrain() {
    let dir = scratch("pocket");
    let out = dir.join("out");
    let scenario = short_drive();
    let report = simulate(&SimulateArgs {
        rover: None,
        scenario: scenario.clone(),
        out: out.clone(),
        quiet: true,
        no_plots: false,
        generic: false,
        mcap: false,
    })
    .unwrap();
    assert!(report.summary.complete, "{:?}", report.summary.error);
    for f in [
        "ruts.csv",
        "ruts.png",
        "ground.csv",
        "ruts_map.png",
        "ruts_map.svg",
    ] {
        assert!(
            report.files.contains(&out.join(f)),
            "{f} not among {:?}",
            report.files
        );
        assert!(out.join(f).metadata().unwrap().len() > 0, "{f} empty");
    }
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let ruts = &summary["ruts"];
    let deepest = ruts["deepest_m"].as_f64().unwrap();
    let cell = ruts["cell_m"].as_f64().unwrap();
    assert_eq!(cell, 0.02);
    assert!(
        deepest > 0.0 && ruts["tiles"].as_u64().unwrap() > 0,
        "{ruts}"
    );

    // The CSV grid: where the summary says, its deepest the summary's.
    let rut = read_csv(&out.join("ruts.csv"), None).unwrap();
    let g = &ruts["grid"];
    let origin = [0, 1].map(|k| g["origin_m"][k].as_f64().unwrap());
    let spacing = g["spacing_m"].as_f64().unwrap();
    assert_eq!(rut.origin(), origin);
    assert_eq!(rut.spacing(), [spacing; 2]);
    assert_eq!(
        [rut.nx(), rut.ny()].map(|n| n as u64),
        [0, 1].map(|k| g["nodes"][k].as_u64().unwrap())
    );
    let max = rut
        .heights()
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    assert_eq!(max, deepest);
    let touched = rut.heights().iter().filter(|d| **d > 0.0).count();
    let area = ruts["touched_area_m2"].as_f64().unwrap();
    assert!((area - touched as f64 * cell * cell).abs() < 1e-12 * area.max(1.0));

    // The PNG: the same depths to its scale's resolution.
    let scale = g["png_scale_m"].as_f64().unwrap();
    assert_eq!(scale, 1e-5);
    let png = read_png(
        &out.join("ruts.png"),
        Georeference {
            origin,
            spacing: [spacing; 2],
        },
        SampleScale { scale, offset: 0.0 },
    )
    .unwrap();
    assert_eq!([png.nx(), png.ny()], [rut.nx(), rut.ny()]);
    for (a, b) in png.heights().iter().zip(rut.heights()) {
        assert!((a - b).abs() <= 0.5 * scale + 1e-15, "{a} against {b}");
    }

    // The ground: the run's terrain minus the rut, at every node with a
    // rut and at a stride of the others.
    let ground = read_csv(&out.join("ground.csv"), None).unwrap();
    assert_eq!(ground.origin(), origin);
    let prepared = rover_scenario::prepare::Prepared::from_file(None, &scenario).unwrap();
    let terrain = prepared.scenario.terrain.build(&prepared.base).unwrap();
    let nx = rut.nx();
    for (k, (&z, &d)) in ground.heights().iter().zip(rut.heights()).enumerate() {
        if d == 0.0 && k % 97 != 0 {
            continue;
        }
        let (x, y) = (
            origin[0] + (k % nx) as f64 * spacing,
            origin[1] + (k / nx) as f64 * spacing,
        );
        let expected = terrain.height(x, y).unwrap() - d;
        assert!(
            (z - expected).abs() < 1e-12,
            "({x}, {y}): {z} against {expected}"
        );
    }

    // The next run's terrain: the ground file, as docs/TERRAIN.md loads it.
    let next = dir.join("next.toml");
    std::fs::write(
        &next,
        "rover = \"mer\"\nduration = 1.0\n[terrain]\nkind = \"file\"\npath = \"out/ground.csv\"\n",
    )
    .unwrap();
    let prepared = rover_scenario::prepare::Prepared::from_file(None, &next).unwrap();
    let loaded = prepared.scenario.terrain.build(&prepared.base).unwrap();
    let k = rut.heights().iter().position(|d| *d == deepest).unwrap();
    let (x, y) = (
        origin[0] + (k % nx) as f64 * spacing,
        origin[1] + (k / nx) as f64 * spacing,
    );
    let below = terrain.height(x, y).unwrap() - deepest;
    assert!((loaded.height(x, y).unwrap() - below).abs() < 1e-12);

    // A run without ruts in the same folder leaves none of these behind.
    let firm = dir.join("firm.toml");
    std::fs::write(&firm, "rover = \"mer\"\nduration = 0.2\n").unwrap();
    let report = simulate(&SimulateArgs {
        rover: None,
        scenario: firm,
        out: out.clone(),
        quiet: true,
        no_plots: true,
        generic: false,
        mcap: false,
    })
    .unwrap();
    assert!(report.summary.ruts.is_none());
    for f in [
        "ruts.csv",
        "ruts.png",
        "ground.csv",
        "ruts_map.png",
        "ruts_map.svg",
    ] {
        assert!(!out.join(f).exists(), "{f} left from the run before");
    }
}
