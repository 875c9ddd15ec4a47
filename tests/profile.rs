//! `profile = true`: where a run's wall time goes.

use crate::support::run::run;

const ROUGH: &str = "duration = 6.0\noutput_rate = 10.0\n\
    [terrain]\nkind = \"random\"\nz_r = 0.3\nseed = 2\nnode_amplitude = 0.25\npatch_radius = 0.3\n\
    extent = [-3.0, 3.0, -3.0, 3.0]\n[control.speed]\nspeed = 0.1\n";

/// A profiled run accounts for its whole wall time in its parts, every part
/// took time, every right-hand side (the integrator's and the output rows')
/// was timed, and the same run unprofiled reports none and ends in the same
/// state (the clock changes no result).
#[test]
fn a_profiled_run_accounts_for_its_wall_time() {
    let plain = run("swing4", ROUGH);
    let profiled = run("swing4", &format!("profile = true\n{ROUGH}"));
    assert!(plain.summary.profile.is_none());
    let p = profiled.summary.profile.expect("a profile");
    assert_eq!(plain.summary.final_state, profiled.summary.final_state);
    for (part, s) in [
        ("wheels", p.wheels_s),
        ("contact", p.contact_s),
        ("law", p.law_s),
        ("plant", p.plant_s),
        ("integrator and output", p.integrator_and_output_s),
    ] {
        assert!(s > 0.0, "{part}: {s} s");
    }
    let wall = profiled.summary.wall_time_s;
    assert!(
        (p.total_s() - wall).abs() <= 1e-9 * wall.max(1.0),
        "{} s accounted for of {wall} s",
        p.total_s()
    );
    let rows = profiled.rows.len() as u64;
    assert_eq!(p.evaluations, profiled.summary.rhs_evals + rows);
}
