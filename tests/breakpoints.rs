//! Command steps on the integrator's restart breakpoints: a jump of the
//! commanded torques that falls on an output instant restarts the default
//! integrator there, and the run must still follow the solution a
//! tight-tolerance run finds, whatever the output rate.

use crate::support::rng::Rng;
use crate::support::run::{Run, run};

/// Final position and attitude within these of the tight-tolerance run, for
/// BDF at rtol 1e-6 on the rover's error scales ([`CHECK`]): over these few
/// seconds its global error on swing4 is below 3e-7 driving straight and
/// reaches 2.2e-6 m where uneven torques turn it and its wheels creep
/// sideways (BDF at rtol 1e-8 is still 2.7e-7 m off there). A run that strays
/// from the solution at a restart is off by 5e-5 m to centimetres.
const POSITION_TOL: f64 = 1e-5;
const ANGLE_TOL: f64 = 1e-5;

/// The default integrator (BDF) with a relative tolerance tight enough that
/// a restart gone wrong stands out of its own error; the same code path as
/// the default (restarts on the breakpoints, outputs from the interpolant).
const CHECK: &str = "[integrator.bdf]\nrtol = 1e-6\n";

/// The accuracy the default tolerances promise on a run (docs/PERFORMANCE.md):
/// 1 mm and 0.01°.
const DEFAULT_POSITION_TOL: f64 = 1e-3;
const DEFAULT_ANGLE_TOL: f64 = 0.01 * std::f64::consts::PI / 180.0;

/// A command file in the test's scratch folder; its absolute path.
fn command_file(name: &str, text: &str) -> String {
    crate::support::scratch_file("breakpoints", name, text)
}

/// swing4 on flat ground, dropped from 2 cm (its lowest rim point) at rest,
/// driven by the step commands of `file`; `integrator` is a TOML table or "".
fn drive(duration: f64, rate: f64, file: &str, integrator: &str) -> Run {
    run(
        "swing4",
        &format!(
            "duration = {duration}\noutput_rate = {rate}\n[terrain]\nkind = \"flat\"\n\
             [initial]\nz = 0.3110556724244685\n\
             [control.commands]\nfile = \"{file}\"\ninterpolation = \"step\"\n{integrator}"
        ),
    )
}

/// Dormand–Prince at rtol 1e-10: the reference.
const TIGHT: &str = "[integrator.dopri5]\nrtol = 1e-10\natol = 1e-12\n";

/// The final pose of `r` agrees with the reference's to [`POSITION_TOL`]
/// and [`ANGLE_TOL`].
fn assert_same_pose(r: &Run, reference: &Run, what: &str) {
    assert_pose_within(r, reference, POSITION_TOL, ANGLE_TOL, what);
}

/// The final pose of `r` agrees with the reference's to `position` (m) and
/// `angle` (rad).
fn assert_pose_within(r: &Run, reference: &Run, position: f64, angle: f64, what: &str) {
    assert!(r.summary.complete, "{what}: {:?}", r.summary.error);
    for (name, tol) in [
        ("X", position),
        ("Y", position),
        ("Z", position),
        ("phi", angle),
        ("theta", angle),
        ("psi", angle),
    ] {
        let (a, b) = (r.final_value(name), reference.final_value(name));
        assert!(
            (a - b).abs() < tol,
            "{what}: final {name} {a} against the reference's {b} (tolerance {tol})"
        );
    }
}

/// 0.3 N·m on every wheel from t = 1 s, an instant shared by every output
/// rate tried: the integrator restarts there. Each rate gives the
/// tight-tolerance run's pitch and final position (and the default
/// tolerances end within their promise), and the speed gained
/// agrees with the closed form Στ/(lever·m) (flat ground, straight, no
/// rolling resistance: the pulls τ/|G_jH| are the only horizontal forces).
#[test]
fn a_torque_step_on_an_output_instant_keeps_to_the_solution_at_every_output_rate() {
    let file = command_file(
        "step.csv",
        "t,tau1,tau2,tau3,tau4\n0,0,0,0,0\n1.0,0.3,0.3,0.3,0.3\n",
    );
    let reference = drive(4.0, 100.0, &file, TIGHT);
    assert!(reference.summary.complete);
    for rate in [10.0, 50.0, 100.0, 200.0] {
        let r = drive(4.0, rate, &file, CHECK);
        assert_same_pose(&r, &reference, &format!("output at {rate} Hz"));
        let default = drive(4.0, rate, &file, "");
        assert_pose_within(
            &default,
            &reference,
            DEFAULT_POSITION_TOL,
            DEFAULT_ANGLE_TOL,
            &format!("default tolerances, output at {rate} Hz"),
        );
        assert!(
            (r.summary.max_pitch_deg - reference.summary.max_pitch_deg).abs() < 1e-3,
            "output at {rate} Hz: max pitch {}° against {}°",
            r.summary.max_pitch_deg,
            reference.summary.max_pitch_deg
        );
    }
    // Speed gained over the 3 s of drive against the closed form.
    let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
    let mass = spec.model.total_mass();
    let (t, vx) = (reference.col("t"), reference.col("vx"));
    let at = |time: f64| t.iter().position(|&v| (v - time).abs() < 1e-9).unwrap();
    let (i1, i4) = (at(1.0), at(4.0));
    let lever = reference.col("W1Z")[i4] - reference.col("H1Z")[i4];
    let gained = vx[i4] - vx[i1];
    let closed_form = 4.0 * 0.3 / lever / mass * 3.0;
    assert!(
        (gained / closed_form - 1.0).abs() < 0.01,
        "speed gained {gained} m/s, closed form {closed_form} m/s"
    );
}

/// A seeded family of torque steps, each on an output instant of a rate
/// drawn from 10–200 Hz, different on each wheel (the rover yaws and rolls
/// too): every run ends where the tight-tolerance run ends.
#[test]
fn random_torque_steps_on_output_instants_keep_to_the_tight_tolerance_run() {
    let mut rng = Rng::new(0x05ee_db0f);
    let rates = [10.0, 20.0, 50.0, 100.0, 200.0];
    for case in 0..6 {
        let rate = rates[(rng.next_u64() % rates.len() as u64) as usize];
        // A step time on an output instant between 0.6 s and 1.6 s, then a
        // second one 0.2–0.8 s later, also on an output instant.
        let first = (rng.uniform(0.6, 1.6) * rate).round() / rate;
        let second = first + (rng.uniform(0.2, 0.8) * rate).round() / rate;
        let torques = |rng: &mut Rng| {
            (0..4)
                .map(|_| format!("{:.3}", rng.uniform(-0.4, 0.6)))
                .collect::<Vec<_>>()
                .join(",")
        };
        let text = format!(
            "t,tau1,tau2,tau3,tau4\n0,0,0,0,0\n{first},{}\n{second},{}\n",
            torques(&mut rng),
            torques(&mut rng)
        );
        let file = command_file(&format!("random{case}.csv"), &text);
        let reference = drive(3.0, rate, &file, TIGHT);
        let r = drive(3.0, rate, &file, CHECK);
        assert_same_pose(
            &r,
            &reference,
            &format!("case {case} at {rate} Hz:\n{text}"),
        );
    }
}
