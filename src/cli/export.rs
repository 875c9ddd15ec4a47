//! `rover export fmu ROVER --scenario FILE --out FILE.fmu [--fmi 2]
//! [--inputs torques]` and `rover export c ROVER --scenario FILE --out DIR`:
//! the plant as an FMU or a C library (docs/EXPORT.md).

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand, ValueEnum};
use rover_export::model_description::FmiVersion;
use rover_export::package::{self, COptions, FmuOptions, LibraryKind, Written};
use rover_export::variables::Inputs;

use crate::error::CliError;

/// Arguments of `rover export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// What to export.
    #[command(subcommand)]
    pub kind: ExportKind,
}

/// What `rover export` writes.
#[derive(Debug, Subcommand)]
pub enum ExportKind {
    /// An FMI Co-Simulation FMU for this platform (FMI 3.0; 2.0 with `--fmi 2`).
    Fmu(FmuArgs),
    /// A folder with a C header, a static library, an example main.c and the packed scenario.
    C(CArgs),
}

/// The FMI versions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum FmiArg {
    /// FMI 2.0 Co-Simulation.
    #[value(name = "2")]
    Two,
    /// FMI 3.0 Co-Simulation.
    #[default]
    #[value(name = "3")]
    Three,
}

/// What an FMU takes from outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum InputsArg {
    /// Nothing: the scenario's own controllers drive the rover.
    #[default]
    None,
    /// The wheels' motor torques, steering angles and spring neutrals.
    Torques,
}

/// Arguments of `rover export fmu`.
#[derive(Debug, Args)]
pub struct FmuArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file;
    /// overrides the scenario's `rover`.
    pub rover: Option<String>,
    /// The scenario file (TOML): terrain, soil, contact, integrator, controllers.
    #[arg(long)]
    pub scenario: PathBuf,
    /// The FMU to write.
    #[arg(long, default_value = "rover.fmu")]
    pub out: PathBuf,
    /// FMI version.
    #[arg(long, value_enum, default_value_t = FmiArg::Three)]
    pub fmi: FmiArg,
    /// The FMU's inputs: none (the scenario's controllers) or torques
    /// (motor torques, steering angles and spring neutrals, added to the
    /// scenario's controllers).
    #[arg(long, value_enum, default_value_t = InputsArg::None)]
    pub inputs: InputsArg,
    /// The prebuilt plant library to pack (default: librover_plant.so
    /// beside this executable, or in $ROVER_PLANT_LIB_DIR).
    #[arg(long)]
    pub library: Option<PathBuf>,
}

/// Arguments of `rover export c`.
#[derive(Debug, Args)]
pub struct CArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file;
    /// overrides the scenario's `rover`.
    pub rover: Option<String>,
    /// The scenario file (TOML).
    #[arg(long)]
    pub scenario: PathBuf,
    /// The folder to write (created if missing).
    #[arg(long, default_value = "rover-c")]
    pub out: PathBuf,
    /// The prebuilt static library to copy (default: librover_plant.a
    /// beside this executable, or in $ROVER_PLANT_LIB_DIR).
    #[arg(long)]
    pub library: Option<PathBuf>,
}

/// Write the FMU or the C folder.
pub fn export(args: &ExportArgs) -> Result<Written, CliError> {
    match &args.kind {
        ExportKind::Fmu(a) => {
            let rover_path = a.rover.as_deref().map(Path::new);
            let inputs: Vec<&Path> = [Some(a.scenario.as_path()), rover_path]
                .into_iter()
                .flatten()
                .collect();
            CliError::check_output_file("--out", &a.out, &inputs)?;
            let library = package::find_library(LibraryKind::Shared, a.library.as_deref())?;
            Ok(package::export_fmu(&FmuOptions {
                rover: a.rover.clone(),
                scenario: a.scenario.clone(),
                out: a.out.clone(),
                version: match a.fmi {
                    FmiArg::Two => FmiVersion::Fmi2,
                    FmiArg::Three => FmiVersion::Fmi3,
                },
                inputs: match a.inputs {
                    InputsArg::None => Inputs::None,
                    InputsArg::Torques => Inputs::Torques,
                },
                library,
            })?)
        }
        ExportKind::C(a) => {
            if a.out.is_file() {
                return Err(CliError::Usage(format!(
                    "--out {}: is a file; give a folder to write the header, the library and the example into",
                    a.out.display()
                )));
            }
            let library = package::find_library(LibraryKind::Static, a.library.as_deref())?;
            Ok(package::export_c(&COptions {
                rover: a.rover.clone(),
                scenario: a.scenario.clone(),
                out: a.out.clone(),
                library,
            })?)
        }
    }
}

/// What the command prints.
pub fn report(w: &Written) -> String {
    let mut s = format!(
        "wrote {} ({}: {} outputs, {} inputs)\n",
        w.path.display(),
        w.identifier,
        w.outputs,
        w.inputs
    );
    if !w.next.is_empty() {
        s.push_str(&format!("build and run the example: {}\n", w.next));
    }
    s
}
