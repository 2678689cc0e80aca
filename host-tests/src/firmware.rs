//! Boot the release firmware in QEMU and talk to it over its serial port: the harness
//! of the end-to-end test and of `cargo xtask run`.
//!
//! QEMU runs `mps2-an386` with UART0 on its stdio (`-serial stdio`), so the protocol is
//! the child's stdin/stdout, one JSON line each way; the firmware's defmt frames come
//! out on QEMU's stderr (semihosting, see `firmware/src/board/qemu/log.rs`) and are
//! decoded by `defmt-print` when one is given, else counted and dropped. Every wait has
//! a deadline and the QEMU process is killed when the [`Firmware`] is dropped, so a hung
//! firmware cannot hang the caller.

use std::io::{self, BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, ExitStatus, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

/// The QEMU command that boots `elf` with UART0 on stdio and semihosting enabled.
pub fn qemu_command(elf: &Path) -> Command {
    let mut qemu = Command::new("qemu-system-arm");
    qemu.args(["-machine", "mps2-an386", "-cpu", "cortex-m4"])
        .args(["-display", "none", "-monitor", "none", "-serial", "stdio"])
        .args(["-semihosting-config", "enable=on,target=native"])
        .arg("-kernel")
        .arg(elf);
    qemu
}

/// The release ELF of `firmware/` (honours `CUESIGHT_FIRMWARE_ELF`).
pub fn default_elf() -> PathBuf {
    if let Some(elf) = std::env::var_os("CUESIGHT_FIRMWARE_ELF") {
        return PathBuf::from(elf);
    }
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../firmware/target/thumbv7em-none-eabihf/release/cuesight-firmware")
}

/// A failure talking to the firmware.
#[derive(Debug)]
pub enum FirmwareError {
    /// Starting QEMU or defmt-print, or writing to QEMU, failed.
    Io(io::Error),
    /// No answer line within the deadline.
    Timeout(Duration),
    /// The serial output ended (QEMU exited) before an answer.
    Closed,
}

impl std::fmt::Display for FirmwareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FirmwareError::Io(e) => write!(f, "{e}"),
            FirmwareError::Timeout(t) => write!(f, "no answer within {:.1} s", t.as_secs_f64()),
            FirmwareError::Closed => f.write_str("the firmware's serial output ended"),
        }
    }
}

impl std::error::Error for FirmwareError {}

impl From<io::Error> for FirmwareError {
    fn from(e: io::Error) -> Self {
        FirmwareError::Io(e)
    }
}

/// How QEMU ended.
#[derive(Debug)]
pub struct Ended {
    /// QEMU's exit status (the firmware's verdict); `None` if it was killed at the
    /// deadline.
    pub status: Option<ExitStatus>,
    /// The decoded defmt log (empty without defmt-print).
    pub log: Vec<String>,
    /// Raw log bytes received on QEMU's stderr.
    pub log_bytes: usize,
}

/// A running firmware.
pub struct Firmware {
    qemu: Child,
    decoder: Option<Child>,
    serial_in: Option<ChildStdin>,
    answers: Receiver<String>,
    log: Option<JoinHandle<(Vec<String>, usize)>>,
}

impl Firmware {
    /// Boots `elf`. With `defmt_print`, the log is decoded as it arrives.
    pub fn boot(elf: &Path, defmt_print: Option<&Path>) -> Result<Self, FirmwareError> {
        if !elf.is_file() {
            return Err(FirmwareError::Io(io::Error::new(
                io::ErrorKind::NotFound,
                format!(
                    "no firmware at {} (build it: cargo xtask test)",
                    elf.display()
                ),
            )));
        }
        let mut qemu = qemu_command(elf)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()?;
        let serial_in = qemu.stdin.take();
        let serial_out = qemu
            .stdout
            .take()
            .ok_or_else(|| io::Error::other("no stdout"))?;
        let log_out = qemu
            .stderr
            .take()
            .ok_or_else(|| io::Error::other("no stderr"))?;

        let (send, answers) = mpsc::channel();
        thread::spawn(move || {
            for line in BufReader::new(serial_out).lines().map_while(Result::ok) {
                if send.send(line).is_err() {
                    break;
                }
            }
        });

        let (decoder, log) = match defmt_print {
            Some(tool) => {
                let mut decoder = Command::new(tool)
                    .arg("-e")
                    .arg(elf)
                    .stdin(Stdio::from(log_out))
                    .stdout(Stdio::piped())
                    .stderr(Stdio::null())
                    .spawn()?;
                let decoded = decoder
                    .stdout
                    .take()
                    .ok_or_else(|| io::Error::other("no stdout"))?;
                let handle = thread::spawn(move || {
                    let lines: Vec<String> = BufReader::new(decoded)
                        .lines()
                        .map_while(Result::ok)
                        .collect();
                    let bytes = lines.iter().map(String::len).sum();
                    (lines, bytes)
                });
                (Some(decoder), handle)
            }
            None => {
                let handle = thread::spawn(move || {
                    let mut raw = Vec::new();
                    let _ = BufReader::new(log_out).read_to_end(&mut raw);
                    (Vec::new(), raw.len())
                });
                (None, handle)
            }
        };
        Ok(Self {
            qemu,
            decoder,
            serial_in,
            answers,
            log: Some(log),
        })
    }

