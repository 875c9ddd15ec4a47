//! The paper's roughness claims that docs/REPRODUCTION.md reproduces, each
//! on a short version of its runs on the report's calibrated terrain
//! (`rover::cli::calibrated`). `rover reproduce` itself fails when a claim
//! its stored record says held stops holding over all of its seeds; its
//! quick form (`rover reproduce --quick`) runs here, in CI's test run.

use rover::cli::calibrated;
use rover_scenario::output::fit_circle;

use crate::support::run::{Run, run};

/// Example 1 turning with δ₁ = 20° for 46 s (40 s after settling).
fn turn(z_r: f64, speed: f64, seed: u64) -> Run {
    run(
        "exomars",
        &format!(
            "duration = 46.0\nsettle = 6.0\noutput_rate = 10.0\n{}[control.speed]\nspeed = {speed}\nki = 5.0\n\
             [control.steering]\nkind = \"ackermann\"\nfront_left_deg = 20.0\n\
             [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n",
            calibrated::terrain(z_r, seed)
        ),
    )
}

/// |R/R_k − 1| with R fitted to G's path on the rough part; a run that
/// stopped (rolled over, or left without a radius) counts as 0.1, the
/// report's "unacceptable".
fn deviation(r: &Run) -> f64 {
    let s = &r.summary;
    let (t, x, y) = (r.col("t"), r.col("X"), r.col("Y"));
    let points: Vec<[f64; 2]> = (0..t.len())
        .filter(|&k| t[k] >= 6.0 && x[k].hypot(y[k]) >= calibrated::FIT_FROM_M)
        .map(|k| [x[k], y[k]])
        .collect();
    match (s.complete, fit_circle(&points), s.kinematic_radius) {
        (true, Some(c), Some(rk)) => (c.radius / rk - 1.0).abs(),
        _ => 0.1,
    }
}

#[test]
fn kinematic_steering_breaks_down_on_very_rough_ground() {
    // Fig. 6: at Z_R = 1 the kinematic radius is "unacceptable" (over 10 %
    // off, or the rover cannot complete the turn), on average over seeds.
    let d: Vec<f64> = [1, 2, 3]
        .map(|seed| deviation(&turn(1.0, 0.05, seed)))
        .to_vec();
    let mean = d.iter().sum::<f64>() / d.len() as f64;
    assert!(mean >= 0.1, "Z_R = 1: |R/R_k − 1| {d:?}");
}

#[test]
fn kinematic_steering_degrades_with_speed() {
    // Fig. 7 at Z_R = 0.3: further from R_k at 1 m/s than at 0.05 m/s.
    for seed in [1, 2] {
        let slow = deviation(&turn(0.3, 0.05, seed));
        let fast = deviation(&turn(0.3, 1.0, seed));
        assert!(fast > slow, "seed {seed}: slow {slow}, fast {fast}");
    }
}

/// The rough field (node amplitude 0.5 m, spacing 0.5 m) on which the
/// passive rover pitches beyond 10° and slides, as the paper's does; the
/// report's calibrated field is gentler (docs/REPRODUCTION.md gives the
/// trade-off).
fn rough_field(z_r: f64, seed: u64) -> String {
    format!(
        "[terrain]\nkind = \"random\"\nz_r = {z_r}\nseed = {seed}\nnode_amplitude = 0.5\nnode_spacing = 0.5\n\
         patch_radius = 0.63\npatch_blend = 0.15\n"
    )
}

/// Example 2 slip-steered with Δτ = 0.2 N·m at 0.05 m/s on Z_R = 0.2.
fn example2(terrain: &str, active: bool, duration: f64) -> Run {
    run(
        "swing4",
        &format!(
            "duration = {duration}\nsettle = 6.0\noutput_rate = 10.0\n{terrain}\
             [control.speed]\nspeed = 0.05\n[control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n\
             [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n{}",
            if active {
                calibrated::ACTIVE_SUSPENSION
            } else {
                ""
            }
        ),
    )
}

