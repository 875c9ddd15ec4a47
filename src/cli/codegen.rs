//! `rover codegen <file-or-builtin> [--out <file>] [--fidelity <level>]
//! [--type-name <Name>] [--no-jacobian]`: the generated plant of a rover as
//! a formatted, standalone Rust module (docs/CODEGEN.md).

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use rover_dynamics::fidelity::Fidelity;

use rover_scenario::output::write_whole;
use rover_scenario::prepare::{load_rover, reduced_level_reference_of};

use crate::error::{CliError, print_stdout};

/// The dynamic fidelity levels a plant can be generated at (MODEL.md §9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum CodegenLevel {
    /// Level 1, the full model.
    #[default]
    Full,
    /// Level 2: kinematics frozen, M constant, Ṁ = f2 = 0.
    Simplified,
    /// Level 3, the paper's: as level 2, plus the rotation, the angle rates,
    /// the gravity direction and the wheel positions to first order.
    Linearized,
    /// Level 3 keeping the rotation exact.
    LinearizedExactRotation,
}

/// Arguments of `rover codegen`.
#[derive(Debug, Args)]
pub struct CodegenArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file.
    pub rover: String,
    /// Write the module here instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Fidelity level; the reduced levels are frozen at the rover's loaded
    /// static equilibrium on flat ground, as `simulate` freezes them.
    #[arg(long, value_enum, default_value_t = CodegenLevel::Full)]
    pub fidelity: CodegenLevel,
    /// Name of the plant type (default: the rover's name in UpperCamelCase).
    #[arg(long)]
    pub type_name: Option<String>,
    /// Leave out the exact Jacobian (a smaller module that compiles faster).
    #[arg(long)]
    pub no_jacobian: bool,
}

/// Generate the module and write it to `--out` or standard output.
pub fn codegen(args: &CodegenArgs) -> Result<String, CliError> {
    if let Some(out) = &args.out {
        CliError::check_output_file("--out", out, &[Path::new(&args.rover)])?;
    }
    let spec = load_rover(&args.rover, None)?;
    let source = rover_models::builtin_path(&args.rover).unwrap_or(&args.rover);
    let fidelity = match args.fidelity {
        CodegenLevel::Full => None,
        CodegenLevel::Simplified => Some(Fidelity::Simplified),
        CodegenLevel::Linearized => Some(Fidelity::Linearized),
        CodegenLevel::LinearizedExactRotation => Some(Fidelity::LinearizedExactRotation),
    };
    let level = match fidelity {
        None => None,
        Some(fidelity) => Some(rover_codegen::trace::Level {
            fidelity,
            y_ref: reduced_level_reference_of(&spec)?,
        }),
    };
    if let Some(name) = &args.type_name
        && (!is_type_name(name) || rover_codegen::check_type_name(name).is_err())
    {
        return Err(CliError::Usage(format!(
            "--type-name {name:?} is not a Rust type name: use letters, digits and \
             underscores, starting with an uppercase letter, and not a keyword such as \
             `Self` (e.g. MyRover)"
        )));
    }
    let options = rover_codegen::ModuleOptions {
        type_name: args.type_name.clone(),
        jacobian: !args.no_jacobian,
        level,
    };
    let text = rover_codegen::generate_module_with(&spec, source, &options)?;
    match &args.out {
        Some(p) => write_whole(p, &text)?,
        None => print_stdout(&text)?,
    }
    Ok(text)
}

/// An UpperCamelCase-style identifier: `[A-Z][A-Za-z0-9_]*`.
fn is_type_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_uppercase())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
