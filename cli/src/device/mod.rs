//! `cuesight device`: a console for a cuesight device over the link
//! (`cuesight_link`): it reads requests as JSON, one per line (a person typing, or a
//! session file), sends each as a frame, and prints each answer as a one-line summary
//! ([`text::Summary`]) or as JSON (`--json`).
//!
//! The JSON is the link's own vocabulary: [`cuesight_link::Request`] parsed by
//! serde_json (`{"collide":{"speed":2,"cut":30}}`, `{"version":{}}`, ...;
//! `docs/protocol.md`), the field names of `cuesight collide` and `cuesight shot`.
//!
//! Links ([`transport`]): `--serial PATH [--baud N]`, `--tcp HOST:PORT`, `--qemu [ELF]`
//! (the firmware booted under QEMU's `mps2-an386`, its UART on QEMU's stdio, its defmt
//! log decoded by `defmt-print` and printed on stderr at the end) and `--loopback` (a
//! device in this process).
//!
//! At connect the console sends `version` (frame 0) and compares the device's schema
//! hash with its own: on a mismatch it stops with "device speaks schema X, this host Y"
//! (exit 4). Requests are then numbered 1, 2, ...; the session format is in
//! [`session`].
//!
//! Exit codes ([`EXIT_OK`] ...): 0 every request answered, and no error that was not
//! marked expected; 1 the session failed (unexpected error answers, lines that are no
//! request, unreadable answers: all listed on stderr after the whole session played);
//! 2 usage (options, an unreadable session file, one over 1 MiB, a line over 64 KiB);
//! 3 the link failed (cannot open or connect, no answer in time, the device closed,
//! QEMU failed); 4 the device speaks another schema. The output as every subcommand's
//! ([`crate::cli::output_error`]): a closed stdout ends the session quietly with 0,
//! another write error (a full disk) is `error: writing the output: <cause>` and 1.

pub mod session;
pub mod text;
pub mod transport;

use std::io::{self, BufRead, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use cuesight_link::{Request, Response};

use cuesight_host::firmware::{self, Ended, Firmware};
use session::{play, Console, DeviceError, Reply, Show, Tally};
use text::Summary;
use transport::{Loopback, Qemu, Stream, Transport};

/// Exit code: all answered, no unexpected error.
pub const EXIT_OK: u8 = 0;
/// Exit code: the session failed (unexpected errors, listed).
pub const EXIT_FAILED: u8 = 1;
/// Exit code: a usage error.
pub const EXIT_USAGE: u8 = crate::cli::EXIT_USAGE;
/// Exit code: the link (or the output) failed.
pub const EXIT_LINK: u8 = 3;
/// Exit code: the device speaks another schema.
pub const EXIT_SCHEMA: u8 = 4;

/// The exit code for a console error.
pub fn exit_code(error: &DeviceError) -> u8 {
    match error {
        DeviceError::Schema { .. } => EXIT_SCHEMA,
        DeviceError::Input(_) => EXIT_USAGE,
        DeviceError::Output(e) => crate::cli::output_exit_code(e),
        _ => EXIT_LINK,
    }
}

/// `cuesight device` options.
#[derive(clap::Args, Debug)]
#[command(group(
    clap::ArgGroup::new("link")
        .required(true)
        .args(["serial", "tcp", "qemu", "loopback"])
))]
pub struct Flags {
    /// A serial port (e.g. /dev/ttyACM0), 8N1.
    #[arg(long, value_name = "PATH")]
    pub serial: Option<String>,
    /// The serial port's baud rate [default: 115200].
    #[arg(long, value_name = "N", conflicts_with_all = ["tcp", "qemu", "loopback"])]
    pub baud: Option<u32>,
    /// A TCP socket (e.g. QEMU's -serial tcp::4444,server).
    #[arg(long, value_name = "HOST:PORT")]
    pub tcp: Option<String>,
    /// Boot the firmware under QEMU (mps2-an386) [default ELF: the release build,
    /// or CUESIGHT_FIRMWARE_ELF]; its defmt log follows on stderr.
    #[arg(long, value_name = "ELF", num_args = 0..=1)]
    pub qemu: Option<Option<PathBuf>>,
    /// A device in this process (cuesight-device's Session, as the firmware runs it), to
    /// try the console.
    #[arg(long)]
    pub loopback: bool,
    /// Play this session file (one request per line; `#` headings, `##` comments,
    /// `!expect-error ` before a request whose answer must be an error) instead of
    /// reading stdin.
    #[arg(long, value_name = "FILE")]
    pub session: Option<PathBuf>,
    /// Print each answer as one line of JSON instead of a summary.
    #[arg(long)]
    pub json: bool,
    /// Seconds to wait for each answer.
    #[arg(long, value_name = "SECS", default_value_t = 10.0)]
    pub timeout: f64,
}

/// Writes a line to stderr, ignoring a closed stderr.
fn note(text: std::fmt::Arguments<'_>) {
    let _ = writeln!(io::stderr(), "{text}");
}

/// Runs `cuesight device`.
pub fn main(flags: &Flags) -> ExitCode {
    ExitCode::from(run(flags))
}

