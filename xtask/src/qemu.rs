//! Boot the firmware in QEMU and talk to it through the device console
//! (`cuesight_cli::device`, what `cuesight device --qemu` runs): a scripted session
//! (`cargo xtask run`, the demo `firmware/demo/session.jsonl` or `--session FILE`), or
//! requests typed by a person (`cargo xtask run --interactive`).
//!
//! QEMU's stdio is the firmware's UART0 (link frames each way, `cuesight_link::frame`);
//! the console sends each request line as a frame and prints it (`>`) with a one-line
//! summary of its answer (`<`). The firmware's defmt frames arrive on QEMU's stderr and
//! go through `defmt-print -e <elf>` (the harness is `cuesight_host::firmware`). The
//! decoded log is printed after the session, so it never interleaves with the requests
//! and answers, and is also written to `target/xtask/firmware.log`. QEMU's exit code is
//! the firmware's verdict; an error answer the session file did not mark
//! `!expect-error` fails the run (after the whole session, listed).

use std::io::{self, IsTerminal};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cuesight_cli::device::session::{play, Console, DeviceError, Reply, Show, Tally};
use cuesight_cli::device::text::Summary;
use cuesight_cli::device::transport::{Qemu, TransportError};
use cuesight_host::firmware::{qemu_command, Ended, Firmware};
use cuesight_link::{Request, Response};

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// Default limit for a scripted session.
pub const DEFAULT_TIMEOUT_SECS: u64 = 60;

/// Exit code for a timed-out run, as coreutils' `timeout` uses.
const TIMEOUT_EXIT: u8 = 124;

const FIRMWARE_BIN: &str = "cuesight-firmware";

/// `cargo build --release` in `firmware/`.
pub fn build_release() -> Result {
    cmd::run(
        cmd::cargo()
            .args(["build", "--release"])
            .current_dir(cmd::firmware_dir()),
    )
}

/// The release ELF (honours `CARGO_TARGET_DIR`, which cargo resolves from the cwd).
pub fn elf_path() -> PathBuf {
    let target_dir = match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => cmd::firmware_dir().join(dir),
        None => cmd::firmware_dir().join("target"),
    };
    target_dir
        .join(tools::TARGET)
        .join("release")
        .join(FIRMWARE_BIN)
}

/// The checked-in demo session.
pub fn demo_session() -> PathBuf {
    cmd::firmware_dir().join("demo").join("session.jsonl")
}

fn boot(elf: &Path) -> Result<Qemu> {
    let defmt_print = tools::defmt_print()?;
    println!(
        "$ {}\n  (UART0 on stdio, link frames; the defmt log on stderr, through {} -e <elf>)",
        cmd::display(&qemu_command(elf)),
        defmt_print.display(),
    );
    let fw = Firmware::boot(elf, Some(&defmt_print))
        .map_err(|e| Failure::new(format!("cannot boot the firmware in QEMU: {e}")))?;
    Ok(Qemu::new(fw))
}

/// Plays `session` (the console's session format, `cuesight_cli::device::session`)
/// against the firmware and prints each request with a one-line summary of its answer,
/// then the firmware's log. Fails on an error answer the file did not mark expected (or
/// a marked line that got none, or a line that is no request), a schema mismatch, a
/// missing or unreadable answer, a non-zero QEMU exit, or after `timeout` (code 124).
pub fn run_session(elf: &Path, session: &Path, timeout: Duration) -> Result {
    let text = std::fs::read_to_string(session)
        .map_err(|e| Failure::new(format!("reading {}: {e}", session.display())))?;
    // Install QEMU and defmt-print (minutes on a bare machine) before the deadline
    // starts: the timeout is for the session, not for the installs.
    tools::ensure_qemu()?;
    tools::defmt_print()?;
    let deadline = Instant::now() + timeout;
    println!(
        "xtask: playing {} (timeout {} s)",
        session.display(),
        timeout.as_secs()
    );
    let mut link = boot(elf)?;
    let show = Show {
        json: false,
        echo: true,
        lenient: false,
    };
    let played = converse(&mut link, text.as_bytes(), show, Some(deadline));
    let tally = match played {
        Ok(tally) => tally,
        Err(error) => return Err(session_failure(link.into_firmware(), error, deadline)),
    };
    let ended = link
        .into_firmware()
        .wait(deadline.saturating_duration_since(Instant::now()));
    print_log(&ended);
    finish(
        &ended,
        &format!("{} requests of the session answered", tally.sent),
    )?;
    verdict(&tally)
}

