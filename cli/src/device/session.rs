//! The console's session: connect (schema check), then requests read as JSON lines,
//! sent as frames numbered from 0, and each answer printed.
//!
//! Session files (`--session FILE`, `firmware/demo/session.jsonl`), one item per line:
//!
//! * a request in JSON, the link's vocabulary (`{"collide":{"speed":2,"cut":30}}`);
//! * `!expect-error ` and a request: an error answer is expected (the line shows one);
//!   any other answer is then a failure;
//! * `# heading`: printed (as `== heading`);
//! * `## comment`: not printed;
//! * a blank line: skipped.
//!
//! A line that is no request of the schema (bad JSON, an unknown field, a `NaN`) is
//! reported here with serde_json's message and its line number, and not sent. Every
//! error (an error answer, an unreadable answer, or a line not sent) on a line not marked
//! `!expect-error` is *unexpected*: the session plays on to its end and then fails,
//! listing them ([`Tally::unexpected`]).

use std::fmt;
use std::io::{self, BufRead, Read, Write};
use std::time::{Duration, Instant};

use cuesight_link::frame::MAX_FRAME;
use cuesight_link::{frame, LinkError, Request, Response, VersionAnswer, SCHEMA_HASH, UNPROMPTED};

use super::text::{Schema, Summary, Unreadable};
use super::transport::{Transport, TransportError};
use cuesight_host::firmware::{open_answer, FirmwareError};

/// The marker of a request whose answer must be an error.
pub const EXPECT_ERROR: &str = "!expect-error ";

/// Why the console stopped.
#[derive(Debug)]
pub enum DeviceError {
    /// The transport failed: I/O, no answer in time, closed.
    Transport(TransportError),
    /// The device speaks another schema.
    Schema {
        /// The device's hash.
        device: u32,
    },
    /// The device's `version` answer was not a `version` (at connect).
    Handshake(String),
    /// The session file or stdin could not be read.
    Input(io::Error),
    /// The output could not be written (a closed pipe).
    Output(io::Error),
}

impl fmt::Display for DeviceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DeviceError::Transport(e) => write!(f, "link: {e}"),
            DeviceError::Schema { device } => write!(
                f,
                "device speaks schema {}, this host {}",
                Schema(*device),
                Schema(SCHEMA_HASH)
            ),
            DeviceError::Handshake(what) => write!(f, "connect: {what}"),
            DeviceError::Input(e) => write!(f, "reading the requests: {e}"),
            DeviceError::Output(e) => write!(f, "writing the answers: {e}"),
        }
    }
}

impl std::error::Error for DeviceError {}

impl From<TransportError> for DeviceError {
    fn from(e: TransportError) -> Self {
        DeviceError::Transport(e)
    }
}

/// What came back for one request.
#[derive(Clone, Debug, PartialEq)]
// One per request, never stored in bulk: as the link's own `Response`, not boxed.
#[allow(clippy::large_enum_variant)]
pub enum Reply {
    /// The device's answer (an error answer too).
    Answer(Response),
    /// A frame that could not be read in its place (COBS, CRC, body).
    Garbled(LinkError),
}

/// A connected device: the frame count and the answer to the `version` sent at connect.
/// `T` is a [`Transport`], or `&mut` one to keep it after the session.
pub struct Console<T> {
    link: T,
    next_seq: u16,
    timeout: Duration,
    deadline: Option<Instant>,
    version: VersionAnswer,
    notes: Vec<String>,
}

