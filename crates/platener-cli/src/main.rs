//! The `platener` command line: parses flags, resolves them into library settings, prints.
//!
//! Exit codes: as `platener --help` and the README say (`args::MAIN_EXAMPLES`): 0 success, 1
//! something failed, 2 a usage error.

mod args;
mod batch;
mod completions;
mod convert;
mod fault;
mod hinge_test;
mod inputs;
mod inspect;
mod progress;
mod report;
mod scene;
mod setting_args;
mod test_strip;
mod verify;
mod web;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    let result = match cli.command {
        args::Command::Convert(a) => convert::run(&a),
        args::Command::Inspect(a) => inspect::run(&a).map(|()| 0),
        args::Command::TestStrip(a) => test_strip::run(&a).map(|()| 0),
        args::Command::HingeTest(a) => hinge_test::run(&a).map(|()| 0),
        args::Command::Verify(a) => verify::run(&a),
        args::Command::Scene(a) => scene::run(&a).map(|()| 0),
        args::Command::Serve(a) => web::serve(&a).map(|()| 0),
        args::Command::Worker(a) => web::worker(&a),
        args::Command::Completions(a) => {
            completions::run(&a);
            Ok(0)
        }
    };
    match result {
        Ok(code) => ExitCode::from(code),
        Err(e) if e.is::<convert::UsageError>() => {
            eprintln!("error: {}", setting_args::flags(&format!("{e:#}")));
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {}", setting_args::flags(&format!("{e:#}")));
            ExitCode::from(1)
        }
    }
}
