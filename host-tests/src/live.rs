//! The live cue under QEMU (issue 15): an IMU trace played through the firmware's
//! emulated LSM6DSOX, the strokes it reports read back from the link.
//!
//! The firmware reads the trace from [`TRACE_FILE`] in QEMU's working directory
//! (`firmware/src/board/qemu/trace_file.rs`), in the binary form of
//! `firmware/src/live/feed.rs`: the magic `CUE1`, the output data rate (`u16` Hz) and
//! the sample count (`u32`), then each sample's six `i16` words, all little-endian.
//! [`trace_binary`] writes it; [`boot`] makes [`TRACE_FILE`] a named pipe in a fresh
//! directory, streams the trace into it from a thread of its own as the firmware reads
//! (the pipe holds 64 KiB; the firmware's semihosting read waits for the next bytes,
//! which stops QEMU's virtual clock with it), and boots QEMU there with `-icount shift=0,sleep=off`: one instruction per virtual nanosecond (the
//! instruction counts the firmware reports), and no real-time waits (an idle guest jumps
//! to its next timer), so a trace plays as fast as QEMU runs.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};
use std::{fs, io};

use cuesight_link::frame::UNPROMPTED;
use cuesight_link::live::LiveReport;
use cuesight_link::{Empty, Request, Response, ShotRequest};
use cuesight_sensors::trace::{parse_trace, TraceError, TraceSample};

use crate::firmware::{open_answer, qemu_command, Ended, Firmware, FirmwareError};

/// The trace's file name in QEMU's working directory.
pub const TRACE_FILE: &str = "cuesight-imu-trace.bin";

/// Output data rates the firmware samples at (Hz): the LSM6DSOX's 3.33 and 6.66 kHz.
pub const RATES_HZ: [u16; 2] = [3333, 6667];

/// The samples of a CSV trace (`firmware/traces/README.md`); the first bad line's
/// error, which names it.
pub fn csv_samples(csv: &[u8]) -> Result<Vec<TraceSample>, TraceError> {
    let mut samples = Vec::new();
    parse_trace(csv, |_, sample| samples.push(sample))?;
    Ok(samples)
}

/// The binary trace the firmware reads: header, then `samples`.
pub fn trace_binary(samples: &[TraceSample], rate_hz: u16) -> Vec<u8> {
    trace_binary_with_faults(samples, rate_hz, &[])
}

/// Samples `from .. from + count` of a trace delivered with the emulated part's faults
/// (issue 15's bad inputs: a failed bus read, a stalled sensor).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaultWindow {
    /// First sample.
    pub from: usize,
    /// Samples.
    pub count: usize,
    /// Every bus transaction fails.
    pub bus_failing: bool,
    /// The part converts nothing (no data-ready).
    pub stalled: bool,
}

fn header(out: &mut Vec<u8>, magic: &[u8; 4], word: u16, samples: usize) {
    out.extend_from_slice(magic);
    out.extend_from_slice(&word.to_le_bytes());
    out.extend_from_slice(&(samples as u32).to_le_bytes());
}

/// [`trace_binary`] with fault windows (sorted, not overlapping, within the trace; the
/// others are dropped): a `CUEF` segment for each window and one after it with the
/// faults cleared (`firmware/src/live/feed.rs`).
pub fn trace_binary_with_faults(
    samples: &[TraceSample],
    rate_hz: u16,
    windows: &[FaultWindow],
) -> Vec<u8> {
    let mut out = Vec::with_capacity(10 + 12 * samples.len() + 20 * windows.len());
    // (start, faults word) of each segment after the first.
    let mut cuts: Vec<(usize, u16)> = Vec::new();
    for w in windows {
        let end = w.from.saturating_add(w.count);
        let after_last = cuts.last().map_or(0, |&(at, _)| at);
        if w.count == 0 || w.from < after_last || end > samples.len() {
            continue;
        }
        cuts.push((w.from, u16::from(w.bus_failing) | u16::from(w.stalled) << 1));
        cuts.push((end, 0));
    }
    let mut start = 0;
    let mut magic_word = (b"CUE1", rate_hz);
    for (at, faults) in cuts.into_iter().chain([(samples.len(), 0)]) {
        header(&mut out, magic_word.0, magic_word.1, at - start);
        for sample in &samples[start..at] {
            for word in sample {
                out.extend_from_slice(&word.to_le_bytes());
            }
        }
        start = at;
        magic_word = (b"CUEF", faults);
    }
    out
}

/// A directory of its own for one run (removed on drop), with the trace's pipe.
pub struct RunDir {
    path: PathBuf,
    /// The thread writing the trace into [`TRACE_FILE`], once [`Self::stream`] started it.
    writer: Option<std::thread::JoinHandle<io::Result<()>>>,
}

