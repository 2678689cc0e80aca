//! The device session against hostile frames, in process: for each class — a duplicated
//! frame, a dropped one, reordered ones, a truncated one, bit flips, a lost `0x00`, an
//! oversized frame, a wrong schema hash, a glitch sample in a stroke, a duplicated,
//! missing or reordered stroke chunk (and the other upload faults) — the answer is a
//! `Response::Error` of the expected [`LinkError`], naming the right sequence number,
//! chunk or sample, and a valid request afterwards is answered as a fresh session
//! answers it: the session keeps serving.
//!
//! The bytes go through the device's [`FrameReader`] one by one into
//! [`Session::serve`]; every answer frame is read back as the host reads it
//! ([`FrameReader`], [`frame::open`], [`frame::decode`]), and its schema, sequence
//! number and the `Served` report are checked against it.

use cuesight_device::{Control, Identity, Session};
use cuesight_link::error::{FrameFault, SequenceFault};
use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME, MAX_RAW};
use cuesight_link::response::ParamsAnswer;
use cuesight_link::{
    Collide, Defaults, Empty, LinkError, Overrides, Request, Response, StrokeAnswer, StrokeChunk,
    StrokeSetup, UploadFault, MAX_CHUNKS, MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY, UNPROMPTED,
};
use cuesight_sensors::GlitchKind;

const IDENTITY: Identity = Identity {
    firmware: "session-test 1",
    board: "host",
};

/// One answer as the host read it.
#[derive(Debug)]
struct Answer {
    seq: u16,
    response: Response,
}

/// A device session and its frame reader, with the counts the session must keep.
struct Device {
    session: Session,
    reader: FrameReader,
    answers: u32,
    errors: u32,
}

impl Device {
    fn new() -> Self {
        Self {
            session: Session::new(IDENTITY),
            reader: FrameReader::new(),
            answers: 0,
            errors: 0,
        }
    }

    /// Feeds `bytes` to the device; returns its answers, read back by the host.
    fn send(&mut self, bytes: &[u8]) -> Vec<Answer> {
        let mut answers = Vec::new();
        let mut out = [0u8; MAX_FRAME];
        for &byte in bytes {
            let Some(received) = self.reader.push(byte) else {
                continue;
            };
            let served = self.session.serve(received, &mut out);
            let answer = host_read(&out[..served.len]);
            match (&answer.response, served.outcome) {
                (Response::Error(error), Err(reported)) => assert_eq!(*error, reported),
                (Response::Error(error), Ok(name)) => panic!("{error:?} served as {name}"),
                (response, Err(error)) => panic!("{response:?} served as {error:?}"),
                (_, Ok(_)) => {}
            }
            assert_eq!(
                served.control == Control::Shutdown,
                matches!(answer.response, Response::Shutdown(_))
            );
            self.answers += 1;
            self.errors += u32::from(served.outcome.is_err());
            assert_eq!(self.session.requests(), self.answers, "requests counted");
            assert_eq!(self.session.errors(), self.errors, "errors counted");
            answers.push(answer);
        }
        answers
    }

    /// Sends `bytes`, which must get exactly one answer.
    fn one(&mut self, bytes: &[u8]) -> Answer {
        let mut answers = self.send(bytes);
        assert_eq!(answers.len(), 1, "answers {answers:?}");
        answers.remove(0)
    }

    /// Sends `request` as frame `seq`; the answer, which carries `seq`.
    fn request(&mut self, seq: u16, request: &Request) -> Response {
        let answer = self.one(&wire(seq, request));
        assert_eq!(answer.seq, seq, "answer to {request:?}");
        answer.response
    }

    /// Sends `request` as frame `seq` and expects the error `expected`, with `seq`.
    fn refused(&mut self, seq: u16, request: &Request, expected: LinkError) {
        let response = self.request(seq, request);
        assert_eq!(
            response,
            Response::Error(expected),
            "to {request:?} as {seq}"
        );
    }

