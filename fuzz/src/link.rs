//! What the two link targets share: a script that turns the fuzzer's bytes into a byte
//! stream of frames (valid, damaged, out of order), the frame layout written out again
//! as an oracle (COBS and CRC-32 of its own), valid requests of every kind, and a
//! synthetic stroke.
//!
//! # Script
//!
//! A script is a list of records; a record is five header bytes, `op a b len_lo len_hi`,
//! then up to `len` body bytes (fewer if the input ends). The script keeps a sequence
//! number `next` (from 0) and every whole frame it built, and `op % OPS` picks what goes
//! on the wire:
//!
//! | op | wire |
//! |---|---|
//! | 0 `SEND` | a frame `next` with the body as its postcard message; `next` moves on |
//! | 1 `RESEND` | an earlier frame again, verbatim: the `a`-th before the last (0: the last, a duplicate) |
//! | 2 `SEQ` | a frame numbered `next + i16(a, b)` (a gap, a stale or a duplicate number) |
//! | 3 `SCHEMA` | a frame `next` under a foreign schema hash |
//! | 4 `TRUNCATE` | a frame `next` cut after `u16(a, b) % len` bytes, then its zero |
//! | 5 `FLIP` | a frame `next` with bit `a % 8` of byte `u16(a, b) / 8 % len` flipped (its zero too) |
//! | 6 `MERGE` | a frame `next` without its zero: it runs into what follows |
//! | 7 `RAW` | the body bytes themselves, zeros and all |
//! | 8 `OVERSIZED` | `MAX_FRAME + 1 + 8a + b` non-zero bytes, then a zero |
//! | 9 `VERSION` | a valid `version` numbered `u16(a, b)`, which restarts the count: `next` follows it |
//! | 10 `EXAMPLE` | [`examples`]`[a % n]` as frame `next`; `next` moves on |
//! | 11 `STROKE` | the [`synthetic_stroke`] as stroke `a`, chunk by chunk from `next` on, see [`StrokePlan`] |
//!
//! The frames a script builds use this module's encoder, not the link's.

use std::sync::OnceLock;

use cuesight_link::frame::{MAX_FRAME, MAX_RAW};
use cuesight_link::{
    Collide, Empty, ModelName, Overrides, Request, ShotRequest, StrokeChunk, StrokeSetup,
    TableName, MAX_SAMPLES, SCHEMA_HASH,
};

use crate::input::Input;

/// Number of script operations.
pub const OPS: u8 = 12;

/// The operations (see the module docs).
pub mod op {
    pub const SEND: u8 = 0;
    pub const RESEND: u8 = 1;
    pub const SEQ: u8 = 2;
    pub const SCHEMA: u8 = 3;
    pub const TRUNCATE: u8 = 4;
    pub const FLIP: u8 = 5;
    pub const MERGE: u8 = 6;
    pub const RAW: u8 = 7;
    pub const OVERSIZED: u8 = 8;
    pub const VERSION: u8 = 9;
    pub const EXAMPLE: u8 = 10;
    pub const STROKE: u8 = 11;
}

/// Longest stream a script builds: past it, records are ignored.
pub const MAX_STREAM: usize = 1 << 16;