impl<T: Transport> Console<T> {
    /// Sends `version` as frame 0 and checks the schema of what comes back: the frame's
    /// header, the device's own hash in the answer, or its `schema_mismatch` refusal.
    /// An unprompted `version` (the device's hello at boot) is checked and skipped.
    pub fn connect(link: T, timeout: Duration) -> Result<Self, DeviceError> {
        let mut console = Self {
            link,
            next_seq: 0,
            timeout,
            deadline: None,
            version: VersionAnswer {
                schema: 0,
                firmware: heapless::String::new(),
                board: heapless::String::new(),
                max_frame: 0,
                max_samples: 0,
                stroke_capacity: 0,
                shot: false,
            },
            notes: Vec::new(),
        };
        // A leading zero ends any partial frame the device holds (it skips empty ones).
        console.link.send(&[0])?;
        // Unnumbered errors are the device's answer to whatever it held before the
        // zero, not to this `version`: skipped.
        match console.exchange(&Request::Version(Default::default()), false)? {
            Reply::Answer(Response::Version(version)) if version.schema == SCHEMA_HASH => {
                console.version = version;
                Ok(console)
            }
            Reply::Answer(Response::Version(version)) => Err(DeviceError::Schema {
                device: version.schema,
            }),
            Reply::Answer(Response::Error(LinkError::SchemaMismatch { device, .. })) => {
                Err(DeviceError::Schema { device })
            }
            Reply::Answer(other) => Err(DeviceError::Handshake(format!(
                "the device answered version with {}",
                Summary(&other)
            ))),
            Reply::Garbled(error) => Err(DeviceError::Handshake(format!(
                "unreadable answer to version: {error:?}"
            ))),
        }
    }

    /// The device's answer to the `version` at connect.
    pub fn version(&self) -> &VersionAnswer {
        &self.version
    }

    /// No answer is awaited past `deadline` (a whole session's limit), whatever the
    /// timeout per answer.
    pub fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
    }

    /// The sequence number the next request goes out with.
    pub fn next_seq(&self) -> u16 {
        self.next_seq
    }

    /// Things seen on the link that answered nothing (a restart, a stray frame), taken.
    pub fn take_notes(&mut self) -> Vec<String> {
        std::mem::take(&mut self.notes)
    }

    /// The transport back.
    pub fn into_inner(self) -> T {
        self.link
    }

    /// Sends `request` as the next frame and waits for the answer carrying its number.
    /// An error answer the device sent without a number (it could not read the frame's
    /// header) is taken as this request's; an unprompted `version` (a restart) and
    /// answers to other numbers are noted and skipped.
    pub fn ask(&mut self, request: &Request) -> Result<Reply, DeviceError> {
        self.exchange(request, true)
    }

    /// [`Console::ask`]; `adopt` takes an unnumbered error answer as the request's.
    fn exchange(&mut self, request: &Request, adopt: bool) -> Result<Reply, DeviceError> {
        let seq = self.next_seq;
        let mut wire = [0u8; MAX_FRAME];
        let len = match frame::encode(SCHEMA_HASH, seq, request, &mut wire) {
            Ok(len) => len,
            // Too large for a frame: nothing sent, the number stays free.
            Err(error) => return Ok(Reply::Garbled(error)),
        };
        self.link.send(&wire[..len])?;
        self.next_seq = cuesight_link::next_seq(seq);
        let per_answer = Instant::now() + self.timeout;
        let deadline = self.deadline.map_or(per_answer, |d| d.min(per_answer));
        let waited = deadline.saturating_duration_since(Instant::now());
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let incoming = match self.link.next_frame(left) {
                Err(TransportError::Timeout(_)) => {
                    return Err(TransportError::Timeout(waited).into())
                }
                other => other?,
            };
            let answer = match open_answer(&incoming) {
                Ok(answer) => answer,
                Err(FirmwareError::Schema(device)) => return Err(DeviceError::Schema { device }),
                Err(FirmwareError::Garbled(error)) => return Ok(Reply::Garbled(error)),
                Err(other) => return Err(DeviceError::Handshake(other.to_string())),
            };
            match answer.response {
                response if answer.seq == seq => return Ok(Reply::Answer(response)),
                Response::Version(version) if answer.seq == UNPROMPTED => {
                    if version.schema != SCHEMA_HASH {
                        return Err(DeviceError::Schema {
                            device: version.schema,
                        });
                    }
                    if seq != 0 {
                        self.notes.push(format!(
                            "the device (re)started: {}",
                            Summary(&Response::Version(version))
                        ));
                    }
                }
                Response::Error(error) if answer.seq == UNPROMPTED && adopt => {
                    return Ok(Reply::Answer(Response::Error(error)))
                }
                other => self.notes.push(format!(
                    "skipped an answer to frame {} while waiting for {seq}: {}",
                    answer.seq,
                    Summary(&other)
                )),
            }
        }
    }
}

