//! Boot the release firmware in QEMU and talk to it over its serial port in link frames
//! (`cuesight_link::frame`): the harness of the end-to-end tests, of `cuesight device
//! --qemu` and of `cargo xtask run`.
//!
//! QEMU runs `mps2-an386` with UART0 on its stdio (`-serial stdio`), so the link is the
//! child's stdin (requests) and stdout (answers), COBS frames each ended by `0x00`. A
//! reader thread cuts stdout into frames with a [`FrameReader`] (never more than
//! [`cuesight_link::frame::MAX_RAW`] bytes kept per frame; a longer one arrives as
//! [`Incoming::Fault`]). The firmware's defmt frames come out on QEMU's stderr
//! (semihosting, see `firmware/src/board/qemu/log.rs`) and are decoded by `defmt-print`
//! when one is given, else counted and dropped.
//!
//! * Write: [`Firmware::send_request`] (an encoded request with this host's schema),
//!   [`Firmware::send_frame`] (any raw frame content, COBS-encoded and ended: wrong CRC,
//!   schema or body on purpose) and [`Firmware::send_bytes`] (bytes as they are:
//!   truncated, merged or unterminated frames).
//! * Read: [`Firmware::next_frame`] (the next frame as received), [`Firmware::next_answer`]
//!   (the next frame, opened and decoded) and [`Firmware::request`] (send, then the
//!   answer with the same sequence number).
//!
//! Every wait has a deadline and the QEMU process is killed when the [`Firmware`] is
//! dropped, so a hung firmware cannot hang the caller.

use std::io::{self, BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, ExitStatus, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

use cuesight_link::error::FrameFault;
use cuesight_link::frame::{self, FrameReader, Header, Received, MAX_FRAME};
use cuesight_link::{LinkError, Request, Response, SCHEMA_HASH};

/// The QEMU command that boots `elf` with UART0 on stdio and semihosting enabled.
///
/// Single-threaded TCG (`-accel tcg,thread=single`): the board has one core, and QEMU's
/// default for it, a vCPU thread beside the I/O thread, hands every serial byte from one
/// thread to the other (the CMSDK UART takes one byte at a time). Measured on the
/// end-to-end test (`cargo xtask test --only "end-to-end test"`), 136,679 frames through
/// two instances: 205.8 s wall with the default, 187.4 s with one thread (2026-11-27,
/// QEMU 7.2, two cores). `-icount` (the live runs) implies it anyway.
pub fn qemu_command(elf: &Path) -> Command {
    let mut qemu = Command::new("qemu-system-arm");
    qemu.args(["-machine", "mps2-an386", "-cpu", "cortex-m4"])
        .args(["-accel", "tcg,thread=single"])
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
    /// No frame within the deadline.
    Timeout(Duration),
    /// The serial output ended (QEMU exited) before a frame.
    Closed,
    /// A frame arrived but could not be read: bad COBS or too long
    /// ([`Incoming::Fault`]), short, a wrong CRC, or a body that is no [`Response`].
    Garbled(LinkError),
    /// A frame of another schema (its header's hash).
    Schema(u32),
    /// [`Firmware::request`]: the answer carried another sequence number.
    Sequence {
        /// The request's.
        sent: u16,
        /// The answer's.
        answered: u16,
    },
}

impl std::fmt::Display for FirmwareError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FirmwareError::Io(e) => write!(f, "{e}"),
            FirmwareError::Timeout(t) => write!(f, "no answer within {:.1} s", t.as_secs_f64()),
            FirmwareError::Closed => f.write_str("the firmware's serial output ended"),
            FirmwareError::Garbled(e) => write!(f, "unreadable frame from the firmware: {e:?}"),
            FirmwareError::Schema(schema) => write!(
                f,
                "device speaks schema {schema:#010x}, this host {SCHEMA_HASH:#010x}"
            ),
            FirmwareError::Sequence { sent, answered } => {
                write!(f, "request {sent} answered with sequence number {answered}")
            }
        }
    }
}

impl std::error::Error for FirmwareError {}

impl From<io::Error> for FirmwareError {
    fn from(e: io::Error) -> Self {
        FirmwareError::Io(e)
    }
}