/// The byte stream of `script` (see the module docs).
pub fn build(script: &[u8]) -> Vec<u8> {
    let mut reader = script;
    let mut take = |n: usize| {
        let (head, rest) = reader.split_at(n.min(reader.len()));
        reader = rest;
        head
    };
    let mut out = Vec::new();
    let mut next: u16 = 0;
    let mut history: Vec<Vec<u8>> = Vec::new();
    loop {
        let header = take(5);
        if header.is_empty() || out.len() >= MAX_STREAM {
            break;
        }
        let get = |i: usize| header.get(i).copied().unwrap_or(0);
        let (code, a, b) = (get(0), get(1), get(2));
        let len = usize::from(u16::from_le_bytes([get(3), get(4)]));
        let body = take(len);
        let ab = u16::from_le_bytes([a, b]);
        let mut frame = |schema: u32, seq: u16, body: &[u8]| {
            let wire = wire(schema, seq, body);
            history.push(wire.clone());
            wire
        };
        match code % OPS {
            op::SEND => {
                out.extend(frame(SCHEMA_HASH, next, body));
                next = next.wrapping_add(1);
            }
            op::RESEND => {
                if let Some(back) = history.len().checked_sub(1 + usize::from(a)) {
                    out.extend_from_slice(&history[back]);
                }
            }
            op::SEQ => {
                let seq = next.wrapping_add(ab as i16 as u16);
                out.extend(frame(SCHEMA_HASH, seq, body));
            }
            op::SCHEMA => {
                let schema = SCHEMA_HASH ^ (1u32 << (a % 32)) ^ (u32::from(b) << 8);
                out.extend(frame(schema, next, body));
            }
            op::TRUNCATE => {
                let wire = wire(SCHEMA_HASH, next, body);
                let keep = usize::from(ab) % wire.len();
                out.extend_from_slice(&wire[..keep]);
                out.push(0);
            }
            op::FLIP => {
                let mut wire = wire(SCHEMA_HASH, next, body);
                let at = usize::from(ab / 8) % wire.len();
                wire[at] ^= 1 << (a % 8);
                out.extend(wire);
            }
            op::MERGE => {
                let wire = wire(SCHEMA_HASH, next, body);
                out.extend_from_slice(&wire[..wire.len() - 1]);
            }
            op::RAW => out.extend_from_slice(body),
            op::OVERSIZED => {
                let fill = body.first().map_or(0x55, |&b| b | 1);
                let n = MAX_FRAME + 1 + 8 * usize::from(a) + usize::from(b);
                out.extend(std::iter::repeat_n(fill, n));
                out.push(0);
            }
            op::VERSION => {
                out.extend(frame(
                    SCHEMA_HASH,
                    ab,
                    &body_of(&Request::Version(Empty {})),
                ));
                next = ab.wrapping_add(1);
            }
            op::EXAMPLE => {
                let examples = examples();
                let (_, request) = &examples[usize::from(a) % examples.len()];
                out.extend(frame(SCHEMA_HASH, next, &body_of(request)));
                next = next.wrapping_add(1);
            }
            _ => {
                let plan = StrokePlan::read(a, b, body);
                for chunk in plan.chunks() {
                    out.extend(frame(SCHEMA_HASH, next, &body_of(&chunk)));
                    next = next.wrapping_add(1);
                }
            }
        }
    }
    out
}

/// Writes scripts (for the seeds): each call one record.
#[derive(Clone, Debug, Default)]
pub struct Script {
    bytes: Vec<u8>,
}

impl Script {
    /// An empty script.
    pub fn new() -> Self {
        Self::default()
    }

    /// One record.
    pub fn record(&mut self, op: u8, a: u8, b: u8, body: &[u8]) -> &mut Self {
        let len = u16::try_from(body.len()).expect("a body under 64 KB");
        self.bytes.extend_from_slice(&[op, a, b]);
        self.bytes.extend_from_slice(&len.to_le_bytes());
        self.bytes.extend_from_slice(body);
        self
    }

    /// `SEND` of `request`.
    pub fn send(&mut self, request: &Request) -> &mut Self {
        self.record(op::SEND, 0, 0, &body_of(request))
    }

    /// A record whose `a, b` are `ab` (little-endian).
    pub fn record_ab(&mut self, op: u8, ab: u16, body: &[u8]) -> &mut Self {
        let [a, b] = ab.to_le_bytes();
        self.record(op, a, b, body)
    }

    /// The script's bytes.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }
}

/// The postcard body of `request`.
pub fn body_of(request: &Request) -> Vec<u8> {
    postcard::to_stdvec(request).expect("a request serializes")
}

