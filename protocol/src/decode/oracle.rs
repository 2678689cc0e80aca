//! The serde-json-core decoder the hand-written one ([`super::decode`]) replaced, kept
//! as the oracle of the tests that the two agree on every line: the same request or the
//! same problem. (The firmware no longer links serde-json-core's deserializer: its
//! generic code cost several KB of the 64 KiB flash budget.)
//!
//! serde's derived code reports unknown fields, missing fields and wrong types through
//! `de::Error::custom`, whose text serde-json-core drops, so these visitors record
//! *what* went wrong in a [`Diag`] that travels with the `DeserializeSeed`s, and the
//! innermost field being read, so a bare serde-json-core error can still be pinned to a
//! field.

use core::fmt;

use heapless::Vec;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};

use crate::names::ModelName;
use crate::problem::{Name, NotARequest, Problem};
use crate::request::{Collide, Overrides, Request, Spin, Stroke};
#[cfg(feature = "shot")]
use crate::shot::{Shot, TableName, MAX_OBJECT_BALLS};
use crate::{json, MAX_SAMPLES};

/// Decode one request line (without its newline), as before.
pub(crate) fn decode_with_serde(line: &[u8]) -> Result<Request, Problem> {
    json::check(line).map_err(Problem::Syntax)?;
    let mut diag = Diag::default();
    let mut de = serde_json_core::de::Deserializer::new(line, None);
    let result = RequestSeed { diag: &mut diag }
        .deserialize(&mut de)
        .and_then(|request| de.end().map(|_| request));
    result.map_err(|_| diag.into_problem())
}

/// What the visitors learnt before an error.
#[derive(Default)]
struct Diag {
    /// The field whose value was being read, and what it should have been.
    at: Option<(&'static str, &'static str)>,
    /// A problem a visitor found itself (takes precedence).
    problem: Option<Problem>,
}

impl Diag {
    /// Record `problem` and return an error to unwind the deserializer with.
    fn fail<E: de::Error>(&mut self, problem: Problem) -> E {
        self.problem = Some(problem);
        E::custom("")
    }

    fn into_problem(self) -> Problem {
        match (self.problem, self.at) {
            (Some(problem), _) => problem,
            // The JSON is valid (checked first): the value had the wrong shape.
            (None, Some((field, expected))) => Problem::WrongType { field, expected },
            (None, None) => Problem::NotARequest(NotARequest::NotAnObject),
        }
    }

    /// Read the value of `field` into `slot` (refusing duplicates), with `expected`
    /// named if it has the wrong type.
    fn value<'de, A, T>(
        &mut self,
        map: &mut A,
        field: &'static str,
        expected: &'static str,
        slot: &mut Option<T>,
    ) -> Result<(), A::Error>
    where
        A: MapAccess<'de>,
        T: de::Deserialize<'de>,
    {
        if slot.is_some() {
            return Err(self.fail(Problem::DuplicateField(field)));
        }
        self.at = Some((field, expected));
        let value = map.next_value::<T>()?;
        self.at = None;
        *slot = Some(value);
        Ok(())
    }

    /// Read the request body under `field` (an object of `T`'s fields).
    fn body<'de, A, T>(
        &mut self,
        map: &mut A,
        field: &'static str,
        expected: &'static str,
    ) -> Result<T, A::Error>
    where
        A: MapAccess<'de>,
        T: Body,
    {
        self.at = Some((field, expected));
        let body = map.next_value_seed(BodySeed::<T>::new(self))?;
        self.at = None;
        Ok(body)
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

struct RequestSeed<'d> {
    diag: &'d mut Diag,
}

impl<'de> DeserializeSeed<'de> for RequestSeed<'_> {
    type Value = Request;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Request, D::Error> {
        deserializer.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for RequestSeed<'_> {
    type Value = Request;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a request object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Request, A::Error> {
        let diag = self.diag;
        let Some(tag) = map.next_key::<&str>()? else {
            return Err(diag.fail(Problem::NotARequest(NotARequest::Empty)));
        };
        let request =
            match tag {
                "collide" => Request::Collide(diag.body(&mut map, "collide", OBJECT)?),
                "params" => Request::Params(diag.body(&mut map, "params", OBJECT)?),
                "stroke" => Request::Stroke(diag.body(&mut map, "stroke", OBJECT)?),
                #[cfg(feature = "shot")]
                "shot" => Request::Shot(diag.body(&mut map, "shot", OBJECT)?),
                #[cfg(not(feature = "shot"))]
                "shot" => return Err(diag.fail(Problem::Unsupported {
                    field: "shot",
                    reason:
                        "this firmware image has no shot guidance (build it with --features shot)",
                })),
                "version" => {
                    diag.body::<_, ()>(&mut map, "version", EMPTY)?;
                    Request::Version
                }
                "shutdown" => {
                    diag.body::<_, ()>(&mut map, "shutdown", EMPTY)?;
                    Request::Shutdown
                }
                other => return Err(diag.fail(Problem::UnknownRequest(Name::of(other)))),
            };
        if map.next_key::<&str>()?.is_some() {
            return Err(diag.fail(Problem::NotARequest(NotARequest::SeveralKeys)));
        }
        Ok(request)
    }
}

