//! The `raylab` program: the command line now, the desktop window later.

mod cli;
mod output;
mod render_cmd;

use clap::Parser;
use cli::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Render(args) => match render_cmd::run(&args) {
            Ok(elapsed) => {
                println!(
                    "wrote {} in {:.3} s",
                    args.output.display(),
                    elapsed.as_secs_f64()
                );
                ExitCode::SUCCESS
            }
            Err(error) => {
                eprintln!("error: {error:#}");
                ExitCode::from(2)
            }
        },
    }
}
