//! Open-loop commands (`RoverSystem::set_torques`, `set_steering`): what an
//! external controller drives the rover with. They act exactly as the
//! built-in loops' own commands do, are checked, and are held until changed.

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::ContactMethod;
use rover_runtime::sim::{CommandError, RoverSystem};
use rover_runtime::terrain::Terrain;

fn model(name: &str) -> Model {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name)
        .unwrap()
        .model
}

/// `plant` on flat ground under `control` (TOML of a `[control]` table),
/// wheels 2 mm in, at rest.
fn system<P: Plant>(m: &Model, plant: P, control: &str) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let ground = rover_runtime::ground::Ground::new(
        Terrain::default(),
        m,
        ContactMethod::Meridional,
        Default::default(),
        Default::default(),
    );
    let config: ControllerConfig = toml::from_str(control).unwrap();
    let sys = RoverSystem::new(
        plant,
        Some(ground),
        Controller::new(config, m, 0.0).unwrap(),
    );
    let n = m.dof();
    let mut y = vec![0.0; sys.dim()];
    y[6..n].copy_from_slice(&m.rest());
    y[2] = m.touchdown_height() - 2e-3;
    (sys, y)
}

/// `steps` RK4 steps of 1 ms.
fn advance<S: OdeSystem>(sys: &mut S, y: &mut [f64], steps: usize)
where
    S::Error: std::fmt::Debug,
{
    let mut rk4 = Rk4::new(y.len(), &FixedStepConfig { step: 1e-3 }).unwrap();
    let mut t = 0.0;
    for k in 1..=steps {
        rk4.advance(sys, &mut t, y, k as f64 * 1e-3).unwrap();
    }
}

/// Two states equal bit for bit.
fn same_bits(a: &[f64], b: &[f64]) {
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(x.to_bits(), y.to_bits(), "state {i}: {x} vs {y}");
    }
}

/// Slip steering's torques, `∓Δτ` on the left and right wheels (here with a
/// speed loop of zero gain, so they are the whole torque), given instead
/// as open-loop torques: the same run, bit for bit, in x and w.
#[test]
fn open_loop_torques_drive_as_the_built_in_slip_steering_does() {
    let m = model("swing4");
    let n = m.dof();
    let (mut built_in, mut y1) = system(
        &m,
        rover_models::Swing4::new(),
        "[speed]\nspeed = 0.0\nkp = 0.0\n[steering]\nkind = \"slip\"\ndelta_tau = 0.2\n",
    );
    let (mut open, mut y2) = system(&m, rover_models::Swing4::new(), "");
    // front_left, front_right, rear_left, rear_right.
    open.set_torques(&[-0.2, 0.2, -0.2, 0.2]).unwrap();
    advance(&mut built_in, &mut y1, 3000);
    advance(&mut open, &mut y2, 3000);
    assert_eq!(built_in.torques(), open.torques());
    same_bits(&y1[..2 * n], &y2[..2 * n]);
    assert!(y1[5] > 1e-3, "it turns left: ψ = {}", y1[5]);
}

/// The Ackermann angles of the built-in steering, given as open-loop
/// angles on top of the same speed loop: the same run, bit for bit.
#[test]
fn open_loop_steering_angles_steer_as_the_built_in_ackermann_does() {
    let m = model("lrv");
    let n = m.dof();
    let speed = "[speed]\nspeed = 0.5\nki = 50.0\n";
    let (mut built_in, mut y1) = system(
        &m,
        rover_models::Lrv::new(),
        &format!("{speed}[steering]\nkind = \"ackermann\"\nradius = 4.0\n"),
    );
    // The built-in angles, read off one evaluation.
    let mut dy = vec![0.0; y1.len()];
    built_in.rhs(0.0, &y1, &mut dy).unwrap();
    let angles = built_in.steering().to_vec();
    assert!(angles.iter().any(|a| a.abs() > 0.05), "{angles:?}");
    let (mut open, mut y2) = system(&m, rover_models::Lrv::new(), speed);
    open.set_steering(&angles).unwrap();
    advance(&mut built_in, &mut y1, 3000);
    advance(&mut open, &mut y2, 3000);
    assert_eq!(built_in.steering(), open.steering());
    same_bits(&y1[..2 * n + 1], &y2[..2 * n + 1]);
    assert!(y1[5] > 0.05, "it turns left: ψ = {}", y1[5]);
}

