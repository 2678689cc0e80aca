//! End-to-end: the release firmware in QEMU, driven over its serial port in link frames
//! (`cuesight_link::frame`), every answer compared with an in-process host
//! [`Session`] (the "mirror") fed the very same bytes: the answer frames must be equal
//! byte for byte (the physics compiled for the host and for the Cortex-M4F agree to the
//! bit), and each must also be what this test expects of its frame.
//!
//! 1. 250 seeded `collide` requests over the grid's domain (every core model, natural
//!    roll, speed-dependent friction).
//! 2. Synthetic strokes uploaded in chunks, one of them filling the whole
//!    [`STROKE_CAPACITY`] window (5,000 samples in equal chunks).
//! 3. Hostile frames, at least [`PER_CLASS`] of each class, interleaved with valid
//!    requests; each must get exactly one answer, a typed error of the expected variant
//!    (with the sequence number, chunk and sample it names), and after each class a
//!    valid request must get its normal answer:
//!    * duplicate (a frame sent again, same seq) → `Sequence(Duplicate)`;
//!    * drop (seqs skipped) → `Sequence(Gap)`;
//!    * reorder (an older frame replayed, or two frames swapped) → `Sequence(Stale)`
//!      (the first of a swapped pair: `Gap`);
//!    * truncate (a frame cut short, then its `0x00`) → `Frame(Cobs | Short | Crc)`;
//!    * bit flip (one bit of the raw frame, re-encoded; or of the COBS bytes, never
//!      making a zero) → `Frame(Crc)` (`Cobs` or `Short` when a COBS code byte flipped);
//!    * wrong schema (a valid frame with another schema hash) → `SchemaMismatch`;
//!    * oversized (more than `MAX_FRAME` bytes before the `0x00`) → `Frame(Oversized)`;
//!    * stroke chunks duplicated, skipped or reordered under fresh seqs →
//!      `Upload(Duplicate | Missing | NotStarted)`;
//!    * glitch sample (a stroke with a −32768 in its rest window) →
//!      `Upload(Glitch)` naming the chunk and the sample.
//! 4. `shutdown`: its counts are the frames sent and the error answers received; no
//!    frame follows it; QEMU exits 0.
//!
//! Frames are pipelined (up to [`WINDOW`] bytes in flight, well under a pipe's 64 KiB,
//! so a write never waits on a stuck firmware) and the work is split over
//! [`DEFAULT_INSTANCES`] firmware instances booted side by side (`CUESIGHT_E2E_QEMUS`
//! overrides): QEMU moves one UART byte per main-loop turn (~20 µs of two threads'
//! time), so the 10,000 oversized frames alone (over `MAX_FRAME` bytes each) take
//! minutes in one instance; each instance runs its share of every class and is checked
//! on its own. A table of the figures closes the output.
//!
//! Needs the release firmware and QEMU, so it is `#[ignore]`d in a plain `cargo test`;
//! `cargo xtask test` builds the firmware and runs it:
//! `cargo test -p cuesight-host --test e2e -- --ignored --nocapture`
//! (`CUESIGHT_FIRMWARE_ELF` overrides the ELF path, `DEFMT_PRINT` the log decoder).

use cuesight_figures::thousands;
use std::collections::{BTreeMap, VecDeque};
use std::path::Path;
use std::process::ExitStatus;
use std::time::{Duration, Instant};

use cuesight_device::{Identity, Session};
use cuesight_host::firmware::{self, cobs_frame, open_answer, Answer, Firmware, Incoming};
use cuesight_host::grid;
use cuesight_host::strokes::{stroke_chunks, synthetic_stroke, synthetic_stroke_of};
use cuesight_link::error::{FrameFault, SequenceFault};
use cuesight_link::frame::{self, FrameReader, MAX_FRAME, MAX_RAW};
use cuesight_link::{
    Collide, Empty, LinkError, ModelName, Overrides, Request, Response, StrokeChunk, StrokeSetup,
    UploadFault, MAX_CHUNKS, MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY, UNPROMPTED,
};
use cuesight_sensors::GlitchKind;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Hostile frames of each of the eight classes of issue 14, over all instances.
const PER_CLASS: usize = 10_000;
/// Hostile frames of each stroke-chunk class (duplicated, missing, reordered chunk).
const PER_CHUNK_CLASS: usize = 1_000;
/// Seeded collide requests.
const COLLIDES: usize = 250;
/// Firmware instances booted side by side.
const DEFAULT_INSTANCES: usize = 2;
/// Bytes sent but not yet answered, at most.
const WINDOW: usize = 32 * 1024;
/// The longest wait for one answer (a collide under a loaded machine is milliseconds).
const ANSWER_TIMEOUT: Duration = Duration::from_secs(60);
/// Synthetic strokes: (seed, sample rate in Hz, cue speed at impact in m/s, samples:
/// `None` for the generator's 1.33 s, or exactly this many).
const STROKES: [(u64, f64, f64, Option<usize>); 5] = [
    (11, 3333.0, 1.5, None),
    (12, 3333.0, 3.0, None),
    (13, 3333.0, 5.0, None),
    (14, 1000.0, 0.8, None),
    (15, 3333.0, 2.5, Some(STROKE_CAPACITY)),
];
/// Fault kinds a truncated frame or a flipped COBS byte may get.
const CUT_FAULTS: &[&str] = &["cobs", "short", "crc"];

/// What a frame is, for the tally.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Class {
    Control,
    Collide,
    Stroke,
    Duplicate,
    Drop,
    Reorder,
    Truncate,
    BitFlip,
    Schema,
    Oversized,
    ChunkDuplicate,
    ChunkMissing,
    ChunkReorder,
    Glitch,
    /// The valid request after each class.
    Probe,
}

/// The hostile classes, in the order each instance runs them: the glitch class last
/// (it depends on the sensors crate's detector, and a failure there should not hide
/// the others).
const HOSTILE: [Class; 11] = [
    Class::Duplicate,
    Class::Drop,
    Class::Reorder,
    Class::Truncate,
    Class::BitFlip,
    Class::Schema,
    Class::Oversized,
    Class::ChunkDuplicate,
    Class::ChunkMissing,
    Class::ChunkReorder,
    Class::Glitch,
];

impl Class {
    fn name(self) -> &'static str {
        match self {
            Class::Control => "version/shutdown",
            Class::Collide => "collide",
            Class::Stroke => "stroke",
            Class::Duplicate => "duplicate",
            Class::Drop => "drop",
            Class::Reorder => "reorder",
            Class::Truncate => "truncate",
            Class::BitFlip => "bit flip",
            Class::Schema => "wrong schema",
            Class::Oversized => "oversized",
            Class::ChunkDuplicate => "chunk duplicated",
            Class::ChunkMissing => "chunk missing",
            Class::ChunkReorder => "chunk reordered",
            Class::Glitch => "glitch sample",
            Class::Probe => "probe after class",
        }
    }

    /// Hostile frames this class must reach over all instances.
    fn quota(self) -> usize {
        match self {
            Class::ChunkDuplicate | Class::ChunkMissing | Class::ChunkReorder => PER_CHUNK_CLASS,
            _ => PER_CLASS,
        }
    }
}

/// What an answer must be.
#[derive(Clone, Debug)]
enum Check {
    /// A normal answer of this kind ([`kind`]) with this seq.
    Answer { seq: u16, kind: &'static str },
    /// Exactly this error, with this seq.
    Error { seq: u16, error: LinkError },
    /// A frame fault of one of these kinds ([`fault_name`]), unprompted seq.
    Fault(&'static [&'static str]),
}