/// Runs `cuesight device`; returns the exit code.
pub fn run(flags: &Flags) -> u8 {
    if !(flags.timeout.is_finite() && flags.timeout > 0.0 && flags.timeout <= 86_400.0) {
        note(format_args!(
            "error: --timeout {} is outside (0, 86400] s",
            flags.timeout
        ));
        return EXIT_USAGE;
    }
    let timeout = Duration::from_secs_f64(flags.timeout);
    let stdin = io::stdin();
    let interactive = flags.session.is_none() && stdin.is_terminal();
    let input: Box<dyn BufRead> = match &flags.session {
        // A session file is read whole first, at most 1 MiB; stdin line by line, each
        // line at most 64 KiB (session::MAX_LINE_BYTES).
        Some(path) => match crate::cli::read_input(path) {
            Ok(bytes) => Box::new(io::Cursor::new(bytes)),
            Err(e) => {
                note(format_args!("error: cannot read {}: {e}", path.display()));
                return EXIT_USAGE;
            }
        },
        None => Box::new(stdin.lock()),
    };
    let show = Show {
        json: flags.json,
        echo: !interactive,
        lenient: interactive,
    };
    if interactive {
        note(format_args!(
            "type one request per line, e.g. {{\"collide\":{{\"speed\":2,\"cut\":30}}}} \
             {{\"params\":{{}}}} {{\"version\":{{}}}} {{\"shutdown\":{{}}}} \
             (docs/protocol.md); Ctrl-D ends"
        ));
    }
    let outcome = if let Some(elf) = &flags.qemu {
        let elf = elf.clone().unwrap_or_else(firmware::default_elf);
        let defmt_print = firmware::find_defmt_print();
        let fw = match Firmware::boot(&elf, defmt_print.as_deref()) {
            Ok(fw) => fw,
            Err(e) => {
                note(format_args!(
                    "error: cannot boot {} in QEMU: {e}",
                    elf.display()
                ));
                return EXIT_LINK;
            }
        };
        let mut link = Qemu::new(fw);
        let outcome = converse(&mut link, timeout, input, show, true);
        let ended = link.into_firmware().wait(Duration::from_secs(10));
        print_log(&ended, defmt_print.is_some());
        match (outcome, ended.status) {
            (Ok(_), Some(status)) if !status.success() => {
                note(format_args!("error: QEMU ended with {status}"));
                return EXIT_LINK;
            }
            (outcome, _) => outcome,
        }
    } else if let Some(path) = &flags.serial {
        match Stream::serial(path, flags.baud.unwrap_or(115_200)) {
            Ok(mut link) => converse(&mut link, timeout, input, show, false),
            Err(e) => Err(DeviceError::Transport(e)),
        }
    } else if let Some(address) = &flags.tcp {
        match Stream::tcp(address) {
            Ok(mut link) => converse(&mut link, timeout, input, show, false),
            Err(e) => Err(DeviceError::Transport(e)),
        }
    } else {
        converse(&mut Loopback::new(), timeout, input, show, false)
    };
    match outcome {
        Ok(tally) => verdict(&tally),
        Err(DeviceError::Output(e)) => crate::cli::output_error(&e),
        Err(error) => {
            note(format_args!("error: {error}"));
            exit_code(&error)
        }
    }
}

/// Connects, prints the device, plays `input`; with `shutdown_at_end`, sends `shutdown`
/// if the input did not.
fn converse(
    link: &mut dyn Transport,
    timeout: Duration,
    input: Box<dyn BufRead>,
    show: Show,
    shutdown_at_end: bool,
) -> Result<Tally, DeviceError> {
    let mut console = Console::connect(link, timeout)?;
    for seen in console.take_notes() {
        note(format_args!("note: {seen}"));
    }
    let device = Summary(&Response::Version(console.version().clone())).to_string();
    if show.json {
        note(format_args!("connected: {device}"));
    } else {
        let mut out = io::stdout().lock();
        writeln!(out, "connected: {device}").map_err(DeviceError::Output)?;
    }
    let mut out = io::stdout().lock();
    let mut err = io::stderr().lock();
    let tally = play(&mut console, input, &mut out, &mut err, show)?;
    if shutdown_at_end && !tally.shut_down {
        let reply = console.ask(&Request::Shutdown(Default::default()))?;
        if let Reply::Answer(response) = &reply {
            let _ = writeln!(err, "(end of input: shutdown) {}", Summary(response));
        }
    }
    Ok(tally)
}

/// The exit code of a played session, the unexpected errors listed on stderr.
pub fn verdict(tally: &Tally) -> u8 {
    if tally.passed() {
        return EXIT_OK;
    }
    note(format_args!(
        "error: {} unexpected error(s) in {} request(s):",
        tally.unexpected.len(),
        tally.sent
    ));
    for unexpected in &tally.unexpected {
        note(format_args!(
            "  line {}: {}",
            unexpected.line, unexpected.problem
        ));
    }
    EXIT_FAILED
}

/// The firmware's decoded defmt log, on stderr.
fn print_log(ended: &Ended, decoded: bool) {
    if decoded {
        note(format_args!(
            "== firmware log (defmt, {} lines)",
            ended.log.len()
        ));
        for line in &ended.log {
            note(format_args!("{line}"));
        }
    } else {
        note(format_args!(
            "(no defmt-print: {} bytes of defmt log dropped)",
            ended.log_bytes
        ));
    }
}

#[cfg(test)]
mod tests;
