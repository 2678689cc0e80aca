//! Writing answers by hand: the JSON text serde-json-core wrote for them, byte for
//! byte, without its generic serializer (issue 6's flash budget).
//!
//! What serde-json-core writes, and so what [`Writer`] does: no whitespace; keys and
//! values in field order; an `f32` in `ryu`'s shortest round-trip form (`2.0`,
//! `0.031433225`, `1e-7`), a non-finite one as `null`; an absent optional value as
//! `null` (the field is kept) but for the error's `field`, which is left out; names
//! (`kim-grip`, `sliding`, `cushion`, keys) as they are, plain ASCII with nothing to
//! escape; text that may hold anything (messages, names echoed from the request) with
//! serde-json-core's escapes. The tests hold each encoder to serde-json-core's output.

use crate::answer::{
    Answer, BallAnswer, CollideAnswer, ErrorAnswer, InputEcho, ParamsAnswer, StrokeAnswer,
};
use crate::session::AnswerLine;
use crate::MAX_ANSWER;

/// Appends JSON to an answer line, remembering whether all of it fitted.
pub(crate) struct Writer<'a> {
    out: &'a mut AnswerLine,
    /// Everything written so far fitted.
    fits: bool,
    /// No field written yet in the object just opened (no `,` before the next key).
    first: bool,
}

impl<'a> Writer<'a> {
    /// Writes into `out`, emptied first.
    pub(crate) fn new(out: &'a mut AnswerLine) -> Self {
        out.clear();
        Self {
            out,
            fits: true,
            first: true,
        }
    }

    /// Raw text.
    pub(crate) fn raw(&mut self, text: &[u8]) {
        self.fits &= self.out.extend_from_slice(text).is_ok();
    }

    /// `{`: opens an object.
    pub(crate) fn open(&mut self) {
        self.raw(b"{");
        self.first = true;
    }

    /// `}`: closes the object.
    pub(crate) fn close(&mut self) {
        self.raw(b"}");
        self.first = false;
    }

    /// `"key":` (after a `,` unless it is the object's first).
    pub(crate) fn key(&mut self, key: &str) {
        if !self.first {
            self.raw(b",");
        }
        self.first = false;
        self.raw(b"\"");
        self.raw(key.as_bytes());
        self.raw(b"\":");
    }

    /// `{"key":` — an object's first key, for a tagged answer `{"shot":{...}}`.
    pub(crate) fn tag(&mut self, key: &str) {
        self.open();
        self.key(key);
    }

    /// A number: `ryu`'s shortest form, or `null` if it is not finite.
    pub(crate) fn f32(&mut self, value: f32) {
        if value.is_finite() {
            let mut buffer = ryu::Buffer::new();
            self.raw(buffer.format_finite(value).as_bytes());
        } else {
            self.raw(b"null");
        }
    }

    /// `[a,b,...]`.
    pub(crate) fn f32s(&mut self, values: &[f32]) {
        self.raw(b"[");
        for (i, &value) in values.iter().enumerate() {
            if i > 0 {
                self.raw(b",");
            }
            self.f32(value);
        }
        self.raw(b"]");
    }

    /// An unsigned integer in decimal.
    pub(crate) fn u32(&mut self, value: u32) {
        let mut digits = [0u8; 10];
        let mut at = digits.len();
        let mut rest = value;
        loop {
            at = at.saturating_sub(1);
            if let Some(slot) = digits.get_mut(at) {
                *slot = b'0' + (rest % 10) as u8;
            }
            rest /= 10;
            if rest == 0 || at == 0 {
                break;
            }
        }
        self.raw(digits.get(at..).unwrap_or_default());
    }

    /// `true` or `false`.
    pub(crate) fn bool(&mut self, value: bool) {
        self.raw(if value { b"true" } else { b"false" });
    }

    /// `"text"`; `text` has nothing to escape (see the module docs).
    pub(crate) fn str(&mut self, text: &str) {
        self.raw(b"\"");
        self.raw(text.as_bytes());
        self.raw(b"\"");
    }

