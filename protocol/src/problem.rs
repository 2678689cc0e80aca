//! Everything that can be wrong with a request line, and the `{"error":{...}}` answer
//! that names it.

use core::fmt::{self, Write};

use serde::{Deserialize, Serialize};

use cuesight::aim::AimError;
use cuesight_sensors::{ConfigField, StrokeError};

use crate::answer::ErrorAnswer;
use crate::decimal::Plain;
use crate::json::Syntax;
use crate::names::ModelNames;
use crate::request::Request;

/// Longest name (field, request, board) kept in an answer, in bytes.
pub const NAME_LEN: usize = 32;
/// Longest error message, in bytes.
pub const MESSAGE_LEN: usize = 200;

/// A short name: a field, a request, a board. Longer text is cut at a character
/// boundary.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Name(pub heapless::String<NAME_LEN>);

impl Name {
    /// `text`, cut to [`NAME_LEN`] bytes.
    pub fn of(text: &str) -> Self {
        let mut name = heapless::String::new();
        push_truncated(&mut name, text);
        Self(name)
    }

    /// The text.
    pub fn as_str(&self) -> &str {
        self.0.as_str()
    }
}

impl fmt::Display for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// An error message, cut to [`MESSAGE_LEN`] bytes.
pub type Message = heapless::String<MESSAGE_LEN>;

/// Appends as much of `text` as fits, never splitting a character.
fn push_truncated<const N: usize>(out: &mut heapless::String<N>, text: &str) {
    for c in text.chars() {
        if out.push(c).is_err() {
            break;
        }
    }
}

/// `fmt::Write` into a fixed string that drops what does not fit instead of failing.
struct Truncating<'a, const N: usize>(&'a mut heapless::String<N>);

impl<const N: usize> Write for Truncating<'_, N> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        push_truncated(self.0, s);
        Ok(())
    }
}

/// The class of an error, as on the wire (`"kind"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// The line is not JSON (or is cut short).
    MalformedJson,
    /// The line is longer than [`crate::MAX_LINE`].
    LineTooLong,
    /// Valid JSON, but not an object with exactly one request key.
    NotARequest,
    /// The request name is not one of [`Request::NAMES`].
    UnknownRequest,
    /// A field the request does not have.
    UnknownField,
    /// A field given twice.
    DuplicateField,
    /// A required field is missing.
    MissingField,
    /// A field's value has the wrong JSON type or shape.
    WrongType,
    /// A field's value is of the right type but not an accepted one (unknown model).
    InvalidValue,
    /// Two fields that exclude each other (`spin` and `roll`).
    Conflict,
    /// A number that is NaN or infinite (`null`, or too large for `f32`, e.g. `1e39`).
    NotFinite,
    /// A number outside its accepted range (the message gives the range).
    OutOfRange,
    /// The core produced a non-finite result (a guard, never observed).
    NumericalFailure,
    /// A valid request this device cannot answer.
    Unsupported,
    /// The `stroke` samples hold no usable stroke (no rest, no impact, saturated, ...).
    StrokeRejected,
    /// `shot`: no aim pockets the ball (it is not hit first, cannot reach the pocket,
    /// or the solver did not converge).
    NoAim,
    /// The answer did not fit the answer buffer (a bug: sizes are checked by tests).
    Internal,
}

impl ErrorKind {
    /// The wire name (`malformed_json`, `out_of_range`, ...).
    pub const fn name(self) -> &'static str {
        match self {
            ErrorKind::MalformedJson => "malformed_json",
            ErrorKind::LineTooLong => "line_too_long",
            ErrorKind::NotARequest => "not_a_request",
            ErrorKind::UnknownRequest => "unknown_request",
            ErrorKind::UnknownField => "unknown_field",
            ErrorKind::DuplicateField => "duplicate_field",
            ErrorKind::MissingField => "missing_field",
            ErrorKind::WrongType => "wrong_type",
            ErrorKind::InvalidValue => "invalid_value",
            ErrorKind::Conflict => "conflict",
            ErrorKind::NotFinite => "not_finite",
            ErrorKind::OutOfRange => "out_of_range",
            ErrorKind::NumericalFailure => "numerical_failure",
            ErrorKind::Unsupported => "unsupported",
            ErrorKind::StrokeRejected => "stroke_rejected",
            ErrorKind::NoAim => "no_aim",
            ErrorKind::Internal => "internal",
        }
    }
}