    /// Writes `line` and a newline to the serial port.
    pub fn send(&mut self, line: &[u8]) -> Result<(), FirmwareError> {
        let port = self
            .serial_in
            .as_mut()
            .ok_or_else(|| io::Error::other("the serial input was handed out"))?;
        port.write_all(line)?;
        port.write_all(b"\n")?;
        port.flush()?;
        Ok(())
    }

    /// Hands out the serial input, for a writer thread that streams requests while
    /// this side reads answers.
    pub fn take_serial_in(&mut self) -> Option<ChildStdin> {
        self.serial_in.take()
    }

    /// The next answer line (without its newline).
    pub fn answer(&self, timeout: Duration) -> Result<String, FirmwareError> {
        match self.answers.recv_timeout(timeout) {
            Ok(line) => Ok(line),
            Err(RecvTimeoutError::Timeout) => Err(FirmwareError::Timeout(timeout)),
            Err(RecvTimeoutError::Disconnected) => Err(FirmwareError::Closed),
        }
    }

    /// Sends `line` and returns its answer.
    pub fn request(&mut self, line: &[u8], timeout: Duration) -> Result<String, FirmwareError> {
        self.send(line)?;
        self.answer(timeout)
    }

    /// Waits for QEMU to exit (after a `shutdown`), killing it at `timeout`, and
    /// collects the log.
    pub fn wait(mut self, timeout: Duration) -> Ended {
        drop(self.serial_in.take());
        let deadline = Instant::now() + timeout;
        let status = loop {
            match self.qemu.try_wait() {
                Ok(Some(status)) => break Some(status),
                Ok(None) if Instant::now() < deadline => thread::sleep(Duration::from_millis(10)),
                _ => {
                    let _ = self.qemu.kill();
                    let _ = self.qemu.wait();
                    break None;
                }
            }
        };
        // QEMU's end closes the log pipe; the decoder drains it and exits.
        if let Some(mut decoder) = self.decoder.take() {
            let limit = Instant::now() + Duration::from_secs(10);
            while matches!(decoder.try_wait(), Ok(None)) && Instant::now() < limit {
                thread::sleep(Duration::from_millis(10));
            }
            let _ = decoder.kill();
            let _ = decoder.wait();
        }
        let (log, log_bytes) = self
            .log
            .take()
            .and_then(|h| h.join().ok())
            .unwrap_or_default();
        Ended {
            status,
            log,
            log_bytes,
        }
    }
}

impl Drop for Firmware {
    fn drop(&mut self) {
        let _ = self.qemu.kill();
        let _ = self.qemu.wait();
        if let Some(decoder) = self.decoder.as_mut() {
            let _ = decoder.kill();
            let _ = decoder.wait();
        }
    }
}

/// `defmt-print` from `DEFMT_PRINT`, the `PATH` or cargo's bin directory, if runnable.
pub fn find_defmt_print() -> Option<PathBuf> {
    let from_env = std::env::var_os("DEFMT_PRINT").map(PathBuf::from);
    let cargo_home = std::env::var_os("CARGO_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cargo")));
    let in_cargo_bin = cargo_home.map(|h| h.join("bin").join("defmt-print"));
    [from_env, Some(PathBuf::from("defmt-print")), in_cargo_bin]
        .into_iter()
        .flatten()
        .find(|tool| {
            Command::new(tool)
                .arg("--version")
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success())
        })
}