/// Commands add to the built-in loops' and stay within the motors' limits.
#[test]
fn open_loop_torques_add_to_the_loops_within_the_motor_limits() {
    let m = model("swing4");
    let (mut sys, y) = system(&m, rover_models::Swing4::new(), "[speed]\nspeed = 0.1\n");
    let mut dy = vec![0.0; y.len()];
    sys.rhs(0.0, &y, &mut dy).unwrap();
    let alone = sys.torques().to_vec();
    sys.set_torques(&[0.01, -0.01, 0.0, 0.02]).unwrap();
    sys.rhs(0.0, &y, &mut dy).unwrap();
    let added: Vec<f64> = sys
        .torques()
        .iter()
        .zip(&alone)
        .map(|(a, b)| a - b)
        .collect();
    for (got, want) in added.iter().zip([0.01, -0.01, 0.0, 0.02]) {
        assert!((got - want).abs() < 1e-15, "{added:?}");
    }
    let cap = m.wheels[0].max_torque;
    sys.set_torques(&[1e3 * cap, -1e3 * cap, 0.0, 0.0]).unwrap();
    sys.rhs(0.0, &y, &mut dy).unwrap();
    assert_eq!(sys.torques()[..2], [cap, -cap]);
    assert_eq!(sys.commands().0, [1e3 * cap, -1e3 * cap, 0.0, 0.0]);
}

/// Bad commands are refused with what is wrong, and leave the held ones.
#[test]
fn bad_commands_are_refused() {
    let m = model("swing4");
    let (mut sys, _) = system(&m, rover_models::Swing4::new(), "");
    sys.set_torques(&[0.1; 4]).unwrap();
    let count = sys.set_torques(&[0.1; 3]).unwrap_err();
    assert!(matches!(
        count,
        CommandError::Count {
            wheels: 4,
            given: 3,
            ..
        }
    ));
    assert!(count.to_string().contains("4 wheels, 3 values"), "{count}");
    let nan = sys.set_torques(&[0.0, f64::NAN, 0.0, 0.0]).unwrap_err();
    assert!(nan.to_string().contains("wheel 2"), "{nan}");
    let fixed = sys.set_steering(&[0.1, 0.0, 0.0, 0.0]).unwrap_err();
    assert!(
        matches!(fixed, CommandError::NotSteerable { wheel: 1, .. }),
        "{fixed}"
    );
    assert!(fixed.to_string().contains("steerable = true"), "{fixed}");
    assert_eq!(sys.commands(), (&[0.1; 4][..], &[0.0; 4][..]));
}

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

/// Bad command files are refused with the file, the line and the fix.
#[test]
fn bad_command_files_are_refused_with_the_line() {
    let m = model("swing4");
    let error = |text: &str| {
        let file = command_file("bad.csv", text);
        let config: ControllerConfig =
            toml::from_str(&format!("[commands]\nfile = \"{file}\"\n")).unwrap();
        Controller::new(config, &m, 0.0).unwrap_err().to_string()
    };
    let cases = [
        ("", "empty"),
        (
            "time,tau1\n0,1\n",
            "bad.csv:1: the header must start with `t`",
        ),
        ("t,torque1\n0,1\n", "bad.csv:1: unknown column `torque1`"),
        ("t,tau5\n0,1\n", "wheels 1 to 4"),
        ("t,delta1\n0,0.1\n", "wheel 1 is not steerable"),
        ("t,tau1,tau1\n0,1,1\n", "appears twice"),
        (
            "t,tau1\n0,1\n# fine\n1,2,3\n",
            "bad.csv:4: 3 values, the header names 2",
        ),
        (
            "t,tau1\n0,1\n1,NaN\n",
            "bad.csv:3: `NaN` is not a finite number",
        ),
        (
            "t,tau1\n1,1\n1,2\n",
            "bad.csv:3: t = 1 s does not come after t = 1 s",
        ),
        ("t,tau1\n", "no rows"),
    ];
    for (text, want) in cases {
        let message = error(text);
        assert!(
            message.contains("control.commands.file") && message.contains(want),
            "{text:?}: {message}"
        );
    }
    let config: ControllerConfig =
        toml::from_str("[commands]\nfile = \"no/such/file.csv\"\n").unwrap();
    let missing = Controller::new(config, &m, 0.0).unwrap_err().to_string();
    assert!(
        missing.contains("cannot read the command file"),
        "{missing}"
    );
}