/// A `STROKE` record: stroke id `a`; `b % 8` chunks sent (0: all); the body, when long
/// enough, a glitch (`u16` sample index, `i16` value), a chunk fault (`mode`, chunk `k`:
/// 1 sends chunk `k` twice, 2 leaves it out, 3 swaps it with the next), and the rest
/// the last chunk's setup, read as [`Input`] numbers (empty: 1 kHz and the defaults).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StrokePlan {
    /// Stroke id.
    pub id: u8,
    /// Chunks sent, 0 for all.
    pub chunks: u8,
    /// Sample index (modulo the stroke's length) and its new value.
    pub glitch: Option<(u16, i16)>,
    /// Chunk fault: mode (0 none, 1 duplicate, 2 drop, 3 swap with the next) and chunk.
    pub fault: (u8, u8),
    /// The setup's bytes (see [`StrokePlan::setup`]).
    pub setup: Vec<u8>,
}

impl StrokePlan {
    fn read(a: u8, b: u8, body: &[u8]) -> Self {
        let glitch = (body.len() >= 4).then(|| {
            (
                u16::from_le_bytes([body[0], body[1]]),
                i16::from_le_bytes([body[2], body[3]]),
            )
        });
        let (fault, setup) = match body {
            [_, _, _, _, mode, k, setup @ ..] => ((mode % 4, *k), setup.to_vec()),
            _ => ((0, 0), Vec::new()),
        };
        Self {
            id: a,
            chunks: b % 8,
            glitch,
            fault,
            setup,
        }
    }

    /// The last chunk's setup: with no bytes, the stroke's rate and the defaults; else
    /// a rate mostly in [500, 8000] Hz, then each of scale, tip offset, cue mass and tip
    /// restitution absent or a number mostly in a plausible range.
    pub fn setup(&self) -> StrokeSetup {
        if self.setup.is_empty() {
            return StrokeSetup {
                rate_hz: STROKE_RATE_HZ,
                tip_offset: Some([0.0, 0.01]),
                ..StrokeSetup::default()
            };
        }
        let mut input = Input::new(&self.setup);
        let rate_hz = input.real(500.0, 8000.0);
        let scale = input.flag().then(|| input.real(-0.01, 0.01));
        let tip_offset = input.flag().then(|| input.pair(-0.02, 0.02));
        let cue_mass = input.flag().then(|| input.real(0.1, 2.0));
        let tip_restitution = input.flag().then(|| input.real(0.0, 1.0));
        StrokeSetup {
            rate_hz,
            scale,
            tip_offset,
            cue_mass,
            tip_restitution,
        }
    }

    /// The record's body.
    pub fn body(&self) -> Vec<u8> {
        let (index, value) = self.glitch.unwrap_or((u16::MAX, 0));
        let mut body = index.to_le_bytes().to_vec();
        body.extend_from_slice(&value.to_le_bytes());
        body.extend_from_slice(&[self.fault.0, self.fault.1]);
        body.extend_from_slice(&self.setup);
        body
    }

    /// The chunks, in the order sent.
    pub fn chunks(&self) -> Vec<Request> {
        let mut samples = synthetic_stroke().to_vec();
        // An index past the end (the writer's "none") glitches nothing.
        if let Some((index, value)) = self.glitch {
            if let Some(sample) = samples.get_mut(usize::from(index)) {
                *sample = value;
            }
        }
        let mut chunks = stroke_chunks(u16::from(self.id), &samples);
        if let Some(Request::Stroke(last)) = chunks.last_mut() {
            last.setup = Some(self.setup());
        }
        let n = chunks.len();
        let k = usize::from(self.fault.1) % n;
        match self.fault.0 {
            1 => chunks.insert(k, chunks[k].clone()),
            2 => {
                chunks.remove(k);
            }
            3 if k + 1 < n => chunks.swap(k, k + 1),
            _ => {}
        }
        if self.chunks > 0 {
            chunks.truncate(usize::from(self.chunks));
        }
        chunks
    }
}