impl RunDir {
    /// A new empty directory under the system's temporary directory.
    pub fn new() -> io::Result<Self> {
        let nanos = SystemTime::now()
            .duration_since(UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0);
        let path =
            std::env::temp_dir().join(format!("cuesight-live-{}-{nanos}", std::process::id()));
        fs::create_dir_all(&path)?;
        Ok(Self { path, writer: None })
    }

    /// Its path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Makes [`TRACE_FILE`] a named pipe and writes `trace` into it from a thread: the
    /// write starts when the firmware opens the pipe at boot, and the pipe's end (the
    /// thread closing it) is the trace's end the firmware reads.
    #[cfg(unix)]
    pub fn stream(&mut self, trace: Vec<u8>) -> io::Result<()> {
        use std::io::Write;
        let fifo = self.path.join(TRACE_FILE);
        make_fifo(&fifo)?;
        self.writer = Some(std::thread::spawn(move || {
            // Opening for writing waits for the reader (the firmware's `SYS_OPEN`).
            let mut pipe = fs::OpenOptions::new().write(true).open(&fifo)?;
            pipe.write_all(&trace)
        }));
        Ok(())
    }

    /// Without named pipes: the trace as a file in the directory.
    #[cfg(not(unix))]
    pub fn stream(&mut self, trace: Vec<u8>) -> io::Result<()> {
        fs::write(self.path.join(TRACE_FILE), trace)
    }
}

