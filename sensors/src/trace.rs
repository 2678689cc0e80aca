//! IMU traces: the CSV a host streams into the emulated IMU ([`crate::emulated`]), and a
//! `no_std`, allocation-free parser that takes it one byte at a time (as a firmware
//! reads it from a UART).
//!
//! # Format
//!
//! ```text
//! ax,ay,az,gx,gy,gz
//! -290,3,2036,-4,17,9
//! -301,-6,2041,2,11,-3
//! ```
//!
//! * The first line is the header [`HEADER`], exactly.
//! * Then one line per sample, in time order at the trace's output data rate (6667 Hz
//!   unless the player is told otherwise): six decimal integers separated by commas, in
//!   the header's order, each in the `i16` range (an optional `+` or `-`, then digits; no
//!   spaces, no decimal point).
//! * The values are raw LSM6DSOX output words: accelerometer at ±16 g, 0.488 mg/LSB;
//!   gyroscope at ±2000 dps, 70 mdps/LSB ([`crate::lsm6dsox::ACCEL_MPS2_PER_LSB`],
//!   [`crate::lsm6dsox::GYRO_RADPS_PER_LSB`]).
//! * Axes: `x` along the cue, forward (towards the tip) positive; `z` perpendicular to
//!   it in the vertical plane, up (a cue at rest reads `az ≈ +1 g·cos θ`, `ax ≈ −1 g·sin θ`
//!   at elevation θ); `y = z × x`, to the player's left. The pitch rate (positive when the
//!   butt rises) is `gy`.
//! * Lines end with `\n`; a `\r` just before it is dropped. At most [`MAX_LINE_LEN`]
//!   bytes per line, the end excluded. Empty lines are errors (a wrong field count),
//!   so that a line number always names a sample. The last line's `\n` may be missing
//!   ([`TraceParser::finish`] takes that line).
//!
//! # Errors
//!
//! Each [`TraceError`] names its line (1 = the header) and, for a value, its column.
//! The parser reports an error once, at the end of the offending line (at the
//! offending byte for a line that is too long, whose rest is then skipped), and goes
//! on with the next line; until a header has been accepted every line is checked as a
//! header. Sample `n` (0-based, the `impact_sample` of the truth files) is line `n + 2`
//! of a trace with no bad line.

use core::fmt;

/// The header line.
pub const HEADER: &str = "ax,ay,az,gx,gy,gz";

/// Longest line taken (bytes, without the line end). A sample line is at most 41
/// (six `-32768` and five commas); the rest is room for leading zeros and `+`.
pub const MAX_LINE_LEN: usize = 64;

/// The column names, in order.
pub const COLUMNS: [&str; 6] = ["ax", "ay", "az", "gx", "gy", "gz"];

/// One sample: `[ax, ay, az, gx, gy, gz]` in raw LSB (what
/// [`crate::emulated::EmulatedLsm6dsox::latch`] takes).
pub type TraceSample = [i16; 6];

/// A line of a trace that is not what the format says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum TraceError {
    /// The line where the header belongs is not [`HEADER`].
    BadHeader {
        /// 1-based line number.
        line: u32,
    },
    /// A sample line without exactly six fields (`found` saturates at 255).
    FieldCount {
        /// 1-based line number.
        line: u32,
        /// Comma-separated fields on the line.
        found: u8,
    },
    /// A field that is not a decimal integer (empty, a sign alone, any other character).
    NotInteger {
        /// 1-based line number.
        line: u32,
        /// 0-based column, an index into [`COLUMNS`].
        column: u8,
    },
    /// An integer outside `i16` (−32768 ..= 32767).
    OutOfRange {
        /// 1-based line number.
        line: u32,
        /// 0-based column, an index into [`COLUMNS`].
        column: u8,
    },
    /// More than [`MAX_LINE_LEN`] bytes before the line end.
    LineTooLong {
        /// 1-based line number.
        line: u32,
    },
    /// The input ended without a header line.
    MissingHeader,
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = |column: &u8| COLUMNS.get(usize::from(*column)).copied().unwrap_or("?");
        match self {
            TraceError::BadHeader { line } => write!(f, "line {line}: header is not {HEADER}"),
            TraceError::FieldCount { line, found } => {
                write!(f, "line {line}: {found} fields, expected 6 ({HEADER})")
            }
            TraceError::NotInteger { line, column } => {
                write!(f, "line {line}, {}: not an integer", name(column))
            }
            TraceError::OutOfRange { line, column } => write!(
                f,
                "line {line}, {}: outside the i16 range -32768..=32767",
                name(column)
            ),
            TraceError::LineTooLong { line } => {
                write!(f, "line {line}: longer than {MAX_LINE_LEN} bytes")
            }
            TraceError::MissingHeader => write!(f, "no header line ({HEADER})"),
        }
    }
}

impl core::error::Error for TraceError {}