    /// The session still serves as a fresh one does: `collide` and `params` (read only)
    /// as frames `seq` and `seq + 1`; returns the next free sequence number.
    fn serves_normally(&mut self, seq: u16) -> u16 {
        let collide = Request::Collide(Collide::new(2.0, 30.0));
        assert_eq!(self.request(seq, &collide), fresh_answer(&collide));
        let params = Request::Params(Overrides::default());
        let seq = seq.wrapping_add(1);
        assert_eq!(
            self.request(seq, &params),
            Response::Params(ParamsAnswer::from(&Defaults::POOL))
        );
        seq.wrapping_add(1)
    }
}

/// The one frame in `bytes` as the host reads it.
fn host_read(bytes: &[u8]) -> Answer {
    assert!(
        !bytes.is_empty() && bytes.len() <= MAX_FRAME,
        "{} bytes",
        bytes.len()
    );
    let mut reader = FrameReader::new();
    let mut answer = None;
    for (i, &byte) in bytes.iter().enumerate() {
        if let Some(received) = reader.push(byte) {
            assert_eq!(i + 1, bytes.len(), "an answer is one frame");
            let Received::Frame(raw) = received else {
                panic!("answer frame: {received:?}");
            };
            let (header, body) = frame::open(raw).expect("the answer opens");
            assert_eq!(header.schema, SCHEMA_HASH, "the answer's schema");
            let response = frame::decode::<Response>(body).expect("the answer decodes");
            answer = Some(Answer {
                seq: header.seq,
                response,
            });
        }
    }
    answer.expect("one answer frame")
}

/// `request` as frame `seq`.
fn wire(seq: u16, request: &Request) -> Vec<u8> {
    wire_as(SCHEMA_HASH, seq, request)
}

fn wire_as(schema: u32, seq: u16, request: &Request) -> Vec<u8> {
    let mut out = [0u8; MAX_FRAME];
    let len = frame::encode(schema, seq, request, &mut out).expect("the request fits");
    out[..len].to_vec()
}

/// What a fresh session answers to `request` (as its first frame).
fn fresh_answer(request: &Request) -> Response {
    Device::new().request(0, request)
}

/// A device that answered `version` (frame 0) and `collide` (frame 1): frame 2 is next.
fn warm() -> Device {
    let mut device = Device::new();
    let version = device.request(0, &Request::Version(Empty {}));
    assert!(matches!(version, Response::Version(v) if v.schema == SCHEMA_HASH));
    device.request(1, &Request::Collide(Collide::new(1.0, 0.0)));
    device
}

fn collide() -> Request {
    Request::Collide(Collide::new(3.0, -20.0))
}

// ---------------------------------------------------------------------------------------
// The frame layout, written out again (as in tests/roundtrip.rs): to predict what a
// damaged frame is read as.

fn cobs_decode(encoded: &[u8]) -> Option<Vec<u8>> {
    let mut raw = Vec::new();
    let mut i = 0;
    while i < encoded.len() {
        let code = usize::from(encoded[i]);
        if code == 0 || i + code > encoded.len() {
            return None;
        }
        raw.extend_from_slice(&encoded[i + 1..i + code]);
        i += code;
        if code < 0xff && i < encoded.len() {
            raw.push(0);
        }
    }
    Some(raw)
}