/// `mkfifo(path, 0600)`.
#[cfg(unix)]
fn make_fifo(path: &Path) -> io::Result<()> {
    use std::os::unix::ffi::OsStrExt;
    let name = std::ffi::CString::new(path.as_os_str().as_bytes())
        .map_err(|_| io::Error::other("a NUL in the run directory's path"))?;
    // SAFETY: `name` is a NUL-terminated path that lives across the call.
    #[allow(unsafe_code)]
    let status = unsafe { libc::mkfifo(name.as_ptr(), 0o600) };
    if status == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

impl Drop for RunDir {
    fn drop(&mut self) {
        // A writer still waiting for the firmware (which never opened the pipe, or
        // stopped reading) is let go: a non-blocking reader releases its `open`, and
        // closing it makes its writes fail (EPIPE).
        #[cfg(unix)]
        if let Some(writer) = self.writer.take() {
            use std::os::unix::fs::OpenOptionsExt;
            let release = fs::OpenOptions::new()
                .read(true)
                .custom_flags(libc::O_NONBLOCK)
                .open(self.path.join(TRACE_FILE));
            drop(release);
            let _ = writer.join();
        }
        let _ = fs::remove_dir_all(&self.path);
    }
}

/// The QEMU command of a live run: [`qemu_command`] with `-icount shift=0,sleep=off`,
/// in `dir`.
pub fn live_command(elf: &Path, dir: &Path) -> Command {
    let mut qemu = qemu_command(elf);
    qemu.args(["-icount", "shift=0,sleep=off"]).current_dir(dir);
    qemu
}

/// Streams `binary` (from [`trace_binary`]) as the trace through a named pipe in a new
/// run directory and boots `elf` there. Keep the directory until the firmware has
/// exited.
pub fn boot(
    elf: &Path,
    defmt_print: Option<&Path>,
    binary: &[u8],
) -> Result<(Firmware, RunDir), FirmwareError> {
    // QEMU runs in the run directory: the ELF's path must not be relative.
    let elf = &elf.canonicalize()?;
    let mut dir = RunDir::new()?;
    dir.stream(binary.to_vec())?;
    let firmware = Firmware::boot_command(elf, defmt_print, live_command(elf, dir.path()))?;
    Ok((firmware, dir))
}

/// What a trace played through the firmware gave.
pub struct Played {
    /// The answer to `plan`, when one was sent.
    pub plan: Option<Response>,
    /// Every live report, in order (the last is the trace's end).
    pub reports: Vec<LiveReport>,
    /// How QEMU ended (after the `shutdown` that follows the trace's end).
    pub ended: Ended,
}

/// Plays `binary` through `elf`: boots it, sets `plan` if given, then says `version`
/// (the firmware starts its emulated IMU on the host's first request, so a plan set
/// first holds from the first stroke), collects the unprompted live reports until the
/// trace's end, and shuts the firmware down. Fails on a frame that cannot be read, an
/// answer out of turn, or no frame within `timeout`.
pub fn play(
    elf: &Path,
    defmt_print: Option<&Path>,
    binary: &[u8],
    plan: Option<&ShotRequest>,
    timeout: Duration,
) -> Result<Played, FirmwareError> {
    let (mut firmware, dir) = boot(elf, defmt_print, binary)?;
    let deadline = Instant::now() + timeout;
    let left = || deadline.saturating_duration_since(Instant::now());
    let hello = firmware.next_answer(left())?;
    if !matches!(hello.response, Response::Version(_)) {
        return Err(FirmwareError::Sequence {
            sent: UNPROMPTED,
            answered: hello.seq,
        });
    }
    let mut seq = 0;
    let mut plan_answer = None;
    let mut reports = Vec::new();
    let mut ask = |firmware: &mut Firmware, request: &Request, reports: &mut Vec<LiveReport>| {
        let sent = seq;
        seq += 1;
        firmware.send_request(sent, request)?;
        loop {
            let answer = open_answer(&firmware.next_frame(left())?)?;
            match (answer.seq, answer.response) {
                (UNPROMPTED, Response::Live(report)) => reports.push(report),
                (answered, response) if answered == sent => return Ok(response),
                (answered, _) => return Err(FirmwareError::Sequence { sent, answered }),
            }
        }
    };
    if let Some(plan) = plan {
        plan_answer = Some(ask(
            &mut firmware,
            &Request::Plan(Some(plan.clone())),
            &mut reports,
        )?);
    }
    ask(&mut firmware, &Request::Version(Empty {}), &mut reports)?;
    while !matches!(reports.last(), Some(LiveReport::TraceEnd(_))) {
        match open_answer(&firmware.next_frame(left())?)? {
            answer if answer.seq == UNPROMPTED => match answer.response {
                Response::Live(report) => reports.push(report),
                _ => {
                    return Err(FirmwareError::Sequence {
                        sent: UNPROMPTED,
                        answered: answer.seq,
                    })
                }
            },
            answer => {
                return Err(FirmwareError::Sequence {
                    sent: UNPROMPTED,
                    answered: answer.seq,
                })
            }
        }
    }
    ask(&mut firmware, &Request::Shutdown(Empty {}), &mut reports)?;
    let ended = firmware.wait(left().max(Duration::from_secs(5)));
    drop(dir);
    Ok(Played {
        plan: plan_answer,
        reports,
        ended,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_binary_trace_has_the_header_and_every_word_little_endian() {
        let binary = trace_binary(&[[1, -2, 3, -4, 5, -32768], [32767, 0, 0, 0, 0, 0]], 6667);
        assert_eq!(&binary[..4], b"CUE1");
        assert_eq!(u16::from_le_bytes([binary[4], binary[5]]), 6667);
        assert_eq!(
            u32::from_le_bytes([binary[6], binary[7], binary[8], binary[9]]),
            2
        );
        assert_eq!(binary.len(), 10 + 24);
        assert_eq!(&binary[10..12], &[1, 0]);
        assert_eq!(&binary[12..14], &(-2i16).to_le_bytes());
        assert_eq!(&binary[20..22], &[0x00, 0x80]);
        assert_eq!(&binary[22..24], &[0xFF, 0x7F]);
    }

    #[test]
    fn a_fault_window_is_a_segment_of_its_own_and_one_after_it() {
        let samples = [[7i16; 6]; 10];
        let window = FaultWindow {
            from: 3,
            count: 4,
            bus_failing: false,
            stalled: true,
        };
        let binary = trace_binary_with_faults(&samples, 3333, &[window]);
        assert_eq!(binary.len(), 3 * 10 + 10 * 12);
        let at = |i: usize| &binary[i..i + 10];
        assert_eq!(
            at(0),
            [
                b"CUE1".as_slice(),
                &3333u16.to_le_bytes(),
                &3u32.to_le_bytes()
            ]
            .concat()
        );
        assert_eq!(
            at(10 + 36),
            [b"CUEF".as_slice(), &2u16.to_le_bytes(), &4u32.to_le_bytes()].concat()
        );
        assert_eq!(
            at(2 * 10 + 84),
            [b"CUEF".as_slice(), &0u16.to_le_bytes(), &3u32.to_le_bytes()].concat()
        );
        // A window past the end, or overlapping an earlier one, is dropped.
        let past = FaultWindow {
            from: 8,
            count: 5,
            ..window
        };
        assert_eq!(
            trace_binary_with_faults(&samples, 3333, &[past]),
            trace_binary(&samples, 3333)
        );
    }

    #[test]
    fn a_bad_csv_line_is_named() {
        let error = csv_samples(b"ax,ay,az,gx,gy,gz\n1,2,3,4,5,6\n1,2,x,4,5,6\n").unwrap_err();
        assert!(error.to_string().contains("line 3"), "{error}");
    }
}