/// One line of a session.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Line<'a> {
    /// Blank or a `##` comment.
    Skip,
    /// A `#` heading.
    Heading(&'a str),
    /// A request (its JSON text), and whether an error answer is expected.
    Request {
        /// The JSON.
        json: &'a str,
        /// Marked `!expect-error`.
        expect_error: bool,
    },
}

/// Reads one line of a session file.
pub fn parse_line(line: &str) -> Line<'_> {
    let line = line.trim();
    if line.is_empty() || line.starts_with("##") {
        Line::Skip
    } else if let Some(heading) = line.strip_prefix('#') {
        Line::Heading(heading.trim())
    } else if let Some(json) = line.strip_prefix(EXPECT_ERROR.trim_end()) {
        Line::Request {
            json: json.trim(),
            expect_error: true,
        }
    } else {
        Line::Request {
            json: line,
            expect_error: false,
        }
    }
}

/// How a session is shown.
#[derive(Clone, Copy, Debug, Default)]
pub struct Show {
    /// Print each answer as one line of JSON (the link's, externally tagged) instead of
    /// the request and a summary; headings and notes then go to stderr.
    pub json: bool,
    /// Print each request line before its answer (`> ...`).
    pub echo: bool,
    /// Error answers are shown but never make the session fail (a person typing).
    pub lenient: bool,
}

/// An error where none was expected (or none where one was).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unexpected {
    /// Line number in the input (from 1).
    pub line: usize,
    /// What happened.
    pub problem: String,
}

/// What a played session did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Requests sent.
    pub sent: usize,
    /// Error answers (and lines not sent) that were marked as expected.
    pub expected_errors: usize,
    /// Everything that makes the session fail.
    pub unexpected: Vec<Unexpected>,
    /// Whether a `shutdown` was answered (the device has stopped; later lines are not
    /// played).
    pub shut_down: bool,
}

impl Tally {
    /// Whether the session passed.
    pub fn passed(&self) -> bool {
        self.unexpected.is_empty()
    }
}

/// `line`, cut to about two terminal lines.
pub fn shorten(line: &str) -> String {
    const SHOWN: usize = 150;
    match line.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!("{}... ({} bytes)", &line[..cut], line.len()),
        None => line.to_owned(),
    }
}

/// The longest line the console reads, its end not counted: 64 KiB (a request that
/// fits a frame is under a few KiB of JSON).
pub const MAX_LINE_BYTES: usize = 64 << 10;

/// The lines of `input` as [`BufRead::lines`] gives them (without `\n` or `\r\n`), but
/// none longer than [`MAX_LINE_BYTES`]: a longer one (or bytes without end and without a
/// newline, `/dev/zero`) is an [`io::ErrorKind::InvalidData`] error naming the line and
/// the bound, after reading no more than the bound and two bytes.
pub fn bounded_lines(input: impl BufRead) -> impl Iterator<Item = io::Result<String>> {
    let mut input = input;
    let mut buf = Vec::new();
    let mut number = 0usize;
    let mut failed = false;
    std::iter::from_fn(move || {
        if failed {
            return None;
        }
        buf.clear();
        number += 1;
        let limit = MAX_LINE_BYTES as u64 + 2;
        let line = match (&mut input).take(limit).read_until(b'\n', &mut buf) {
            Ok(0) => return None,
            Ok(_) => {
                if buf.last() == Some(&b'\n') {
                    buf.pop();
                    if buf.last() == Some(&b'\r') {
                        buf.pop();
                    }
                }
                if buf.len() > MAX_LINE_BYTES {
                    Err(io::Error::new(
                        io::ErrorKind::InvalidData,
                        format!(
                            "line {number} is longer than {MAX_LINE_BYTES} bytes (64 KiB), refused"
                        ),
                    ))
                } else {
                    String::from_utf8(std::mem::take(&mut buf)).map_err(|_| {
                        io::Error::new(
                            io::ErrorKind::InvalidData,
                            "stream did not contain valid UTF-8",
                        )
                    })
                }
            }
            Err(e) => Err(e),
        };
        failed = line.is_err();
        Some(line)
    })
}

