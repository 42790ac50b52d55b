//! The `platener` command line: parses flags, resolves them into library settings, prints.
//!
//! Exit codes: 0 success, 1 a model failed, 2 usage error (clap's default).

mod args;
mod inspect;
mod test_strip;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    let result = match cli.command {
        args::Command::Inspect(a) => inspect::run(&a),
        args::Command::TestStrip(a) => test_strip::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}