/// `samples` as the chunks of stroke `id`, [`MAX_SAMPLES`] each, the last with the rate.
pub fn stroke_chunks(id: u16, samples: &[i16]) -> Vec<Request> {
    let parts: Vec<&[i16]> = samples.chunks(MAX_SAMPLES).collect();
    let count = parts.len() as u16;
    parts
        .iter()
        .enumerate()
        .map(|(i, part)| {
            Request::Stroke(StrokeChunk {
                stroke: id,
                index: i as u16,
                count,
                samples: heapless::Vec::from_slice(part).expect("a chunk fits"),
                setup: (i + 1 == parts.len()).then_some(StrokeSetup {
                    rate_hz: STROKE_RATE_HZ,
                    tip_offset: Some([0.0, 0.01]),
                    ..StrokeSetup::default()
                }),
            })
        })
        .collect()
}

/// Sample rate of [`synthetic_stroke`] (Hz).
pub const STROKE_RATE_HZ: f32 = 1000.0;

/// Cue speed at the impact of [`synthetic_stroke`] (m/s).
pub const STROKE_SPEED: f64 = 2.5;

/// Raw words (LSM6DSOX, ±16 g) of a stroke at 1 kHz reaching 2.5 m/s at the impact, as
/// `host-tests/src/strokes.rs` draws them (rest 0.4 s, a half-cosine backswing, a pause,
/// a half-cosine forward stroke, a −50 g impact clipped at the full scale, a
/// follow-through; cue tilt, offset and 8 mg RMS noise from a fixed seed): 1,332
/// samples.
pub fn synthetic_stroke() -> &'static [i16] {
    static STROKE: OnceLock<Vec<i16>> = OnceLock::new();
    STROKE.get_or_init(|| {
        const G: f64 = 9.806_65;
        let mut state = 3u64;
        let mut uniform = move || {
            // SplitMix64.
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        let (rate, speed) = (f64::from(STROKE_RATE_HZ), STROKE_SPEED);
        let scale = f64::from(cuesight_sensors::ACCEL_MPS2_PER_LSB);
        let (rest, back, pause, forward) = (0.4, 0.45, 0.12, 0.3);
        let (impact, follow) = (0.0015, 0.06);
        let backswing = 0.12;
        let total: f64 = rest + back + pause + forward + impact + follow;
        let bias = G * 5f64.to_radians().sin() + 0.02 * G;
        let pi = std::f64::consts::PI;
        (0..(total * rate).round() as usize)
            .map(|i| {
                let t = i as f64 / rate;
                let a = if t < rest {
                    0.0
                } else if t < rest + back {
                    -backswing * pi * pi / (2.0 * back * back) * (pi * (t - rest) / back).cos()
                } else if t < rest + back + pause {
                    0.0
                } else if t < rest + back + pause + forward {
                    speed * pi / (2.0 * forward) * (pi * (t - rest - back - pause) / forward).sin()
                } else if t < rest + back + pause + forward + impact {
                    -50.0 * G
                } else {
                    -speed / 0.2
                };
                let (u1, u2) = (uniform().max(1e-12), uniform());
                let noise = 0.008 * G * (-2.0 * u1.ln()).sqrt() * (2.0 * pi * u2).cos();
                ((a + bias + noise) / scale)
                    .round()
                    .clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
            })
            .collect()
    })
}