/// A request body: an object whose fields `T` knows how to read.
trait Body: Sized {
    /// The request's name, for messages.
    const NAME: &'static str;
    /// Every field name, for messages.
    const EXPECTED: &'static str;
    /// Read the fields from `map`.
    fn read<'de, A: MapAccess<'de>>(map: A, diag: &mut Diag) -> Result<Self, A::Error>;
}

struct BodySeed<'d, T> {
    diag: &'d mut Diag,
    body: core::marker::PhantomData<T>,
}

impl<'d, T> BodySeed<'d, T> {
    fn new(diag: &'d mut Diag) -> Self {
        Self {
            diag,
            body: core::marker::PhantomData,
        }
    }
}

impl<'de, T: Body> DeserializeSeed<'de> for BodySeed<'_, T> {
    type Value = T;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<T, D::Error> {
        deserializer.deserialize_map(self)
    }
}

impl<'de, T: Body> Visitor<'de> for BodySeed<'_, T> {
    type Value = T;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(T::NAME)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<T, A::Error> {
        T::read(map, self.diag)
    }
}

fn unknown<E: de::Error>(diag: &mut Diag, request: &'static str, field: &str) -> E {
    diag.fail(Problem::UnknownField {
        request,
        field: Name::of(field),
        expected: match request {
            "collide" => Collide::EXPECTED,
            "params" => Overrides::EXPECTED,
            "stroke" => Stroke::EXPECTED,
            #[cfg(feature = "shot")]
            "shot" => Shot::EXPECTED,
            _ => "no fields",
        },
    })
}

/// Reads one of the [`Overrides`] fields; `false` if `key` is not one.
fn read_override<'de, A: MapAccess<'de>>(
    map: &mut A,
    diag: &mut Diag,
    key: &str,
    with: &mut Overrides,
    model: &mut Option<&'de str>,
) -> Result<bool, A::Error> {
    let (slot, name) = match key {
        "mu" => (&mut with.mu, "mu"),
        "mu_b" => (&mut with.mu_b, "mu_b"),
        "mu_c" => (&mut with.mu_c, "mu_c"),
        "restitution" => (&mut with.restitution, "restitution"),
        "mu_s" => (&mut with.mu_s, "mu_s"),
        "radius" => (&mut with.radius, "radius"),
        "mass" => (&mut with.mass, "mass"),
        "model" => {
            diag.value(map, "model", MODEL, model)?;
            return Ok(true);
        }
        _ => return Ok(false),
    };
    diag.value(map, name, NUMBER, slot)?;
    Ok(true)
}

fn parse_model<E: de::Error>(diag: &mut Diag, name: Option<&str>) -> Result<Option<ModelName>, E> {
    match name {
        None => Ok(None),
        Some(name) => match ModelName::from_name(name) {
            Some(model) => Ok(Some(model)),
            None => Err(diag.fail(Problem::UnknownModel(Name::of(name)))),
        },
    }
}

impl Body for Overrides {
    const NAME: &'static str = "params";
    const EXPECTED: &'static str = "mu, mu_b, mu_c, restitution, mu_s, radius, mass, model";

    fn read<'de, A: MapAccess<'de>>(mut map: A, diag: &mut Diag) -> Result<Self, A::Error> {
        let mut with = Overrides::default();
        let mut model = None;
        while let Some(key) = map.next_key::<&str>()? {
            if !read_override(&mut map, diag, key, &mut with, &mut model)? {
                return Err(unknown(diag, Self::NAME, key));
            }
        }
        with.model = parse_model(diag, model)?;
        Ok(with)
    }
}

impl Body for Collide {
    const NAME: &'static str = "collide";
    const EXPECTED: &'static str =
        "speed, cut, spin, roll, mu, mu_b, mu_c, restitution, mu_s, radius, mass, model";