/// One frame off the serial port, as [`FrameReader`] cut it (an owned [`Received`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Incoming {
    /// A whole frame, COBS-decoded: header, body and CRC, not yet checked
    /// ([`cuesight_link::frame::open`]).
    Frame(Vec<u8>),
    /// Bytes up to a `0x00` that were no frame: not COBS, or longer than `MAX_RAW`.
    Fault(FrameFault),
}

impl Incoming {
    /// The owned copy of what a [`FrameReader`] handed out.
    pub fn from_received(received: Received<'_>) -> Self {
        match received {
            Received::Frame(raw) => Incoming::Frame(raw.to_vec()),
            Received::Fault(fault) => Incoming::Fault(fault),
        }
    }
}

/// An answer frame, opened and decoded.
#[derive(Clone, Debug, PartialEq)]
pub struct Answer {
    /// The sequence number: the request's it answers, or [`cuesight_link::UNPROMPTED`].
    pub seq: u16,
    /// The answer.
    pub response: Response,
}

/// Opens and decodes a frame from the device: the CRC, then the schema (a foreign one is
/// [`FirmwareError::Schema`], not decoded), then the body as a [`Response`].
pub fn open_answer(incoming: &Incoming) -> Result<Answer, FirmwareError> {
    let raw = match incoming {
        Incoming::Frame(raw) => raw,
        Incoming::Fault(fault) => return Err(FirmwareError::Garbled(LinkError::Frame(*fault))),
    };
    let (Header { schema, seq }, body) = frame::open(raw).map_err(FirmwareError::Garbled)?;
    if schema != SCHEMA_HASH {
        return Err(FirmwareError::Schema(schema));
    }
    let response = frame::decode::<Response>(body).map_err(FirmwareError::Garbled)?;
    Ok(Answer { seq, response })
}

/// `raw` COBS-encoded and ended by `0x00`, whatever it holds (no length limit).
pub fn cobs_frame(raw: &[u8]) -> Vec<u8> {
    let mut out = vec![0u8; raw.len() + raw.len() / 254 + 2];
    let len = cobs::encode(raw, &mut out);
    out.truncate(len);
    out.push(0);
    out
}

/// `request` as a frame with this host's schema and `seq`, ready to send.
pub fn request_frame(seq: u16, request: &Request) -> Result<Vec<u8>, LinkError> {
    let mut out = vec![0u8; MAX_FRAME];
    let len = frame::encode(SCHEMA_HASH, seq, request, &mut out)?;
    out.truncate(len);
    Ok(out)
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
    frames: Receiver<Incoming>,
    log: Option<JoinHandle<(Vec<String>, usize)>>,
}

impl Firmware {
    /// Boots `elf`. With `defmt_print`, the log is decoded as it arrives. The firmware's
    /// unprompted `version` frame is the first [`Firmware::next_frame`].
    pub fn boot(elf: &Path, defmt_print: Option<&Path>) -> Result<Self, FirmwareError> {
        Self::boot_command(elf, defmt_print, qemu_command(elf))
    }

