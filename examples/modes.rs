//! Tune a heading hold on the linearized rover: swing4 driving at 0.1 m/s
//! under its speed loop, following the line Y = 0 by slip steering, for a
//! few line-following gains; prints the line-following loop's frequency
//! and damping ratio (the slowest oscillatory mode) for each. Run:
//! `cargo run --release --example modes`.

use rover_runtime::control::ControllerConfig;
use rover_scenario::linearize::{ModeKind, OperatingPoint, linearize_at};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let spec = rover_spec::load_str(
        rover_models::builtin("swing4").ok_or("no swing4")?,
        "models/swing4.toml",
    )?;
    for cross_track in [0.5, 1.0, 2.0, 4.0, 8.0] {
        let control: ControllerConfig = toml::from_str(&format!(
            "[speed]\nspeed = 0.1\n[steering]\nkind = \"heading\"\nkp = 5.0\nkd = 0.5\ncross_track = {cross_track}\n"
        ))?;
        let point = OperatingPoint {
            speed: 0.1,
            control,
            ..Default::default()
        };
        let lin = linearize_at(&spec.model, rover_models::Swing4::new(), &point)?;
        // Modes come sorted: oscillatory by frequency first.
        let slowest = lin.modes.iter().find(|m| m.kind == ModeKind::Oscillatory);
        let stable = lin
            .modes
            .iter()
            .all(|m| m.kind == ModeKind::Neutral || m.eigenvalue[0] < 0.0);
        match slowest {
            Some(m) => println!(
                "cross_track = {cross_track:>3} rad/m: slowest pair {:.3} Hz, damping ratio {:.2}, {} ({})",
                m.natural_hz,
                m.damping_ratio,
                if stable { "stable" } else { "UNSTABLE" },
                m.dominant
                    .iter()
                    .map(|(name, share)| format!("{name} {:.0}%", 100.0 * share))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            None => println!(
                "cross_track = {cross_track:>3} rad/m: no oscillatory mode, {}",
                if stable { "stable" } else { "UNSTABLE" }
            ),
        }
    }
    Ok(())
}
