//! Open-loop commands (`RoverSystem::set_torques`, `set_steering`): what an
//! external controller drives the rover with. They act exactly as the
//! built-in loops' own commands do, are checked, and are held until changed.

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, Rk4};
use rover_runtime::control::{Controller, ControllerConfig};
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
    rover_test_support::scratch_file(env!("CARGO_TARGET_TMPDIR"), "commands", name, text)
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
            "bad.csv:1: the first line is not a header starting with the column `t`",
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
