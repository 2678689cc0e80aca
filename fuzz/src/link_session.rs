//! Target `link_session`: a script (`crate::link`: valid frames of every request kind,
//! whole stroke uploads with glitches and duplicated, dropped or swapped chunks, and
//! frames resent, renumbered, truncated, bit-flipped, merged, oversized, under a foreign
//! schema, raw bytes) through the device's [`FrameReader`] into one [`Session`], as the
//! firmware serves a serial port; then a zero and a valid `version`.
//!
//! Checked for every frame: no panic; exactly one answer, a single frame of at most
//! [`MAX_FRAME`] bytes under the device's schema that decodes as a [`Response`]; the
//! answer's sequence number is [`UNPROMPTED`] for a frame that could not be read (and
//! the error is then the fault the layout predicts, `crate::link::expected`), else the
//! frame's; a frame under a foreign schema gets `SchemaMismatch` naming both hashes,
//! and a sequence error names the frame's number; an answer that is no error answers a
//! frame that decodes as a request, of the request's kind (`shutdown` with the
//! session's counts, and the only one with `Control::Shutdown`); `Served` reports what
//! the frame says; the session's request and error counters count the answers and the
//! errors; never `AnswerTooLarge` nor `NumericalFailure` (the core's guard, which
//! validated input never trips). A stroke is estimated only from a whole upload: the
//! chunks accepted since the last error or chunk 0 are chunks 0, 1, ..., count − 1 of
//! one stroke, holding the samples the estimate counts. After the script, the session
//! still serves: a valid `version` is answered with the version, and a `collide` after
//! it with a prediction.

use cuesight_device::{Control, Identity, Session};
use cuesight_link::error::{FrameFault, SequenceFault};
use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME};
use cuesight_link::{
    Collide, Empty, LinkError, ModelName, Request, Response, StrokeChunk, SCHEMA_HASH, UNPROMPTED,
};

use crate::link::{self, Expected};

/// Who answers, for `version`.
const IDENTITY: Identity = Identity {
    firmware: "cuesight-fuzz",
    board: "fuzz",
};

/// What one input reached (for checking seeds).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    /// Frames answered (the final `version` and `collide` not counted).
    pub answers: u32,
    /// The errors among them.
    pub errors: Vec<LinkError>,
    /// Stroke estimates.
    pub estimates: u32,
    /// Shot answers.
    pub shots: u32,
    /// Collide answers.
    pub collides: u32,
}

/// The device under test and what the checks remember.
struct Device {
    session: Box<Session>,
    reader: Box<FrameReader>,
    out: Box<[u8; MAX_FRAME]>,
    answers: u32,
    errors: u32,
    /// The chunks of the upload in progress, as the answers acknowledged them.
    upload: Vec<StrokeChunk>,
}

/// Runs one input (see the module docs).
pub fn run(data: &[u8]) -> Report {
    let stream = link::build(data);
    let mut device = Device {
        session: Box::new(Session::new(IDENTITY)),
        reader: Box::new(FrameReader::new()),
        out: Box::new([0; MAX_FRAME]),
        answers: 0,
        errors: 0,
        upload: Vec::new(),
    };
    let mut report = Report::default();
    let (pieces, tail) = link::pieces(&stream);
    let mut pieces = pieces.into_iter().chain([tail]);
    let mut piece = pieces.next().unwrap_or_default();
    // The stream, then a zero that ends whatever was left open.
    for &byte in stream.iter().chain([&0]) {
        if let Some(response) = device.push(byte, piece) {
            report.answers += 1;
            match &response {
                Response::Error(error) => report.errors.push(*error),
                Response::Stroke(_) => report.estimates += 1,
                Response::Shot(_) => report.shots += 1,
                Response::Collide(_) => report.collides += 1,
                _ => {}
            }
        }
        if byte == 0 {
            piece = pieces.next().unwrap_or_default();
        }
    }
    // The session keeps serving.
    let version = request_wire(0x4321, &Request::Version(Empty {}));
    let answers = device.feed(&version);
    assert!(
        matches!(&answers[..], [Response::Version(v)] if v.schema == SCHEMA_HASH),
        "after the script, version got {answers:?}"
    );
    // With `Exact`, which answers every valid input: the script may have set defaults
    // outside another model's validity domain (e.g. `params` with mu_b 0.49 makes μ(0)
    // 0.54, past `KimGrip`'s 0.15, the default model), where the session's answer is a
    // defined refusal, not a wedged session (found by this target in CI).
    let probe = Collide {
        model: Some(ModelName::Exact),
        ..Collide::new(2.0, 30.0)
    };
    let collide = request_wire(0x4322, &Request::Collide(probe));
    let answers = device.feed(&collide);
    assert!(
        matches!(&answers[..], [Response::Collide(_)]),
        "after the script, collide got {answers:?}"
    );
    report
}

