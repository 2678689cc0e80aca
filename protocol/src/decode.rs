//! Decoding a request line: strict JSON syntax first ([`crate::json::check`]), then the
//! schema, read by hand over the checked line ([`json::Reader`]), with every problem
//! named.
//!
//! This replaced serde and serde-json-core (issue 6: their generic code cost the
//! firmware several KB of its 64 KiB of flash). It reads every value exactly as
//! serde-json-core did — the same numbers (its own `f32` parser), strings as written
//! (escapes kept: it was given no unescape buffer), the same checks in the same order,
//! down to its quirks (an integer field reads `0` of `0.5` and then fails on `.5` with
//! an error that names nothing, `not_a_request`) — so every line gets the answer it got
//! before. The serde decoder is kept as the tests' oracle (`decode/oracle.rs`).
//!
//! Order of the checks in a body: fields in line order (a duplicate, an unknown field
//! or a value of the wrong type fails at once), then, once the body is read, the model
//! name, the request's own checks (conflicts, the table name), the required fields.

use heapless::Vec;

use crate::json::{self, Reader, WrongKind};
use crate::names::ModelName;
use crate::problem::{Name, NotARequest, Problem};
use crate::request::{Collide, Overrides, Request, Spin, Stroke};
#[cfg(feature = "shot")]
use crate::shot::{Shot, TableName, MAX_OBJECT_BALLS};
use crate::MAX_SAMPLES;

/// Decode one request line (without its newline).
pub fn decode(line: &[u8]) -> Result<Request, Problem> {
    let (kind, mut r) = open(line)?;
    let request = match kind {
        Kind::Collide => Request::Collide(read_collide(&mut r)?),
        Kind::Params => Request::Params(read_params(&mut r)?),
        Kind::Stroke => Request::Stroke(read_stroke(&mut r)?),
        #[cfg(feature = "shot")]
        Kind::Shot => Request::Shot(read_shot(&mut r)?),
        Kind::Version => {
            read_empty(&mut r, "version")?;
            Request::Version
        }
        Kind::Shutdown => {
            read_empty(&mut r, "shutdown")?;
            Request::Shutdown
        }
    };
    close(&mut r)?;
    Ok(request)
}

/// Which request a line holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Collide,
    Params,
    Stroke,
    #[cfg(feature = "shot")]
    Shot,
    Version,
    Shutdown,
}

impl Kind {
    /// The wire name.
    pub(crate) const fn name(self) -> &'static str {
        match self {
            Kind::Collide => "collide",
            Kind::Params => "params",
            Kind::Stroke => "stroke",
            #[cfg(feature = "shot")]
            Kind::Shot => "shot",
            Kind::Version => "version",
            Kind::Shutdown => "shutdown",
        }
    }
}

/// The first step of [`decode`]: the syntax check, then the request object and its
/// name, the reader left before the body (read with `read_*`, then [`close`]). The
/// session answers each request in its own function, reading the body there, so the
/// largest request's body is never on the stack of another's answer.
// Not inlined: see `read_shot`.
#[inline(never)]
pub(crate) fn open(line: &[u8]) -> Result<(Kind, Reader<'_>), Problem> {
    json::check(line).map_err(Problem::Syntax)?;
    let mut r = Reader::new(line);
    if !r.open_object() {
        return Err(Problem::NotARequest(NotARequest::NotAnObject));
    }
    let tag = match r.key() {
        Ok(Some(tag)) => tag,
        Ok(None) => return Err(Problem::NotARequest(NotARequest::Empty)),
        Err(WrongKind) => return Err(Problem::NotARequest(NotARequest::NotAnObject)),
    };
    let kind = match tag {
        "collide" => Kind::Collide,
        "params" => Kind::Params,
        "stroke" => Kind::Stroke,
        #[cfg(feature = "shot")]
        "shot" => Kind::Shot,
        #[cfg(not(feature = "shot"))]
        "shot" => {
            return Err(Problem::Unsupported {
                field: "shot",
                reason: "this firmware image has no shot guidance (build it with --features shot)",
            })
        }
        "version" => Kind::Version,
        "shutdown" => Kind::Shutdown,
        other => return Err(Problem::UnknownRequest(Name::of(other))),
    };
    Ok((kind, r))
}

/// The last step of [`decode`]: after the body, the request object must end.
pub(crate) fn close(r: &mut Reader<'_>) -> Result<(), Problem> {
    match r.key() {
        Ok(None) => Ok(()),
        _ => Err(Problem::NotARequest(NotARequest::SeveralKeys)),
    }
}