/// Writes a line to `out`, a closed pipe being an [`DeviceError::Output`].
fn put(out: &mut dyn Write, text: fmt::Arguments<'_>) -> Result<(), DeviceError> {
    out.write_fmt(text)
        .and_then(|()| out.write_all(b"\n"))
        .map_err(DeviceError::Output)
}

/// Plays `input` (session lines) through `console`, writing to `out` (answers) and
/// `notes` (headings and local errors in JSON mode, link notes). Stops after a
/// `shutdown` answer or at the end of the input; the caller decides what a session
/// without a `shutdown` means.
pub fn play<T: Transport>(
    console: &mut Console<T>,
    input: impl BufRead,
    out: &mut dyn Write,
    notes: &mut dyn Write,
    show: Show,
) -> Result<Tally, DeviceError> {
    let mut tally = Tally::default();
    for (index, line) in bounded_lines(input).enumerate() {
        let number = index + 1;
        let line = line.map_err(DeviceError::Input)?;
        if tally.shut_down {
            if let Line::Request { .. } = parse_line(&line) {
                put(
                    notes,
                    format_args!("line {number}: not sent, the device has shut down"),
                )?;
                tally.unexpected.push(Unexpected {
                    line: number,
                    problem: "a request after shutdown".to_owned(),
                });
            }
            continue;
        }
        let (json, expect_error) = match parse_line(&line) {
            Line::Skip => continue,
            Line::Heading(heading) => {
                let to: &mut dyn Write = if show.json { &mut *notes } else { &mut *out };
                put(to, format_args!("\n== {heading}"))?;
                continue;
            }
            Line::Request { json, expect_error } => (json, expect_error),
        };
        if show.echo && !show.json {
            let mark = if expect_error {
                "(error expected) "
            } else {
                ""
            };
            put(out, format_args!("> {mark}{}", shorten(json)))?;
        }
        let request: Request = match serde_json::from_str(json) {
            Ok(request) => request,
            Err(error) => {
                let to: &mut dyn Write = if show.json { &mut *notes } else { &mut *out };
                put(
                    to,
                    format_args!("! line {number}: not a request, not sent: {error}"),
                )?;
                if expect_error {
                    tally.expected_errors += 1;
                } else if !show.lenient {
                    tally.unexpected.push(Unexpected {
                        line: number,
                        problem: format!("not a request: {error}"),
                    });
                }
                continue;
            }
        };
        let reply = console.ask(&request)?;
        tally.sent += 1;
        for note in console.take_notes() {
            put(notes, format_args!("note: {note}"))?;
        }
        match &reply {
            Reply::Answer(response) => {
                if show.json {
                    let text = serde_json::to_string(response)
                        .unwrap_or_else(|e| format!("{{\"unprintable\":\"{e}\"}}"));
                    put(out, format_args!("{text}"))?;
                } else {
                    put(out, format_args!("< {}", Summary(response)))?;
                }
                tally.shut_down = matches!(response, Response::Shutdown(_));
            }
            Reply::Garbled(error) => {
                let text = Unreadable(error);
                put(notes, format_args!("line {number}: {text}"))?;
                if !show.json {
                    put(out, format_args!("< ({text})"))?;
                }
            }
        }
        let problem = match &reply {
            // Never the error a line expects: the device's answer is unknown.
            Reply::Garbled(error) => Some(Unreadable(error).to_string()),
            Reply::Answer(response) => {
                match (expect_error, matches!(response, Response::Error(_))) {
                    (true, true) => {
                        tally.expected_errors += 1;
                        None
                    }
                    (true, false) => Some(format!(
                        "an error was expected, the answer was: {}",
                        Summary(response)
                    )),
                    (false, true) => Some(Summary(response).to_string()),
                    (false, false) => None,
                }
            }
        };
        if let Some(problem) = problem {
            if !show.lenient {
                tally.unexpected.push(Unexpected {
                    line: number,
                    problem,
                });
            }
        }
    }
    Ok(tally)
}
