//! `platener completions SHELL`: prints a completion script (clap_complete).

use clap::CommandFactory as _;

use crate::args::{Cli, CompletionsArgs};

/// Examples shown under `platener completions --help`.
pub const EXAMPLES: &str = "Examples:
  platener completions bash > ~/.local/share/bash-completion/completions/platener
  platener completions zsh > ~/.zfunc/_platener
  platener completions fish > ~/.config/fish/completions/platener.fish";

/// Runs the command.
pub fn run(args: &CompletionsArgs) {
    let mut command = Cli::command();
    clap_complete::generate(args.shell, &mut command, "platener", &mut std::io::stdout());
}