    /// `"text"` with serde-json-core's escapes: `\\`, `\"`, `\b`, `\t`, `\n`, `\f`,
    /// `\r`, `\u00XX` (upper-case hex) for the other control characters; the rest as
    /// it is (UTF-8).
    pub(crate) fn escaped(&mut self, text: &str) {
        self.raw(b"\"");
        for &byte in text.as_bytes() {
            let short = match byte {
                b'\\' => b'\\',
                b'"' => b'"',
                0x08 => b'b',
                b'\t' => b't',
                b'\n' => b'n',
                0x0c => b'f',
                b'\r' => b'r',
                0x00..=0x1f => {
                    let hex = |nibble: u8| match nibble {
                        0..=9 => b'0' + nibble,
                        _ => b'A' + nibble - 10,
                    };
                    self.raw(&[b'\\', b'u', b'0', b'0', hex(byte >> 4), hex(byte & 0xf)]);
                    continue;
                }
                _ => {
                    self.raw(&[byte]);
                    continue;
                }
            };
            self.raw(&[b'\\', short]);
        }
        self.raw(b"\"");
    }

    /// `null`.
    #[cfg(feature = "shot")]
    pub(crate) fn null(&mut self) {
        self.raw(b"null");
    }

    /// `"key":` then a number.
    pub(crate) fn f32_field(&mut self, key: &str, value: f32) {
        self.key(key);
        self.f32(value);
    }

    /// `"key":` then `[a,b,...]`.
    pub(crate) fn f32s_field(&mut self, key: &str, values: &[f32]) {
        self.key(key);
        self.f32s(values);
    }

    /// `"key":` then an integer.
    pub(crate) fn u32_field(&mut self, key: &str, value: u32) {
        self.key(key);
        self.u32(value);
    }

    /// `"key":` then a string.
    pub(crate) fn str_field(&mut self, key: &str, text: &str) {
        self.key(key);
        self.str(text);
    }

    /// Ends the line: its `\n` if the JSON fitted with room for it (`true`); otherwise
    /// the line is emptied (`false`) for the caller's `internal` error.
    pub(crate) fn finish(self) -> bool {
        let done = self.fits && self.out.len() < MAX_ANSWER && self.out.push(b'\n').is_ok();
        if !done {
            self.out.clear();
        }
        done
    }
}

impl Answer {
    /// The answer line, tagged JSON and its `\n`, into `out`; if it does not fit (never,
    /// by the size tests), the `internal` error line.
    pub fn write(&self, out: &mut AnswerLine) {
        if !write_answer(self, out) {
            let error = ErrorAnswer::internal();
            // The shortest answer there is: it fits.
            write_answer(&Answer::Error(error), out);
        }
    }
}

/// [`Answer::write`], reporting whether it fitted.
fn write_answer(answer: &Answer, out: &mut AnswerLine) -> bool {
    let mut w = Writer::new(out);
    match answer {
        Answer::Collide(c) => {
            w.tag("collide");
            collide(&mut w, c);
        }
        Answer::Params(p) => {
            w.tag("params");
            params(&mut w, p);
        }
        Answer::Stroke(s) => {
            w.tag("stroke");
            stroke(&mut w, s);
        }
        Answer::StrokeChunk(c) => {
            w.tag("stroke_chunk");
            w.open();
            w.u32_field("samples", c.samples);
            w.u32_field("capacity", c.capacity);
            w.close();
        }
        Answer::Version(v) => {
            w.tag("version");
            w.open();
            w.u32_field("protocol", v.protocol);
            w.key("firmware");
            w.escaped(v.firmware.as_str());
            w.key("board");
            w.escaped(v.board.as_str());
            w.u32_field("max_line", v.max_line);
            w.u32_field("max_samples", v.max_samples);
            w.u32_field("stroke_capacity", v.stroke_capacity);
            w.close();
        }
        Answer::Shutdown(s) => {
            w.tag("shutdown");
            w.open();
            w.u32_field("requests", s.requests);
            w.u32_field("errors", s.errors);
            w.close();
        }
        Answer::Error(e) => {
            w.tag("error");
            error(&mut w, e);
        }
    }
    w.close();
    w.finish()
}

/// The body of a `collide` answer (also what `cuesight collide --json` prints).
pub(crate) fn collide(w: &mut Writer<'_>, c: &CollideAnswer) {
    w.open();
    w.str_field("model", c.model.name());
    w.str_field("regime", c.regime.name());
    w.key("input");
    input(w, &c.input);
    w.key("cue");
    ball(w, &c.cue);
    w.key("object");
    ball(w, &c.object);
    w.f32_field("throw_deg", c.throw_deg);
    w.f32_field("cue_deflection_deg", c.cue_deflection_deg);
    w.f32_field("separation_deg", c.separation_deg);
    w.key("impulses");
    w.open();
    w.f32_field("normal", c.impulses.normal);
    w.f32s_field("friction", &c.impulses.friction);
    w.f32_field("table_friction", c.impulses.table_friction);
    w.close();
    w.close();
}

