//! The cuesight firmware's serial protocol: newline-delimited JSON requests and answers,
//! `no_std` and heap-free (fixed buffers from heapless). The device reads and writes the
//! JSON by hand (`decode.rs`, `encode.rs`: the same text serde-json-core read and wrote,
//! without its generic code); hosts use the serde impls here with serde_json.
//!
//! One request per line, one answer line per request, in order:
//!
//! ```text
//! → {"collide":{"speed":2,"cut":30,"spin":[0,40,0],"mu":0.06}}
//! ← {"collide":{"model":"kim-grip","regime":"sliding","input":{...},"cue":{...},...}}
//! → {"collide":{"speed":-1,"cut":0}}
//! ← {"error":{"kind":"out_of_range","field":"speed","message":"speed = -1 is outside (0, 100] m/s"}}
//! ```
//!
//! The schema, with examples, is in `docs/protocol.md`. The same types serve both ends:
//! the firmware decodes with [`decode`] and answers with [`Session::serve`]; the host
//! serializes [`Request`]s and reads [`Answer`]s with serde_json, and the `cuesight`
//! CLI prints a [`CollideAnswer`] for `collide --json`.
//!
//! ```
//! use cuesight_protocol::{AnswerLine, Identity, Session};
//! let mut session = Session::new(Identity { firmware: "doc 0", board: "none" });
//! let mut out = AnswerLine::new();
//! session.serve_line(br#"{"collide":{"speed":2,"cut":30}}"#, &mut out);
//! assert!(out.starts_with(br#"{"collide":{"model":"kim-grip","regime":"sliding""#));
//! session.serve_line(br#"{"collide":{"speed":2,"cut":30,"spin":[0,0]}}"#, &mut out);
//! assert!(out.starts_with(br#"{"error":{"kind":"wrong_type","field":"spin""#));
//! ```
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod answer;
mod decimal;
mod decode;
mod display;
mod encode;
pub mod json;
mod line;
mod names;
mod problem;
pub mod request;
mod session;
#[cfg(feature = "shot")]
pub mod shot;
mod text;

pub use answer::{Answer, CollideAnswer, ErrorAnswer, InputEcho, StrokeAnswer, StrokeChunkAnswer};
pub use decode::decode;
pub use display::Summary;
pub use line::{Event, LineReader};
pub use names::{ModelName, RegimeName};
pub use problem::{ErrorKind, Message, Name, NotARequest, Problem, MESSAGE_LEN, NAME_LEN};
pub use request::{Collide, Defaults, Overrides, Request, Spin, Stroke};
pub use session::{AnswerLine, Control, Identity, Served, Session};
#[cfg(feature = "shot")]
pub use shot::{Shot, ShotAnswer, TableName};

/// Protocol version, reported by `version`. Bumped on any incompatible change of a
/// request or answer.
pub const PROTOCOL_VERSION: u32 = 1;

/// Longest request line, in bytes without the `\n` (a `\r` before it counts). Holds a
/// `stroke` chunk of [`MAX_SAMPLES`] samples of up to 9 characters each (2,304 bytes)
/// and its other fields; `collide` needs about 200.
pub const MAX_LINE: usize = 3 * 1024;

/// Longest answer line, `\n` included. The largest answer is `shot`'s: 1,903 bytes seen,
/// at most about 2,450 with every number at its longest (14 characters; checked by
/// `host-tests/tests/shot_protocol.rs`); `collide`'s is at most 782 bytes.
pub const MAX_ANSWER: usize = 2560;

/// Most accelerometer samples in one `stroke` chunk (one line). Kept small because the
/// decoded chunk travels by value through the decoder: the firmware's peak stack
/// grows with it (1,024 took it past 30 KB; the stack budget is 8 KB).
pub const MAX_SAMPLES: usize = 256;

/// Most samples in one stroke, all chunks: 1.5 s at the LSM6DSOX's 3.33 kHz, the rate
/// the device captures strokes at (0.75 s at 6.66 kHz). 10 KB of `i16`, held by the
/// [`Session`]: sized so the firmware's static RAM stays within its 16 KiB budget
/// (issue 6) next to the line and answer buffers. The estimator reaches 0.95 % at
/// 3.33 kHz (`docs/sensors.md`).
pub const STROKE_CAPACITY: usize = 5_000;
