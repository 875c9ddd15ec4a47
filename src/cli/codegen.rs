//! `rover codegen <file-or-builtin> [--out <file>]`: the generated plant of a
//! rover as a formatted, standalone Rust module (docs/CODEGEN.md).

use std::path::PathBuf;

use clap::Args;

use super::CliError;
use crate::rover_source::load_rover;

/// Arguments of `rover codegen`.
#[derive(Debug, Args)]
pub struct CodegenArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file.
    pub rover: String,
    /// Write the module here instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Generate the module and write it to `--out` or standard output.
pub fn codegen(args: &CodegenArgs) -> Result<String, CliError> {
    let spec = load_rover(&args.rover, None)?;
    let source = rover_models::builtin_path(&args.rover).unwrap_or(&args.rover);
    let text = rover_codegen::generate_module(&spec, source)
        .map_err(|e| CliError::Other(e.to_string()))?;
    match &args.out {
        Some(p) => std::fs::write(p, &text)
            .map_err(|e| CliError::Other(format!("{}: {e}", p.display())))?,
        None => print!("{text}"),
    }
    Ok(text)
}