/// Why valid JSON is not a request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NotARequest {
    /// Not a JSON object.
    NotAnObject,
    /// `{}`.
    Empty,
    /// More than one key.
    SeveralKeys,
}

/// A problem with one line.
#[derive(Clone, Debug, PartialEq)]
pub enum Problem {
    /// Not JSON.
    Syntax(Syntax),
    /// Longer than the line buffer.
    LineTooLong {
        /// Bytes received before the newline.
        length: usize,
        /// [`crate::MAX_LINE`].
        limit: usize,
    },
    /// Valid JSON that is not a request object.
    NotARequest(NotARequest),
    /// An unknown request name.
    UnknownRequest(Name),
    /// An unknown field.
    UnknownField {
        /// The request.
        request: &'static str,
        /// The field as given.
        field: Name,
        /// The fields the request has.
        expected: &'static str,
    },
    /// A field given twice.
    DuplicateField(&'static str),
    /// A required field missing.
    MissingField(&'static str),
    /// A value of the wrong type.
    WrongType {
        /// The field.
        field: &'static str,
        /// What it should be.
        expected: &'static str,
    },
    /// A value of the right type that is not accepted.
    InvalidValue {
        /// The field.
        field: &'static str,
        /// What it should be.
        expected: &'static str,
    },
    /// Two fields that exclude each other.
    Conflict {
        /// The field that was refused.
        field: &'static str,
        /// The field it conflicts with.
        with: &'static str,
    },
    /// A model name that is not one of [`crate::ModelName::names`].
    UnknownModel(Name),
    /// More elements than the fixed buffer holds.
    TooMany {
        /// The field.
        field: &'static str,
        /// The capacity.
        limit: usize,
    },
    /// A value the core refused, or its numerical guard.
    Value(cuesight::Error),
    /// The stroke estimator refused the samples or its settings.
    Stroke(StrokeError),
    /// `shot`: the aim solver found no aim (the reason; never `AimError::Invalid`,
    /// which is a [`Problem::Value`]).
    NoAim(AimError),
    /// A request this device cannot answer.
    Unsupported {
        /// The field or request concerned.
        field: &'static str,
        /// Why.
        reason: &'static str,
    },
}

impl From<AimError> for Problem {
    fn from(error: AimError) -> Self {
        match error {
            AimError::Invalid(error) => Problem::Value(error),
            other => Problem::NoAim(other),
        }
    }
}

impl From<cuesight::Error> for Problem {
    fn from(error: cuesight::Error) -> Self {
        Problem::Value(error)
    }
}

impl Problem {
    /// The wire class.
    pub const fn kind(&self) -> ErrorKind {
        match self {
            Problem::Syntax(_) => ErrorKind::MalformedJson,
            Problem::LineTooLong { .. } => ErrorKind::LineTooLong,
            Problem::NotARequest(_) => ErrorKind::NotARequest,
            Problem::UnknownRequest(_) => ErrorKind::UnknownRequest,
            Problem::UnknownField { .. } => ErrorKind::UnknownField,
            Problem::DuplicateField(_) => ErrorKind::DuplicateField,
            Problem::MissingField(_) => ErrorKind::MissingField,
            Problem::WrongType { .. } => ErrorKind::WrongType,
            Problem::InvalidValue { .. } | Problem::UnknownModel(_) => ErrorKind::InvalidValue,
            Problem::Conflict { .. } => ErrorKind::Conflict,
            Problem::TooMany { .. } => ErrorKind::OutOfRange,
            Problem::Value(error) | Problem::Stroke(StrokeError::Strike(error)) => {
                value_kind(error)
            }
            Problem::Unsupported { .. } => ErrorKind::Unsupported,
            Problem::NoAim(_) => ErrorKind::NoAim,
            Problem::Stroke(StrokeError::InvalidConfig(_) | StrokeError::NotFinite { .. }) => {
                ErrorKind::OutOfRange
            }
            Problem::Stroke(_) => ErrorKind::StrokeRejected,
        }
    }

    /// The field (or request name) the problem concerns, if any.
    pub fn field(&self) -> Option<Name> {
        match self {
            Problem::Syntax(_) | Problem::LineTooLong { .. } | Problem::NotARequest(_) => None,
            Problem::UnknownRequest(name) | Problem::UnknownField { field: name, .. } => {
                Some(name.clone())
            }
            Problem::DuplicateField(field)
            | Problem::MissingField(field)
            | Problem::WrongType { field, .. }
            | Problem::InvalidValue { field, .. }
            | Problem::Conflict { field, .. }
            | Problem::TooMany { field, .. }
            | Problem::Unsupported { field, .. } => Some(Name::of(field)),
            Problem::UnknownModel(_) => Some(Name::of("model")),
            Problem::NoAim(_) => Some(Name::of("pocket")),
            Problem::Value(error) => error.field().map(|f| Name::of(f.name())),
            Problem::Stroke(error) => Some(Name::of(stroke_field(error))),
        }
    }

    /// The error answer for this problem.
    pub fn to_answer(&self) -> ErrorAnswer {
        let mut message = Message::new();
        // Truncating never fails.
        let _ = write!(Truncating(&mut message), "{self}");
        ErrorAnswer {
            kind: self.kind(),
            field: self.field(),
            message,
        }
    }
}

/// `a, b, c` from a list of names.
struct List<'a>(&'a [&'a str]);

impl fmt::Display for List<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, name) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str(name)?;
        }
        Ok(())
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Problem::Syntax(syntax) => write!(f, "malformed JSON: {syntax}"),
            Problem::LineTooLong { length, limit } => write!(
                f,
                "line too long: {length} bytes before the newline, the limit is {limit}"
            ),
            Problem::NotARequest(why) => {
                f.write_str("not a request: ")?;
                f.write_str(match why {
                    NotARequest::NotAnObject => "expected a JSON object",
                    NotARequest::Empty => "the object is empty",
                    NotARequest::SeveralKeys => "one request per line, found several keys",
                })?;
                write!(
                    f,
                    " (one of {} as its only key, e.g. {{\"version\":{{}}}})",
                    List(Request::NAMES)
                )
            }
            Problem::UnknownRequest(name) => write!(
                f,
                "unknown request \"{name}\", expected one of {}",
                List(Request::NAMES)
            ),
            Problem::UnknownField {
                request,
                field,
                expected,
            } => write!(
                f,
                "unknown field \"{field}\" in {request}, expected {expected}"
            ),
            Problem::DuplicateField(field) => write!(f, "field \"{field}\" given twice"),
            Problem::MissingField(field) => write!(f, "missing field \"{field}\""),
            Problem::WrongType { field, expected } | Problem::InvalidValue { field, expected } => {
                write!(f, "{field}: expected {expected}")
            }
            Problem::UnknownModel(name) => {
                write!(f, "model: unknown model \"{name}\", expected {ModelNames}")
            }
            Problem::Conflict { field, with } => {
                write!(f, "{field} and {with} cannot both be given")
            }
            Problem::TooMany { field, limit } => {
                write!(f, "{field}: more than {limit}, the buffer's capacity")
            }
            Problem::Value(error) => write_value_error(f, error),
            Problem::Stroke(error) => write_stroke_error(f, error),
            Problem::Unsupported { field, reason } => write!(f, "{field}: {reason}"),
            Problem::NoAim(error) => f.write_str(match error {
                AimError::ObjectBallNotHit => {
                    "no aim: at the ghost-ball aim the cue ball does not reach the object ball first (another ball in the way, or too slow)"
                }
                AimError::PocketUnreachable => {
                    "no aim: the object ball cannot reach the pocket (it stops short, or the cut is too thin)"
                }
                AimError::NotConverged | AimError::Invalid(_) => {
                    "no aim: the solver did not converge (the cut may be too thin)"
                }
            }),
        }
    }
}