fn input(w: &mut Writer<'_>, i: &InputEcho) {
    w.open();
    w.f32_field("speed", i.speed);
    w.f32_field("cut_deg", i.cut_deg);
    w.f32s_field("spin", &i.spin);
    w.key("roll");
    w.bool(i.roll);
    w.f32_field("mu", i.mu);
    w.f32_field("mu_b", i.mu_b);
    w.f32_field("mu_c", i.mu_c);
    w.f32_field("restitution", i.restitution);
    w.f32_field("mu_s", i.mu_s);
    w.f32_field("radius", i.radius);
    w.f32_field("mass", i.mass);
    w.close();
}

fn ball(w: &mut Writer<'_>, b: &BallAnswer) {
    w.open();
    w.f32s_field("v", &b.v);
    w.f32s_field("w", &b.w);
    w.close();
}

fn params(w: &mut Writer<'_>, p: &ParamsAnswer) {
    w.open();
    w.f32_field("mu", p.mu);
    w.f32_field("mu_b", p.mu_b);
    w.f32_field("mu_c", p.mu_c);
    w.f32_field("restitution", p.restitution);
    w.f32_field("mu_s", p.mu_s);
    w.f32_field("radius", p.radius);
    w.f32_field("mass", p.mass);
    w.str_field("model", p.model.name());
    w.close();
}

fn stroke(w: &mut Writer<'_>, s: &StrokeAnswer) {
    w.open();
    w.f32_field("cue_speed", s.cue_speed);
    w.f32_field("ball_speed", s.ball_speed);
    w.f32s_field("ball_spin", &s.ball_spin);
    w.u32_field("samples", s.samples);
    w.u32_field("impact_index", s.impact_index);
    w.f32_field("stroke_duration", s.stroke_duration);
    w.f32_field("rest_noise", s.rest_noise);
    w.close();
}

fn error(w: &mut Writer<'_>, e: &ErrorAnswer) {
    w.open();
    w.str_field("kind", e.kind.name());
    if let Some(field) = &e.field {
        w.key("field");
        w.escaped(field.as_str());
    }
    w.key("message");
    w.escaped(e.message.as_str());
    w.close();
}

#[cfg(test)]
mod tests {
    //! Every answer against serde-json-core's serialization of it (the encoder this
    //! replaced): the same bytes.

    extern crate std;

    use std::string::String;

    use cuesight::{Model, Regime};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::answer::{ImpulsesAnswer, ShutdownAnswer, StrokeChunkAnswer, VersionAnswer};
    use crate::names::{ModelName, RegimeName};
    use crate::problem::{ErrorKind, Message, Name};

    fn serde_line(answer: &Answer) -> std::vec::Vec<u8> {
        let mut buf = [0u8; MAX_ANSWER];
        let n = serde_json_core::to_slice(answer, &mut buf).unwrap();
        let mut line = buf[..n].to_vec();
        line.push(b'\n');
        line
    }

    /// A number of any kind: ordinary, tiny, huge, zero of either sign, not finite.
    fn number(rng: &mut ChaCha8Rng) -> f32 {
        match rng.random_range(0..8) {
            0 => f32::from_bits(rng.random()),
            1 => [0.0, -0.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY][rng.random_range(0..5)],
            2 => [f32::MAX, f32::MIN, f32::MIN_POSITIVE, f32::from_bits(1)][rng.random_range(0..4)],
            _ => rng.random_range(-100.0..100.0),
        }
    }

    fn numbers<const N: usize>(rng: &mut ChaCha8Rng) -> [f32; N] {
        core::array::from_fn(|_| number(rng))
    }

    /// Text with everything serde-json-core escapes, and non-ASCII.
    fn text(rng: &mut ChaCha8Rng) -> String {
        let pieces = [
            "speed", "\"", "\\", "\u{8}", "\t", "\n", "\u{c}", "\r", "\u{0}", "\u{1f}", "\u{7f}",
            "é", "→", "😀", " ", "x", "/",
        ];
        (0..rng.random_range(0..12))
            .map(|_| pieces[rng.random_range(0..pieces.len())])
            .collect()
    }