const NUMBER: &str = "a number";
const SPIN: &str = "[wx, wy, wz], three numbers (rad/s)";
const BOOL: &str = "true or false";
const MODEL: &str = "a model name (a string)";
const OBJECT: &str = "an object of the request's fields";
const EMPTY: &str = "an empty object {}";
const SAMPLES: &str = "an array of raw samples, integers in -32768..=32767";
const TIP: &str = "[side, height], two numbers (m)";
#[cfg(feature = "shot")]
const POINT: &str = "[x, y], two numbers (m)";
#[cfg(feature = "shot")]
const BALLS: &str = "an array of [x, y] ball centres (m)";
#[cfg(feature = "shot")]
const TABLE: &str = "a table name (a string)";
#[cfg(feature = "shot")]
const INDEX: &str = "a non-negative integer";
#[cfg(feature = "shot")]
const TIP_RADII: &str = "[side, height], two numbers (ball radii)";

/// The fields of each request, for `unknown_field`.
const PARAMS_FIELDS: &str = "mu, mu_b, mu_c, restitution, mu_s, radius, mass, model";
const COLLIDE_FIELDS: &str =
    "speed, cut, spin, roll, mu, mu_b, mu_c, restitution, mu_s, radius, mass, model";
const STROKE_FIELDS: &str = "samples, more, rate_hz, scale, tip_offset, cue_mass, tip_restitution";
#[cfg(feature = "shot")]
const SHOT_FIELDS: &str = "table, cue, balls, speed, tip, aim, object, pocket, mu_cloth, mu_roll, \
     cue_mass, tip_restitution, mu, mu_b, mu_c, restitution, mu_s, mass, model";

/// How one field's value is read.
type Read<'a, T> = fn(&mut Reader<'a>) -> Result<T, WrongKind>;

/// Reads one field's value with `read` into `slot`, refusing a duplicate first; a
/// value of the wrong kind is `wrong_type`, naming `expected`.
// Not inlined into each of its ~30 calls: one copy per value type (the image
// with `shot` 480 B smaller).
#[inline(never)]
fn field<'a, T>(
    r: &mut Reader<'a>,
    slot: &mut Option<T>,
    name: &'static str,
    expected: &'static str,
    read: Read<'a, T>,
) -> Result<(), Problem> {
    if slot.is_some() {
        return Err(Problem::DuplicateField(name));
    }
    *slot = Some(read(r).map_err(|WrongKind| Problem::WrongType {
        field: name,
        expected,
    })?);
    Ok(())
}

fn number(r: &mut Reader<'_>, slot: &mut Option<f32>, name: &'static str) -> Result<(), Problem> {
    field(r, slot, name, NUMBER, Reader::f32)
}

fn string<'a>(r: &mut Reader<'a>) -> Result<&'a str, WrongKind> {
    r.string().ok_or(WrongKind)
}

/// Steps into the body of request `name`: `wrong_type` if it is not an object.
fn open_body(
    r: &mut Reader<'_>,
    name: &'static str,
    expected: &'static str,
) -> Result<(), Problem> {
    if r.open_object() {
        Ok(())
    } else {
        Err(Problem::WrongType {
            field: name,
            expected,
        })
    }
}

/// The next key of a body; `Err` after an integer that stopped early (`"object":0.5`),
/// which serde-json-core answered with an error that named nothing.
fn next_key<'a>(r: &mut Reader<'a>) -> Result<Option<&'a str>, Problem> {
    r.key()
        .map_err(|WrongKind| Problem::NotARequest(NotARequest::NotAnObject))
}

fn unknown(request: &'static str, key: &str, expected: &'static str) -> Problem {
    Problem::UnknownField {
        request,
        field: Name::of(key),
        expected,
    }
}

/// Reads `key`'s value if it is one of the [`Overrides`] (`model` into `model`, by
/// name); `Ok(false)` if it is not one.
fn read_override<'a>(
    r: &mut Reader<'a>,
    key: &str,
    with: &mut Overrides,
    model: &mut Option<&'a str>,
) -> Result<bool, Problem> {
    let (slot, name) = match key {
        "mu" => (&mut with.mu, "mu"),
        "mu_b" => (&mut with.mu_b, "mu_b"),
        "mu_c" => (&mut with.mu_c, "mu_c"),
        "restitution" => (&mut with.restitution, "restitution"),
        "mu_s" => (&mut with.mu_s, "mu_s"),
        "radius" => (&mut with.radius, "radius"),
        "mass" => (&mut with.mass, "mass"),
        "model" => {
            field(r, model, "model", MODEL, string)?;
            return Ok(true);
        }
        _ => return Ok(false),
    };
    number(r, slot, name)?;
    Ok(true)
}

