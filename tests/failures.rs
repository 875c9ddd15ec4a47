//! Runs that cannot finish: they stop with an error naming
//! the time and the cause, keep the rows computed so far, and say so.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rover_runtime::GenericPlant;
use rover_scenario::output::Status;
use rover_scenario::scenario::Scenario;

use crate::support::run::{Run, run};

#[test]
fn a_rover_that_rolls_over_stops_with_the_time_and_the_cause() {
    let r = run(
        "swing4",
        "duration = 5.0\nfree_flight = true\noutput_rate = 100.0\n[initial]\nz = 1.0\nangular_velocity = [3.0, 0.0, 0.0]\n\
         [integrator.dopri5]\nrtol = 1e-8\n",
    );
    let s = &r.summary;
    assert_eq!(s.status, Status::Failed);
    assert!(!s.complete);
    let e = s.error.as_deref().unwrap();
    assert!(e.starts_with("the rover rolled over at t = 0.4"), "{e}");
    assert!(e.contains("(limit 80°)"), "{e}");
    // The CSV holds every row before the failure, and nothing past it.
    let t = r.col("t");
    assert!(
        t.len() > 40 && *t.last().unwrap() < s.t_end,
        "{} rows up to {}",
        t.len(),
        t.last().unwrap()
    );
    assert!(r.col("phi").iter().all(|p| p.abs() <= 80f64.to_radians()));
}

#[test]
fn leaving_the_terrain_map_stops_the_run_naming_the_wheel() {
    // A 2 m × 2 m grid around the start; the rover drives out at 0.5 m/s.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("offmap");
    std::fs::create_dir_all(&dir).unwrap();
    let mut asc = String::from("ncols 41\nnrows 41\nxllcenter -1\nyllcenter -1\ncellsize 0.05\n");
    for _ in 0..41 {
        asc += &vec!["0"; 41].join(" ");
        asc += "\n";
    }
    std::fs::write(dir.join("small.asc"), asc).unwrap();
    let text = "duration = 10.0\n[terrain]\nkind = \"file\"\npath = \"small.asc\"\n\
                [initial]\nvelocity = [0.5, 0.0, 0.0]\n[control.speed]\nspeed = 0.5\n[integrator.bdf]\nrtol = 1e-5\n";
    let scenario = Scenario::parse(text, &dir.join("s.toml")).unwrap();
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let mut csv = Vec::new();
    let summary = rover_scenario::simulate::simulate(
        GenericPlant::new(spec.model.clone()).unwrap(),
        &spec.model,
        "swing4",
        &scenario,
        &dir,
        &mut csv,
        &AtomicBool::new(false),
        |_| {},
    )
    .unwrap();
    assert_eq!(summary.status, Status::Failed);
    let e = summary.error.unwrap();
    assert!(
        e.contains("wheel 1 left the terrain") || e.contains("wheel 2 left the terrain"),
        "{e}"
    );
    assert!(e.contains("is off the terrain map"), "{e}");
    assert!(
        summary.t_end > 1.0 && summary.t_end < 3.0,
        "left at t = {}",
        summary.t_end
    );
}

#[test]
fn an_interrupted_run_keeps_what_was_computed_marked_partial() {
    let scenario = Scenario::parse("duration = 10.0\n", Path::new("s.toml")).unwrap();
    let spec = rover_spec::load_str(rover_models::builtin("exomars").unwrap(), "exomars").unwrap();
    let mut csv = Vec::new();
    let summary = rover_scenario::simulate::simulate(
        GenericPlant::new(spec.model.clone()).unwrap(),
        &spec.model,
        "exomars",
        &scenario,
        Path::new("."),
        &mut csv,
        &AtomicBool::new(true),
        |_| {},
    )
    .unwrap();
    assert_eq!(summary.status, Status::Interrupted);
    assert!(!summary.complete);
    assert_eq!(
        String::from_utf8(csv).unwrap().lines().count(),
        2,
        "header and the t = 0 row"
    );
}

/// `rover` driving on the seeded random ground of roughness `z_r` for
/// `duration` seconds, with `more` scenario text (the speed loop, the
/// contact search) appended.
fn on_rough_ground(rover: &str, z_r: f64, seed: u64, duration: f64, more: &str) -> Run {
    run(
        rover,
        &format!(
            "duration = {duration}\n[terrain]\nkind = \"random\"\nz_r = {z_r}\nseed = {seed}\n\
             extent = [-5.0, 40.0, -15.0, 15.0]\n{more}"
        ),
    )
}

#[test]
fn a_wheel_buried_on_very_rough_ground_does_not_stop_the_integrator() {
    // ExoMars at 0.15 m/s on the roughest ground of the paper's range: at
    // t ≈ 6.3 s a wheel is buried past half its radius while the speed
    // loop sits at its set-point. Eq. 38's pull τ/|G_jH| with |G_jH| → 0
    // used to flip by ±μx·F_n with the sign of a 1e-10 N·m torque, and BDF
    // stopped there ("step size below the minimum"); with the lever
    // floored the run goes on (the wheel is reported as a deep penetration).
    let r = on_rough_ground("exomars", 1.0, 2, 6.6, "[control.speed]\nspeed = 0.15\n");
    let s = &r.summary;
    assert_eq!(s.status, Status::Completed, "{:?}", s.error);
    assert!(
        !s.deep_penetration_wheels.is_empty(),
        "the wheel was buried"
    );
}

#[test]
fn a_patch_born_beside_another_on_very_rough_ground_does_not_stop_the_integrator() {
    // MER on the roughest ground of the paper's range: at t ≈ 3.2 s a patch
    // is born on a wheel next to another across a shallow trough. Blended
    // in at once, it added 2.4 mm of deflection within 1e-10 m of motion,
    // and BDF made 100,000 attempts without passing it; born as a separate
    // chord of zero length, it passes.
    let r = on_rough_ground("mer", 1.0, 1, 3.5, "[control.speed]\nspeed = 0.15\n");
    assert_eq!(r.summary.status, Status::Completed, "{:?}", r.summary.error);
}

#[test]
fn a_tracked_contact_that_stops_the_integrator_names_the_search_to_use() {
    // The LRV's large wheels meet this ground at two places at once; the
    // tracked search's single patch jumps between them and BDF at
    // rtol 1e-8 stops at t ≈ 5.27 s (looser tolerances may step over the
    // jump). The error names the search that keeps the forces continuous,
    // the default one, and that search runs through at the same tolerance.
    let control = "[control.speed]\nspeed = 0.2\nki = 100.0\n[integrator.bdf]\nrtol = 1e-8\n";
    let tracked = format!("{control}[contact]\nmethod = \"tracked\"\n");
    let r = on_rough_ground("lrv", 0.3, 2, 5.5, &tracked);
    let e = r.summary.error.as_deref().unwrap_or("");
    assert_eq!(r.summary.status, Status::Failed);
    assert!(
        e.contains("step size") && e.contains("method = \"bounded\"`, the default"),
        "{e}"
    );
    let r = on_rough_ground("lrv", 0.3, 2, 5.5, control);
    assert_eq!(r.summary.status, Status::Completed, "{:?}", r.summary.error);
}
