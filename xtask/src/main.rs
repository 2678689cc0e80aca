//! `cargo xtask`: the project's automation, in Rust so it needs nothing but cargo.
//!
//! * `cargo xtask run`  — build the firmware, boot it in QEMU and play the demo session
//!   (`firmware/demo/session.jsonl`) over its serial port, then the live cue on an
//!   example IMU trace (`cargo xtask live`); `--interactive` lets a person type the
//!   requests. The decoded defmt log follows the session.
//! * `cargo xtask test` — every check: host fmt/clippy/tests, core for the target,
//!   firmware fmt/clippy/build and size, the demo session and the end-to-end test in
//!   QEMU.
//! * `cargo xtask live --trace FILE [--odr HZ] [--plan FILE]` — play an IMU trace
//!   through the firmware's emulated IMU in QEMU; one JSON line per detected stroke.
//! * `cargo xtask docs [--check]` — regenerate the figures of README.md and docs/ that
//!   commands produce (generated blocks); `--check` fails on any that is stale.
//! * `cargo xtask fuzz [--seconds N] [TARGET...]` — the cargo-fuzz targets of `fuzz/`,
//!   each for a bounded time (60 s in `cargo xtask test`).
//!
//! They install what they need first (rustup target and components, QEMU, defmt-print).

mod bench;
mod cmd;
mod docs;
mod format;
mod fuzz;
mod host_tests;
mod images;
mod install;
mod lines;
mod live;
mod python;
mod qemu;
mod size;
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
    /// Build the firmware (release), boot it in QEMU (mps2-an386) and play a session of
    /// requests over its serial port; the decoded defmt log follows.
    Run {
        /// Type the requests yourself (stdin to the serial port; Ctrl-D ends).
        #[arg(long, conflicts_with = "session")]
        interactive: bool,
        /// The session to play, one JSON request per line [default: firmware/demo/session.jsonl].
        #[arg(long, value_name = "FILE")]
        session: Option<std::path::PathBuf>,
        /// Kill QEMU after this many seconds and fail (not with --interactive).
        #[arg(long, default_value_t = qemu::DEFAULT_TIMEOUT_SECS)]
        timeout: u64,
        /// Boot this firmware ELF instead of building the release one (what `cargo run`
        /// in firmware/ passes, through its runner `firmware/qemu-run`).
        #[arg(long, value_name = "ELF")]
        elf: Option<std::path::PathBuf>,
    },
    /// Play an IMU trace (CSV, raw LSM6DSOX words) through the firmware's emulated IMU
    /// in QEMU; print one JSON line per stroke the device detects, then a summary.
    Live(live::Args),
    /// Measure every model x backend x precision (Cortex-M4 instructions under QEMU, host
    /// ns, error on the grid); write target/bench/tradeoff.{json,md,svg} (with
    /// --update-docs, the report and plot over docs/tradeoff.{md,svg}).
    Bench(bench::Args),
    /// Build the cargo-fuzz targets (fuzz/) and run each for a bounded time on its
    /// committed seeds; fails on any crash (installs cargo-fuzz and a C++ compiler if
    /// missing; stable toolchain through RUSTC_BOOTSTRAP=1).
    Fuzz(fuzz::Args),
    /// Regenerate the generated blocks of README.md and docs/*.md (figures that a
    /// command produces); with --check, change nothing and fail on any stale block.
    Docs(docs::Args),
    /// Run every check, stopping at the first failure.
    Test {
        /// Run the remaining steps after a failure instead of stopping.
        #[arg(long)]
        keep_going: bool,
        /// Run only the steps whose title contains this text (e.g. "host: tests").
        #[arg(long, value_name = "TEXT")]
        only: Option<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            interactive,
            session,
            timeout,
            elf,
        } => tools::ensure_for_qemu()
            .and_then(|()| match elf {
                Some(_) => Ok(()),
                None => qemu::build_release(),
            })
            .and_then(|()| {
                let elf = elf.unwrap_or_else(qemu::elf_path);
                if interactive {
                    qemu::run_interactive(&elf)
                } else {
                    let demo = session.is_none();
                    let session = session.unwrap_or_else(qemu::demo_session);
                    qemu::run_session(&elf, &session, Duration::from_secs(timeout))?;
                    if !demo {
                        return Ok(());
                    }
                    // Then the live cue on an example trace, with a planned shot.
                    println!("\nxtask: the live cue: {}", live::DEMO_COMMAND);
                    live::run(&live::Args::demo())
                }
            }),
        Command::Test { keep_going, only } => test::run_all(keep_going, only.as_deref()),
        Command::Live(args) => live::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Docs(args) => docs::run(&args),
        Command::Fuzz(args) => fuzz::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("xtask: {}", failure.message);
            ExitCode::from(failure.code)
        }
    }
}