    fn read<'de, A: MapAccess<'de>>(mut map: A, diag: &mut Diag) -> Result<Self, A::Error> {
        let (mut speed, mut cut, mut spin, mut roll) = (None, None, None, None);
        let mut with = Overrides::default();
        let mut model = None;
        while let Some(key) = map.next_key::<&str>()? {
            match key {
                "speed" => diag.value(&mut map, "speed", NUMBER, &mut speed)?,
                "cut" => diag.value(&mut map, "cut", NUMBER, &mut cut)?,
                "spin" => diag.value::<_, [f32; 3]>(&mut map, "spin", SPIN, &mut spin)?,
                "roll" => diag.value(&mut map, "roll", BOOL, &mut roll)?,
                _ => {
                    if !read_override(&mut map, diag, key, &mut with, &mut model)? {
                        return Err(unknown(diag, Self::NAME, key));
                    }
                }
            }
        }
        with.model = parse_model(diag, model)?;
        let spin = match (spin, roll) {
            (Some(_), Some(true)) => {
                return Err(diag.fail(Problem::Conflict {
                    field: "roll",
                    with: "spin",
                }))
            }
            (_, Some(true)) => Spin::Roll,
            (spin, _) => Spin::Given(spin.unwrap_or([0.0; 3])),
        };
        let Some(speed) = speed else {
            return Err(diag.fail(Problem::MissingField("speed")));
        };
        let Some(cut) = cut else {
            return Err(diag.fail(Problem::MissingField("cut")));
        };
        Ok(Collide {
            speed,
            cut,
            spin,
            with,
        })
    }
}

impl Body for Stroke {
    const NAME: &'static str = "stroke";
    const EXPECTED: &'static str =
        "samples, more, rate_hz, scale, tip_offset, cue_mass, tip_restitution";

    fn read<'de, A: MapAccess<'de>>(mut map: A, diag: &mut Diag) -> Result<Self, A::Error> {
        // The samples are decoded in place (no `Option<Vec>` moved through the
        // visitor's result): each copy of a chunk costs the firmware's stack its size.
        let (mut samples, mut have_samples, mut more) = (Vec::new(), false, None);
        let (mut rate_hz, mut scale, mut tip_offset) = (None, None, None);
        let (mut cue_mass, mut tip_restitution) = (None, None);
        while let Some(key) = map.next_key::<&str>()? {
            match key {
                "samples" => {
                    if have_samples {
                        return Err(diag.fail(Problem::DuplicateField("samples")));
                    }
                    diag.at = Some(("samples", SAMPLES));
                    map.next_value_seed(SamplesSeed {
                        diag: &mut *diag,
                        out: &mut samples,
                    })?;
                    have_samples = true;
                    diag.at = None;
                }
                "more" => diag.value(&mut map, "more", BOOL, &mut more)?,
                "rate_hz" => diag.value(&mut map, "rate_hz", NUMBER, &mut rate_hz)?,
                "scale" => diag.value(&mut map, "scale", NUMBER, &mut scale)?,
                "tip_offset" => {
                    diag.value::<_, [f32; 2]>(&mut map, "tip_offset", TIP, &mut tip_offset)?
                }
                "cue_mass" => diag.value(&mut map, "cue_mass", NUMBER, &mut cue_mass)?,
                "tip_restitution" => {
                    diag.value(&mut map, "tip_restitution", NUMBER, &mut tip_restitution)?
                }
                _ => return Err(unknown(diag, Self::NAME, key)),
            }
        }
        if !have_samples {
            return Err(diag.fail(Problem::MissingField("samples")));
        }
        let more = more.unwrap_or(false);
        if more {
            // The settings belong to the last chunk, which gets the estimate.
            let given = [
                ("rate_hz", rate_hz.is_some()),
                ("scale", scale.is_some()),
                ("tip_offset", tip_offset.is_some()),
                ("cue_mass", cue_mass.is_some()),
                ("tip_restitution", tip_restitution.is_some()),
            ];
            if let Some((field, _)) = given.into_iter().find(|(_, given)| *given) {
                return Err(diag.fail(Problem::Conflict {
                    field,
                    with: "more",
                }));
            }
        } else if rate_hz.is_none() {
            return Err(diag.fail(Problem::MissingField("rate_hz")));
        }
        Ok(Stroke {
            samples,
            more,
            rate_hz,
            scale,
            tip_offset,
            cue_mass,
            tip_restitution,
        })
    }
}

#[cfg(feature = "shot")]
impl Body for Shot {
    const NAME: &'static str = "shot";
    const EXPECTED: &'static str = "table, cue, balls, speed, tip, aim, object, pocket, mu_cloth, \
         mu_roll, cue_mass, tip_restitution, mu, mu_b, mu_c, restitution, mu_s, mass, model";

