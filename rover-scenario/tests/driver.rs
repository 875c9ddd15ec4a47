//! One driver for every run: a scenario stepped one output interval at a
//! time gives the whole run's rows bit for bit, with every integrator, on
//! rough ground with a sampled controller (the active suspension) and
//! command breakpoints (the end of settling, a stepped speed profile); and
//! a blow-up is reported as the same divergence by both.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rover_runtime::sim::RunError;
use rover_scenario::prepare::{PrepareError, Prepared};

/// swing4 on rough ground, slip-steered, its speed stepped at 1.5 s, its
/// active suspension sampled every 0.1 s, with `integrator` (a TOML table).
fn scenario(integrator: &str) -> String {
    format!(
        "rover = \"swing4\"\nduration = 3.0\nsettle = 0.5\noutput_rate = 20.0\n\
         [terrain]\nkind = \"random\"\nz_r = 0.2\nseed = 3\n\
         [control.speed]\nkp = 10.0\nspeed = {{ points = [[0.0, 0.1], [1.0, 0.2]] }}\n\
         [control.steering]\nkind = \"slip\"\ndelta_tau = 0.1\n\
         [control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.6\nkp_roll = 0.6\n\
         {integrator}"
    )
}

const INTEGRATORS: [&str; 5] = [
    "[integrator.rk4]\nstep = 1e-3\n",
    "[integrator.semi_implicit_euler]\nstep = 2e-4\n",
    "[integrator.dopri5]\nrtol = 1e-6\n",
    "[integrator.bdf]\nrtol = 1e-6\n",
    "[integrator.ros2]\nstep = 2e-3\n",
];

fn prepared(text: &str) -> Prepared {
    Prepared::from_text(None, text, Path::new("driver.toml"), Path::new("."))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The whole run's rows, parsed back from its CSV (each number's shortest
/// exact form: the computed value bit for bit).
fn whole_rows(p: &Prepared, generic: bool) -> Vec<Vec<f64>> {
    let mut csv = Vec::new();
    let summary = p
        .run(generic, &mut csv, &AtomicBool::new(false), |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(summary.complete, "{:?}", summary.error);
    String::from_utf8(csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// The step-wise run's row now.
fn stepped_row(s: &rover_scenario::Stepper<rover_scenario::prepare::RunPlant>) -> Vec<f64> {
    let mut row = vec![0.0; s.columns().len()];
    s.row_into(&mut row);
    row
}

/// Steps `p` one output interval at a time and checks each row against the
/// whole run's `whole`, bit for bit; `what` heads the message. Returns the
/// stepper, at the whole run's end.
fn assert_steps_give(
    p: &Prepared,
    generic: bool,
    whole: &[Vec<f64>],
    what: &str,
) -> rover_scenario::Stepper<rover_scenario::prepare::RunPlant> {
    let mut s = p.stepper(generic).unwrap_or_else(|e| panic!("{e}"));
    for (k, want) in whole.iter().enumerate() {
        if k > 0 {
            s.step(1).unwrap_or_else(|e| panic!("{what}: {e}"));
        }
        let got = stepped_row(&s);
        let same = got
            .iter()
            .zip(want)
            .all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(
            same,
            "{what} row {k} at t = {}: stepped {got:?}, whole {want:?}",
            want[0]
        );
    }
    s
}

#[test]
fn a_stepped_run_gives_the_whole_runs_rows_bit_for_bit_with_every_integrator() {
    for integrator in INTEGRATORS {
        let p = prepared(&scenario(integrator));
        for generic in [false, true] {
            let whole = whole_rows(&p, generic);
            assert_eq!(whole.len(), 61, "{integrator}");
            assert_steps_give(
                &p,
                generic,
                &whole,
                &format!("{integrator} (generic {generic})"),
            );
        }
    }
}

#[test]
fn without_a_sampled_controller_a_stepped_run_lands_on_the_whole_runs_end() {
    // With no controller sample at the run's end, the whole run's last
    // step lands there because the run ends; a stepped run has no end of
    // its own and goes on, but lands there too (BDF steps past the other
    // output instants and interpolates them).
    for integrator in ["", "[integrator.bdf]\nrtol = 1e-6\n"] {
        let text = scenario(integrator).replace(
            "[control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.6\nkp_roll = 0.6\n",
            "",
        );
        assert!(!text.contains("active_suspension"));
        let p = prepared(&text);
        let whole = whole_rows(&p, false);
        let mut s = assert_steps_give(&p, false, &whole, &format!("{integrator:?}"));
        // And goes on past it.
        s.step(2).unwrap_or_else(|e| panic!("{integrator}: {e}"));
        assert!(s.time() > 3.0 + 0.09, "{}", s.time());
    }
}

#[test]
fn with_sensor_instants_a_stepped_run_still_gives_the_whole_runs_rows_with_every_integrator() {
    // The integrator lands on every sensor instant (100 Hz, between the
    // 20 Hz output instants) whether the readings are written or not.
    let sensors = "[sensors]\nrate = 100.0\n[sensors.wheel_encoders]\nresolution = 0.001\n";
    for integrator in INTEGRATORS {
        let p = prepared(&format!("{}{sensors}", scenario(integrator)));
        let whole = whole_rows(&p, false);
        assert_eq!(whole.len(), 61, "{integrator}");
        assert_steps_give(&p, false, &whole, integrator);
    }
}

#[test]
fn a_blow_up_is_a_divergence_whole_or_stepped() {
    // A step far too long for the tyre's stiffness, on flat ground (which
    // no wheel can leave).
    let p = prepared(
        "rover = \"swing4\"\nduration = 3.0\n[control.active_suspension]\nsample_time = 0.1\nkp_pitch = 0.6\nkp_roll = 0.6\n\
         [integrator.rk4]\nstep = 10.0\n",
    );
    let summary = p
        .run(false, std::io::sink(), &AtomicBool::new(false), |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    let whole = summary.error.expect("the run fails");
    let mut s = p
        .stepper(false)
        .unwrap_or_else(|e: PrepareError| panic!("{e}"));
    let stepped = loop {
        if let Err(e) = s.step(1) {
            break e;
        }
        assert!(s.time() < 3.0, "the stepped run did not fail");
    };
    // The attitude jumps past half a turn: no roll-over.
    assert!(matches!(stepped, RunError::Diverged { .. }), "{stepped}");
    assert_eq!(whole, stepped.to_string());
    // A failed run stays failed, with the same error, until reset.
    assert_eq!(s.step(1), Err(stepped));
}