/// Valid requests of every kind, named: what the device serves without an error
/// (the stroke's chunk 0 only starts an upload).
pub fn examples() -> &'static [(&'static str, Request)] {
    static EXAMPLES: OnceLock<Vec<(&'static str, Request)>> = OnceLock::new();
    EXAMPLES.get_or_init(|| {
        let collide = Collide::new(2.0, 30.0);
        let chunks = stroke_chunks(1, synthetic_stroke());
        vec![
            ("version", Request::Version(Empty {})),
            ("collide-stun", Request::Collide(collide)),
            (
                "collide-topspin-overrides",
                Request::Collide(Collide {
                    spin: Some([0.0, 40.0, 0.0]),
                    mu: Some(0.06),
                    mu_b: Some(0.108),
                    mu_c: Some(1.088),
                    restitution: Some(0.93),
                    mu_s: Some(0.2),
                    radius: Some(0.028575),
                    mass: Some(0.17),
                    model: Some(ModelName::Exact),
                    ..collide
                }),
            ),
            (
                "collide-roll-auto",
                Request::Collide(Collide {
                    roll: true,
                    model: Some(ModelName::Auto),
                    ..Collide::new(1.5, -45.0)
                }),
            ),
            (
                "params-set",
                Request::Params(Overrides {
                    mu: Some(0.05),
                    restitution: Some(0.9),
                    model: Some(ModelName::Kim),
                    ..Overrides::default()
                }),
            ),
            ("params-read", Request::Params(Overrides::default())),
            ("stroke-chunk-0", chunks[0].clone()),
            (
                "shot-solve",
                Request::Shot(ShotRequest {
                    cue: [0.635, 0.635],
                    balls: heapless::Vec::from_slice(&[[1.9, 0.9]]).unwrap(),
                    speed: 3.0,
                    tip: [0.0, 0.2],
                    pocket: Some(3),
                    model: Some(ModelName::Auto),
                    ..ShotRequest::default()
                }),
            ),
            (
                "shot-aim-snooker",
                Request::Shot(ShotRequest {
                    table: TableName::Snooker,
                    cue: [1.0, 0.9],
                    balls: heapless::Vec::from_slice(&[[2.5, 1.1], [3.0, 0.4]]).unwrap(),
                    speed: 2.5,
                    tip: [-0.2, -0.3],
                    aim: Some(7.6),
                    object: Some(1),
                    pocket: Some(3),
                    model: Some(ModelName::Exact),
                    ..ShotRequest::default()
                }),
            ),
            (
                "shot-carom-every-field",
                Request::Shot(ShotRequest {
                    table: TableName::Carom,
                    cue: [0.7, 0.7],
                    balls: heapless::Vec::from_slice(&[[2.0, 0.8]]).unwrap(),
                    speed: 1.0,
                    tip: [0.25, 0.1],
                    aim: Some(90.0),
                    object: Some(1),
                    pocket: None,
                    mu_cloth: Some(0.25),
                    mu_roll: Some(0.015),
                    cue_mass: Some(0.5),
                    tip_restitution: Some(0.8),
                    mu: Some(0.00995),
                    mu_b: Some(0.108),
                    mu_c: Some(1.088),
                    restitution: Some(0.93),
                    mu_s: Some(0.2),
                    mass: Some(0.16),
                    model: Some(ModelName::Kim),
                }),
            ),
            ("shutdown", Request::Shutdown(Empty {})),
        ]
    })
}

// ---------------------------------------------------------------------------------------
// The frame layout, written out again (link/src/frame.rs's module docs).

/// COBS-encodes `raw` (without the zero).
pub fn cobs_encode(raw: &[u8]) -> Vec<u8> {
    let mut out = vec![0];
    let mut code_at = 0;
    for &byte in raw {
        if byte != 0 {
            out.push(byte);
        }
        if byte == 0 || out.len() - code_at == 0xff {
            out[code_at] = (out.len() - code_at) as u8;
            code_at = out.len();
            out.push(0);
        }
    }
    out[code_at] = (out.len() - code_at) as u8;
    out
}

/// A COBS piece (the bytes between two zeros) decoded: the bytes it yields, and whether
/// it ends where its last block does (else it was cut short: not valid COBS).
pub fn cobs_decode(piece: &[u8]) -> (Vec<u8>, bool) {
    let mut raw = Vec::new();
    let mut i = 0;
    while i < piece.len() {
        let code = usize::from(piece[i]);
        let end = (i + code).min(piece.len());
        raw.extend_from_slice(&piece[i + 1..end]);
        if i + code > piece.len() {
            return (raw, false);
        }
        i += code;
        if code < 0xff && i < piece.len() {
            raw.push(0);
        }
    }
    (raw, true)
}

/// CRC-32/ISO-HDLC (reflected 0x04C11DB7, init and xor-out all ones), bit by bit.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A whole frame on the wire, its zero included: schema, seq, body, CRC, COBS.
pub fn wire(schema: u32, seq: u16, body: &[u8]) -> Vec<u8> {
    let mut raw = schema.to_le_bytes().to_vec();
    raw.extend_from_slice(&seq.to_le_bytes());
    raw.extend_from_slice(body);
    raw.extend_from_slice(&crc32(&raw).to_le_bytes());
    let mut wire = cobs_encode(&raw);
    wire.push(0);
    wire
}

/// What the link's reader and `open` must make of one piece, by the layout.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Expected {
    /// More than [`MAX_RAW`] raw bytes: `Oversized` with the piece's length.
    Oversized(u32),
    /// Cut short: `Cobs`.
    Cobs,
    /// Fewer than ten raw bytes: `Short`.
    Short(u16),
    /// The CRC does not hold: `Crc` with the seq as read.
    Crc(u16),
    /// A frame that opens: header and body.
    Open {
        /// Schema hash.
        schema: u32,
        /// Sequence number.
        seq: u16,
        /// The raw frame.
        raw: Vec<u8>,
    },
}