/// `request` as a frame numbered `seq`.
fn request_wire(seq: u16, request: &Request) -> Vec<u8> {
    link::wire(SCHEMA_HASH, seq, &link::body_of(request))
}

impl Device {
    /// Feeds a whole frame; the answers.
    fn feed(&mut self, bytes: &[u8]) -> Vec<Response> {
        let (pieces, _) = link::pieces(bytes);
        let mut pieces = pieces.into_iter();
        let mut answers = Vec::new();
        for &byte in bytes {
            let piece = if byte == 0 {
                pieces.next().unwrap_or_default()
            } else {
                &[]
            };
            answers.extend(self.push(byte, piece));
        }
        answers
    }

    /// One byte; at a zero that ends `piece`, the answer to it, checked.
    fn push(&mut self, byte: u8, piece: &[u8]) -> Option<Response> {
        let received = self.reader.push(byte);
        if byte != 0 {
            assert!(received.is_none(), "a frame before its zero");
            return None;
        }
        let Some(received) = received else {
            assert!(piece.is_empty(), "no frame for {piece:?}");
            return None;
        };
        assert!(!piece.is_empty(), "a frame out of an empty piece");
        // What the frame is, by the layout (the reader itself is `link_frame`'s).
        let expected = link::expected(piece);
        let (expected_seq, request) = match &expected {
            Expected::Open { seq, raw, .. } => {
                let body = &raw[6..raw.len() - 4];
                let request = match postcard::take_from_bytes::<Request>(body) {
                    Ok((request, [])) => Some(request),
                    _ => None,
                };
                (*seq, request)
            }
            _ => (UNPROMPTED, None),
        };
        let served = self.session.serve(received, &mut self.out[..]);
        let (seq, response) = read_answer(&self.out[..served.len]);
        assert_eq!(
            seq, expected_seq,
            "the answer's sequence number, for {expected:?}"
        );
        self.answers += 1;
        assert_eq!(self.session.requests(), self.answers, "requests counted");
        match (&response, served.outcome) {
            (Response::Error(error), Err(reported)) => {
                assert_eq!(*error, reported, "served");
                self.errors += 1;
                check_error(error, &expected);
                // Any error drops an upload in progress.
                self.upload.clear();
            }
            (response, Ok(name)) => {
                let Some(request) = &request else {
                    panic!("{response:?} answered {expected:?}, which is no request");
                };
                assert_eq!(name, request.name(), "served");
                if let Expected::Open { schema, .. } = expected {
                    assert_eq!(schema, SCHEMA_HASH, "a foreign schema was served");
                }
                self.check_answer(request, response);
            }
            (response, Err(error)) => panic!("{response:?} served as {error:?}"),
        }
        assert_eq!(self.session.errors(), self.errors, "errors counted");
        assert_eq!(
            served.control == Control::Shutdown,
            matches!(response, Response::Shutdown(_)),
            "control {:?} for {response:?}",
            served.control
        );
        Some(response)
    }

    /// An answer that is no error, against its request.
    fn check_answer(&mut self, request: &Request, response: &Response) {
        match (request, response) {
            (Request::Version(_), Response::Version(v)) => {
                assert_eq!(v.schema, SCHEMA_HASH);
                assert_eq!(usize::from(v.max_frame), MAX_FRAME);
            }
            (Request::Collide(_), Response::Collide(_))
            | (Request::Params(_), Response::Params(_))
            | (Request::Shot(_), Response::Shot(_)) => {}
            (Request::Plan(plan), Response::Plan(set)) => assert_eq!(*set, plan.is_some()),
            (Request::Shutdown(_), Response::Shutdown(counts)) => {
                assert_eq!(counts.requests, self.session.requests(), "shutdown's count");
                assert_eq!(counts.errors, self.session.errors(), "shutdown's errors");
            }
            (Request::Stroke(chunk), Response::StrokeChunk(progress)) => {
                if chunk.index == 0 {
                    self.upload.clear();
                }
                self.upload.push(chunk.clone());
                self.check_upload(chunk.stroke, chunk.count);
                let held: usize = self.upload.iter().map(|c| c.samples.len()).sum();
                assert_eq!(
                    (progress.stroke, progress.count),
                    (chunk.stroke, chunk.count)
                );
                assert_eq!(
                    usize::from(progress.chunks),
                    self.upload.len(),
                    "{progress:?}"
                );
                assert_eq!(usize::from(progress.samples), held, "{progress:?}");
                assert!(progress.chunks < progress.count, "{progress:?}");
            }
            (Request::Stroke(chunk), Response::Stroke(estimate)) => {
                if chunk.index == 0 {
                    self.upload.clear();
                }
                self.upload.push(chunk.clone());
                self.check_upload(chunk.stroke, chunk.count);
                assert_eq!(
                    self.upload.len(),
                    usize::from(chunk.count),
                    "a partial upload estimated"
                );
                let held: usize = self.upload.iter().map(|c| c.samples.len()).sum();
                assert_eq!(usize::from(estimate.samples), held, "{estimate:?}");
                assert_eq!(estimate.stroke, chunk.stroke);
                self.upload.clear();
            }
            _ => panic!("{response:?} answered {request:?}"),
        }
    }

