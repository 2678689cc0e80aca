//! Boot the firmware in QEMU and talk to it: a scripted session (`cargo xtask run`),
//! or requests typed by a person (`cargo xtask run --interactive`).
//!
//! QEMU's stdio is the firmware's UART0 (the protocol, one JSON line each way); the
//! firmware's defmt frames arrive on QEMU's stderr and go through `defmt-print -e <elf>`
//! (the harness is `cuesight_host::firmware`). The decoded log is printed after the
//! session, so it never interleaves with the requests and answers, and is also written
//! to `target/xtask/firmware.log`. QEMU's exit code is the firmware's verdict.

use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cuesight_host::firmware::{qemu_command, Ended, Firmware, FirmwareError};
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

fn boot(elf: &Path) -> Result<Firmware> {
    let defmt_print = tools::defmt_print()?;
    println!(
        "$ {}\n  (UART0 on stdio; the defmt log on stderr, through {} -e <elf>)",
        cmd::display(&qemu_command(elf)),
        defmt_print.display(),
    );
    let fw = Firmware::boot(elf, Some(&defmt_print))
        .map_err(|e| Failure::new(format!("cannot boot the firmware in QEMU: {e}")))?;
    // The unprompted `version` frame at boot.
    let _ = fw.next_frame(Duration::from_secs(10));
    Ok(fw)
}

/// Plays `session` (one request per line; `#` lines are headings, `##` lines comments)
/// against the firmware and prints each request with a one-line summary of its answer.
/// Fails on a missing or unparseable answer, a non-zero QEMU exit, or after `timeout`
/// (code 124).
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
    let mut fw = boot(elf)?;
    let mut answered = 0usize;
    let mut shut_down = false;
    for line in text.lines() {
        let line = line.trim_end();
        if line.starts_with("##") {
            continue; // a comment about the file
        }
        if let Some(heading) = line.strip_prefix('#') {
            println!("\n== {}", heading.trim());
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        println!("> {}", shorten(line));
        let request: Request = match serde_json::from_str(line) {
            Ok(request) => request,
            Err(e) => {
                println!("! not a request: {e}");
                continue;
            }
        };
        let left = deadline.saturating_duration_since(Instant::now());
        let seq = answered as u16;
        let response = match fw.request(seq, &request, left) {
            Ok(response) => response,
            Err(error) => return Err(session_failure(fw, error, deadline)),
        };
        answered += 1;
        println!("< {response:?}");
        shut_down = matches!(response, Response::Shutdown(_));
        if shut_down {
            break;
        }
    }
    if !shut_down {
        println!("> {{\"shutdown\":{{}}}}   (end of the session file)");
        let left = deadline.saturating_duration_since(Instant::now());
        match fw.request(
            answered as u16,
            &Request::Shutdown(Default::default()),
            left,
        ) {
            Ok(answer) => println!("< {answer:?}"),
            Err(error) => return Err(session_failure(fw, error, deadline)),
        }
    }
    let ended = fw.wait(deadline.saturating_duration_since(Instant::now()));
    print_log(&ended);
    finish(&ended, &format!("{answered} requests answered"))
}

/// `line`, cut to about two terminal lines.
fn shorten(line: &str) -> String {
    const SHOWN: usize = 150;
    match line.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!("{}... ({} bytes)", &line[..cut], line.len()),
        None => line.to_owned(),
    }
}

/// A person types requests; each answer is printed raw and summarised. End of input
/// (Ctrl-D) sends `shutdown`; so does typing it. No timeout.
pub fn run_interactive(elf: &Path) -> Result {
    let mut fw = boot(elf)?;
    println!(
        "xtask: type one request per line, e.g.\n  \
         {{\"collide\":{{\"speed\":2,\"cut\":30,\"spin\":[0,40,0]}}}}\n  \
         {{\"params\":{{\"mu\":0.06}}}}   {{\"version\":{{}}}}   {{\"shutdown\":{{}}}}\n\
         (docs/protocol.md has them all); Ctrl-D ends the session, the log follows."
    );
    let stdin = std::io::stdin();
    let mut seq = 0u16;
    let mut lines = stdin.lock().lines().map_while(std::io::Result::ok);
    loop {
        let request = match lines.next() {
            Some(line) => match serde_json::from_str::<Request>(&line) {
                Ok(request) => request,
                Err(e) => {
                    println!("! not a request: {e}");
                    continue;
                }
            },
            None => Request::Shutdown(Default::default()),
        };
        match fw.request(seq, &request, Duration::from_secs(60)) {
            Ok(response) => {
                println!("< {response:?}");
                if matches!(response, Response::Shutdown(_)) {
                    break;
                }
            }
            Err(FirmwareError::Closed) => break,
            Err(e) => return Err(Failure::new(e.to_string())),
        }
        seq = seq.wrapping_add(1);
    }
    let ended = fw.wait(Duration::from_secs(10));
    print_log(&ended);
    finish(&ended, "session over")
}

/// Builds the failure for a session that stopped answering, with the log so far.
fn session_failure(fw: Firmware, error: FirmwareError, deadline: Instant) -> Failure {
    let timed_out = matches!(error, FirmwareError::Timeout(_)) || Instant::now() >= deadline;
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