/// The class of a value the core refused.
const fn value_kind(error: &cuesight::Error) -> ErrorKind {
    match error {
        cuesight::Error::NotFinite { .. } => ErrorKind::NotFinite,
        cuesight::Error::OutOfRange { .. } => ErrorKind::OutOfRange,
        cuesight::Error::NumericalFailure => ErrorKind::NumericalFailure,
    }
}

/// The request field a stroke error concerns.
fn stroke_field(error: &StrokeError) -> &'static str {
    match error {
        StrokeError::InvalidConfig(ConfigField::SampleRate) => "rate_hz",
        StrokeError::InvalidConfig(ConfigField::FullScale) | StrokeError::NotFinite { .. } => {
            "scale"
        }
        StrokeError::Strike(error) => error.field().map_or("stroke", |f| f.name()),
        _ => "samples",
    }
}

fn write_stroke_error(f: &mut fmt::Formatter<'_>, error: &StrokeError) -> fmt::Result {
    match error {
        StrokeError::InvalidConfig(ConfigField::SampleRate) => {
            f.write_str("rate_hz must be in [500, 100000] Hz")
        }
        StrokeError::InvalidConfig(ConfigField::FullScale) => f.write_str(
            "scale: the full scale, 32768 x |scale|, must exceed the 8 g impact threshold",
        ),
        StrokeError::InvalidConfig(field) => {
            write!(f, "stroke estimator setting out of range: {field:?}")
        }
        StrokeError::NotFinite { .. } => f.write_str("scale must be a finite, non-zero number"),
        StrokeError::TooShort { len, min } => write!(
            f,
            "samples: {len} samples, at least {min} are needed at this rate"
        ),
        StrokeError::NotAtRest => f.write_str(
            "samples: no rest of 150 ms before an impact (start the capture with the cue held still)",
        ),
        StrokeError::NoImpact => {
            f.write_str("samples: no impact (a deceleration of 8 g) after the rest")
        }
        StrokeError::Saturated { index } => write!(
            f,
            "samples: sample {index} reached the sensor's full scale before the impact"
        ),
        StrokeError::NotForward { speed } => write!(
            f,
            "samples: the cue speed at impact integrates to {} m/s, not forward (a negative scale flips the axis)",
            Plain(*speed)
        ),
        StrokeError::LengthMismatch { accel, pitch } => write!(
            f,
            "samples: {accel} accelerometer and {pitch} gyro samples"
        ),
        StrokeError::Strike(error) => write_value_error(f, error),
    }
}

/// The core error's own `Display` text, with the value written by [`Plain`] rather
/// than core's float formatting (which has panic paths; see `decimal.rs`).
fn write_value_error(f: &mut fmt::Formatter<'_>, error: &cuesight::Error) -> fmt::Result {
    match error {
        cuesight::Error::NotFinite { field } => {
            write!(f, "{} must be a finite number", field.name())
        }
        cuesight::Error::OutOfRange { field, value } => write!(
            f,
            "{} = {} is outside {}",
            field.name(),
            Plain(*value),
            field.valid_range()
        ),
        cuesight::Error::NumericalFailure => {
            f.write_str("internal numerical failure (non-finite result)")
        }
    }
}