impl Check {
    /// The error this check expects, by [`error_name`].
    fn error(&self) -> Option<String> {
        match self {
            Check::Error { error, .. } => Some(error_name(error)),
            _ => None,
        }
    }

    fn verify(&self, answer: &Answer) -> Result<(), String> {
        let ok = match self {
            Check::Answer { seq, kind: want } => {
                answer.seq == *seq && kind(&answer.response) == *want
            }
            Check::Error { seq, error } => {
                answer.seq == *seq && answer.response == Response::Error(*error)
            }
            Check::Fault(kinds) => {
                answer.seq == UNPROMPTED
                    && matches!(answer.response, Response::Error(LinkError::Frame(fault))
                        if kinds.contains(&fault_name(&fault)))
            }
        };
        if ok {
            Ok(())
        } else {
            Err(format!(
                "expected {self:?}, got seq {} {:?}",
                answer.seq, answer.response
            ))
        }
    }
}

/// What a request's accepted answer is.
#[derive(Clone, Copy, Debug)]
enum Accepted {
    Kind(&'static str),
    Error(LinkError),
}

/// The response's variant, as named in JSON.
fn kind(response: &Response) -> &'static str {
    match response {
        Response::Version(_) => "version",
        Response::Collide(_) => "collide",
        Response::Params(_) => "params",
        Response::StrokeChunk(_) => "stroke_chunk",
        Response::Stroke(_) => "stroke",
        Response::Shot(_) => "shot",
        Response::Plan(_) => "plan",
        Response::Live(_) => "live",
        Response::Shutdown(_) => "shutdown",
        Response::Error(_) => "error",
    }
}

fn fault_name(fault: &FrameFault) -> &'static str {
    match fault {
        FrameFault::Cobs => "cobs",
        FrameFault::Oversized { .. } => "oversized",
        FrameFault::Short { .. } => "short",
        FrameFault::Crc { .. } => "crc",
        FrameFault::Undecodable => "undecodable",
        FrameFault::TrailingBytes { .. } => "trailing_bytes",
    }
}

/// An error's variant path (`frame.crc`, `sequence.gap`, `upload.glitch`, ...).
fn error_name(error: &LinkError) -> String {
    match error {
        LinkError::Frame(fault) => format!("frame.{}", fault_name(fault)),
        LinkError::SchemaMismatch { .. } => "schema_mismatch".to_owned(),
        LinkError::Sequence(SequenceFault::Duplicate { .. }) => "sequence.duplicate".to_owned(),
        LinkError::Sequence(SequenceFault::Stale { .. }) => "sequence.stale".to_owned(),
        LinkError::Sequence(SequenceFault::Gap { .. }) => "sequence.gap".to_owned(),
        LinkError::Upload(fault) => {
            let name = format!("{fault:?}");
            let end = name.find([' ', '{', '(']).unwrap_or(name.len());
            format!("upload.{}", snake(&name[..end]))
        }
        other => {
            let name = format!("{other:?}");
            let end = name.find(['(', ' ', '{']).unwrap_or(name.len());
            let mut out = snake(&name[..end]);
            if let Some(inner) = name.get(end + 1..).filter(|_| name[end..].starts_with('(')) {
                let inner_end = inner.find(['(', ' ', '{', ')']).unwrap_or(inner.len());
                out = format!("{out}.{}", snake(&inner[..inner_end]));
            }
            out
        }
    }
}