/// The model named in a body, if any.
fn parse_model(name: Option<&str>) -> Result<Option<ModelName>, Problem> {
    match name {
        None => Ok(None),
        Some(name) => ModelName::from_name(name)
            .map(Some)
            .ok_or_else(|| Problem::UnknownModel(Name::of(name))),
    }
}

// Not inlined: see `read_shot`.
#[inline(never)]
pub(crate) fn read_params(r: &mut Reader<'_>) -> Result<Overrides, Problem> {
    open_body(r, "params", OBJECT)?;
    let mut with = Overrides::default();
    let mut model = None;
    while let Some(key) = next_key(r)? {
        if !read_override(r, key, &mut with, &mut model)? {
            return Err(unknown("params", key, PARAMS_FIELDS));
        }
    }
    with.model = parse_model(model)?;
    Ok(with)
}

pub(crate) fn read_collide(r: &mut Reader<'_>) -> Result<Collide, Problem> {
    open_body(r, "collide", OBJECT)?;
    let (mut speed, mut cut, mut spin, mut roll) = (None, None, None, None);
    let mut with = Overrides::default();
    let mut model = None;
    while let Some(key) = next_key(r)? {
        match key {
            "speed" => number(r, &mut speed, "speed")?,
            "cut" => number(r, &mut cut, "cut")?,
            "spin" => field(r, &mut spin, "spin", SPIN, Reader::f32s::<3>)?,
            "roll" => field(r, &mut roll, "roll", BOOL, Reader::bool)?,
            _ => {
                if !read_override(r, key, &mut with, &mut model)? {
                    return Err(unknown("collide", key, COLLIDE_FIELDS));
                }
            }
        }
    }
    with.model = parse_model(model)?;
    let spin = match (spin, roll) {
        (Some(_), Some(true)) => {
            return Err(Problem::Conflict {
                field: "roll",
                with: "spin",
            })
        }
        (_, Some(true)) => Spin::Roll,
        (spin, _) => Spin::Given(spin.unwrap_or([0.0; 3])),
    };
    Ok(Collide {
        speed: speed.ok_or(Problem::MissingField("speed"))?,
        cut: cut.ok_or(Problem::MissingField("cut"))?,
        spin,
        with,
    })
}

// Inlined into `Session::stroke`, unlike the other bodies' readers: in a frame of its
// own (52 B less flash) it took the stack of a session with strokes 600 B deeper.
pub(crate) fn read_stroke(r: &mut Reader<'_>) -> Result<Stroke, Problem> {
    open_body(r, "stroke", OBJECT)?;
    let mut stroke = Stroke::chunk(Vec::new());
    let (mut have_samples, mut more) = (false, None);
    while let Some(key) = next_key(r)? {
        match key {
            "samples" => {
                if have_samples {
                    return Err(Problem::DuplicateField("samples"));
                }
                // In place: each copy of a chunk costs the firmware's stack its size.
                read_samples(r, &mut stroke.samples)?;
                have_samples = true;
            }
            "more" => field(r, &mut more, "more", BOOL, Reader::bool)?,
            "rate_hz" => number(r, &mut stroke.rate_hz, "rate_hz")?,
            "scale" => number(r, &mut stroke.scale, "scale")?,
            "tip_offset" => field(
                r,
                &mut stroke.tip_offset,
                "tip_offset",
                TIP,
                Reader::f32s::<2>,
            )?,
            "cue_mass" => number(r, &mut stroke.cue_mass, "cue_mass")?,
            "tip_restitution" => number(r, &mut stroke.tip_restitution, "tip_restitution")?,
            _ => return Err(unknown("stroke", key, STROKE_FIELDS)),
        }
    }
    if !have_samples {
        return Err(Problem::MissingField("samples"));
    }
    stroke.more = more.unwrap_or(false);
    if stroke.more {
        // The settings belong to the last chunk, which gets the estimate.
        let given = [
            ("rate_hz", stroke.rate_hz.is_some()),
            ("scale", stroke.scale.is_some()),
            ("tip_offset", stroke.tip_offset.is_some()),
            ("cue_mass", stroke.cue_mass.is_some()),
            ("tip_restitution", stroke.tip_restitution.is_some()),
        ];
        if let Some((field, _)) = given.into_iter().find(|(_, given)| *given) {
            return Err(Problem::Conflict {
                field,
                with: "more",
            });
        }
    } else if stroke.rate_hz.is_none() {
        return Err(Problem::MissingField("rate_hz"));
    }
    Ok(stroke)
}