/// Connects (the schema check), plays `input`, and sends `shutdown` if the input did
/// not. Everything goes to stdout.
fn converse(
    link: &mut Qemu,
    input: impl io::BufRead,
    show: Show,
    deadline: Option<Instant>,
) -> std::result::Result<Tally, DeviceError> {
    let per_answer = match deadline {
        Some(deadline) => deadline.saturating_duration_since(Instant::now()),
        None => Duration::from_secs(24 * 3600),
    };
    let mut console = Console::connect(link, per_answer)?;
    console.set_deadline(deadline);
    for note in console.take_notes() {
        println!("note: {note}");
    }
    println!(
        "connected: {}",
        Summary(&Response::Version(console.version().clone()))
    );
    let (mut out, mut notes) = (io::stdout(), io::stdout());
    let tally = play(&mut console, input, &mut out, &mut notes, show)?;
    if !tally.shut_down {
        println!("> {{\"shutdown\":{{}}}}   (end of the session)");
        match console.ask(&Request::Shutdown(Default::default()))? {
            Reply::Answer(response) => println!("< {}", Summary(&response)),
            Reply::Garbled(error) => println!("< (unreadable answer: {error:?})"),
        }
    }
    Ok(tally)
}

/// Fails when the session had unexpected errors, listing them.
fn verdict(tally: &Tally) -> Result {
    if tally.passed() {
        println!(
            "xtask: {} requests, {} expected error(s), no unexpected one",
            tally.sent, tally.expected_errors
        );
        return Ok(());
    }
    let mut message = format!(
        "{} unexpected error(s) in the session:",
        tally.unexpected.len()
    );
    for unexpected in &tally.unexpected {
        message.push_str(&format!(
            "\n  line {}: {}",
            unexpected.line, unexpected.problem
        ));
    }
    Err(Failure::new(message))
}

/// A person types requests; each answer is summarised. Typed at a terminal, error
/// answers are shown but do not fail the run; piped in, stdin is a session like a file
/// (echoed, and an unexpected error fails the run). End of input (Ctrl-D) sends
/// `shutdown`; so does typing it. No timeout.
pub fn run_interactive(elf: &Path) -> Result {
    let mut link = boot(elf)?;
    println!(
        "xtask: type one request per line, e.g.\n  \
         {{\"collide\":{{\"speed\":2,\"cut\":30,\"spin\":[0,40,0]}}}}\n  \
         {{\"params\":{{\"mu\":0.06}}}}   {{\"version\":{{}}}}   {{\"shutdown\":{{}}}}\n\
         (docs/protocol.md has them all); Ctrl-D ends the session, the log follows."
    );
    let stdin = io::stdin();
    let typing = stdin.is_terminal();
    let show = Show {
        json: false,
        echo: !typing,
        lenient: typing,
    };
    let played = converse(&mut link, stdin.lock(), show, None);
    let far = Instant::now() + Duration::from_secs(24 * 3600);
    let tally = match played {
        Ok(tally) => tally,
        Err(error) => return Err(session_failure(link.into_firmware(), error, far)),
    };
    let ended = link.into_firmware().wait(Duration::from_secs(10));
    print_log(&ended);
    finish(&ended, "session over")?;
    verdict(&tally)
}

/// Builds the failure for a session that stopped, with the log so far.
fn session_failure(fw: Firmware, error: DeviceError, deadline: Instant) -> Failure {
    let timed_out = matches!(error, DeviceError::Transport(TransportError::Timeout(_)))
        || Instant::now() >= deadline;
    if !matches!(error, DeviceError::Transport(_)) {
        // The link works but the session cannot go on (another schema, a closed
        // output): stop the firmware, show its log, say why.
        let ended = fw.wait(Duration::ZERO);
        print_log(&ended);
        return Failure::new(error.to_string());
    }
    let ended = fw.wait(Duration::from_secs(1));
    print_log(&ended);
    match ended.status {
        Some(status) if !timed_out => Failure {
            message: format!("the firmware stopped answering ({error}); QEMU ended with {status}"),
            code: status
                .code()
                .and_then(|c| u8::try_from(c).ok())
                .filter(|&c| c != 0)
                .unwrap_or(1),
        },
        _ => Failure {
            message: format!("no answer in time ({error}); QEMU was killed"),
            code: TIMEOUT_EXIT,
        },
    }
}

/// Where the last session's decoded firmware log is written.
pub fn log_file() -> PathBuf {
    cmd::root()
        .join("target")
        .join("xtask")
        .join("firmware.log")
}

fn print_log(ended: &Ended) {
    let path = log_file();
    let written = path
        .parent()
        .is_some_and(|dir| std::fs::create_dir_all(dir).is_ok())
        && std::fs::write(&path, ended.log.join("\n") + "\n").is_ok();
    println!(
        "\n== firmware log (defmt over semihosting, {} lines{})",
        ended.log.len(),
        if written {
            format!(", also in {}", path.display())
        } else {
            String::new()
        }
    );
    for line in &ended.log {
        println!("{line}");
    }
}

fn finish(ended: &Ended, what: &str) -> Result {
    match ended.status {
        None => Err(Failure {
            message: "QEMU did not exit after the session and was killed".into(),
            code: TIMEOUT_EXIT,
        }),
        Some(status) => {
            cmd::check("qemu-system-arm", status)?;
            if ended.log.is_empty() {
                return Err(Failure::new(
                    "QEMU exited 0 but defmt-print decoded no log line",
                ));
            }
            println!("xtask: {what}; the firmware exited 0 under QEMU");
            Ok(())
        }
    }
}