/// Streaming trace parser: [`TraceParser::push`] each byte, [`TraceParser::finish`] at the
/// end of the input. 80 bytes on a 32-bit target (88 on a 64-bit host), no allocation.
#[derive(Clone, Debug)]
pub struct TraceParser {
    /// The line so far, with room for a `\r` after [`MAX_LINE_LEN`] bytes.
    buf: [u8; MAX_LINE_LEN + 1],
    len: usize,
    /// The line being read, 1-based.
    line: u32,
    header_seen: bool,
    /// The current line was too long (already reported): skip to its end.
    skipping: bool,
    samples: u32,
}

impl Default for TraceParser {
    fn default() -> Self {
        Self::new()
    }
}

impl TraceParser {
    /// A parser at the start of a trace.
    pub const fn new() -> Self {
        Self {
            buf: [0; MAX_LINE_LEN + 1],
            len: 0,
            line: 1,
            header_seen: false,
            skipping: false,
            samples: 0,
        }
    }

    /// Take one byte: a sample when it ends a sample line, an error when it ends a bad
    /// line (or overflows one), else nothing.
    pub fn push(&mut self, byte: u8) -> Result<Option<TraceSample>, TraceError> {
        if byte == b'\n' {
            let skipped = core::mem::replace(&mut self.skipping, false);
            let result = if skipped { Ok(None) } else { self.end_line() };
            self.len = 0;
            self.line = self.line.saturating_add(1);
            return result;
        }
        if self.skipping {
            return Ok(None);
        }
        // Past MAX_LINE_LEN only the `\r` of a `\r\n` fits (the last byte of `buf`).
        if self.len > MAX_LINE_LEN || (self.len == MAX_LINE_LEN && byte != b'\r') {
            self.skipping = true;
            return Err(TraceError::LineTooLong { line: self.line });
        }
        self.buf[self.len] = byte;
        self.len += 1;
        Ok(None)
    }

    /// End of input: the last line if it had no `\n`, or [`TraceError::MissingHeader`]
    /// when no header was accepted. The parser is then ready for a new trace.
    pub fn finish(&mut self) -> Result<Option<TraceSample>, TraceError> {
        let result = if self.len > 0 && !self.skipping {
            self.end_line()
        } else {
            Ok(None)
        };
        let header_seen = self.header_seen;
        *self = Self::new();
        match result {
            Ok(None) if !header_seen => Err(TraceError::MissingHeader),
            other => other,
        }
    }

    /// The 1-based number of the line being read.
    pub const fn line(&self) -> u32 {
        self.line
    }

    /// Samples returned so far (the index the next one will have).
    pub const fn samples(&self) -> u32 {
        self.samples
    }

    /// Whether the header has been accepted.
    pub const fn header_seen(&self) -> bool {
        self.header_seen
    }

    fn end_line(&mut self) -> Result<Option<TraceSample>, TraceError> {
        let mut text = &self.buf[..self.len];
        if let [rest @ .., b'\r'] = text {
            text = rest;
        }
        let line = self.line;
        if !self.header_seen {
            if text == HEADER.as_bytes() {
                self.header_seen = true;
                return Ok(None);
            }
            return Err(TraceError::BadHeader { line });
        }
        let found = text.iter().filter(|&&b| b == b',').count() + 1;
        if found != 6 || text.is_empty() {
            let found = if text.is_empty() { 0 } else { found };
            return Err(TraceError::FieldCount {
                line,
                found: found.min(255) as u8,
            });
        }
        let mut sample = [0i16; 6];
        for (column, field) in text.split(|&b| b == b',').enumerate() {
            sample[column] = parse_i16(field).map_err(|e| match e {
                FieldError::NotInteger => TraceError::NotInteger {
                    line,
                    column: column as u8,
                },
                FieldError::OutOfRange => TraceError::OutOfRange {
                    line,
                    column: column as u8,
                },
            })?;
        }
        self.samples = self.samples.saturating_add(1);
        Ok(Some(sample))
    }
}

enum FieldError {
    NotInteger,
    OutOfRange,
}

/// `[+-]?[0-9]+` in the `i16` range.
fn parse_i16(field: &[u8]) -> Result<i16, FieldError> {
    let (negative, digits) = match field {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, field),
    };
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return Err(FieldError::NotInteger);
    }
    // Saturates far above the range, so a long run of digits cannot wrap.
    let magnitude = digits
        .iter()
        .fold(0u32, |m, d| (m * 10 + u32::from(d - b'0')).min(1 << 20));
    let value = if negative {
        -(magnitude as i32)
    } else {
        magnitude as i32
    };
    i16::try_from(value).map_err(|_| FieldError::OutOfRange)
}

/// Parse a whole trace held in memory, calling `on_sample(index, sample)` for each
/// sample; stops at the first error. Returns the number of samples.
pub fn parse_trace(
    bytes: &[u8],
    mut on_sample: impl FnMut(u32, TraceSample),
) -> Result<u32, TraceError> {
    let mut parser = TraceParser::new();
    for &byte in bytes {
        if let Some(sample) = parser.push(byte)? {
            on_sample(parser.samples() - 1, sample);
        }
    }
    let count = parser.samples();
    match parser.finish()? {
        Some(sample) => {
            on_sample(count, sample);
            Ok(count + 1)
        }
        None => Ok(count),
    }
}
