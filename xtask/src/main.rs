//! `cargo xtask`: the project's automation, in Rust so it needs nothing but cargo.
//!
//! * `cargo xtask run`  — build the firmware and boot it in QEMU, log decoded by defmt-print.
//! * `cargo xtask test` — every check: host fmt/clippy/tests, core for the target,
//!   firmware fmt/clippy/build, and the QEMU run.
//!
//! Both install what they need first (rustup target and components, QEMU, defmt-print).

mod cmd;
mod qemu;
mod test;
mod tools;

use std::process::ExitCode;
use std::time::Duration;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "cargo xtask",
    bin_name = "cargo xtask",
    about = "cuesight project automation"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build the firmware (release) and run it in QEMU (mps2-an386), decoding its defmt log.
    Run {
        /// Kill QEMU after this many seconds and fail.
        #[arg(long, default_value_t = qemu::DEFAULT_TIMEOUT_SECS)]
        timeout: u64,
    },
    /// Run every check, stopping at the first failure.
    Test {
        /// Run the remaining steps after a failure instead of stopping.
        #[arg(long)]
        keep_going: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { timeout } => tools::ensure_for_qemu()
            .and_then(|()| qemu::build_and_run(Duration::from_secs(timeout))),
        Command::Test { keep_going } => test::run_all(keep_going),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("xtask: {}", failure.message);
            ExitCode::from(failure.code)
        }
    }
}
