//! `planlab`: command-line front end of planlab-core.
//!
//! Every failure prints one line `planlab: error: …` on stderr and exits
//! non-zero; usage errors exit 2 (clap's convention).

mod serve;

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "planlab",
    version,
    about = "Robot path planning you can watch, poke and measure"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Serve the playground (a built site folder) over HTTP on loopback.
    Serve {
        /// Site folder to serve (must contain index.html).
        #[arg(long, default_value = "web/dist")]
        dir: PathBuf,
        /// Address to bind; keep the default unless you know why.
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Port; 0 picks a free one (printed on start).
        #[arg(long, default_value_t = 8080)]
        port: u16,
    },
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Serve { dir, host, port } => serve::serve(&dir, &host, port),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("planlab: error: {e}");
            ExitCode::FAILURE
        }
    }
}
