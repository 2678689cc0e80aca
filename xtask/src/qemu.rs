//! Boot the firmware in QEMU and decode its defmt log.
//!
//! The firmware writes defmt frames to semihosting stdout, which QEMU
//! (`-semihosting-config enable=on,target=native`) forwards to its own stdout; that
//! is piped into `defmt-print -e <elf>`, which turns the frames back into text with
//! the format strings stored in the ELF. QEMU's exit code is the firmware's verdict.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// Default limit for one QEMU run; the firmware itself needs well under a second.
pub const DEFAULT_TIMEOUT_SECS: u64 = 60;

/// Exit code for a timed-out run, as coreutils' `timeout` uses.
const TIMEOUT_EXIT: u8 = 124;

const FIRMWARE_BIN: &str = "cuesight-firmware";

/// Builds the firmware in release and runs it (QEMU and defmt-print must be present).
pub fn build_and_run(timeout: Duration) -> Result {
    build_release()?;
    run(&elf_path(), timeout)
}

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

/// Runs `elf` in QEMU with its stdout piped through defmt-print; kills QEMU and fails
/// after `timeout`. Fails with QEMU's exit code if it is not 0, and also when nothing
/// was decoded (a silent firmware is a broken one).
pub fn run(elf: &Path, timeout: Duration) -> Result {
    let defmt_print = tools::defmt_print()?;
    let mut qemu = Command::new("qemu-system-arm");
    qemu.args(["-machine", "mps2-an386", "-cpu", "cortex-m4", "-nographic"])
        .args(["-semihosting-config", "enable=on,target=native"])
        .arg("-kernel")
        .arg(elf);
    let mut decoder = Command::new(&defmt_print);
    decoder.arg("-e").arg(elf);
    let shown = format!("{} | {}", cmd::display(&qemu), cmd::display(&decoder));
    println!("$ {shown}   (timeout {} s)", timeout.as_secs());

    let mut qemu_child = qemu
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start qemu-system-arm: {e}")))?;
    let qemu_out = qemu_child.stdout.take().expect("stdout is piped");
    let mut decoder_child = match decoder.stdin(qemu_out).stdout(Stdio::piped()).spawn() {
        Ok(child) => child,
        Err(e) => {
            kill(&mut qemu_child);
            return Err(Failure::new(format!(
                "cannot start {}: {e}",
                defmt_print.display()
            )));
        }
    };
    // Forward the decoded log line by line, counting the lines.
    let decoded = decoder_child.stdout.take().expect("stdout is piped");
    let forwarder = thread::spawn(move || {
        let mut lines = 0usize;
        for line in BufReader::new(decoded)
            .lines()
            .map_while(std::io::Result::ok)
        {
            println!("{line}");
            lines += 1;
        }
        lines
    });

    let qemu_status = match wait_with_timeout(&mut qemu_child, timeout) {
        Some(status) => status,
        None => {
            kill(&mut qemu_child);
            kill(&mut decoder_child);
            return Err(Failure {
                message: format!(
                    "QEMU did not exit within {} s and was killed",
                    timeout.as_secs()
                ),
                code: TIMEOUT_EXIT,
            });
        }
    };
    // QEMU's end closes the pipe; defmt-print then drains it and exits.
    let decoder_status = wait_with_timeout(&mut decoder_child, Duration::from_secs(10));
    if decoder_status.is_none() {
        kill(&mut decoder_child);
    }
    let lines = forwarder.join().unwrap_or(0);

    cmd::check("qemu-system-arm", qemu_status)?;
    match decoder_status {
        Some(status) => cmd::check("defmt-print", status)?,
        None => return Err(Failure::new("defmt-print did not exit after QEMU did")),
    }
    if lines == 0 {
        return Err(Failure::new(
            "QEMU exited 0 but defmt-print decoded no log line",
        ));
    }
    println!("xtask: firmware exited 0 under QEMU ({lines} log lines)");
    Ok(())
}

/// Polls `child` until it exits or `timeout` passes (`None`).
fn wait_with_timeout(child: &mut Child, timeout: Duration) -> Option<std::process::ExitStatus> {
    let deadline = Instant::now() + timeout;
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return Some(status),
            Ok(None) if Instant::now() < deadline => thread::sleep(Duration::from_millis(20)),
            Ok(None) | Err(_) => return None,
        }
    }
}

fn kill(child: &mut Child) {
    let _ = child.kill();
    let _ = child.wait();
}
