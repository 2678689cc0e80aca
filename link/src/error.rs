//! Typed errors: everything the device can refuse, as data. The device never formats
//! text; the host console turns these into sentences (`cuesight device`), as defmt does
//! for logs. [`LinkError`] also implements `Display` (a short line, its parts in their
//! `Debug` form) and `core::error::Error`, for host programs that use the codec with
//! `?`; the firmware never calls them, so they are not in its image.

use core::fmt;

use cuesight::aim::AimError;
use cuesight_sensors::{GlitchKind, StrokeError};
use serde::{Deserialize, Serialize};

/// Why a request got no answer but this one.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum LinkError {
    /// The frame itself could not be read.
    Frame(FrameFault),
    /// The frame's schema hash is not the device's: the two ends were built from
    /// different schemas. Nothing in the frame was read.
    SchemaMismatch {
        /// The device's schema hash ([`crate::SCHEMA_HASH`] of its build).
        device: u32,
        /// The hash the frame carried.
        host: u32,
    },
    /// The frame is out of sequence (see [`SequenceFault`]); it was not acted on.
    Sequence(SequenceFault),
    /// An input value is refused by the core (the field and the value).
    Invalid(cuesight::Error),
    /// `spin` and `roll` were both given.
    SpinAndRoll,
    /// `shot`: neither `aim` nor `pocket`.
    MissingAim,
    /// A valid request this device does not serve.
    Unsupported(Unsupported),
    /// `shot`: no aim pockets the ball.
    NoAim(NoAim),
    /// The stroke's samples hold no usable stroke, or the strike model refused the
    /// estimate (the estimator's own error; sample indices count from the stroke's first
    /// sample, all chunks).
    Stroke(StrokeError),
    /// A stroke chunk that breaks the upload (the stroke in progress is dropped).
    Upload(UploadFault),
    /// The answer did not fit a frame (a bug: sizes are tested).
    AnswerTooLarge,
}

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinkError::Frame(fault) => write!(f, "unreadable frame: {fault:?}"),
            LinkError::SchemaMismatch { device, host } => write!(
                f,
                "schema mismatch: device {device:#010x}, host {host:#010x}"
            ),
            LinkError::Sequence(fault) => write!(f, "frame out of sequence: {fault:?}"),
            LinkError::Invalid(error) => write!(f, "{error}"),
            LinkError::SpinAndRoll => f.write_str("spin and roll were both given"),
            LinkError::MissingAim => f.write_str("shot: neither aim nor pocket given"),
            LinkError::Unsupported(what) => write!(f, "unsupported: {what:?}"),
            LinkError::NoAim(why) => write!(f, "no aim: {why:?}"),
            LinkError::Stroke(why) => write!(f, "stroke rejected: {why}"),
            LinkError::Upload(fault) => write!(f, "stroke upload dropped: {fault:?}"),
            LinkError::AnswerTooLarge => f.write_str("the answer did not fit a frame"),
        }
    }
}

/// The message of [`LinkError::Invalid`] is the core error's, so no `source` is
/// reported separately.
///
/// ```
/// use cuesight_link::frame;
///
/// fn read(raw: &[u8]) -> Result<u16, Box<dyn std::error::Error>> {
///     let (header, _body) = frame::open(raw)?;
///     Ok(header.seq)
/// }
///
/// let error = read(&[1, 2, 3]).unwrap_err();
/// assert_eq!(error.to_string(), "unreadable frame: Short { length: 3 }");
/// ```
impl core::error::Error for LinkError {}

/// What is wrong with a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum FrameFault {
    /// Not valid COBS: a zero byte cut a block short (bytes lost).
    Cobs,
    /// Longer than [`crate::frame::MAX_FRAME`]; skipped to its end.
    Oversized {
        /// Encoded bytes received before its zero.
        length: u32,
    },
    /// Shorter than a header and a CRC.
    Short {
        /// Raw bytes.
        length: u16,
    },
    /// The CRC does not match: bytes were changed on the way.
    Crc {
        /// The sequence number as read (not to be trusted).
        seq_as_read: u16,
    },
    /// The body is not a message of the schema.
    Undecodable,
    /// The body is a message, with bytes left over.
    TrailingBytes {
        /// How many.
        count: u16,
    },
}

