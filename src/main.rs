//! `rover`: simulate wheeled planetary rovers (see the README).

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = rover::cli::Cli::parse();
    match rover::cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            if e.is_rendered() {
                eprintln!("{e}");
            } else {
                eprintln!("error: {e}");
            }
            ExitCode::from(2)
        }
    }
}
