//! The streaming stroke estimator's bench (`stream-count`, issue 15's per-sample
//! budget): the sample stream baked into the image by `build.rs`, and the functions
//! whose calls `cargo xtask bench` counts.
//!
//! Stream layout, little-endian: magic `b"CSS1"`, the sample rate (`f32`, Hz), the
//! sample count (`u32`), then per sample the accelerometer's cue-axis word and the
//! gyro's pitch-rate word (`i16` each, raw LSM6DSOX LSBs).
//!
//! [`bench_stream_push`] is what a sampling interrupt calls per sample: `push_raw` with
//! a pitch word. Its calls are counted from an instruction trace (QEMU
//! `-d exec,nochain` with one instruction per block): from its first instruction to
//! its return, callees included; the caller's `bl` is not counted. The trace tells
//! each call's caller apart by the unmangled names of [`bench_stream_loop`] (every
//! sample, in order) and [`bench_stream_timed`] (the timer cross-check).

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight_sensors::{StreamEvent, StreamFault, StreamingEstimator};

use crate::out::Out;
use crate::timer;

static BLOB: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/stream.bin"));

const MAGIC: &[u8; 4] = b"CSS1";
const HEADER: usize = 12;
const STRIDE: usize = 4;

/// One estimator step: the signature of [`bench_stream_push`] and [`bench_stream_empty`].
pub type Push = fn(&mut StreamingEstimator, i16, i16) -> Option<StreamEvent>;

/// The baked stream (header checked).
pub struct Stream {
    /// Sample rate (Hz).
    pub rate_hz: f32,
    /// Number of samples.
    pub len: usize,
}

impl Stream {
    /// The baked stream, or `None` if the image was built without one (or it is
    /// malformed).
    pub fn baked() -> Option<Self> {
        if BLOB.len() < HEADER || &BLOB[..4] != MAGIC {
            return None;
        }
        let rate_hz = f32::from_le_bytes(BLOB[4..8].try_into().ok()?);
        let len = u32::from_le_bytes(BLOB[8..12].try_into().ok()?) as usize;
        if BLOB.len() != HEADER + len * STRIDE {
            return None;
        }
        Some(Self { rate_hz, len })
    }

    /// Sample `index` (`< len`): the accelerometer and pitch words.
    #[inline(always)]
    pub fn get(&self, index: usize) -> (i16, i16) {
        let at = HEADER + index * STRIDE;
        match BLOB.get(at..at + STRIDE) {
            Some(&[a0, a1, p0, p1]) => (i16::from_le_bytes([a0, a1]), i16::from_le_bytes([p0, p1])),
            _ => (0, 0),
        }
    }
}

/// What is counted: one sample, as the sampling interrupt hands it over (the
/// accelerometer's cue axis and the gyro's pitch axis). Unmangled, so that the
/// instruction trace can find it.
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_push(
    estimator: &mut StreamingEstimator,
    accel: i16,
    pitch: i16,
) -> Option<StreamEvent> {
    estimator.push_raw(accel, Some(pitch))
}

/// The empty call: same signature, returns `None` at once.
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_empty(_: &mut StreamingEstimator, _: i16, _: i16) -> Option<StreamEvent> {
    None
}

/// Ticks for the first `samples` samples of `stream` through `push`. The loop is the
/// same machine code whatever `push` is.
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_timed(
    push: Push,
    estimator: &mut StreamingEstimator,
    stream: &Stream,
    samples: usize,
) -> u32 {
    let push = black_box(push);
    let samples = black_box(samples);
    let start = timer::now();
    for index in 0..samples {
        let (accel, pitch) = stream.get(index);
        let event = push(estimator, accel, pitch);
        black_box(&event);
    }
    timer::elapsed(start, timer::now())
}

/// Every sample of `stream` through `push`, in order, with a `stream-mark <index>
/// <what>` line where something observable happened: `rest-end` (a stroke starts
/// integrating), `re-anchor` (a later rest replaces its origin), `stroke-end` (it stops
/// without an event: `max_stroke`), or the event (`stroke`, `follow-through`,
/// `double-hit`, `not-at-rest`, `not-forward`, `saturated`, `not-finite`).
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_loop(
    push: Push,
    estimator: &mut StreamingEstimator,
    stream: &Stream,
    out: &mut Out,
) {
    let push = black_box(push);
    for index in 0..stream.len {
        let (accel, pitch) = stream.get(index);
        let before = estimator.rest_end();
        let event = push(estimator, accel, pitch);
        let after = estimator.rest_end();
        let what = match (event, before, after) {
            (Some(event), _, _) => name(&event),
            (None, None, Some(_)) => "rest-end",
            (None, Some(_), None) => "stroke-end",
            (None, Some(a), Some(b)) if a != b => "re-anchor",
            _ => continue,
        };
        let _ = writeln!(out, "stream-mark {index} {what}");
    }
}

/// The event's name in `stream-mark` lines.
fn name(event: &StreamEvent) -> &'static str {
    match event {
        StreamEvent::Stroke(_) => "stroke",
        StreamEvent::FollowThrough { .. } => "follow-through",
        StreamEvent::Fault(fault) => match fault {
            StreamFault::NotAtRest { .. } => "not-at-rest",
            StreamFault::DoubleHit { .. } => "double-hit",
            StreamFault::Saturated { .. } => "saturated",
            StreamFault::NotForward { .. } => "not-forward",
            StreamFault::NotFinite { .. } => "not-finite",
            StreamFault::EndedMidStroke { .. } => "ended-mid-stroke",
        },
    }
}

/// The semihosting command line (QEMU: the `arg=` values of `-semihosting-config`,
/// joined by spaces) contains `word`.
#[allow(unsafe_code)]
pub fn command_line_has(word: &str) -> bool {
    let mut buffer = [0u8; 128];
    let block = [buffer.as_mut_ptr() as usize, buffer.len()];
    // SAFETY: SYS_GET_CMDLINE writes at most `buffer.len()` bytes (NUL-terminated) into
    // `buffer` and the length into `block[1]`; both outlive the call.
    let failed =
        unsafe { cortex_m_semihosting::syscall(cortex_m_semihosting::nr::GET_CMDLINE, &block) };
    if failed != 0 {
        return false;
    }
    let buffer = black_box(buffer);
    let end = buffer.iter().position(|&b| b == 0).unwrap_or(buffer.len());
    buffer[..end]
        .split(|&b| b == b' ')
        .any(|w| w == word.as_bytes())
}