    /// Boots `elf` with the QEMU command `qemu` (what [`qemu_command`] gives, with more
    /// options or another working directory: `crate::live`).
    pub fn boot_command(
        elf: &Path,
        defmt_print: Option<&Path>,
        mut qemu: Command,
    ) -> Result<Self, FirmwareError> {
        if !elf.is_file() {
            return Err(FirmwareError::Io(io::Error::new(
                io::ErrorKind::NotFound,
                format!(
                    "no firmware at {} (build it: cargo xtask test)",
                    elf.display()
                ),
            )));
        }
        let mut qemu = qemu
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

        let (send, frames) = mpsc::channel();
        thread::spawn(move || {
            let mut reader = FrameReader::new();
            let mut serial_out = serial_out;
            let mut buf = [0u8; 4096];
            loop {
                let n = match serial_out.read(&mut buf) {
                    Ok(0) => return,
                    Ok(n) => n,
                    Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                    Err(_) => return,
                };
                for &byte in &buf[..n] {
                    if let Some(received) = reader.push(byte) {
                        if send.send(Incoming::from_received(received)).is_err() {
                            return;
                        }
                    }
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
            frames,
            log: Some(log),
        })
    }

    /// Writes `bytes` to the serial port exactly as given (no framing).
    pub fn send_bytes(&mut self, bytes: &[u8]) -> Result<(), FirmwareError> {
        let port = self
            .serial_in
            .as_mut()
            .ok_or_else(|| io::Error::other("the serial input is closed"))?;
        port.write_all(bytes)?;
        port.flush()?;
        Ok(())
    }

    /// Writes `raw` (header, body and CRC, valid or not) COBS-encoded and ended by
    /// `0x00`: one frame as the device's [`FrameReader`] will cut it.
    pub fn send_frame(&mut self, raw: &[u8]) -> Result<(), FirmwareError> {
        self.send_bytes(&cobs_frame(raw))
    }

    /// Writes `request` as a frame with this host's schema and sequence number `seq`.
    pub fn send_request(&mut self, seq: u16, request: &Request) -> Result<(), FirmwareError> {
        let frame = request_frame(seq, request).map_err(FirmwareError::Garbled)?;
        self.send_bytes(&frame)
    }

    /// The next frame from the firmware, as cut from the serial output.
    pub fn next_frame(&self, timeout: Duration) -> Result<Incoming, FirmwareError> {
        match self.frames.recv_timeout(timeout) {
            Ok(incoming) => Ok(incoming),
            Err(RecvTimeoutError::Timeout) => Err(FirmwareError::Timeout(timeout)),
            Err(RecvTimeoutError::Disconnected) => Err(FirmwareError::Closed),
        }
    }

    /// The next frame, opened and decoded ([`open_answer`]).
    pub fn next_answer(&self, timeout: Duration) -> Result<Answer, FirmwareError> {
        open_answer(&self.next_frame(timeout)?)
    }

    /// Sends `request` as frame `seq` and returns the next answer, which must carry `seq`
    /// (an error answer is `Ok(Response::Error(..))`).
    pub fn request(
        &mut self,
        seq: u16,
        request: &Request,
        timeout: Duration,
    ) -> Result<Response, FirmwareError> {
        self.send_request(seq, request)?;
        let answer = self.next_answer(timeout)?;
        if answer.seq != seq {
            return Err(FirmwareError::Sequence {
                sent: seq,
                answered: answer.seq,
            });
        }
        Ok(answer.response)
    }

    /// Closes the serial input (QEMU sees end of file; the firmware keeps running).
    pub fn close_input(&mut self) {
        drop(self.serial_in.take());
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

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight_device::{Identity, Session};
    use cuesight_link::Collide;

    /// What the device's session answers to `bytes`, cut into frames as the harness does.
    fn device_answers(bytes: &[u8]) -> Vec<Incoming> {
        let mut device = Session::new(Identity {
            firmware: "test",
            board: "none",
        });
        let mut reader = FrameReader::new();
        let mut host = FrameReader::new();
        let mut out = vec![0u8; MAX_FRAME];
        let mut answers = Vec::new();
        for &byte in bytes {
            if let Some(received) = reader.push(byte) {
                let served = device.serve(received, &mut out);
                for &b in &out[..served.len] {
                    if let Some(r) = host.push(b) {
                        answers.push(Incoming::from_received(r));
                    }
                }
            }
        }
        answers
    }

    #[test]
    fn a_request_frame_is_answered_with_its_seq() {
        let frame = request_frame(7, &Request::Collide(Collide::new(2.0, 30.0))).unwrap();
        let answers = device_answers(&frame);
        assert_eq!(answers.len(), 1);
        let answer = open_answer(&answers[0]).unwrap();
        assert_eq!(answer.seq, 7);
        assert!(matches!(answer.response, Response::Collide(_)));
    }

    #[test]
    fn cobs_frame_carries_any_raw_content() {
        let frame = request_frame(3, &Request::Version(Default::default())).unwrap();
        let mut raw = vec![0u8; MAX_FRAME];
        let len = cobs::decode(&frame[..frame.len() - 1], &mut raw).unwrap();
        assert_eq!(cobs_frame(&raw[..len]), frame);
        // A flipped CRC bit: still a frame, answered with a CRC fault.
        raw[len - 1] ^= 1;
        let answers = device_answers(&cobs_frame(&raw[..len]));
        let answer = open_answer(&answers[0]).unwrap();
        assert!(matches!(
            answer.response,
            Response::Error(LinkError::Frame(FrameFault::Crc { .. }))
        ));
    }
}
