//! Ruts: the wheels that follow meet the ruts the wheels before them left,
//! on soil those compacted; the ruts stay where they were made; a map of
//! one soil is that soil; reruns are the same bits.

use std::path::Path;

use rover_scenario::output::Status;
use rover_scenario::prepare::Prepared;

use crate::support::run::{Run, run, run_in};

/// MER driving at 10 cm/s straight over flat dry sand: long enough for the
/// middle wheels (0.69 m behind the front ones) and the rear ones (0.64 m
/// further) to reach the ground the front wheels pressed while moving.
fn straight(extra: &str) -> String {
    format!(
        r#"
rover = "mer"
duration = 20.0
settle = 1.0
output_rate = 10.0
[terrain]
soil = "dry_sand"
{extra}
[control.speed]
speed = 0.1
kp = 500.0
ki = 1000.0
"#
    )
}

/// The mean of `name` over the rows after `t0`.
fn mean_after(r: &Run, name: &str, t0: f64) -> f64 {
    let v = r.after(name, t0);
    v.iter().sum::<f64>() / v.len() as f64
}

/// The middle and rear wheels run in the front wheels' ruts: they read a
/// rut as deep as the front wheels left (their press less the soil's
/// spring-back), sink less below its floor than the front wheels sink
/// into fresh sand, and take less torque from the soil at about the same
/// slip. Without ruts every wheel meets fresh sand and reads none.
#[test]
fn the_wheels_that_follow_run_in_the_ruts_of_those_before() {
    let ruts = run("mer", &straight(""));
    let fresh = run("mer", &straight("ruts = false"));
    for r in [&ruts, &fresh] {
        assert_eq!(r.summary.status, Status::Completed);
    }
    let t0 = 16.0;
    let front_sinkage = mean_after(&ruts, "sinkage1", t0);
    let front_press = mean_after(&ruts, "sinkage_undisturbed1", t0);
    assert_eq!(
        mean_after(&ruts, "rut1", t0),
        0.0,
        "the front wheels meet fresh sand"
    );
    assert_eq!(front_press, front_sinkage);
    // Each pair runs in the rut the pair before it left: its press less
    // the spring-back (about 2 mm in dry sand under these loads).
    let mut press_before = front_press;
    for j in [3, 5] {
        let rut = mean_after(&ruts, &format!("rut{j}"), t0);
        let sinkage = mean_after(&ruts, &format!("sinkage{j}"), t0);
        assert!(
            rut > 0.8 * press_before && rut < press_before,
            "wheel {j}: rut {rut} under a press of {press_before}"
        );
        press_before = mean_after(&ruts, &format!("sinkage_undisturbed{j}"), t0);
        assert!(
            sinkage < 0.5 * front_sinkage,
            "wheel {j} sinks {sinkage} below the rut's floor, the front ones {front_sinkage}"
        );
        let soil_torque = mean_after(&ruts, &format!("T{j}"), t0);
        let in_fresh_sand = mean_after(&fresh, &format!("T{j}"), t0);
        assert!(
            soil_torque < 0.85 * in_fresh_sand,
            "wheel {j}: {soil_torque} N·m in the rut, {in_fresh_sand} in fresh sand"
        );
        assert_eq!(mean_after(&fresh, &format!("rut{j}"), t0), 0.0);
    }
    let header: Vec<_> = ruts
        .header
        .iter()
        .filter(|h| h.starts_with("rut"))
        .collect();
    assert_eq!(header.len(), 6, "{header:?}");
}

/// A run with ruts is deterministic: the same scenario twice gives the
/// same CSV, bit for bit.
#[test]
fn a_rerun_with_ruts_is_bit_identical() {
    let scenario = straight("");
    let a = run("mer", &scenario);
    let b = run("mer", &scenario);
    assert_eq!(a.rows.len(), b.rows.len());
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        let bits = |r: &[f64]| r.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(ra), bits(rb));
    }
}

/// A ground of one soil given as a map (a raster whose every node is that
/// soil's class, over that soil as the background) is that soil: the same
/// run, bit for bit, as the soil given alone.
#[test]
fn a_map_of_one_soil_is_that_soil() {
    let dir = std::env::temp_dir().join(format!("rover-ruts-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let row = vec!["1"; 41].join(",");
    let csv: String = (0..11).map(|_| format!("{row}\n")).collect();
    std::fs::write(dir.join("classes.csv"), csv).unwrap();
    let mapped = straight(
        r#"[terrain.soil_map]
path = "classes.csv"
origin = [-5.0, -2.5]
spacing = [0.5, 0.5]
classes = { 1 = "dry_sand" }"#,
    );
    let plain = straight("");
    let a = run_in("mer", &mapped, &dir);
    let b = run_in("mer", &plain, &dir);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(a.rows.len(), b.rows.len());
    for (ra, rb) in a.rows.iter().zip(&b.rows) {
        for (x, y) in ra.iter().zip(rb) {
            assert_eq!(x.to_bits(), y.to_bits());
        }
    }
}

/// Turning on an arc, each wheel leaves its rut along its own arc: the rut
/// is found where the wheels passed, where they were when it was pressed,
/// and nowhere else (not at the arc's centre, not outside the outer
/// wheels' arc); and a rut, once made, never moves or fills in as the
/// rover goes on turning.
#[test]
fn the_rut_stays_where_it_was_made_when_the_rover_turns() {
    let scenario = r#"
rover = "mer"
duration = 24.0
settle = 1.0
output_rate = 10.0
[terrain]
soil = "dry_sand"
[control.speed]
speed = 0.1
kp = 500.0
ki = 1000.0
[control.steering]
kind = "ackermann"
radius = 2.0
"#;
    let prepared = Prepared::from_text(
        Some("mer"),
        scenario,
        Path::new("turn.toml"),
        Path::new("."),
    )
    .unwrap();
    let mut stepper = prepared.stepper(false).unwrap();
    let steps = (12.0 / stepper.dt()).round() as u64;
    stepper.step(steps).unwrap();
    let map = |s: &rover_scenario::Stepper<_>| {
        let ground = s.system().ground.as_ref().unwrap();
        ground.ruts().unwrap().map().clone()
    };
    let halfway = map(&stepper);
    let (origin, [nx, ny], before) = halfway.depth_grid().unwrap();
    stepper.step(steps).unwrap();
    let end = map(&stepper);
    let (end_origin, [end_nx, _], after) = end.depth_grid().unwrap();
    let cell = end.cell();
    let mut pressed = 0;
    for j in 0..ny {
        for i in 0..nx {
            let d = before[j * nx + i];
            if d > 0.0 {
                pressed += 1;
                let (x, y) = (origin[0] + i as f64 * cell, origin[1] + j as f64 * cell);
                // The same node in the later, larger grid.
                let (ie, je) = (
                    ((x - end_origin[0]) / cell).round() as usize,
                    ((y - end_origin[1]) / cell).round() as usize,
                );
                let now = after[je * end_nx + ie];
                assert!(now >= d, "({x}, {y}): {d} then {now}");
            }
        }
    }
    assert!(pressed > 100, "{pressed} nodes pressed in 12 s");
    assert!(end.tile_count() > halfway.tile_count());
    // The turn's centre is 2 m to the left of the start (ackermann radius
    // 2 m about the body's centre): no wheel passes near it, nor 1 m
    // outside the outer wheels' arc.
    for (x, y) in [(0.0, 2.0), (0.0, -1.6), (1.0, 2.0)] {
        assert_eq!(end.sample(x, y).depth, 0.0, "({x}, {y})");
    }
}
