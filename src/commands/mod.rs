//! The commands: one file per subcommand, each a `run(args)` that turns the command
//! line into validated parameters and calls the library; nothing below imports this layer.

pub mod analyze;
mod animate;
mod batch;
mod bench;
pub mod common;
mod generate;
mod presets;
mod render;
mod spectrum;

use anyhow::Result;

use crate::cli::{Cli, Command};

/// Runs one command.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Generate(args) => generate::run(*args),
        Command::Presets { name } => presets::run(name.as_deref()),
        Command::Animate(args) => animate::run(*args),
        Command::Batch(args) => batch::run(*args),
        Command::Analyze(args) => analyze::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Spectrum(args) => spectrum::run(args),
        Command::Render(args) => render::run(*args),
    }
}
