//! Everything that can be wrong with a request line, and the `{"error":{...}}` answer
//! that names it.

use core::fmt;

use serde::{Deserialize, Serialize};

use cuesight::aim::AimError;
use cuesight_sensors::{ConfigField, StrokeError};

use crate::answer::ErrorAnswer;
use crate::decimal::plain;
use crate::json::Syntax;
use crate::names::model_names;
use crate::request::Request;
use crate::text::{list, push_truncated, unsigned, Fmt, Sink};

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
        self.write_message(&mut message);
        ErrorAnswer {
            kind: self.kind(),
            field: self.field(),
            message,
        }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Fmt::write(f, |out| self.write_message(out))
    }
}

impl Problem {
    /// The one-line message (the answer's `message`, cut to [`MESSAGE_LEN`]; the
    /// `Display` text), built piece by piece: no `core::fmt` on the device.
    pub(crate) fn write_message(&self, f: &mut dyn Sink) {
        match self {
            Problem::Syntax(syntax) => {
                f.put("malformed JSON: ");
                syntax.write_message(f);
            }
            Problem::LineTooLong { length, limit } => {
                f.put("line too long: ");
                unsigned(f, *length);
                f.put(" bytes before the newline, the limit is ");
                unsigned(f, *limit);
            }
            Problem::NotARequest(why) => {
                f.put("not a request: ");
                f.put(match why {
                    NotARequest::NotAnObject => "expected a JSON object",
                    NotARequest::Empty => "the object is empty",
                    NotARequest::SeveralKeys => "one request per line, found several keys",
                });
                f.put(" (one of ");
                list(f, Request::NAMES.iter().copied(), ", ");
                f.put(" as its only key, e.g. {\"version\":{}})");
            }
            Problem::UnknownRequest(name) => {
                f.put("unknown request \"");
                f.put(name.as_str());
                f.put("\", expected one of ");
                list(f, Request::NAMES.iter().copied(), ", ");
            }
            Problem::UnknownField {
                request,
                field,
                expected,
            } => {
                f.put("unknown field \"");
                f.put(field.as_str());
                f.put("\" in ");
                f.put(request);
                f.put(", expected ");
                f.put(expected);
            }
            Problem::DuplicateField(field) => {
                f.put("field \"");
                f.put(field);
                f.put("\" given twice");
            }
            Problem::MissingField(field) => {
                f.put("missing field \"");
                f.put(field);
                f.put("\"");
            }
            Problem::WrongType { field, expected } | Problem::InvalidValue { field, expected } => {
                f.put(field);
                f.put(": expected ");
                f.put(expected);
            }
            Problem::UnknownModel(name) => {
                f.put("model: unknown model \"");
                f.put(name.as_str());
                f.put("\", expected ");
                model_names(f);
            }
            Problem::Conflict { field, with } => {
                f.put(field);
                f.put(" and ");
                f.put(with);
                f.put(" cannot both be given");
            }
            Problem::TooMany { field, limit } => {
                f.put(field);
                f.put(": more than ");
                unsigned(f, *limit);
                f.put(", the buffer's capacity");
            }
            Problem::Value(error) => write_value_error(f, error),
            Problem::Stroke(error) => write_stroke_error(f, error),
            Problem::Unsupported { field, reason } => {
                f.put(field);
                f.put(": ");
                f.put(reason);
            }
            Problem::NoAim(error) => f.put(match error {
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

fn write_stroke_error(f: &mut dyn Sink, error: &StrokeError) {
    match error {
        StrokeError::InvalidConfig(ConfigField::SampleRate) => {
            f.put("rate_hz must be in [500, 100000] Hz")
        }
        StrokeError::InvalidConfig(ConfigField::FullScale) => f.put(
            "scale: the full scale, 32768 x |scale|, must exceed the 8 g impact threshold",
        ),
        StrokeError::InvalidConfig(field) => {
            f.put("stroke estimator setting out of range: ");
            f.put(config_field_name(*field));
        }
        StrokeError::NotFinite { .. } => f.put("scale must be a finite, non-zero number"),
        StrokeError::TooShort { len, min } => {
            f.put("samples: ");
            unsigned(f, *len);
            f.put(" samples, at least ");
            unsigned(f, *min);
            f.put(" are needed at this rate");
        }
        StrokeError::NotAtRest => f.put(
            "samples: no rest of 150 ms before an impact (start the capture with the cue held still)",
        ),
        StrokeError::NoImpact => {
            f.put("samples: no impact (a deceleration of 8 g) after the rest")
        }
        StrokeError::Saturated { index } => {
            f.put("samples: sample ");
            unsigned(f, *index);
            f.put(" reached the sensor's full scale before the impact");
        }
        StrokeError::NotForward { speed } => {
            f.put("samples: the cue speed at impact integrates to ");
            plain(f, *speed);
            f.put(" m/s, not forward (a negative scale flips the axis)");
        }
        StrokeError::LengthMismatch { accel, pitch } => {
            f.put("samples: ");
            unsigned(f, *accel);
            f.put(" accelerometer and ");
            unsigned(f, *pitch);
            f.put(" gyro samples");
        }
        StrokeError::Strike(error) => write_value_error(f, error),
    }
}

/// A [`ConfigField`] as `{:?}` writes it.
const fn config_field_name(field: ConfigField) -> &'static str {
    match field {
        ConfigField::SampleRate => "SampleRate",
        ConfigField::ImpactThreshold => "ImpactThreshold",
        ConfigField::OnsetDrop => "OnsetDrop",
        ConfigField::MinRest => "MinRest",
        ConfigField::RestNoiseLimit => "RestNoiseLimit",
        ConfigField::RestLevelTolerance => "RestLevelTolerance",
        ConfigField::MotionFloor => "MotionFloor",
        ConfigField::FullScale => "FullScale",
        ConfigField::CueElevation => "CueElevation",
    }
}

/// The core error's own `Display` text, with the value written by [`plain`] rather
/// than core's float formatting (which has panic paths; see `decimal.rs`).
fn write_value_error(f: &mut dyn Sink, error: &cuesight::Error) {
    match error {
        cuesight::Error::NotFinite { field } => {
            f.put(field.name());
            f.put(" must be a finite number");
        }
        cuesight::Error::OutOfRange { field, value } => {
            f.put(field.name());
            f.put(" = ");
            plain(f, *value);
            f.put(" is outside ");
            f.put(field.valid_range());
        }
        cuesight::Error::NumericalFailure => {
            f.put("internal numerical failure (non-finite result)")
        }
    }
}

#[cfg(test)]
mod tests {
    //! The messages against the `write!`s they replaced (kept here as the oracle).

    extern crate std;

    use std::format;
    use std::string::{String, ToString};

    use cuesight::Field;
    use cuesight_sensors::ConfigField;

    use super::*;
    use crate::decimal::Plain;
    use crate::json::SyntaxReason;
    use crate::names::ModelNames;

    /// The former `Display` of [`Problem`], with `format!`.
    fn oracle(problem: &Problem) -> String {
        let names = Request::NAMES.join(", ");
        let value = |error: &cuesight::Error| match error {
            cuesight::Error::NotFinite { field } => {
                format!("{} must be a finite number", field.name())
            }
            cuesight::Error::OutOfRange { field, value } => format!(
                "{} = {} is outside {}",
                field.name(),
                Plain(*value),
                field.valid_range()
            ),
            cuesight::Error::NumericalFailure => {
                "internal numerical failure (non-finite result)".to_string()
            }
        };
        match problem {
            Problem::Syntax(syntax) => format!(
                "malformed JSON: {} at byte {}",
                syntax.reason.describe(),
                syntax.at
            ),
            Problem::LineTooLong { length, limit } => format!(
                "line too long: {length} bytes before the newline, the limit is {limit}"
            ),
            Problem::NotARequest(why) => format!(
                "not a request: {} (one of {names} as its only key, e.g. {{\"version\":{{}}}})",
                match why {
                    NotARequest::NotAnObject => "expected a JSON object",
                    NotARequest::Empty => "the object is empty",
                    NotARequest::SeveralKeys => "one request per line, found several keys",
                }
            ),
            Problem::UnknownRequest(name) => {
                format!("unknown request \"{name}\", expected one of {names}")
            }
            Problem::UnknownField {
                request,
                field,
                expected,
            } => format!("unknown field \"{field}\" in {request}, expected {expected}"),
            Problem::DuplicateField(field) => format!("field \"{field}\" given twice"),
            Problem::MissingField(field) => format!("missing field \"{field}\""),
            Problem::WrongType { field, expected } | Problem::InvalidValue { field, expected } => {
                format!("{field}: expected {expected}")
            }
            Problem::UnknownModel(name) => {
                format!("model: unknown model \"{name}\", expected {ModelNames}")
            }
            Problem::Conflict { field, with } => format!("{field} and {with} cannot both be given"),
            Problem::TooMany { field, limit } => {
                format!("{field}: more than {limit}, the buffer's capacity")
            }
            Problem::Value(error) => value(error),
            Problem::Stroke(error) => match error {
                StrokeError::InvalidConfig(ConfigField::SampleRate) => {
                    "rate_hz must be in [500, 100000] Hz".to_string()
                }
                StrokeError::InvalidConfig(ConfigField::FullScale) => {
                    "scale: the full scale, 32768 x |scale|, must exceed the 8 g impact threshold"
                        .to_string()
                }
                StrokeError::InvalidConfig(field) => {
                    format!("stroke estimator setting out of range: {field:?}")
                }
                StrokeError::NotFinite { .. } => "scale must be a finite, non-zero number".to_string(),
                StrokeError::TooShort { len, min } => {
                    format!("samples: {len} samples, at least {min} are needed at this rate")
                }
                StrokeError::NotAtRest => "samples: no rest of 150 ms before an impact (start the capture with the cue held still)".to_string(),
                StrokeError::NoImpact => {
                    "samples: no impact (a deceleration of 8 g) after the rest".to_string()
                }
                StrokeError::Saturated { index } => format!(
                    "samples: sample {index} reached the sensor's full scale before the impact"
                ),
                StrokeError::NotForward { speed } => format!(
                    "samples: the cue speed at impact integrates to {} m/s, not forward (a negative scale flips the axis)",
                    Plain(*speed)
                ),
                StrokeError::LengthMismatch { accel, pitch } => {
                    format!("samples: {accel} accelerometer and {pitch} gyro samples")
                }
                StrokeError::Strike(error) => value(error),
            },
            Problem::Unsupported { field, reason } => format!("{field}: {reason}"),
            Problem::NoAim(error) => match error {
                AimError::ObjectBallNotHit => "no aim: at the ghost-ball aim the cue ball does not reach the object ball first (another ball in the way, or too slow)",
                AimError::PocketUnreachable => "no aim: the object ball cannot reach the pocket (it stops short, or the cut is too thin)",
                AimError::NotConverged | AimError::Invalid(_) => {
                    "no aim: the solver did not converge (the cut may be too thin)"
                }
            }
            .to_string(),
        }
    }

    /// The first [`MESSAGE_LEN`] bytes of `text`, at a character boundary, as the
    /// answer's message keeps them.
    fn cut(text: &str) -> String {
        let mut out = String::new();
        for c in text.chars() {
            if out.len() + c.len_utf8() > MESSAGE_LEN {
                break;
            }
            out.push(c);
        }
        out
    }

    fn problems() -> std::vec::Vec<Problem> {
        let long = "x\u{e9}\u{1f600}".repeat(20);
        let names = ["speed", "", "\u{e9}\"\\", long.as_str()];
        let values = [
            0.0,
            -0.0,
            1.5,
            -1e-7,
            3e38,
            f32::NAN,
            f32::INFINITY,
            f32::from_bits(1),
        ];
        let mut all = std::vec![
            Problem::LineTooLong {
                length: 12_000,
                limit: 3072
            },
            Problem::LineTooLong {
                length: usize::MAX,
                limit: 0
            },
            Problem::NotARequest(NotARequest::NotAnObject),
            Problem::NotARequest(NotARequest::Empty),
            Problem::NotARequest(NotARequest::SeveralKeys),
            Problem::DuplicateField("mu"),
            Problem::MissingField("speed"),
            Problem::WrongType {
                field: "spin",
                expected: "[wx, wy, wz], three numbers (rad/s)"
            },
            Problem::InvalidValue {
                field: "table",
                expected: "pool, snooker or carom"
            },
            Problem::Conflict {
                field: "roll",
                with: "spin"
            },
            Problem::TooMany {
                field: "samples",
                limit: 256
            },
            Problem::Unsupported {
                field: "model",
                reason: "reference runs on the host only"
            },
            Problem::Value(cuesight::Error::NumericalFailure),
            Problem::NoAim(AimError::ObjectBallNotHit),
            Problem::NoAim(AimError::PocketUnreachable),
            Problem::NoAim(AimError::NotConverged),
            Problem::Stroke(StrokeError::NotFinite { index: 3 }),
            Problem::Stroke(StrokeError::TooShort { len: 3, min: 162 }),
            Problem::Stroke(StrokeError::NotAtRest),
            Problem::Stroke(StrokeError::NoImpact),
            Problem::Stroke(StrokeError::Saturated { index: 1234 }),
            Problem::Stroke(StrokeError::LengthMismatch {
                accel: 10,
                pitch: 0
            }),
        ];
        for at in [0, 9, 3071] {
            for reason in [
                SyntaxReason::UnexpectedEnd,
                SyntaxReason::InvalidUtf8,
                SyntaxReason::TrailingCharacters,
            ] {
                all.push(Problem::Syntax(Syntax { at, reason }));
            }
        }
        for name in names {
            all.push(Problem::UnknownRequest(Name::of(name)));
            all.push(Problem::UnknownModel(Name::of(name)));
            for (request, expected) in [
                ("shot", "table, cue, balls, speed, tip, aim, object, pocket, mu_cloth, mu_roll, cue_mass, tip_restitution, mu, mu_b, mu_c, restitution, mu_s, mass, model"),
                ("this request", "no fields"),
            ] {
                all.push(Problem::UnknownField { request, field: Name::of(name), expected });
            }
        }
        for field in [
            ConfigField::SampleRate,
            ConfigField::ImpactThreshold,
            ConfigField::OnsetDrop,
            ConfigField::MinRest,
            ConfigField::RestNoiseLimit,
            ConfigField::RestLevelTolerance,
            ConfigField::MotionFloor,
            ConfigField::FullScale,
            ConfigField::CueElevation,
        ] {
            all.push(Problem::Stroke(StrokeError::InvalidConfig(field)));
        }
        for value in values {
            all.push(Problem::Stroke(StrokeError::NotForward { speed: value }));
            for field in [
                Field::Speed,
                Field::CutAngle,
                Field::Friction,
                Field::Pocket,
                Field::BallIndex,
            ] {
                let error = cuesight::Error::OutOfRange { field, value };
                all.push(Problem::Value(error));
                all.push(Problem::Stroke(StrokeError::Strike(error)));
                all.push(Problem::Value(cuesight::Error::NotFinite { field }));
            }
        }
        all
    }

    #[test]
    fn messages_are_the_former_formatted_text() {
        for problem in problems() {
            let want = oracle(&problem);
            assert_eq!(problem.to_string(), want, "{problem:?}");
            assert_eq!(
                problem.to_answer().message.as_str(),
                cut(&want),
                "{problem:?}"
            );
        }
    }
}
