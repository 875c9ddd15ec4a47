//! `rover wheel-test --soil <name|file> --radius R --width B --load W --slip s1,s2,…`:
//! the single-wheel testbed (docs/SOIL.md).

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;
use rover_runtime::soil::{SoilConfig, WheelTestPoint, wheel_test};

use crate::error::{CliError, print_stdout};

/// Arguments of `rover wheel-test`.
#[derive(Debug, Args)]
// A negative number is a value (`--load -5` is then refused as a load, not
// taken for an unknown flag).
#[command(allow_negative_numbers = true)]
pub struct WheelTestArgs {
    /// A built-in soil (lete_sand, dry_sand, lunar_nominal, lunar_simulant,
    /// mars_simulant) or a TOML file with a `[soil]` table.
    #[arg(long)]
    pub soil: String,
    /// Wheel radius \[m\].
    #[arg(long)]
    pub radius: f64,
    /// Wheel width \[m\].
    #[arg(long)]
    pub width: f64,
    /// Vertical load \[N\].
    #[arg(long)]
    pub load: f64,
    /// Slips, comma-separated, each in (-1, 1): positive driving, negative braking.
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        allow_hyphen_values = true
    )]
    pub slip: Vec<f64>,
    /// Slip angle \[°\]: adds the lateral force.
    #[arg(
        long,
        alias = "slip-angle",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub slip_angle_deg: f64,
    /// Also draw DP/W and T/(W·r) against slip into this PNG (and an SVG beside it).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Run the test and return the CSV it prints.
pub fn wheel_test_cmd(args: &WheelTestArgs) -> Result<String, CliError> {
    let soil = SoilConfig::named_or_file(&args.soil)
        .and_then(|s| s.soil())
        .map_err(|e| CliError::Usage(format!("--soil {}: {e}", args.soil)))?;
    let points = wheel_test(
        &soil,
        args.radius,
        args.width,
        args.load,
        &args.slip,
        args.slip_angle_deg.to_radians(),
    )
    .map_err(|e| CliError::Usage(e.to_string()))?;
    if let Some(path) = &args.plot {
        plot(path, &points, args.load, args.radius)?;
    }
    Ok(csv(&points, args.load, args.radius))
}

/// [`WheelTestPoint::COLUMNS`], then each point's
/// [`row`](WheelTestPoint::row).
fn csv(points: &[WheelTestPoint], load: f64, radius: f64) -> String {
    let mut out = WheelTestPoint::COLUMNS.join(",");
    out.push('\n');
    for p in points {
        let row = p.row(load, radius).map(|v| v.to_string());
        let _ = writeln!(out, "{}", row.join(","));
    }
    out
}

#[cfg(feature = "plots")]
fn plot(
    path: &std::path::Path,
    points: &[WheelTestPoint],
    load: f64,
    radius: f64,
) -> Result<(), CliError> {
    use rover_plot::{Series, line_chart};
    let series = [
        Series {
            name: "DP/W".into(),
            points: points
                .iter()
                .map(|p| (p.slip, p.drawbar_pull_over_load(load)))
                .collect(),
            markers: false,
        },
        Series {
            name: "T/(W·r)".into(),
            points: points
                .iter()
                .map(|p| (p.slip, p.torque_over_load_radius(load, radius)))
                .collect(),
            markers: false,
        },
    ];
    let stem = path.with_extension("");
    line_chart(&stem, "single-wheel test", "slip", "ratio", &series)?;
    Ok(())
}

#[cfg(not(feature = "plots"))]
fn plot(_: &std::path::Path, _: &[WheelTestPoint], _: f64, _: f64) -> Result<(), CliError> {
    Err(CliError::Usage(
        "--plot: this build has no plots (the `plots` feature)".into(),
    ))
}

/// Print the test's CSV.
pub fn run(args: &WheelTestArgs) -> Result<(), CliError> {
    print_stdout(&wheel_test_cmd(args)?)
}