fn cobs_encode(raw: &[u8]) -> Vec<u8> {
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

fn crc32(bytes: &[u8]) -> u32 {
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

/// A raw frame (schema, seq, body, CRC) COBS-encoded with its zero.
fn raw_wire(schema: u32, seq: u16, body: &[u8]) -> Vec<u8> {
    let mut raw = schema.to_le_bytes().to_vec();
    raw.extend_from_slice(&seq.to_le_bytes());
    raw.extend_from_slice(body);
    let crc = crc32(&raw);
    raw.extend_from_slice(&crc.to_le_bytes());
    let mut wire = cobs_encode(&raw);
    wire.push(0);
    wire
}

/// The fault a damaged frame's bytes (without their zero) are read as, and the
/// sequence number of its answer ([`UNPROMPTED`]: the frame's own cannot be trusted).
fn predicted_fault(encoded: &[u8]) -> FrameFault {
    if encoded.len() > MAX_FRAME {
        return FrameFault::Oversized {
            length: encoded.len() as u32,
        };
    }
    let Some(raw) = cobs_decode(encoded) else {
        return FrameFault::Cobs;
    };
    if raw.len() > MAX_RAW {
        return FrameFault::Oversized {
            length: encoded.len() as u32,
        };
    }
    if raw.len() < 10 {
        return FrameFault::Short {
            length: raw.len() as u16,
        };
    }
    let (content, crc) = raw.split_at(raw.len() - 4);
    assert_ne!(
        crc32(content),
        u32::from_le_bytes(crc.try_into().unwrap()),
        "a damaged frame whose CRC holds: {encoded:?}"
    );
    FrameFault::Crc {
        seq_as_read: u16::from_le_bytes([content[4], content[5]]),
    }
}

/// Each zero-delimited piece of `bytes` gets one answer: the error predicted for it.
fn expect_frame_faults(device: &mut Device, bytes: &[u8]) -> usize {
    let pieces: Vec<&[u8]> = bytes
        .split(|&b| b == 0)
        .filter(|piece| !piece.is_empty())
        .collect();
    let answers = device.send(bytes);
    assert_eq!(
        answers.len(),
        pieces.len(),
        "one answer per frame: {answers:?}"
    );
    for (piece, answer) in pieces.iter().zip(&answers) {
        let expected = Response::Error(LinkError::Frame(predicted_fault(piece)));
        assert_eq!(answer.response, expected, "for {piece:?}");
        assert_eq!(answer.seq, UNPROMPTED);
    }
    answers.len()
}

// ---------------------------------------------------------------------------------------
// Sequence.

#[test]
fn a_duplicated_frame_is_refused_and_the_session_goes_on() {
    let mut device = warm();
    let frame = wire(2, &collide());
    assert_eq!(device.one(&frame).response, fresh_answer(&collide()));
    let again = device.one(&frame);
    assert_eq!(
        again.response,
        Response::Error(LinkError::Sequence(SequenceFault::Duplicate { seq: 2 }))
    );
    assert_eq!(again.seq, 2, "the answer names the duplicated frame");
    device.serves_normally(3);
}

#[test]
fn a_dropped_frame_is_a_gap_and_the_count_moves_on() {
    let mut device = warm();
    // Frame 2 is lost on the way.
    device.refused(
        3,
        &collide(),
        LinkError::Sequence(SequenceFault::Gap {
            seq: 3,
            expected: 2,
        }),
    );
    // The lost one, late, is now stale.
    device.refused(
        2,
        &collide(),
        LinkError::Sequence(SequenceFault::Stale {
            seq: 2,
            expected: 4,
        }),
    );
    device.serves_normally(4);
}

#[test]
fn reordered_frames_are_refused_and_the_session_goes_on() {
    let mut device = warm();
    let (two, three, four) = (
        wire(2, &collide()),
        wire(3, &collide()),
        wire(4, &collide()),
    );
    assert_eq!(device.one(&two).response, fresh_answer(&collide()));
    // 4 overtakes 3.
    let answers = device.send(&[four, three].concat());
    let got: Vec<(u16, &Response)> = answers.iter().map(|a| (a.seq, &a.response)).collect();
    assert_eq!(
        got,
        [
            (
                4,
                &Response::Error(LinkError::Sequence(SequenceFault::Gap {
                    seq: 4,
                    expected: 3
                }))
            ),
            (
                3,
                &Response::Error(LinkError::Sequence(SequenceFault::Stale {
                    seq: 3,
                    expected: 5
                }))
            ),
        ]
    );
    // A replay of an old frame, long after.
    device.refused(
        0,
        &collide(),
        LinkError::Sequence(SequenceFault::Stale {
            seq: 0,
            expected: 5,
        }),
    );
    device.serves_normally(5);
}

#[test]
fn the_count_wraps_and_version_restarts_it() {
    let mut device = Device::new();
    // Any number first; then on through the wrap, which skips UNPROMPTED (`next_seq`).
    assert!(matches!(
        device.request(u16::MAX - 1, &collide()),
        Response::Collide(_)
    ));
    assert_eq!(cuesight_link::next_seq(u16::MAX - 1), 0);
    assert!(matches!(
        device.request(0, &collide()),
        Response::Collide(_)
    ));
    device.refused(
        u16::MAX,
        &collide(),
        LinkError::Sequence(SequenceFault::Stale {
            seq: u16::MAX,
            expected: 1,
        }),
    );
    // `version` starts the count again at its own number.
    assert!(matches!(
        device.request(500, &Request::Version(Empty {})),
        Response::Version(_)
    ));
    device.serves_normally(501);
}

// ---------------------------------------------------------------------------------------
// Damaged frames.

#[test]
fn every_truncation_of_a_frame_is_a_frame_fault() {
    let mut device = warm();
    let (mut frames, mut cuts) = (0, 0);
    for request in [
        collide(),
        stroke_requests(7, &synthetic_stroke(3))[1].clone(),
    ] {
        let frame = wire(2, &request);
        let encoded = &frame[..frame.len() - 1];
        for cut in 1..encoded.len() {
            // The tail is lost, the zero arrives.
            let truncated = [&encoded[..cut], &[0]].concat();
            frames += expect_frame_faults(&mut device, &truncated);
            cuts += 1;
        }
    }
    assert_eq!(frames, cuts, "one answer per truncated frame");
    assert!(cuts > 200, "{cuts} truncations");
    // Nothing of it was taken as a frame: 2 is still next.
    device.serves_normally(2);
}

#[test]
fn every_bit_flip_in_a_frame_is_a_frame_fault() {
    let mut device = warm();
    let (mut frames, mut flips) = (0, 0);
    for request in [
        collide(),
        stroke_requests(7, &synthetic_stroke(3))[2].clone(),
    ] {
        let frame = wire(2, &request);
        // Every bit but the zero's (a flipped zero merges the frame with the next: see
        // `a_lost_zero_merges_two_frames_into_one_fault`).
        let encoded = frame.len() - 1;
        for i in 0..encoded {
            for bit in 0..8 {
                let mut flipped = frame.clone();
                flipped[i] ^= 1 << bit;
                // A flip that makes a zero splits the frame: each piece is answered.
                frames += expect_frame_faults(&mut device, &flipped);
                flips += 1;
            }
        }
    }
    assert!(
        frames >= flips,
        "{frames} answers to {flips} flipped frames"
    );
    assert!(flips > 1_600, "{flips} flips");
    device.serves_normally(2);
}

#[test]
fn a_lost_zero_merges_two_frames_into_one_fault() {
    let mut device = warm();
    let (first, second) = (wire(2, &collide()), wire(3, &collide()));
    // The first frame's zero is lost (or flipped): the two arrive as one frame.
    let mut merged = first[..first.len() - 1].to_vec();
    merged.extend_from_slice(&second);
    let answer = device.one(&merged);
    assert_eq!(
        answer.response,
        Response::Error(LinkError::Frame(predicted_fault(
            &merged[..merged.len() - 1]
        )))
    );
    assert_eq!(answer.seq, UNPROMPTED);
    // Both were lost; the host sends them again.
    assert_eq!(device.one(&first).response, fresh_answer(&collide()));
    assert_eq!(device.one(&second).response, fresh_answer(&collide()));
    device.serves_normally(4);
}

#[test]
fn oversized_frames_are_skipped_to_their_end() {
    let mut device = warm();
    // Noise with no zero, longer than any frame.
    let noise = vec![0x55u8; MAX_FRAME + 100];
    for bytes in [
        noise.clone(),
        vec![0xffu8; 100_000],
        // Valid COBS of one raw byte more than a frame holds.
        cobs_encode(&vec![0x11u8; MAX_RAW + 1]),
    ] {
        let answer = device.one(&[&bytes[..], &[0]].concat());
        assert_eq!(
            answer.response,
            Response::Error(LinkError::Frame(FrameFault::Oversized {
                length: bytes.len() as u32
            }))
        );
        assert_eq!(answer.seq, UNPROMPTED);
    }
    // The longest raw frame is read (the sequence number and CRC hold): a `version`
    // with 1,013 bytes after it.
    let body: Vec<u8> = std::iter::once(0u8) // Request::Version
        .chain((0..MAX_RAW - 11).map(|i| (i % 251) as u8 + 1))
        .collect();
    let longest = raw_wire(SCHEMA_HASH, 2, &body);
    assert!(longest.len() <= MAX_FRAME);
    let answer = device.one(&longest);
    assert_eq!(
        (answer.seq, answer.response),
        (
            2,
            Response::Error(LinkError::Frame(FrameFault::TrailingBytes {
                count: (MAX_RAW - 11) as u16
            }))
        )
    );
    // The frame was in sequence, so 3 is next; an oversized frame in between changes
    // nothing.
    device.one(&[&noise[..], &[0]].concat());
    device.serves_normally(3);
}

#[test]
fn frames_too_short_or_undecodable_are_refused() {
    let mut device = warm();
    // Fewer than a header and a CRC.
    for len in 1..10usize {
        let encoded = cobs_encode(&vec![7u8; len]);
        let answer = device.one(&[&encoded[..], &[0]].concat());
        assert_eq!(
            answer.response,
            Response::Error(LinkError::Frame(FrameFault::Short { length: len as u16 }))
        );
    }
    // Whole frames (CRC right, in sequence) whose body is no request: variant 200, and
    // a `version` with three bytes after it. They take their sequence numbers.
    let answer = device.one(&raw_wire(SCHEMA_HASH, 2, &[200]));
    assert_eq!(
        (answer.seq, answer.response),
        (
            2,
            Response::Error(LinkError::Frame(FrameFault::Undecodable))
        )
    );
    let answer = device.one(&raw_wire(SCHEMA_HASH, 3, &[0, 1, 2, 3]));
    assert_eq!(
        (answer.seq, answer.response),
        (
            3,
            Response::Error(LinkError::Frame(FrameFault::TrailingBytes { count: 3 }))
        )
    );
    // An empty frame (two zeros) is no frame: no answer.
    assert!(device.send(&[0, 0, 0]).is_empty());
    device.serves_normally(4);
}

#[test]
fn a_foreign_schema_is_named_and_nothing_else_is_read() {
    let mut device = warm();
    for host in [0, SCHEMA_HASH ^ 1, SCHEMA_HASH ^ 0x8000_0000, u32::MAX] {
        // A `version` too: it would restart the count, but is not read.
        for request in [collide(), Request::Version(Empty {})] {
            let answer = device.one(&wire_as(host, 9, &request));
            assert_eq!(answer.seq, 9, "the answer carries the frame's number");
            assert_eq!(
                answer.response,
                Response::Error(LinkError::SchemaMismatch {
                    device: SCHEMA_HASH,
                    host
                })
            );
        }
    }
    // The body need not be of this schema at all.
    let answer = device.one(&raw_wire(0x1234_5678, 3, &[0xee; 40]));
    assert_eq!(
        answer.response,
        Response::Error(LinkError::SchemaMismatch {
            device: SCHEMA_HASH,
            host: 0x1234_5678
        })
    );
    device.serves_normally(2);
}

// ---------------------------------------------------------------------------------------
// Strokes.

/// Standard gravity (m/s²).
const G: f64 = 9.806_65;

/// Raw words (LSM6DSOX, ±16 g) of a synthetic stroke at 1 kHz reaching 2.5 m/s at the
/// impact, as `host-tests/src/strokes.rs` draws them (rest 0.4 s, a half-cosine
/// backswing, a pause, a half-cosine forward stroke, a −50 g impact clipped at the full
/// scale, a follow-through; 5° of cue tilt, a 20 mg offset, 8 mg RMS noise), with a
/// small generator of its own: 1,332 samples.
fn synthetic_stroke(seed: u64) -> Vec<i16> {
    let mut state = seed;
    let mut uniform = move || {
        // SplitMix64.
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let (rate, speed) = (1000.0, 2.5);
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
}

/// `samples` as the chunks of stroke `id`, [`MAX_SAMPLES`] each; the last with the rate.
fn stroke_requests(id: u16, samples: &[i16]) -> Vec<Request> {
    let chunks: Vec<&[i16]> = samples.chunks(MAX_SAMPLES).collect();
    let count = chunks.len() as u16;
    chunks
        .iter()
        .enumerate()
        .map(|(i, part)| {
            Request::Stroke(StrokeChunk {
                stroke: id,
                index: i as u16,
                count,
                samples: heapless::Vec::from_slice(part).unwrap(),
                setup: (i + 1 == chunks.len()).then_some(StrokeSetup {
                    rate_hz: 1000.0,
                    ..StrokeSetup::default()
                }),
            })
        })
        .collect()
}

/// Uploads `chunks` as frames from `seq` on, expecting progress and then the estimate;
/// returns it and the next sequence number.
fn upload(device: &mut Device, seq: u16, chunks: &[Request]) -> (StrokeAnswer, u16) {
    let mut seq = seq;
    for (i, chunk) in chunks.iter().enumerate() {
        let response = device.request(seq, chunk);
        seq = seq.wrapping_add(1);
        match response {
            Response::StrokeChunk(progress) if i + 1 < chunks.len() => {
                let Request::Stroke(sent) = chunk else {
                    panic!("{chunk:?} is no chunk");
                };
                assert_eq!(progress.chunks, sent.index + 1, "{progress:?}");
            }
            Response::Stroke(answer) if i + 1 == chunks.len() => return (answer, seq),
            other => panic!("chunk {i}: {other:?}"),
        }
    }
    panic!("no estimate")
}

/// The estimate a fresh session gives for `chunks`.
fn fresh_estimate(chunks: &[Request]) -> StrokeAnswer {
    let answer = upload(&mut Device::new(), 0, chunks).0;
    // The synthetic stroke is 2.5 m/s at the tip.
    assert!((answer.cue_speed - 2.5).abs() < 0.1, "estimate {answer:?}");
    answer
}

fn upload_fault(fault: UploadFault) -> LinkError {
    LinkError::Upload(fault)
}

#[test]
fn a_clean_upload_is_estimated_after_a_request_in_between() {
    let chunks = stroke_requests(7, &synthetic_stroke(3));
    assert!(chunks.len() >= 4, "{} chunks", chunks.len());
    let expected = fresh_estimate(&chunks);
    let mut device = warm();
    // A request between two chunks does not disturb the upload.
    device.request(2, &chunks[0]);
    assert_eq!(device.request(3, &collide()), fresh_answer(&collide()));
    let (answer, next) = upload(&mut device, 4, &chunks[1..]);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn a_duplicated_chunk_drops_the_upload() {
    let chunks = stroke_requests(7, &synthetic_stroke(3));
    let expected = fresh_estimate(&chunks);
    let mut device = warm();
    device.request(2, &chunks[0]);
    device.request(3, &chunks[1]);
    // Chunk 1 again, in a frame of its own (the link did not repeat it: the host did).
    device.refused(
        4,
        &chunks[1],
        upload_fault(UploadFault::Duplicate {
            stroke: 7,
            chunk: 1,
        }),
    );
    // The upload is gone: chunk 2 has nothing to follow.
    device.refused(
        5,
        &chunks[2],
        upload_fault(UploadFault::NotStarted {
            stroke: 7,
            chunk: 2,
        }),
    );
    // Sent again from chunk 0, it is estimated as in a fresh session.
    let (answer, next) = upload(&mut device, 6, &chunks);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn a_missing_chunk_drops_the_upload() {
    let chunks = stroke_requests(7, &synthetic_stroke(3));
    let expected = fresh_estimate(&chunks);
    let mut device = warm();
    device.request(2, &chunks[0]);
    device.request(3, &chunks[1]);
    device.refused(
        4,
        &chunks[3],
        upload_fault(UploadFault::Missing {
            stroke: 7,
            expected: 2,
            chunk: 3,
        }),
    );
    // Nothing half-uploaded is estimated: not even on the last chunk.
    let last = chunks.len() - 1;
    device.refused(
        5,
        &chunks[last],
        upload_fault(UploadFault::NotStarted {
            stroke: 7,
            chunk: last as u16,
        }),
    );
    let (answer, next) = upload(&mut device, 6, &chunks);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn reordered_chunks_drop_the_upload() {
    let chunks = stroke_requests(7, &synthetic_stroke(3));
    let expected = fresh_estimate(&chunks);
    let mut device = warm();
    device.request(2, &chunks[0]);
    device.refused(
        3,
        &chunks[2],
        upload_fault(UploadFault::Missing {
            stroke: 7,
            expected: 1,
            chunk: 2,
        }),
    );
    device.refused(
        4,
        &chunks[1],
        upload_fault(UploadFault::NotStarted {
            stroke: 7,
            chunk: 1,
        }),
    );
    let (answer, next) = upload(&mut device, 5, &chunks);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn a_damaged_or_out_of_sequence_chunk_frame_drops_the_upload() {
    let chunks = stroke_requests(7, &synthetic_stroke(3));
    let expected = fresh_estimate(&chunks);
    let mut device = warm();
    device.request(2, &chunks[0]);
    device.request(3, &chunks[1]);
    // Chunk 2's frame with a bit flipped.
    let mut flipped = wire(4, &chunks[2]);
    flipped[20] ^= 0x10;
    expect_frame_faults(&mut device, &flipped);
    // Sent again: the upload was dropped with the damaged frame.
    device.refused(
        4,
        &chunks[2],
        upload_fault(UploadFault::NotStarted {
            stroke: 7,
            chunk: 2,
        }),
    );
    // A duplicated chunk frame (the same frame twice) drops it too.
    device.request(5, &chunks[0]);
    let frame = wire(6, &chunks[1]);
    device.one(&frame);
    let again = device.one(&frame);
    assert_eq!(
        again.response,
        Response::Error(LinkError::Sequence(SequenceFault::Duplicate { seq: 6 }))
    );
    device.refused(
        7,
        &chunks[2],
        upload_fault(UploadFault::NotStarted {
            stroke: 7,
            chunk: 2,
        }),
    );
    let (answer, next) = upload(&mut device, 8, &chunks);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn the_other_upload_faults_name_their_chunk() {
    let samples = synthetic_stroke(3);
    let chunks = stroke_requests(7, &samples);
    let expected = fresh_estimate(&chunks);
    let chunk = |stroke: u16, index: u16, count: u16, len: usize, last: bool| {
        Request::Stroke(StrokeChunk {
            stroke,
            index,
            count,
            samples: heapless::Vec::from_slice(&samples[..len]).unwrap(),
            setup: last.then_some(StrokeSetup {
                rate_hz: 1000.0,
                ..StrokeSetup::default()
            }),
        })
    };
    let mut device = warm();
    let mut seq = 2;
    let mut refused = |device: &mut Device, request: Request, fault: UploadFault| {
        device.refused(seq, &request, upload_fault(fault));
        seq += 1;
    };
    let max = MAX_CHUNKS as u16;
    for (index, count) in [(0, 0), (0, max + 1), (3, 3), (max, max)] {
        refused(
            &mut device,
            chunk(7, index, count, 10, false),
            UploadFault::BadChunk {
                chunk: index,
                count,
            },
        );
    }
    // Chunk 0 with no samples.
    refused(
        &mut device,
        chunk(7, 0, 2, 0, false),
        UploadFault::Empty {
            stroke: 7,
            chunk: 0,
        },
    );
    // The count changes after chunk 0.
    device.request(seq, &chunk(7, 0, 3, 10, false));
    seq += 1;
    let mut refused = |device: &mut Device, request: Request, fault: UploadFault| {
        device.refused(seq, &request, upload_fault(fault));
        seq += 1;
    };
    refused(
        &mut device,
        chunk(7, 1, 4, 10, false),
        UploadFault::CountChanged {
            stroke: 7,
            count: 4,
            expected: 3,
        },
    );
    // Another stroke's chunk in the middle of an upload.
    device.request(seq, &chunk(7, 0, 3, 10, false));
    seq += 1;
    let mut refused = |device: &mut Device, request: Request, fault: UploadFault| {
        device.refused(seq, &request, upload_fault(fault));
        seq += 1;
    };
    refused(
        &mut device,
        chunk(8, 1, 3, 10, false),
        UploadFault::NotStarted {
            stroke: 8,
            chunk: 1,
        },
    );
    // A last chunk without its setup.
    device.request(seq, &chunk(7, 0, 2, 10, false));
    seq += 1;
    let mut refused = |device: &mut Device, request: Request, fault: UploadFault| {
        device.refused(seq, &request, upload_fault(fault));
        seq += 1;
    };
    refused(
        &mut device,
        chunk(7, 1, 2, 10, false),
        UploadFault::NoSetup { stroke: 7 },
    );
    // More samples than a stroke holds: full chunks until one overflows.
    let full = (STROKE_CAPACITY / MAX_SAMPLES) as u16; // 19 chunks fit, the 20th not
    for index in 0..full {
        let response = device.request(seq, &chunk(9, index, max, MAX_SAMPLES, false));
        assert!(matches!(response, Response::StrokeChunk(_)), "{response:?}");
        seq += 1;
    }
    device.refused(
        seq,
        &chunk(9, full, max, MAX_SAMPLES, false),
        upload_fault(UploadFault::Overflow {
            stroke: 9,
            chunk: full,
        }),
    );
    seq += 1;
    // A new chunk 0 drops an unfinished upload and starts another.
    device.request(seq, &chunks[0]);
    device.request(seq + 1, &chunks[1]);
    let (answer, next) = upload(&mut device, seq + 2, &chunks);
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn a_glitch_sample_names_its_chunk_and_sample() {
    let samples = synthetic_stroke(3);
    let expected = fresh_estimate(&stroke_requests(7, &samples));
    let mut device = warm();
    let mut seq = 2;
    // At the rail in the rest window (samples 0..400: the first chunk and a later one),
    // and a one-sample spike there.
    for (index, value, kind) in [
        (100usize, i16::MIN, GlitchKind::Rail),
        (300, i16::MIN, GlitchKind::Rail),
        (300, i16::MAX, GlitchKind::Rail),
        (150, samples[150].saturating_add(8_000), GlitchKind::Spike),
    ] {
        let mut glitched = samples.clone();
        glitched[index] = value;
        let chunks = stroke_requests(7, &glitched);
        for chunk in &chunks[..chunks.len() - 1] {
            device.request(seq, chunk);
            seq += 1;
        }
        device.refused(
            seq,
            &chunks[chunks.len() - 1],
            upload_fault(UploadFault::Glitch {
                stroke: 7,
                chunk: (index / MAX_SAMPLES) as u16,
                sample: (index % MAX_SAMPLES) as u16,
                kind,
                value,
            }),
        );
        seq += 1;
    }
    let (answer, next) = upload(&mut device, seq, &stroke_requests(7, &samples));
    assert_eq!(answer, expected);
    device.serves_normally(next);
}

#[test]
fn shutdown_reports_the_counts_and_the_session_still_answers() {
    let mut device = warm();
    device.refused(
        5,
        &collide(),
        LinkError::Sequence(SequenceFault::Gap {
            seq: 5,
            expected: 2,
        }),
    );
    let response = device.request(6, &Request::Shutdown(Empty {}));
    let Response::Shutdown(counts) = response else {
        panic!("{response:?}");
    };
    assert_eq!((counts.requests, counts.errors), (4, 1));
    device.serves_normally(7);
}

#[test]
fn the_unprompted_version_at_boot_is_a_version_frame() {
    let device = Device::new();
    let mut out = [0u8; MAX_FRAME];
    let len = device.session.hello(&mut out);
    let answer = host_read(&out[..len]);
    assert_eq!(answer.seq, UNPROMPTED);
    let Response::Version(version) = answer.response else {
        panic!("{:?}", answer.response);
    };
    assert_eq!(version.schema, SCHEMA_HASH);
    assert_eq!(
        (version.firmware.as_str(), version.board.as_str()),
        (IDENTITY.firmware, IDENTITY.board)
    );
    assert_eq!(usize::from(version.max_frame), MAX_FRAME);
    assert_eq!(usize::from(version.max_samples), MAX_SAMPLES);
    assert_eq!(usize::from(version.stroke_capacity), STROKE_CAPACITY);
    // The answer to a request numbered 0xffff carries the same number as an unprompted
    // frame: a host counting past 65,535 frames cannot tell them apart by the number.
    let mut device = Device::new();
    let answer = device.one(&wire(u16::MAX, &collide()));
    assert_eq!(answer.seq, UNPROMPTED);
}