    fn random_answer(rng: &mut ChaCha8Rng) -> Answer {
        let models = Model::ALL;
        let model_name = |rng: &mut ChaCha8Rng| {
            if rng.random_bool(0.1) {
                ModelName::Reference
            } else {
                ModelName::from(models[rng.random_range(0..models.len())])
            }
        };
        match rng.random_range(0..7) {
            0 => Answer::Collide(CollideAnswer {
                model: model_name(rng),
                regime: RegimeName::from(
                    [Regime::Frictionless, Regime::Sliding, Regime::Gripping]
                        [rng.random_range(0..3)],
                ),
                input: InputEcho {
                    speed: number(rng),
                    cut_deg: number(rng),
                    spin: numbers(rng),
                    roll: rng.random(),
                    mu: number(rng),
                    mu_b: number(rng),
                    mu_c: number(rng),
                    restitution: number(rng),
                    mu_s: number(rng),
                    radius: number(rng),
                    mass: number(rng),
                },
                cue: BallAnswer {
                    v: numbers(rng),
                    w: numbers(rng),
                },
                object: BallAnswer {
                    v: numbers(rng),
                    w: numbers(rng),
                },
                throw_deg: number(rng),
                cue_deflection_deg: number(rng),
                separation_deg: number(rng),
                impulses: ImpulsesAnswer {
                    normal: number(rng),
                    friction: numbers(rng),
                    table_friction: number(rng),
                },
            }),
            1 => Answer::Params(ParamsAnswer {
                mu: number(rng),
                mu_b: number(rng),
                mu_c: number(rng),
                restitution: number(rng),
                mu_s: number(rng),
                radius: number(rng),
                mass: number(rng),
                model: model_name(rng),
            }),
            2 => Answer::Stroke(StrokeAnswer {
                cue_speed: number(rng),
                ball_speed: number(rng),
                ball_spin: numbers(rng),
                samples: rng.random(),
                impact_index: rng.random(),
                stroke_duration: number(rng),
                rest_noise: number(rng),
            }),
            3 => Answer::StrokeChunk(StrokeChunkAnswer {
                samples: rng.random(),
                capacity: rng.random(),
            }),
            4 => Answer::Version(VersionAnswer {
                protocol: rng.random(),
                firmware: Name::of(&text(rng)),
                board: Name::of(&text(rng)),
                max_line: rng.random(),
                max_samples: rng.random(),
                stroke_capacity: rng.random(),
            }),
            5 => Answer::Shutdown(ShutdownAnswer {
                requests: rng.random(),
                errors: rng.random(),
            }),
            _ => {
                let kinds = [
                    ErrorKind::MalformedJson,
                    ErrorKind::UnknownField,
                    ErrorKind::OutOfRange,
                    ErrorKind::NoAim,
                    ErrorKind::StrokeRejected,
                    ErrorKind::Internal,
                    ErrorKind::NotARequest,
                ];
                let mut message = Message::new();
                for _ in 0..rng.random_range(0..30) {
                    let _ = message.push_str(&text(rng));
                }
                Answer::Error(ErrorAnswer {
                    kind: kinds[rng.random_range(0..kinds.len())],
                    field: rng.random_bool(0.7).then(|| Name::of(&text(rng))),
                    message,
                })
            }
        }
    }

    #[test]
    fn every_answer_is_serde_json_cores_bytes() {
        let mut rng = ChaCha8Rng::seed_from_u64(10);
        let mut out = AnswerLine::new();
        for _ in 0..20_000 {
            let answer = random_answer(&mut rng);
            answer.write(&mut out);
            assert_eq!(
                String::from_utf8_lossy(&out),
                String::from_utf8_lossy(&serde_line(&answer)),
                "{answer:?}"
            );
        }
        let internal = Answer::Error(ErrorAnswer::internal());
        internal.write(&mut out);
        assert_eq!(out.as_slice(), serde_line(&internal).as_slice());
        assert_eq!(
            out.as_slice(),
            b"{\"error\":{\"kind\":\"internal\",\"message\":\"the answer did not fit the answer buffer\"}}\n"
        );
    }

    #[test]
    fn every_error_kind_has_its_wire_name() {
        use ErrorKind::*;
        for kind in [
            MalformedJson,
            LineTooLong,
            NotARequest,
            UnknownRequest,
            UnknownField,
            DuplicateField,
            MissingField,
            WrongType,
            InvalidValue,
            Conflict,
            NotFinite,
            OutOfRange,
            NumericalFailure,
            Unsupported,
            StrokeRejected,
            NoAim,
            Internal,
        ] {
            let answer = Answer::Error(ErrorAnswer {
                kind,
                field: None,
                message: Message::new(),
            });
            let mut out = AnswerLine::new();
            answer.write(&mut out);
            assert_eq!(out.as_slice(), serde_line(&answer).as_slice());
        }
    }
}