#[test]
fn the_passive_rover_pitches_and_slides_suddenly_where_the_active_one_does_not() {
    // Figs. 15–16, the first 60 s of seed 1, on the rough field.
    let terrain = rough_field(0.2, 1);
    let passive = example2(&terrain, false, 60.0);
    let active = example2(&terrain, true, 60.0);
    assert!(passive.summary.complete && active.summary.complete);
    let slide = passive.summary.slide.clone().expect("slide measures");
    let sudden = slide.sudden.clone().expect("the passive rover slides");
    // The rear axle slides sideways faster than the front one.
    assert_eq!(sudden.axle, 1, "{slide:?}");
    assert!(
        slide.axles[1].max_lateral_speed_m_s.abs() > slide.axles[0].max_lateral_speed_m_s.abs(),
        "{slide:?}"
    );
    let calm = active.summary.slide.clone().expect("slide measures");
    assert_eq!(calm.sudden, None, "the active rover slides: {calm:?}");
    // Active suspension keeps the body much flatter (the paper: below 1°,
    // which the arms' travel does not allow on this field; docs/MODEL.md §8).
    assert!(
        passive.summary.max_pitch_deg > 10.0,
        "passive pitch {}°",
        passive.summary.max_pitch_deg
    );
    for (a, p) in [
        (active.summary.max_roll_deg, passive.summary.max_roll_deg),
        (active.summary.max_pitch_deg, passive.summary.max_pitch_deg),
    ] {
        assert!(a < 0.6 * p, "active {a}°, passive {p}°");
    }
    // The neutrals the active law commands are in the CSV and move; the
    // passive rover's stay at the description's.
    for i in 1..=4 {
        let name = format!("y0_{i}");
        let moved = |r: &Run| {
            let v = r.col(&name);
            v.iter().fold(0.0f64, |m, x| m.max((x - v[0]).abs()))
        };
        assert_eq!(moved(&passive), 0.0, "{name}");
        assert!(moved(&active) > 1f64.to_radians(), "{name}");
    }
}

#[test]
fn on_the_calibrated_field_the_active_rover_stays_below_a_degree() {
    // Fig. 15's claim, on the report's field, the first 60 s of seed 2:
    // roll and pitch "always much smaller than 1°" with the leveling law,
    // several degrees without it.
    let terrain = calibrated::terrain(0.2, 2);
    let passive = example2(&terrain, false, 60.0);
    let active = example2(&terrain, true, 60.0);
    assert!(passive.summary.complete && active.summary.complete);
    let (a, p) = (&active.summary, &passive.summary);
    assert!(
        a.max_roll_deg < 1.0 && a.max_pitch_deg < 1.0,
        "active roll {}°, pitch {}°",
        a.max_roll_deg,
        a.max_pitch_deg
    );
    assert!(
        p.max_roll_deg > 3.0,
        "passive roll {}°: the ground is rough enough to matter",
        p.max_roll_deg
    );
}

#[test]
fn active_suspension_levels_the_body_on_a_slope_and_stays_level() {
    // Closed-loop stability: parked across a 4° slope (rising to the left)
    // and along it, the body starts tilted; the incremental law must bring
    // roll and pitch to zero and keep them there.
    let r = run(
        "swing4",
        "duration = 30.0\noutput_rate = 10.0\n[terrain]\nkind = \"slope\"\nangle_deg = 4.0\ndirection_deg = 45.0\n\
         [initial]\nattitude_deg = [2.8, -2.8, 0.0]\n[control.speed]\nspeed = 0.0\nkp = 30.0\nki = 100.0\n\
         [control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.6\nkd_pitch = 0.05\nkp_roll = 0.6\nkd_roll = 0.05\n\
         [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n",
    );
    assert!(r.summary.complete, "{:?}", r.summary.error);
    let early = r
        .after("theta", 0.5)
        .first()
        .copied()
        .unwrap()
        .abs()
        .max(r.after("phi", 0.5).first().copied().unwrap().abs());
    assert!(
        early > 1.5f64.to_radians(),
        "the body starts tilted ({}°)",
        early.to_degrees()
    );
    for c in ["phi", "theta"] {
        let late = r.after(c, 15.0).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            late < 0.1f64.to_radians(),
            "{c} still {}° after 15 s",
            late.to_degrees()
        );
    }
}

#[test]
fn every_claim_the_quick_reproduction_records_as_holding_still_holds() {
    // `rover reproduce --quick`: every claim's case shortened, seed 1,
    // judged against docs/reproduction/quick.csv; an error names each
    // claim that held there and no longer does.
    let work =
        std::env::temp_dir().join(format!("rover-quick-reproduction-{}", std::process::id()));
    let args = rover::cli::ReproduceArgs {
        docs: std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs"),
        work: Some(work.clone()),
        search: false,
        quick: true,
        record: false,
    };
    let table = match rover::cli::reproduce(&args) {
        Ok(path) => std::fs::read_to_string(path).unwrap(),
        Err(e) => panic!("{e}"),
    };
    // Every claim of the report is in the table, judged.
    for figure in [
        "Fig. 5", "Fig. 6", "Fig. 7", "Fig. 11", "Fig. 12", "Fig. 15",
    ] {
        assert!(
            table.contains(&format!("| {figure} |")),
            "{figure}: {table}"
        );
    }
    let _ = std::fs::remove_dir_all(work);
}