/// The `samples` of one chunk into `out`, at most [`MAX_SAMPLES`] (each sample is read
/// before the count is checked, as serde did).
fn read_samples(r: &mut Reader<'_>, out: &mut Vec<i16, MAX_SAMPLES>) -> Result<(), Problem> {
    let wrong = |WrongKind| Problem::WrongType {
        field: "samples",
        expected: SAMPLES,
    };
    out.clear();
    if !r.open_array() {
        return Err(wrong(WrongKind));
    }
    while r.next_element() {
        if out.push(r.i16().map_err(wrong)?).is_err() {
            return Err(Problem::TooMany {
                field: "samples",
                limit: MAX_SAMPLES,
            });
        }
    }
    Ok(())
}

/// The body of `version` and `shutdown`: `{}`.
pub(crate) fn read_empty(r: &mut Reader<'_>, name: &'static str) -> Result<(), Problem> {
    open_body(r, name, EMPTY)?;
    match next_key(r)? {
        None => Ok(()),
        Some(key) => Err(unknown("this request", key, "no fields")),
    }
}

/// The body of a `shot`.
#[cfg(feature = "shot")]
// Not inlined into `Session::prepare_shot`: in a frame of its own the image is
// smaller (280 B measured), as it is with `open` and `read_params` in theirs.
#[inline(never)]
pub(crate) fn read_shot(r: &mut Reader<'_>) -> Result<Shot, Problem> {
    open_body(r, "shot", OBJECT)?;
    let mut shot = Shot {
        table: TableName::Pool,
        cue: [0.0; 2],
        balls: Vec::new(),
        speed: 0.0,
        tip: [0.0; 2],
        aim: None,
        object: None,
        pocket: None,
        mu_cloth: None,
        mu_roll: None,
        cue_mass: None,
        tip_restitution: None,
        with: Overrides::default(),
    };
    let (mut table, mut cue, mut speed, mut tip) = (None, None, None, None);
    let (mut have_balls, mut model) = (false, None);
    while let Some(key) = next_key(r)? {
        match key {
            "table" => field(r, &mut table, "table", TABLE, string)?,
            "cue" => field(r, &mut cue, "cue", POINT, Reader::f32s::<2>)?,
            "balls" => {
                if have_balls {
                    return Err(Problem::DuplicateField("balls"));
                }
                read_balls(r, &mut shot.balls)?;
                have_balls = true;
            }
            "speed" => number(r, &mut speed, "speed")?,
            "tip" => field(r, &mut tip, "tip", TIP_RADII, Reader::f32s::<2>)?,
            "aim" => number(r, &mut shot.aim, "aim")?,
            "object" => field(r, &mut shot.object, "object", INDEX, Reader::u32)?,
            "pocket" => field(r, &mut shot.pocket, "pocket", INDEX, Reader::u32)?,
            "mu_cloth" => number(r, &mut shot.mu_cloth, "mu_cloth")?,
            "mu_roll" => number(r, &mut shot.mu_roll, "mu_roll")?,
            "cue_mass" => number(r, &mut shot.cue_mass, "cue_mass")?,
            "tip_restitution" => number(r, &mut shot.tip_restitution, "tip_restitution")?,
            // The balls are the table's set: their radius is not a shot field.
            "radius" => return Err(unknown("shot", key, SHOT_FIELDS)),
            _ => {
                if !read_override(r, key, &mut shot.with, &mut model)? {
                    return Err(unknown("shot", key, SHOT_FIELDS));
                }
            }
        }
    }
    shot.with.model = parse_model(model)?;
    if let Some(name) = table {
        shot.table = TableName::from_name(name).ok_or(Problem::InvalidValue {
            field: "table",
            expected: TableName::NAMES,
        })?;
    }
    shot.cue = cue.ok_or(Problem::MissingField("cue"))?;
    shot.speed = speed.ok_or(Problem::MissingField("speed"))?;
    shot.tip = tip.unwrap_or([0.0; 2]);
    Ok(shot)
}

/// The `balls` of a `shot` into `out`, at most [`MAX_OBJECT_BALLS`] (each ball is read
/// before the count is checked, as serde did).
#[cfg(feature = "shot")]
fn read_balls(
    r: &mut Reader<'_>,
    out: &mut Vec<[f32; 2], MAX_OBJECT_BALLS>,
) -> Result<(), Problem> {
    let wrong = |WrongKind| Problem::WrongType {
        field: "balls",
        expected: BALLS,
    };
    out.clear();
    if !r.open_array() {
        return Err(wrong(WrongKind));
    }
    while r.next_element() {
        if out.push(r.f32s::<2>().map_err(wrong)?).is_err() {
            return Err(Problem::TooMany {
                field: "balls",
                limit: MAX_OBJECT_BALLS,
            });
        }
    }
    Ok(())
}

// The tests need the `shot` request (the crate's default).
#[cfg(all(test, feature = "shot"))]
mod oracle;

#[cfg(all(test, feature = "shot"))]
mod tests;