    /// The upload so far is chunks 0, 1, ... of one stroke, with one count.
    fn check_upload(&self, stroke: u16, count: u16) {
        for (i, chunk) in self.upload.iter().enumerate() {
            assert_eq!(
                (chunk.stroke, usize::from(chunk.index), chunk.count),
                (stroke, i, count),
                "upload {:?}",
                self.upload
                    .iter()
                    .map(|c| (c.stroke, c.index, c.count))
                    .collect::<Vec<_>>()
            );
        }
    }
}

/// An error, against what the frame is.
fn check_error(error: &LinkError, expected: &Expected) {
    assert!(
        !matches!(
            error,
            LinkError::AnswerTooLarge | LinkError::Invalid(cuesight::Error::NumericalFailure)
        ),
        "{error:?} for {expected:?}"
    );
    match (expected, error) {
        (Expected::Oversized(length), LinkError::Frame(FrameFault::Oversized { length: got })) => {
            assert_eq!(got, length)
        }
        (Expected::Cobs, LinkError::Frame(FrameFault::Cobs)) => {}
        (Expected::Short(length), LinkError::Frame(FrameFault::Short { length: got })) => {
            assert_eq!(got, length)
        }
        (Expected::Crc(seq), LinkError::Frame(FrameFault::Crc { seq_as_read })) => {
            assert_eq!(seq_as_read, seq)
        }
        (Expected::Open { schema, .. }, LinkError::SchemaMismatch { device, host }) => {
            assert_ne!(*schema, SCHEMA_HASH, "a mismatch of the same schema");
            assert_eq!((*device, *host), (SCHEMA_HASH, *schema));
        }
        (Expected::Open { schema, seq, .. }, other) => {
            assert_eq!(*schema, SCHEMA_HASH, "{other:?} for a foreign schema");
            if let LinkError::Sequence(fault) = other {
                let named = match fault {
                    SequenceFault::Duplicate { seq } => *seq,
                    SequenceFault::Stale { seq, expected }
                    | SequenceFault::Gap { seq, expected } => {
                        assert_ne!(seq, expected, "{fault:?}");
                        *seq
                    }
                };
                assert_eq!(named, *seq, "{fault:?}");
            }
            assert!(
                !matches!(
                    other,
                    LinkError::Frame(
                        FrameFault::Cobs
                            | FrameFault::Oversized { .. }
                            | FrameFault::Short { .. }
                            | FrameFault::Crc { .. }
                    )
                ),
                "{other:?} for a frame that opens"
            );
        }
        (expected, error) => panic!("{error:?} for {expected:?}"),
    }
}

/// The one frame of an answer: its sequence number and response.
fn read_answer(bytes: &[u8]) -> (u16, Response) {
    assert!(
        !bytes.is_empty() && bytes.len() <= MAX_FRAME,
        "an answer of {} bytes",
        bytes.len()
    );
    let (&zero, encoded) = bytes.split_last().expect("not empty");
    assert_eq!(zero, 0, "an answer ends in a zero");
    assert!(!encoded.contains(&0), "an answer is one frame");
    let mut reader = FrameReader::new();
    let mut answer = None;
    for &byte in bytes {
        if let Some(received) = reader.push(byte) {
            let Received::Frame(raw) = received else {
                panic!("answer {bytes:?}: {received:?}");
            };
            let (header, body) = frame::open(raw).expect("the answer opens");
            assert_eq!(header.schema, SCHEMA_HASH, "the answer's schema");
            let response = frame::decode::<Response>(body)
                .unwrap_or_else(|e| panic!("the answer does not decode: {e:?}"));
            answer = Some((header.seq, response));
        }
    }
    answer.expect("one answer frame")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::{op, Script, StrokePlan};

    #[test]
    fn a_whole_session_is_served() {
        let mut script = Script::new();
        for (_, request) in link::examples() {
            script.send(request);
        }
        script.record(op::STROKE, 2, 0, &StrokePlan::default().body());
        let report = run(script.bytes());
        assert_eq!(report.errors, []);
        assert_eq!(report.estimates, 1);
        assert_eq!(report.shots, 3);
    }

    #[test]
    fn a_duplicated_chunk_is_refused_and_nothing_estimated() {
        let plan = StrokePlan {
            fault: (1, 2),
            ..StrokePlan::default()
        };
        let mut script = Script::new();
        script.record(op::STROKE, 2, 0, &plan.body());
        let report = run(script.bytes());
        assert_eq!(report.estimates, 0);
        assert!(matches!(
            report.errors[..],
            [
                LinkError::Upload(cuesight_link::UploadFault::Duplicate { chunk: 2, .. }),
                ..
            ]
        ));
    }
}
