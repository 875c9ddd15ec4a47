//! Command files in whole runs (`[control.commands]`): a file drives the
//! run the built-in loops do, bit for bit, and a recorded drive replays.

/// A command file in the test's scratch folder; its absolute path.
fn command_file(name: &str, text: &str) -> String {
    crate::support::scratch_file("commands", name, text)
}

const SWING4_RUN: &str = "duration = 8.0\nsettle = 1.0\noutput_rate = 10.0\n";

/// `[control.commands]` from a file: slip steering's torques given as a
/// one-row file drive the run the built-in slip steering does, bit for bit;
/// a linear ramp and a steering schedule are what the CSV's torque and
/// steering columns show.
#[test]
fn command_files_drive_the_run() {
    use crate::support::run::run;
    let zero_loop = "[control.speed]\nspeed = 0.0\nkp = 0.0\n";
    let built_in = run(
        "swing4",
        &format!("{SWING4_RUN}{zero_loop}[control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n"),
    );
    let file = command_file(
        "slip.csv",
        "# Δτ = 0.2 N·m\nt,tau1,tau2,tau3,tau4\n0.0,-0.2,0.2,-0.2,0.2\n",
    );
    let replayed = run(
        "swing4",
        &format!("{SWING4_RUN}{zero_loop}[control.commands]\nfile = \"{file}\"\n"),
    );
    assert_eq!(built_in.header, replayed.header);
    for (a, b) in built_in.rows.iter().zip(&replayed.rows) {
        for (x, y) in a.iter().zip(b) {
            assert_eq!(x.to_bits(), y.to_bits(), "{a:?}\nvs\n{b:?}");
        }
    }
    // A ramp of the front-left torque, interpolated linearly: 0 → 0.3 N·m
    // over 3 s after settling, held after.
    let ramp = command_file("ramp.csv", "t,tau1\n0,0\n3,0.3\n");
    let ramped = run(
        "swing4",
        &format!("{SWING4_RUN}[control.commands]\nfile = \"{ramp}\"\ninterpolation = \"linear\"\n"),
    );
    for (t, tau) in ramped.col("t").iter().zip(ramped.col("tau1")) {
        let want = (0.1 * (t - 1.0)).clamp(0.0, 0.3);
        assert!(
            (tau - want).abs() < 1e-12,
            "t = {t}: τ1 = {tau}, want {want}"
        );
    }
    assert!(ramped.col("tau2").iter().all(|&v| v == 0.0));
    // The LRV's front wheels steered by a schedule (step: held between rows).
    let steer = command_file("steer.csv", "t,delta1,delta2\n0,0.1,0.1\n2,-0.05,-0.05\n");
    let steered = run(
        "lrv",
        &format!(
            "duration = 5.0\nsettle = 1.0\noutput_rate = 10.0\n[control.speed]\nspeed = 0.3\n\
             [control.commands]\nfile = \"{steer}\"\n"
        ),
    );
    for (t, delta) in steered.col("t").iter().zip(steered.col("delta1")) {
        let want = match t - 1.0 {
            tc if tc < 0.0 => 0.0,
            tc if tc < 2.0 => 0.1,
            _ => -0.05,
        };
        assert!(
            (delta - want).abs() < 1e-15,
            "t = {t}: δ1 = {delta}, want {want}"
        );
    }
    assert!(steered.col("delta3").iter().all(|&v| v == 0.0));
}

/// A recorded drive replayed: the torques a run's speed loop and slip
/// steering gave on rough ground (its CSV) fed back as open-loop commands,
/// interpolated linearly, reproduce its path: to 0.4 mm when recorded at
/// 100 Hz, to 0.02 mm at 1 kHz (linear interpolation's error, second order
/// in the sampling interval).
#[test]
fn a_recorded_drive_replays() {
    use crate::support::run::run;
    let gap = |rate: f64| {
        let scenario = format!(
            "duration = 10.0\nsettle = 0.0\noutput_rate = {rate}\n\
             [terrain]\nkind = \"random\"\nz_r = 0.1\nseed = 3\n"
        );
        let recorded = run(
            "swing4",
            &format!(
                "{scenario}[control.speed]\nspeed = 0.1\n[control.steering]\nkind = \"slip\"\ndelta_tau = 0.1\n"
            ),
        );
        let mut text = String::from("t,tau1,tau2,tau3,tau4\n");
        let taus: Vec<Vec<f64>> = (1..=4).map(|j| recorded.col(&format!("tau{j}"))).collect();
        for (k, t) in recorded.col("t").iter().enumerate() {
            let row: Vec<String> = taus.iter().map(|c| c[k].to_string()).collect();
            text += &format!("{t},{}\n", row.join(","));
        }
        let file = command_file(&format!("recorded_{rate}.csv"), &text);
        let replayed = run(
            "swing4",
            &format!(
                "{scenario}[control.commands]\nfile = \"{file}\"\ninterpolation = \"linear\"\n"
            ),
        );
        let travel = recorded.col("X").last().unwrap() - recorded.col("X")[0];
        assert!(travel > 0.5, "it drives: {travel} m");
        ["X", "Y"]
            .iter()
            .flat_map(|c| recorded.col(c).into_iter().zip(replayed.col(c)))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
    };
    let (coarse, fine) = (gap(100.0), gap(1000.0));
    assert!(coarse < 1e-3, "replayed from 100 Hz: {coarse} m off");
    assert!(fine < 0.1 * coarse, "from 1 kHz: {fine} m vs {coarse} m");
}