    fn read<'de, A: MapAccess<'de>>(mut map: A, diag: &mut Diag) -> Result<Self, A::Error> {
        let (mut table, mut cue, mut speed, mut tip) = (None::<&str>, None, None, None);
        let (mut balls, mut have_balls) = (Vec::new(), false);
        let (mut aim, mut object, mut pocket) = (None, None, None);
        let (mut mu_cloth, mut mu_roll, mut cue_mass, mut tip_restitution) =
            (None, None, None, None);
        let mut with = Overrides::default();
        let mut model = None;
        while let Some(key) = map.next_key::<&str>()? {
            match key {
                "table" => diag.value(&mut map, "table", TABLE, &mut table)?,
                "cue" => diag.value::<_, [f32; 2]>(&mut map, "cue", POINT, &mut cue)?,
                "balls" => {
                    if have_balls {
                        return Err(diag.fail(Problem::DuplicateField("balls")));
                    }
                    diag.at = Some(("balls", BALLS));
                    map.next_value_seed(BallsSeed {
                        diag: &mut *diag,
                        out: &mut balls,
                    })?;
                    have_balls = true;
                    diag.at = None;
                }
                "speed" => diag.value(&mut map, "speed", NUMBER, &mut speed)?,
                "tip" => diag.value::<_, [f32; 2]>(&mut map, "tip", TIP_RADII, &mut tip)?,
                "aim" => diag.value(&mut map, "aim", NUMBER, &mut aim)?,
                "object" => diag.value(&mut map, "object", INDEX, &mut object)?,
                "pocket" => diag.value(&mut map, "pocket", INDEX, &mut pocket)?,
                "mu_cloth" => diag.value(&mut map, "mu_cloth", NUMBER, &mut mu_cloth)?,
                "mu_roll" => diag.value(&mut map, "mu_roll", NUMBER, &mut mu_roll)?,
                "cue_mass" => diag.value(&mut map, "cue_mass", NUMBER, &mut cue_mass)?,
                "tip_restitution" => {
                    diag.value(&mut map, "tip_restitution", NUMBER, &mut tip_restitution)?
                }
                // The balls are the table's set: their radius is not a shot field.
                "radius" => return Err(unknown(diag, Self::NAME, key)),
                _ => {
                    if !read_override(&mut map, diag, key, &mut with, &mut model)? {
                        return Err(unknown(diag, Self::NAME, key));
                    }
                }
            }
        }
        with.model = parse_model(diag, model)?;
        let table = match table {
            None => TableName::default(),
            Some(name) => TableName::from_name(name).ok_or_else(|| {
                diag.fail(Problem::InvalidValue {
                    field: "table",
                    expected: TableName::NAMES,
                })
            })?,
        };
        let Some(cue) = cue else {
            return Err(diag.fail(Problem::MissingField("cue")));
        };
        let Some(speed) = speed else {
            return Err(diag.fail(Problem::MissingField("speed")));
        };
        Ok(Shot {
            table,
            cue,
            balls,
            speed,
            tip: tip.unwrap_or([0.0; 2]),
            aim,
            object,
            pocket,
            mu_cloth,
            mu_roll,
            cue_mass,
            tip_restitution,
            with,
        })
    }
}

/// The `balls` array of a `shot`, into a fixed-capacity vector (`out`, in place).
#[cfg(feature = "shot")]
struct BallsSeed<'d> {
    diag: &'d mut Diag,
    out: &'d mut Vec<[f32; 2], MAX_OBJECT_BALLS>,
}

#[cfg(feature = "shot")]
impl<'de> DeserializeSeed<'de> for BallsSeed<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_seq(self)
    }
}

#[cfg(feature = "shot")]
impl<'de> Visitor<'de> for BallsSeed<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(BALLS)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let balls = self.out;
        balls.clear();
        while let Some(ball) = seq.next_element::<[f32; 2]>()? {
            if balls.push(ball).is_err() {
                return Err(self.diag.fail(Problem::TooMany {
                    field: "balls",
                    limit: MAX_OBJECT_BALLS,
                }));
            }
        }
        Ok(())
    }
}

/// `version` and `shutdown` take no fields.
impl Body for () {
    const NAME: &'static str = "an empty request body";
    const EXPECTED: &'static str = "no fields";

    fn read<'de, A: MapAccess<'de>>(mut map: A, diag: &mut Diag) -> Result<Self, A::Error> {
        match map.next_key::<&str>()? {
            None => Ok(()),
            Some(key) => Err(diag.fail(Problem::UnknownField {
                request: "this request",
                field: Name::of(key),
                expected: Self::EXPECTED,
            })),
        }
    }
}

/// The `samples` array of one chunk, into a fixed-capacity vector (`out`, in place).
struct SamplesSeed<'d> {
    diag: &'d mut Diag,
    out: &'d mut Vec<i16, MAX_SAMPLES>,
}

impl<'de> DeserializeSeed<'de> for SamplesSeed<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for SamplesSeed<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(SAMPLES)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let samples = self.out;
        samples.clear();
        while let Some(sample) = seq.next_element::<i16>()? {
            if samples.push(sample).is_err() {
                return Err(self.diag.fail(Problem::TooMany {
                    field: "samples",
                    limit: MAX_SAMPLES,
                }));
            }
        }
        Ok(())
    }
}
