//! `rover`: simulate wheeled planetary rovers (see the README).

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let args = rover::cli::Cli::parse();
    match rover::cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("{}", e.user_message());
            ExitCode::from(2)
        }
    }
}