/// What one piece (the non-zero bytes before a zero) is, by the layout.
pub fn expected(piece: &[u8]) -> Expected {
    let (raw, whole) = cobs_decode(piece);
    if raw.len() > MAX_RAW {
        return Expected::Oversized(piece.len() as u32);
    }
    if !whole {
        return Expected::Cobs;
    }
    if raw.len() < 10 {
        return Expected::Short(raw.len() as u16);
    }
    let (content, crc) = raw.split_at(raw.len() - 4);
    let seq = u16::from_le_bytes([content[4], content[5]]);
    if crc32(content) != u32::from_le_bytes([crc[0], crc[1], crc[2], crc[3]]) {
        return Expected::Crc(seq);
    }
    Expected::Open {
        schema: u32::from_le_bytes([content[0], content[1], content[2], content[3]]),
        seq,
        raw,
    }
}

/// The pieces of a stream: the bytes before each zero (empty ones included), and what
/// is left after the last zero.
pub fn pieces(stream: &[u8]) -> (Vec<&[u8]>, &[u8]) {
    let mut pieces: Vec<&[u8]> = stream.split(|&b| b == 0).collect();
    let rest = pieces.pop().unwrap_or_default();
    (pieces, rest)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight_link::frame;

    #[test]
    fn the_oracle_encodes_as_the_link_does() {
        for (name, request) in examples() {
            for seq in [0, 1, 0x0100, u16::MAX] {
                let mut out = [0u8; MAX_FRAME];
                let len = frame::encode(SCHEMA_HASH, seq, request, &mut out).unwrap();
                assert_eq!(
                    wire(SCHEMA_HASH, seq, &body_of(request)),
                    &out[..len],
                    "{name}"
                );
            }
        }
        for len in 0..700 {
            for fill in [0u8, 1, 0xff] {
                let raw = vec![fill; len];
                let encoded = cobs_encode(&raw);
                assert!(!encoded.contains(&0));
                assert_eq!(cobs_decode(&encoded), (raw, true), "{len} x {fill}");
            }
        }
    }

    #[test]
    fn a_stroke_plan_reads_back() {
        let plan = StrokePlan {
            id: 4,
            chunks: 3,
            glitch: Some((100, i16::MIN)),
            fault: (1, 2),
            setup: crate::input::Writer::new()
                .real(500.0, 8000.0, 3333.0)
                .flag(false)
                .flag(true)
                .pair(-0.02, 0.02, [0.0, 0.005])
                .bytes()
                .to_vec(),
        };
        let mut script = Script::new();
        script.record(op::STROKE, plan.id, plan.chunks, &plan.body());
        let bytes = script.bytes();
        assert_eq!(StrokePlan::read(bytes[1], bytes[2], &bytes[5..]), plan);
        assert_eq!(plan.chunks().len(), 3);
        assert_eq!(
            StrokePlan::default().chunks().len(),
            synthetic_stroke().len().div_ceil(MAX_SAMPLES)
        );
    }
}