/// A frame out of sequence. The host numbers its frames 0, 1, 2, ... (wrapping); the
/// first frame after boot, and any `version` request, may carry any number and starts
/// the count again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum SequenceFault {
    /// The same number as the frame before: sent twice.
    Duplicate {
        /// The number.
        seq: u16,
    },
    /// Older than the frame before: reordered or replayed.
    Stale {
        /// The frame's number.
        seq: u16,
        /// The number expected.
        expected: u16,
    },
    /// Newer than expected: frames in between were lost.
    Gap {
        /// The frame's number.
        seq: u16,
        /// The number expected.
        expected: u16,
    },
}

/// A request this device does not serve.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum Unsupported {
    /// `model: reference` runs on the host only.
    ReferenceModel,
    /// `shot`: the image was built without `cuesight-device`'s `shot` feature.
    Shot,
    /// `stroke`: the image was built without `cuesight-device`'s `upload` feature (the
    /// live cue's image: its IMU measures the strokes itself).
    Upload,
}

/// Why no aim pockets the ball (`cuesight::aim::AimError`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum NoAim {
    /// At the ghost-ball aim the cue ball does not hit the object ball first.
    ObjectBallNotHit,
    /// The object ball stops, or passes the mouth, before the pocket.
    PocketUnreachable,
    /// The solver did not converge (e.g. the cut is too thin).
    NotConverged,
}

impl From<AimError> for LinkError {
    fn from(error: AimError) -> Self {
        match error {
            AimError::Invalid(error) => LinkError::Invalid(error),
            AimError::ObjectBallNotHit => LinkError::NoAim(NoAim::ObjectBallNotHit),
            AimError::PocketUnreachable => LinkError::NoAim(NoAim::PocketUnreachable),
            AimError::NotConverged => LinkError::NoAim(NoAim::NotConverged),
        }
    }
}

impl From<cuesight::Error> for LinkError {
    fn from(error: cuesight::Error) -> Self {
        LinkError::Invalid(error)
    }
}

impl From<StrokeError> for LinkError {
    fn from(error: StrokeError) -> Self {
        LinkError::Stroke(error)
    }
}

/// A stroke chunk that breaks the upload. The stroke in progress is dropped: nothing
/// half-uploaded is ever estimated. `stroke` is the chunk's stroke id, `chunk` its index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum UploadFault {
    /// A chunk after the first, but its stroke's first chunk was not received (or the
    /// upload was dropped by an earlier error).
    NotStarted {
        /// Stroke id.
        stroke: u16,
        /// Chunk index.
        chunk: u16,
    },
    /// A chunk ahead of the next expected one: chunks in between are missing (lost or
    /// reordered).
    Missing {
        /// Stroke id.
        stroke: u16,
        /// The chunk expected.
        expected: u16,
        /// The chunk received.
        chunk: u16,
    },
    /// A chunk already received.
    Duplicate {
        /// Stroke id.
        stroke: u16,
        /// Chunk index.
        chunk: u16,
    },
    /// The chunk count differs from the stroke's first chunk.
    CountChanged {
        /// Stroke id.
        stroke: u16,
        /// Count in this chunk.
        count: u16,
        /// Count in the first chunk.
        expected: u16,
    },
    /// A chunk count of 0, above [`crate::limits::MAX_CHUNKS`], or an index not below it.
    BadChunk {
        /// Chunk index.
        chunk: u16,
        /// Chunk count.
        count: u16,
    },
    /// A chunk with no samples.
    Empty {
        /// Stroke id.
        stroke: u16,
        /// Chunk index.
        chunk: u16,
    },
    /// The stroke holds more than [`crate::STROKE_CAPACITY`] samples with this chunk.
    Overflow {
        /// Stroke id.
        stroke: u16,
        /// Chunk index.
        chunk: u16,
    },
    /// The last chunk carries no `setup` (the sample rate is needed).
    NoSetup {
        /// Stroke id.
        stroke: u16,
    },
    /// A sample before the impact at the sensor's rail, or a single-sample spike
    /// (`cuesight_sensors::find_glitch`).
    Glitch {
        /// Stroke id.
        stroke: u16,
        /// The chunk holding it.
        chunk: u16,
        /// Its index in that chunk.
        sample: u16,
        /// Rail or spike.
        kind: GlitchKind,
        /// Its raw value.
        value: i16,
    },
}