fn snake(camel: &str) -> String {
    let mut out = String::new();
    for (i, c) in camel.chars().enumerate() {
        if c.is_ascii_uppercase() {
            if i > 0 {
                out.push('_');
            }
            out.push(c.to_ascii_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// A host session fed the bytes the firmware gets: what the firmware must answer.
struct Mirror {
    session: Box<Session>,
    reader: Box<FrameReader>,
    out: Vec<u8>,
}

impl Mirror {
    fn new(identity: Identity) -> Self {
        Self {
            session: Box::new(Session::new(identity)),
            reader: Box::new(FrameReader::new()),
            out: vec![0; MAX_FRAME],
        }
    }

    /// The answer frames (COBS-decoded) to `bytes`.
    fn feed(&mut self, bytes: &[u8]) -> Vec<Incoming> {
        let mut answers = Vec::new();
        for &byte in bytes {
            if let Some(received) = self.reader.push(byte) {
                let served = self.session.serve(received, &mut self.out);
                answers.extend(cut_frames(&self.out[..served.len]));
            }
        }
        answers
    }
}

/// The frames in `bytes`, as the harness's reader cuts them.
fn cut_frames(bytes: &[u8]) -> Vec<Incoming> {
    let mut reader = FrameReader::new();
    bytes
        .iter()
        .filter_map(|&b| reader.push(b).map(Incoming::from_received))
        .collect()
}

/// Figures of one class on one instance (or summed).
#[derive(Clone, Debug, Default)]
struct Tally {
    hostile: usize,
    valid: usize,
    bytes: usize,
    answers: usize,
    errors: BTreeMap<String, usize>,
    seconds: f64,
}

impl Tally {
    fn add(&mut self, other: &Tally) {
        self.hostile += other.hostile;
        self.valid += other.valid;
        self.bytes += other.bytes;
        self.answers += other.answers;
        for (name, n) in &other.errors {
            *self.errors.entry(name.clone()).or_default() += n;
        }
        self.seconds += other.seconds;
    }
}

/// A frame sent, its answer not yet read.
struct Pending {
    class: Class,
    number: usize,
    len: usize,
    check: Check,
    /// The mirror's answer.
    mirror: Incoming,
    /// Whether the mirror's answer passed `check`.
    mirror_ok: bool,
    what: String,
}

/// What one instance did.
struct Report {
    index: usize,
    tallies: BTreeMap<Class, Tally>,
    mismatches: BTreeMap<Class, usize>,
    failures: Vec<String>,
    frames: usize,
    errors: usize,
    differ: usize,
    bytes: usize,
    seconds: f64,
    status: Option<ExitStatus>,
    peak_stack: Option<String>,
    collide_models: BTreeMap<&'static str, usize>,
    stroke_truth: Vec<(usize, f64, f64)>,
    /// Glitch strokes of the generator's full length (or the whole window).
    long_glitches: usize,
}

/// One booted firmware, its mirror, and the test's model of the sequence check.
struct Device {
    index: usize,
    fw: Firmware,
    mirror: Mirror,
    rng: ChaCha8Rng,
    queue: VecDeque<Pending>,
    in_flight: usize,
    /// The seq of the last frame the device accepted (`None` before the first).
    last: Option<u16>,
    /// Recent valid frames (seq, bytes, answer kind), for replays.
    history: VecDeque<(u16, Vec<u8>, &'static str)>,
    stroke_id: u16,
    frames: usize,
    error_answers: usize,
    /// Answers not equal, byte for byte, to the host session's.
    differ: usize,
    bytes: usize,
    tallies: BTreeMap<Class, Tally>,
    mismatches: BTreeMap<Class, usize>,
    failures: Vec<String>,
    last_answer: Option<Answer>,
    started: Instant,
    collide_models: BTreeMap<&'static str, usize>,
    stroke_truth: Vec<(usize, f64, f64)>,
    long_glitches: usize,
}

impl Device {
    fn boot(index: usize, elf: &Path, defmt_print: Option<&Path>) -> Self {
        let started = Instant::now();
        let fw = Firmware::boot(elf, defmt_print)
            .unwrap_or_else(|e| panic!("QEMU {index} does not boot the firmware: {e}"));
        let hello = fw
            .next_frame(ANSWER_TIMEOUT)
            .unwrap_or_else(|e| panic!("QEMU {index}: no version frame at boot: {e}"));
        let answer = open_answer(&hello).unwrap_or_else(|e| panic!("QEMU {index}: {e}"));
        assert_eq!(answer.seq, UNPROMPTED, "the boot frame is unprompted");
        let Response::Version(version) = &answer.response else {
            panic!("QEMU {index}: boot frame {:?}", answer.response)
        };
        let stale = "the firmware was built from another link than this test: rebuild it";
        assert_eq!(version.schema, SCHEMA_HASH, "{stale}");
        assert_eq!(usize::from(version.max_frame), MAX_FRAME, "{stale}");
        assert_eq!(usize::from(version.max_samples), MAX_SAMPLES, "{stale}");
        assert_eq!(
            usize::from(version.stroke_capacity),
            STROKE_CAPACITY,
            "{stale}"
        );
        // The mirror says who it is as the firmware does, so even `version` answers are
        // equal byte for byte.
        let leak = |s: &str| -> &'static str { Box::leak(s.to_owned().into_boxed_str()) };
        let mirror = Mirror::new(Identity {
            firmware: leak(&version.firmware),
            board: leak(&version.board),
        });
        let mut out = vec![0u8; MAX_FRAME];
        let len = mirror.session.hello(&mut out);
        assert_eq!(
            cut_frames(&out[..len]),
            vec![hello],
            "the boot frame is the host session's hello"
        );
        if index == 0 {
            println!(
                "e2e: {} on {}, schema {:#010x}, frames up to {} B, strokes up to {} samples, shot {}",
                version.firmware,
                version.board,
                version.schema,
                version.max_frame,
                version.stroke_capacity,
                version.shot
            );
        }
        Self {
            index,
            fw,
            mirror,
            rng: ChaCha8Rng::seed_from_u64(14_000 + index as u64),
            queue: VecDeque::new(),
            in_flight: 0,
            last: None,
            history: VecDeque::new(),
            stroke_id: 100 * index as u16,
            frames: 0,
            error_answers: 0,
            differ: 0,
            bytes: 0,
            tallies: BTreeMap::new(),
            mismatches: BTreeMap::new(),
            failures: Vec::new(),
            last_answer: None,
            started,
            collide_models: BTreeMap::new(),
            stroke_truth: Vec::new(),
            long_glitches: 0,
        }
    }

    fn fail(&mut self, class: Class, message: String) {
        let count = self.mismatches.entry(class).or_default();
        *count += 1;
        if *count <= 5 {
            self.failures
                .push(format!("QEMU {} {}: {message}", self.index, class.name()));
        }
    }

    /// Sends one unit of bytes ending in one `0x00` (one frame as the device cuts it).
    fn send(&mut self, class: Class, hostile: bool, bytes: Vec<u8>, check: Check, what: String) {
        assert_eq!(bytes.last(), Some(&0), "a unit ends with its zero");
        assert_eq!(
            bytes.iter().filter(|&&b| b == 0).count(),
            1,
            "one zero per unit"
        );
        let mut host = self.mirror.feed(&bytes);
        assert_eq!(host.len(), 1, "the host session answers {what} once");
        let mirror = host.remove(0);
        let mirror_ok = open_answer(&mirror).is_ok_and(|answer| check.verify(&answer).is_ok());
        while self.in_flight + bytes.len() > WINDOW && !self.queue.is_empty() {
            self.receive_one();
        }
        self.fw
            .send_bytes(&bytes)
            .unwrap_or_else(|e| panic!("QEMU {}: writing {what}: {e}", self.index));
        let tally = self.tallies.entry(class).or_default();
        if hostile {
            tally.hostile += 1;
        } else {
            tally.valid += 1;
        }
        tally.bytes += bytes.len();
        self.frames += 1;
        self.bytes += bytes.len();
        self.in_flight += bytes.len();
        self.queue.push_back(Pending {
            class,
            number: self.frames,
            len: bytes.len(),
            check,
            mirror,
            mirror_ok,
            what,
        });
    }

    /// Reads the oldest frame's answer and checks it.
    fn receive_one(&mut self) {
        let pending = self.queue.pop_front().expect("a frame in flight");
        self.in_flight -= pending.len;
        let incoming = self.fw.next_frame(ANSWER_TIMEOUT).unwrap_or_else(|e| {
            panic!(
                "QEMU {}: no answer to frame #{} ({}, {}): {e}",
                self.index,
                pending.number,
                pending.class.name(),
                pending.what
            )
        });
        let class = pending.class;
        self.tallies.entry(class).or_default().answers += 1;
        let verdict = match open_answer(&incoming) {
            Ok(answer) => {
                if let Response::Error(error) = &answer.response {
                    self.error_answers += 1;
                    *self
                        .tallies
                        .entry(class)
                        .or_default()
                        .errors
                        .entry(error_name(error))
                        .or_default() += 1;
                }
                let verdict = pending.check.verify(&answer);
                self.last_answer = Some(answer);
                verdict
            }
            Err(e) => Err(format!("unreadable answer: {e}")),
        };
        let same = incoming == pending.mirror;
        if !same {
            self.differ += 1;
        }
        if !same || verdict.is_err() {
            let context = format!("frame #{} ({})", pending.number, pending.what);
            let message = match (same, verdict) {
                (true, Err(e)) => format!(
                    "{context}: {e} (the host session answers the same: the link's logic, not the firmware)"
                ),
                (false, verdict) => format!(
                    "{context}: the firmware's answer {incoming:?} is not the host session's {:?} \
                     (which {} the expectation); {}",
                    pending.mirror,
                    if pending.mirror_ok { "meets" } else { "misses" },
                    verdict.err().unwrap_or_else(|| "the firmware's meets it".to_owned())
                ),
                (true, Ok(())) => unreachable!(),
            };
            self.fail(class, message);
        }
    }

    fn drain(&mut self) {
        while !self.queue.is_empty() {
            self.receive_one();
        }
    }

    /// The seq the device expects next.
    fn next_seq(&self) -> u16 {
        self.last.map_or(0, following)
    }

    /// The device's sequence check on a (non-`version`) frame `seq`, as the link
    /// documents it, and the model moved on as the device moves on.
    fn sequence(&mut self, seq: u16) -> Option<SequenceFault> {
        let Some(last) = self.last else {
            self.last = Some(seq);
            return None;
        };
        let expected = following(last);
        if seq == expected {
            self.last = Some(seq);
            None
        } else if seq == last {
            Some(SequenceFault::Duplicate { seq })
        } else if expected.wrapping_sub(seq) < 0x8000 {
            Some(SequenceFault::Stale { seq, expected })
        } else {
            self.last = Some(seq);
            Some(SequenceFault::Gap { seq, expected })
        }
    }

    /// Sends an encoded request frame with `seq`; returns the check it got.
    #[allow(clippy::too_many_arguments)]
    fn send_encoded(
        &mut self,
        class: Class,
        hostile: bool,
        seq: u16,
        version: bool,
        bytes: Vec<u8>,
        accepted: Accepted,
        what: String,
    ) -> Check {
        let verdict = if version {
            self.last = Some(seq);
            None
        } else {
            self.sequence(seq)
        };
        let check = match (verdict, accepted) {
            (Some(fault), _) => Check::Error {
                seq,
                error: LinkError::Sequence(fault),
            },
            (None, Accepted::Kind(kind)) => Check::Answer { seq, kind },
            (None, Accepted::Error(error)) => Check::Error { seq, error },
        };
        if verdict.is_none() {
            if let Accepted::Kind(kind) = accepted {
                self.history.push_back((seq, bytes.clone(), kind));
                if self.history.len() > 16 {
                    self.history.pop_front();
                }
            }
        }
        self.send(class, hostile, bytes, check.clone(), what);
        check
    }

    /// Sends `request` as frame `seq`.
    fn request(
        &mut self,
        class: Class,
        hostile: bool,
        seq: u16,
        request: &Request,
        accepted: Accepted,
    ) -> (Vec<u8>, Check) {
        let bytes = firmware::request_frame(seq, request).expect("the request encodes");
        let what = format!("{} seq {seq}", request.name());
        let version = matches!(request, Request::Version(_));
        let check = self.send_encoded(class, hostile, seq, version, bytes.clone(), accepted, what);
        (bytes, check)
    }

    /// Sends `request` as the next frame in sequence.
    fn valid(&mut self, class: Class, request: &Request, accepted: Accepted) -> Vec<u8> {
        let seq = self.next_seq();
        let (bytes, check) = self.request(class, false, seq, request, accepted);
        assert!(!check.error().is_some_and(|e| e.starts_with("sequence.")));
        bytes
    }

    /// A `version` request with a random seq: restarts the count.
    fn restart(&mut self, class: Class) {
        let seq = self.rng.random();
        self.request(
            class,
            false,
            seq,
            &Request::Version(Empty {}),
            Accepted::Kind("version"),
        );
        self.history.clear();
    }

    /// A cheap valid request (collide with a random model, or a `params` read) and the
    /// kind of its answer.
    fn cheap_request(&mut self) -> (Request, Accepted) {
        let rng = &mut self.rng;
        if rng.random_bool(0.3) {
            return (
                Request::Params(Overrides::default()),
                Accepted::Kind("params"),
            );
        }
        let models = core_models();
        let collide = Collide {
            spin: Some([
                rng.random_range(-20.0..20.0),
                rng.random_range(-80.0..80.0),
                rng.random_range(-40.0..40.0),
            ]),
            model: Some(models[rng.random_range(0..models.len())]),
            ..Collide::new(rng.random_range(0.3..5.0), rng.random_range(-75.0..75.0))
        };
        (Request::Collide(collide), Accepted::Kind("collide"))
    }

    fn cheap_valid(&mut self, class: Class) {
        let (request, accepted) = self.cheap_request();
        self.valid(class, &request, accepted);
    }

    /// A request to corrupt: a cheap one, a stroke chunk (up to 64 random samples) or a
    /// shot.
    fn source_request(&mut self) -> (Request, Accepted) {
        match self.rng.random_range(0..10) {
            0..=6 => self.cheap_request(),
            7 | 8 => {
                let len = self.rng.random_range(1..=MAX_SAMPLES.min(64));
                let samples = (0..len).map(|_| self.rng.random::<i16>()).collect();
                let stroke = self.fresh_stroke_id();
                let chunk = StrokeChunk {
                    stroke,
                    index: 0,
                    count: 2,
                    samples,
                    setup: None,
                };
                (Request::Stroke(chunk), Accepted::Kind("stroke_chunk"))
            }
            _ => {
                let body = cuesight_host::shot_scenes::random_body(&mut self.rng);
                let shot = serde_json::from_value(body).expect("a shot request");
                (Request::Shot(shot), Accepted::Kind("shot"))
            }
        }
    }

    fn fresh_stroke_id(&mut self) -> u16 {
        self.stroke_id = self.stroke_id.wrapping_add(1);
        self.stroke_id
    }

    /// Runs one class's share: `quota` hostile frames, then a probe.
    fn segment(&mut self, class: Class, quota: usize) {
        let started = Instant::now();
        self.restart(class);
        let before = self.tallies.get(&class).map_or(0, |t| t.hostile);
        while self.tallies.get(&class).map_or(0, |t| t.hostile) - before < quota {
            match class {
                Class::Duplicate => self.duplicate(),
                Class::Drop => self.drop_frames(),
                Class::Reorder => self.reorder(),
                Class::Truncate => self.truncate(),
                Class::BitFlip => self.bit_flip(),
                Class::Schema => self.wrong_schema(),
                Class::Oversized => self.oversized(),
                Class::ChunkDuplicate => self.chunk_duplicate(),
                Class::ChunkMissing => self.chunk_missing(),
                Class::ChunkReorder => self.chunk_reorder(),
                Class::Glitch => self.glitch(),
                other => unreachable!("{other:?} is not hostile"),
            }
        }
        self.drain();
        self.probe();
        self.tallies.entry(class).or_default().seconds += started.elapsed().as_secs_f64();
    }

    /// A valid collide after a class: the firmware keeps serving.
    fn probe(&mut self) {
        let request = Request::Collide(Collide {
            roll: true,
            mu: Some(0.06),
            ..Collide::new(2.0, 30.0)
        });
        self.valid(Class::Probe, &request, Accepted::Kind("collide"));
        self.drain();
    }

    // --- the hostile classes: each call sends at least one hostile frame ---

    /// A valid frame, then the same bytes once to three times.
    fn duplicate(&mut self) {
        let (request, accepted) = self.cheap_request();
        let seq = self.next_seq();
        let (bytes, _) = self.request(Class::Duplicate, false, seq, &request, accepted);
        for _ in 0..self.rng.random_range(1..=3) {
            let what = format!("duplicate of {} seq {seq}", request.name());
            let check = self.send_encoded(
                Class::Duplicate,
                true,
                seq,
                false,
                bytes.clone(),
                accepted,
                what,
            );
            assert_eq!(check.error().as_deref(), Some("sequence.duplicate"));
        }
    }

    /// Frames lost: the next frame skips 1 to 3 seqs (one in 50 up to 32,768); then,
    /// half the time, a frame in sequence.
    fn drop_frames(&mut self) {
        let skip = if self.rng.random_bool(0.02) {
            self.rng.random_range(1..=0x8000u16)
        } else {
            self.rng.random_range(1..=3)
        };
        let seq = self.next_seq().wrapping_add(skip);
        let (request, accepted) = self.cheap_request();
        let (_, check) = self.request(Class::Drop, true, seq, &request, accepted);
        assert_eq!(check.error().as_deref(), Some("sequence.gap"));
        if self.rng.random_bool(0.5) {
            self.cheap_valid(Class::Drop);
        }
    }

    /// A valid frame, then an older frame replayed (one of the last 16 valid ones), or
    /// two frames swapped.
    fn reorder(&mut self) {
        self.cheap_valid(Class::Reorder);
        if self.rng.random_bool(0.7) {
            let last = self.last;
            let older: Vec<usize> = (0..self.history.len())
                .filter(|&i| Some(self.history[i].0) != last)
                .collect();
            let Some(&pick) = older.get(self.rng.random_range(0..older.len().max(1))) else {
                return;
            };
            let (seq, bytes, kind) = self.history[pick].clone();
            let what = format!("replay of seq {seq}");
            let check = self.send_encoded(
                Class::Reorder,
                true,
                seq,
                false,
                bytes,
                Accepted::Kind(kind),
                what,
            );
            assert_eq!(check.error().as_deref(), Some("sequence.stale"));
        } else {
            let first = self.next_seq();
            let (a, accepted_a) = self.cheap_request();
            let (b, accepted_b) = self.cheap_request();
            let (_, check) =
                self.request(Class::Reorder, true, first.wrapping_add(1), &b, accepted_b);
            assert_eq!(check.error().as_deref(), Some("sequence.gap"));
            let (_, check) = self.request(Class::Reorder, true, first, &a, accepted_a);
            assert_eq!(check.error().as_deref(), Some("sequence.stale"));
        }
    }

    /// A frame cut short (at least one byte kept) and ended; then, most of the time,
    /// the whole frame again.
    fn truncate(&mut self) {
        let (request, accepted) = self.source_request();
        let seq = self.next_seq();
        let whole = firmware::request_frame(seq, &request).expect("encodes");
        let keep = self.rng.random_range(1..whole.len() - 1);
        let mut cut = whole[..keep].to_vec();
        cut.push(0);
        let what = format!(
            "{} seq {seq} cut to {keep} of {} bytes",
            request.name(),
            whole.len() - 1
        );
        self.send(Class::Truncate, true, cut, Check::Fault(CUT_FAULTS), what);
        if self.rng.random_bool(0.6) && !matches!(request, Request::Shot(_)) {
            self.request(Class::Truncate, false, seq, &request, accepted);
        }
    }

    /// One bit flipped: of the raw frame (re-encoded; always a CRC fault, which reports
    /// the seq as read), or of the COBS bytes (never making a zero); then, most of the
    /// time, the intact frame.
    fn bit_flip(&mut self) {
        let (request, accepted) = self.source_request();
        let seq = self.next_seq();
        let whole = firmware::request_frame(seq, &request).expect("encodes");
        let (flipped, check, what) = if self.rng.random_bool(0.5) {
            let mut raw = vec![0u8; MAX_RAW];
            let len = cobs::decode(&whole[..whole.len() - 1], &mut raw).expect("valid COBS");
            raw.truncate(len);
            let bit = self.rng.random_range(0..len * 8);
            raw[bit / 8] ^= 1 << (bit % 8);
            let seq_as_read = u16::from_le_bytes([raw[4], raw[5]]);
            let check = Check::Error {
                seq: UNPROMPTED,
                error: LinkError::Frame(FrameFault::Crc { seq_as_read }),
            };
            let what = format!(
                "{} seq {seq}, raw bit {bit} of {} flipped",
                request.name(),
                len * 8
            );
            (cobs_frame(&raw), check, what)
        } else {
            let mut bytes = whole.clone();
            let (at, mask) = loop {
                let at = self.rng.random_range(0..bytes.len() - 1);
                let mask = 1u8 << self.rng.random_range(0..8);
                if bytes[at] ^ mask != 0 {
                    break (at, mask);
                }
            };
            bytes[at] ^= mask;
            let what = format!("{} seq {seq}, COBS byte {at} ^ {mask:#04x}", request.name());
            (bytes, Check::Fault(CUT_FAULTS), what)
        };
        self.send(Class::BitFlip, true, flipped, check, what);
        if self.rng.random_bool(0.6) && !matches!(request, Request::Shot(_)) {
            self.request(Class::BitFlip, false, seq, &request, accepted);
        }
    }

    /// A valid frame under another schema hash (random, one bit off, 0 or all ones),
    /// with the seq the device expects; then, half the time, a valid frame.
    fn wrong_schema(&mut self) {
        let (request, _) = self.cheap_request();
        let seq = self.next_seq();
        let host = loop {
            let candidate = match self.rng.random_range(0..10) {
                0 => 0,
                1 => u32::MAX,
                2..=4 => SCHEMA_HASH ^ (1 << self.rng.random_range(0..32)),
                _ => self.rng.random(),
            };
            if candidate != SCHEMA_HASH {
                break candidate;
            }
        };
        let mut bytes = vec![0u8; MAX_FRAME];
        let len = frame::encode(host, seq, &request, &mut bytes).expect("encodes");
        bytes.truncate(len);
        let check = Check::Error {
            seq,
            error: LinkError::SchemaMismatch {
                device: SCHEMA_HASH,
                host,
            },
        };
        let what = format!("{} seq {seq} with schema {host:#010x}", request.name());
        self.send(Class::Schema, true, bytes, check, what);
        if self.rng.random_bool(0.5) {
            self.cheap_valid(Class::Schema);
        }
    }

    /// More than `MAX_FRAME` bytes before the zero: random raw content COBS-encoded
    /// (`MAX_FRAME` + 1 to + 64 raw bytes; one in 100 up to 4 × `MAX_FRAME`), or random
    /// non-zero bytes that need not be COBS (1.125 to 1.25 × `MAX_FRAME`); then, a third
    /// of the time, a valid frame.
    fn oversized(&mut self) {
        let bytes = if self.rng.random_bool(0.9) {
            let len = if self.rng.random_bool(0.01) {
                self.rng.random_range(MAX_FRAME + 64..=4 * MAX_FRAME)
            } else {
                self.rng.random_range(MAX_FRAME + 1..=MAX_FRAME + 64)
            };
            let raw: Vec<u8> = (0..len).map(|_| self.rng.random()).collect();
            cobs_frame(&raw)
        } else {
            let len = self.rng.random_range(MAX_FRAME * 9 / 8..=MAX_FRAME * 5 / 4);
            let mut junk: Vec<u8> = (0..len).map(|_| self.rng.random_range(1..=255)).collect();
            junk.push(0);
            junk
        };
        let length = bytes.len() - 1;
        assert!(length > MAX_FRAME);
        let check = Check::Error {
            seq: UNPROMPTED,
            error: LinkError::Frame(FrameFault::Oversized {
                length: length as u32,
            }),
        };
        self.send(
            Class::Oversized,
            true,
            bytes,
            check,
            format!("{length} bytes"),
        );
        if self.rng.random_bool(0.33) {
            self.cheap_valid(Class::Oversized);
        }
    }

    /// Chunks 0..=k of a stroke of 3 to 8 small chunks (4 to 24 random samples), sent
    /// in sequence; `count` and the stroke id with them.
    fn chunk_prefix(&mut self, class: Class, k: u16, count: u16) -> u16 {
        let stroke = self.fresh_stroke_id();
        for index in 0..=k {
            let chunk = self.small_chunk(stroke, index, count);
            self.valid(
                class,
                &Request::Stroke(chunk),
                Accepted::Kind("stroke_chunk"),
            );
        }
        stroke
    }

    fn small_chunk(&mut self, stroke: u16, index: u16, count: u16) -> StrokeChunk {
        let len = self.rng.random_range(4..=24);
        StrokeChunk {
            stroke,
            index,
            count,
            samples: (0..len).map(|_| self.rng.random_range(-500..500)).collect(),
            setup: (index + 1 == count).then_some(StrokeSetup {
                rate_hz: 1000.0,
                ..StrokeSetup::default()
            }),
        }
    }

    /// Sends chunk `index` of `stroke` under a fresh seq; it must fail with `fault`.
    fn bad_chunk(&mut self, class: Class, stroke: u16, index: u16, count: u16, fault: UploadFault) {
        let chunk = self.small_chunk(stroke, index, count);
        let seq = self.next_seq();
        let (_, check) = self.request(
            class,
            true,
            seq,
            &Request::Stroke(chunk),
            Accepted::Error(LinkError::Upload(fault)),
        );
        assert!(check.error().is_some_and(|e| e.starts_with("upload.")));
    }

    /// Chunks 0..=k, then one of 1..=k again: `Duplicate`; a third of the time the next
    /// chunk after it: `NotStarted` (the upload was dropped).
    fn chunk_duplicate(&mut self) {
        let count = self.rng.random_range(3..=8);
        let k = self.rng.random_range(1..count - 1);
        let stroke = self.chunk_prefix(Class::ChunkDuplicate, k, count);
        let again = self.rng.random_range(1..=k);
        let fault = UploadFault::Duplicate {
            stroke,
            chunk: again,
        };
        self.bad_chunk(Class::ChunkDuplicate, stroke, again, count, fault);
        if self.rng.random_bool(0.33) {
            let fault = UploadFault::NotStarted {
                stroke,
                chunk: k + 1,
            };
            self.bad_chunk(Class::ChunkDuplicate, stroke, k + 1, count, fault);
        }
    }

    /// Chunks 0..=k, then one further than k + 1: `Missing`.
    fn chunk_missing(&mut self) {
        let count = self.rng.random_range(3..=8);
        let k = self.rng.random_range(0..count - 2);
        let stroke = self.chunk_prefix(Class::ChunkMissing, k, count);
        let ahead = self.rng.random_range(k + 2..count);
        let fault = UploadFault::Missing {
            stroke,
            expected: k + 1,
            chunk: ahead,
        };
        self.bad_chunk(Class::ChunkMissing, stroke, ahead, count, fault);
    }

    /// Chunks 0..=k, then k + 2 before k + 1 (`Missing`, then `NotStarted`); or a
    /// stroke whose first chunk to arrive is not chunk 0 (`NotStarted`).
    fn chunk_reorder(&mut self) {
        let count = self.rng.random_range(3..=8);
        if self.rng.random_bool(0.7) {
            let k = self.rng.random_range(0..count - 2);
            let stroke = self.chunk_prefix(Class::ChunkReorder, k, count);
            let fault = UploadFault::Missing {
                stroke,
                expected: k + 1,
                chunk: k + 2,
            };
            self.bad_chunk(Class::ChunkReorder, stroke, k + 2, count, fault);
            let fault = UploadFault::NotStarted {
                stroke,
                chunk: k + 1,
            };
            self.bad_chunk(Class::ChunkReorder, stroke, k + 1, count, fault);
        } else {
            let stroke = self.fresh_stroke_id();
            let first = self.rng.random_range(1..count);
            let fault = UploadFault::NotStarted {
                stroke,
                chunk: first,
            };
            self.bad_chunk(Class::ChunkReorder, stroke, first, count, fault);
        }
    }

    /// A stroke with one −32768 in its rest window: mostly a short one at 1 kHz (rest,
    /// a forward push, an impact at the negative rail, a stop) in 1 to 3 chunks (2 to 4
    /// when it needs two); one in 500 the generator's full stroke at 3.33 kHz in chunks
    /// of `MAX_SAMPLES`, or one filling the whole window. Every chunk but the last is held; the last gets `Upload(Glitch)`
    /// naming the chunk and the sample in it.
    fn glitch(&mut self) {
        let stroke = self.fresh_stroke_id();
        let (samples, at, rate, parts) = if self.rng.random_bool(0.002) {
            let count = self.rng.random_bool(0.5).then_some(STROKE_CAPACITY);
            let seed = self.rng.random();
            let speed = self.rng.random_range(1.0..4.0);
            let mut s = synthetic_stroke_of(seed, 3333.0, speed, count);
            // The generator's rest is its first 0.4 s (1,333 samples).
            let at = self.rng.random_range(40..1_200);
            s.samples[at] = i16::MIN;
            let size = if count.is_some() {
                window_chunk()
            } else {
                MAX_SAMPLES
            };
            let sizes = vec![size; s.samples.len().div_ceil(size)];
            self.long_glitches += 1;
            (s.samples, at, 3333.0, sizes)
        } else {
            let (samples, at) = compact_glitch_stroke(&mut self.rng);
            let fewest = samples.len().div_ceil(MAX_SAMPLES);
            let parts = self.rng.random_range(fewest..=fewest + 2);
            let sizes = loop {
                // Random cuts; again if a part is empty or over MAX_SAMPLES.
                let mut cuts: Vec<usize> = (1..parts)
                    .map(|_| self.rng.random_range(1..samples.len()))
                    .collect();
                cuts.push(0);
                cuts.push(samples.len());
                cuts.sort_unstable();
                let sizes: Vec<usize> = cuts.windows(2).map(|w| w[1] - w[0]).collect();
                if sizes.iter().all(|&n| (1..=MAX_SAMPLES).contains(&n)) {
                    break sizes;
                }
            };
            (samples, at, 1000.0, sizes)
        };
        // Cut the samples by the `parts` sizes (the last part may be shorter).
        let mut chunks: Vec<Vec<i16>> = Vec::new();
        let mut start = 0;
        for &size in &parts {
            let end = (start + size).min(samples.len());
            chunks.push(samples[start..end].to_vec());
            start = end;
        }
        assert_eq!(start, samples.len());
        let count = chunks.len() as u16;
        let (mut chunk_of, mut sample_of, mut first) = (0u16, 0u16, 0usize);
        for (i, c) in chunks.iter().enumerate() {
            if at >= first && at < first + c.len() {
                chunk_of = i as u16;
                sample_of = (at - first) as u16;
            }
            first += c.len();
        }
        for (i, part) in chunks.into_iter().enumerate() {
            let last = i + 1 == count as usize;
            let chunk = StrokeChunk {
                stroke,
                index: i as u16,
                count,
                samples: part.into_iter().collect(),
                setup: last.then_some(StrokeSetup {
                    rate_hz: rate,
                    ..StrokeSetup::default()
                }),
            };
            let accepted = if last {
                Accepted::Error(LinkError::Upload(UploadFault::Glitch {
                    stroke,
                    chunk: chunk_of,
                    sample: sample_of,
                    kind: GlitchKind::Rail,
                    value: i16::MIN,
                }))
            } else {
                Accepted::Kind("stroke_chunk")
            };
            let seq = self.next_seq();
            self.request(Class::Glitch, last, seq, &Request::Stroke(chunk), accepted);
        }
    }

    // --- the valid parts ---

    /// The seeded collide requests, against the host session.
    fn collides(&mut self) {
        let started = Instant::now();
        for request in collide_requests() {
            let model = request.model.expect("a model").name();
            *self.collide_models.entry(model).or_default() += 1;
            self.valid(
                Class::Collide,
                &Request::Collide(request),
                Accepted::Kind("collide"),
            );
        }
        self.drain();
        self.tallies.entry(Class::Collide).or_default().seconds += started.elapsed().as_secs_f64();
    }

    /// The synthetic strokes in chunks of `MAX_SAMPLES` (the full window in equal
    /// chunks, [`window_chunk`]), against the host session; the last chunk of each gets
    /// the estimate.
    fn strokes(&mut self) {
        let started = Instant::now();
        for (seed, rate, speed, count) in STROKES {
            let stroke = synthetic_stroke_of(seed, rate, speed, count);
            let size = if count.is_some() {
                window_chunk()
            } else {
                MAX_SAMPLES
            };
            let id = self.fresh_stroke_id();
            let chunks = stroke_chunks(&stroke, id, size);
            let n = chunks.len();
            assert!(n <= MAX_CHUNKS, "{n} chunks");
            for (i, chunk) in chunks.into_iter().enumerate() {
                let kind = if i + 1 == n { "stroke" } else { "stroke_chunk" };
                self.valid(Class::Stroke, &Request::Stroke(chunk), Accepted::Kind(kind));
            }
            self.drain();
            if let Some(Answer {
                response: Response::Stroke(answer),
                ..
            }) = &self.last_answer
            {
                assert_eq!(usize::from(answer.samples), stroke.samples.len());
                self.stroke_truth
                    .push((stroke.samples.len(), speed, f64::from(answer.cue_speed)));
            }
        }
        self.tallies.entry(Class::Stroke).or_default().seconds += started.elapsed().as_secs_f64();
    }

    /// `shutdown`, its counts, the end of the serial output, QEMU's exit.
    fn shutdown(mut self) -> Report {
        self.drain();
        // The last class's probe already showed the firmware serving; one more stroke,
        // a whole one, shows the upload working after all the faults.
        let stroke = synthetic_stroke(21 + self.index as u64, 3333.0, 2.0);
        let id = self.fresh_stroke_id();
        let chunks = stroke_chunks(&stroke, id, MAX_SAMPLES);
        let n = chunks.len();
        for (i, chunk) in chunks.into_iter().enumerate() {
            let kind = if i + 1 == n { "stroke" } else { "stroke_chunk" };
            self.valid(Class::Probe, &Request::Stroke(chunk), Accepted::Kind(kind));
        }
        self.valid(
            Class::Control,
            &Request::Shutdown(Empty {}),
            Accepted::Kind("shutdown"),
        );
        self.drain();
        let Some(Answer {
            response: Response::Shutdown(stats),
            ..
        }) = self.last_answer.clone()
        else {
            panic!(
                "QEMU {}: no shutdown answer: {:?}",
                self.index, self.last_answer
            )
        };
        // The shutdown answer counts itself as a request, and is no error.
        if stats.requests as usize != self.frames || stats.errors as usize != self.error_answers {
            self.fail(
                Class::Control,
                format!(
                    "shutdown counts {} requests, {} errors; sent {} frames, received {} error answers",
                    stats.requests, stats.errors, self.frames, self.error_answers
                ),
            );
        }
        if let Ok(extra) = self.fw.next_frame(Duration::from_millis(500)) {
            self.fail(
                Class::Control,
                format!("a frame after the shutdown answer: {extra:?}"),
            );
        }
        let seconds = self.started.elapsed().as_secs_f64();
        let Device {
            index,
            fw,
            tallies,
            mismatches,
            failures,
            frames,
            error_answers,
            differ,
            bytes,
            collide_models,
            stroke_truth,
            long_glitches,
            ..
        } = self;
        let ended = fw.wait(Duration::from_secs(30));
        let peak_stack = ended
            .log
            .iter()
            .find(|line| line.contains("peak stack"))
            .cloned();
        if ended.status.is_none_or(|s| !s.success()) {
            for line in &ended.log {
                eprintln!("QEMU {index} log: {line}");
            }
        }
        Report {
            index,
            tallies,
            mismatches,
            failures,
            frames,
            errors: error_answers,
            differ,
            bytes,
            seconds,
            status: ended.status,
            peak_stack,
            collide_models,
            stroke_truth,
            long_glitches,
        }
    }
}

/// The largest chunk that cuts the whole window into equal chunks.
fn window_chunk() -> usize {
    (1..=MAX_SAMPLES)
        .rev()
        .find(|d| STROKE_CAPACITY % d == 0)
        .expect("1 divides")
}

/// The core's models the device serves: all but `SeedExact` and `Kim`, which the
/// firmware leaves out (firmware/Cargo.toml; it answers `invalid: model_left_out`, the
/// host session, built with them, would answer the collision).
fn core_models() -> Vec<ModelName> {
    ModelName::ALL
        .into_iter()
        .filter(|m| m.core().is_some() && !matches!(m, ModelName::SeedExact | ModelName::Kim))
        .collect()
}

/// The seeded collide requests: grid scenes as speed and cut angle, cycling through the
/// core's models; every 7th with natural roll, every 5th with TP A.14's
/// speed-dependent friction.
fn collide_requests() -> Vec<Collide> {
    let models = core_models();
    grid::scenes(2024, COLLIDES)
        .iter()
        .enumerate()
        .map(|(i, scene)| {
            let [vx, vy] = scene.velocity.map(f64::from);
            let (mu_b, mu_c) = if i % 5 == 4 {
                (Some(0.108), Some(1.088))
            } else {
                (None, None)
            };
            let roll = i % 7 == 3;
            Collide {
                speed: vx.hypot(vy) as f32,
                cut: vy.atan2(vx).to_degrees() as f32,
                spin: (!roll).then_some(scene.spin),
                roll,
                mu: Some(if mu_b.is_some() { 0.00995 } else { scene.mu }),
                mu_b,
                mu_c,
                restitution: Some(scene.restitution),
                mu_s: Some(scene.mu_s),
                radius: Some(scene.radius),
                mass: Some(scene.mass),
                model: Some(models[i % models.len()]),
            }
        })
        .collect()
}

/// A short stroke at 1 kHz with a −32768 in its rest: 25 to 60 samples of rest (a
/// 0.02 g offset, a cue held level, ±16 LSB of noise: one byte each on the wire), a
/// 15-sample push to 2 g, 3 to 5 samples at the negative rail (the tip impact), 10
/// samples of stop; the glitch at least 15 samples before the push. Returns the
/// samples and the glitch's index.
fn compact_glitch_stroke(rng: &mut ChaCha8Rng) -> (Vec<i16>, usize) {
    let bias = 41i16;
    let rest = rng.random_range(25..60);
    let mut samples: Vec<i16> = (0..rest)
        .map(|_| bias + rng.random_range(-16..=16))
        .collect();
    samples.extend((1..=15).map(|i| bias + 273 * i + rng.random_range(-16..=16)));
    samples.extend(std::iter::repeat_n(i16::MIN, rng.random_range(3..=5)));
    samples.extend((0..10).map(|_| bias - 800 + rng.random_range(-16..=16)));
    let at = rng.random_range(1..rest - 15);
    samples[at] = i16::MIN;
    (samples, at)
}

/// The share of `total` for instance `index` of `instances` (the shares add up to at
/// least `total`).
fn share(total: usize, instances: usize) -> usize {
    total.div_ceil(instances)
}

fn run_instance(index: usize, instances: usize, elf: &Path, defmt_print: Option<&Path>) -> Report {
    let mut device = Device::boot(index, elf, defmt_print);
    device.restart(Class::Control);
    if index == 0 {
        device.collides();
    }
    if index == 1 % instances {
        device.strokes();
    }
    for class in HOSTILE {
        device.segment(class, share(class.quota(), instances));
    }
    device.shutdown()
}

#[test]
#[ignore = "boots the release firmware in QEMU: run by `cargo xtask test` after the firmware build"]
fn firmware_in_qemu_answers_as_the_host_session_and_survives_hostile_frames() {
    let elf = firmware::default_elf();
    let defmt_print = firmware::find_defmt_print();
    let instances = std::env::var("CUESIGHT_E2E_QEMUS")
        .ok()
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| (1..=8).contains(&n))
        .unwrap_or(DEFAULT_INSTANCES);
    let started = Instant::now();
    let reports: Vec<Report> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..instances)
            .map(|i| {
                let (elf, defmt_print) = (&elf, defmt_print.as_deref());
                scope.spawn(move || run_instance(i, instances, elf, defmt_print))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
            .collect()
    });
    let wall = started.elapsed().as_secs_f64();

    // Sums over the instances.
    let mut tallies: BTreeMap<Class, Tally> = BTreeMap::new();
    let mut mismatches: BTreeMap<Class, usize> = BTreeMap::new();
    let mut models: BTreeMap<&str, usize> = BTreeMap::new();
    for report in &reports {
        for (class, tally) in &report.tallies {
            tallies.entry(*class).or_default().add(tally);
        }
        for (class, n) in &report.mismatches {
            *mismatches.entry(*class).or_default() += n;
        }
        for (model, n) in &report.collide_models {
            *models.entry(model).or_default() += n;
        }
    }

    println!();
    println!(
        "e2e: {:<18} {:>8} {:>8} {:>8} {:>9} {:>7}  answers by variant",
        "class", "hostile", "valid", "answers", "KiB sent", "s"
    );
    for (class, tally) in &tallies {
        let errors: Vec<String> = tally
            .errors
            .iter()
            .map(|(name, n)| format!("{name} {}", thousands(*n)))
            .collect();
        let normal = tally.answers - tally.errors.values().sum::<usize>();
        let mut by_variant = errors.join(", ");
        if normal > 0 {
            if !by_variant.is_empty() {
                by_variant.push_str(", ");
            }
            by_variant.push_str(&format!("normal {}", thousands(normal)));
        }
        println!(
            "e2e: {:<18} {:>8} {:>8} {:>8} {:>9.0} {:>7.1}  {by_variant}",
            class.name(),
            thousands(tally.hostile),
            thousands(tally.valid),
            thousands(tally.answers),
            tally.bytes as f64 / 1024.0,
            tally.seconds,
        );
    }
    let (frames, errors, bytes): (usize, usize, usize) =
        reports.iter().fold((0, 0, 0), |(f, e, b), r| {
            (f + r.frames, e + r.errors, b + r.bytes)
        });
    println!(
        "e2e: total: {} frames ({:.1} MB) -> {} answers, {} of them errors; {instances} QEMU \
         instance(s) side by side, {wall:.1} s wall ({:.0} kB/s in all); seconds per class are \
         summed over the instances",
        thousands(frames),
        bytes as f64 / 1e6,
        thousands(tallies.values().map(|t| t.answers).sum::<usize>()),
        thousands(errors),
        bytes as f64 / 1e3 / wall,
    );
    let differ: usize = reports.iter().map(|r| r.differ).sum();
    println!(
        "e2e: answers equal byte for byte to the host session's: {} of {}",
        thousands(frames - differ),
        thousands(frames)
    );
    println!("e2e: collide requests by model: {models:?}");
    println!(
        "e2e: glitch strokes of the generator's length or the whole window: {} (the rest \
         short ones at 1 kHz)",
        reports.iter().map(|r| r.long_glitches).sum::<usize>()
    );
    for report in &reports {
        for (samples, truth, got) in &report.stroke_truth {
            println!(
                "e2e: stroke of {samples} samples: cue speed {got:.4} m/s, generated at {truth} m/s ({:+.2} %)",
                100.0 * (got - truth) / truth
            );
        }
        println!(
            "e2e: QEMU {}: {} frames, {} error answers (the shutdown's counts), {:.1} s, exit {:?}; {}",
            report.index,
            thousands(report.frames),
            thousands(report.errors),
            report.seconds,
            report.status,
            report.peak_stack.as_deref().unwrap_or("no 'peak stack' log line")
        );
    }

    // The checks, the glitch class last.
    let failures: Vec<&String> = reports.iter().flat_map(|r| &r.failures).collect();
    for failure in &failures {
        eprintln!("e2e: FAILED: {failure}");
    }
    let mut problems = Vec::new();
    for (class, n) in &mismatches {
        let answers = tallies.get(class).map_or(0, |t| t.answers);
        problems.push(format!(
            "{} of {} answers wrong in class {}",
            thousands(*n),
            thousands(answers),
            class.name()
        ));
    }
    for class in HOSTILE {
        let hostile = tallies.get(&class).map_or(0, |t| t.hostile);
        if hostile < class.quota() {
            problems.push(format!("{} only {hostile} hostile frames", class.name()));
        }
    }
    for report in &reports {
        if report.status.is_none_or(|s| !s.success()) {
            problems.push(format!(
                "QEMU {} ended with {:?}",
                report.index, report.status
            ));
        }
    }
    let stroke_count = reports.iter().map(|r| r.stroke_truth.len()).sum::<usize>();
    if stroke_count != STROKES.len() {
        problems.push(format!(
            "{stroke_count} of {} strokes estimated",
            STROKES.len()
        ));
    }
    for report in &reports {
        for (_, truth, got) in &report.stroke_truth {
            if ((got - truth) / truth).abs() > 0.03 {
                problems.push(format!("stroke estimate {got} m/s for {truth} m/s"));
            }
        }
    }
    assert!(problems.is_empty(), "e2e: {}", problems.join("; "));

    // The figures docs/protocol.md and docs/reliability.md quote: every count of the
    // table above, for the instance count `cargo xtask test` runs (the work is split
    // per instance, each with its own seed).
    if instances == DEFAULT_INSTANCES {
        let slug = |name: &str| name.replace(['.', '_', ' ', '/'], "-");
        for (class, tally) in &tallies {
            let class = slug(class.name());
            if tally.hostile > 0 {
                let key = format!("protocol-e2e-{class}-hostile");
                cuesight_figures::record!(&key, "{}", thousands(tally.hostile));
            }
            if tally.valid > 0 {
                let key = format!("protocol-e2e-{class}-valid");
                cuesight_figures::record!(&key, "{}", thousands(tally.valid));
            }
            for (name, n) in &tally.errors {
                let key = format!("protocol-e2e-{class}-{}", slug(name));
                cuesight_figures::record!(&key, "{}", thousands(*n));
            }
        }
        cuesight_figures::record!("protocol-e2e-frames", "{}", thousands(frames));
        cuesight_figures::record!("protocol-e2e-megabytes", "{:.1}", bytes as f64 / 1e6);
        cuesight_figures::record!("protocol-e2e-errors", "{}", thousands(errors));
        cuesight_figures::record!("protocol-e2e-collide-models", "{}", models.len());
        let stroke_error_pct = reports
            .iter()
            .flat_map(|r| &r.stroke_truth)
            .map(|(_, truth, got)| 100.0 * ((got - truth) / truth).abs())
            .fold(0.0f64, f64::max);
        cuesight_figures::record!("protocol-e2e-stroke-error-max", "{stroke_error_pct:.2}");
        let peak_stack = reports
            .iter()
            .filter_map(|r| r.peak_stack.as_deref())
            .filter_map(|line| line.split("peak stack ").nth(1)?.split_whitespace().next())
            .filter_map(|n| n.parse::<usize>().ok())
            .max();
        if let Some(peak_stack) = peak_stack {
            cuesight_figures::record!("protocol-e2e-peak-stack", "{}", thousands(peak_stack));
        }
    }
}

/// The number after `seq`, as docs/protocol.md §4 documents it: hosts count 0 … 0xFFFE and
/// wrap to 0 (0xFFFF numbers the device's unprompted frames; a request never carries it).
fn following(seq: u16) -> u16 {
    if seq >= 0xFFFE {
        0
    } else {
        seq + 1
    }
}
