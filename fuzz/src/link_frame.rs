//! Target `link_frame`: byte streams through the device's frame decoder,
//! [`FrameReader`] → [`frame::open`] → [`frame::decode`]`::<Request>`.
//!
//! The first byte picks the stream: even, the rest of the input as it is (arbitrary
//! bytes; the seeds are valid frames of every request kind); odd, the rest as a script
//! (`crate::link`: valid frames, truncated, merged, bit-flipped, out of order,
//! oversized, under a foreign schema, with the fuzzer's bodies and a CRC that holds).
//!
//! Checked, whatever the bytes: no panic; the reader hands out exactly one
//! [`Received`] per zero that ends a non-empty piece and none otherwise, and a zero
//! after the stream ends the last piece; each is what the frame layout, written out
//! again (`crate::link::expected`: a COBS decoder and a CRC-32 of its own), says:
//! `Oversized` with the piece's length when it decodes past [`MAX_RAW`], `Cobs` when it
//! is cut short, else the frame, which [`frame::open`] refuses as `Short` (under ten
//! bytes) or `Crc` (with the sequence number as read), or opens to the same schema,
//! sequence number and body; `decode` fails only as `Undecodable` or `TrailingBytes`
//! with the count left over; and a decoded request re-encodes ([`frame::encode`] under
//! the same header) within [`MAX_FRAME`], exactly as the layout encodes its postcard
//! bytes (no longer than the body it came from), which decode to the same request.

use cuesight_link::error::FrameFault;
use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME, MAX_RAW};
use cuesight_link::{LinkError, Request};

use crate::link::{self, Expected};

/// What one input reached (for checking seeds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// Frames and faults handed out.
    pub received: usize,
    /// Frames that opened (length and CRC held).
    pub opened: usize,
    /// Of which decoded as requests.
    pub requests: usize,
}

/// Runs one input (see the module docs).
pub fn run(data: &[u8]) -> Report {
    let (mode, rest) = data.split_first().unwrap_or((&0, &[]));
    if mode % 2 == 0 {
        check_stream(rest)
    } else {
        check_stream(&link::build(rest))
    }
}

/// Feeds `stream`, then one zero, through a reader, checking every frame.
pub fn check_stream(stream: &[u8]) -> Report {
    let mut reader = Box::new(FrameReader::new());
    let mut report = Report::default();
    let (pieces, tail) = link::pieces(stream);
    let mut pieces = pieces.into_iter().chain([tail]);
    let mut piece = pieces.next().unwrap_or_default();
    for &byte in stream.iter().chain([&0]) {
        let received = reader.push(byte);
        if byte != 0 {
            assert!(received.is_none(), "a frame before its zero");
            continue;
        }
        match received {
            None => assert!(piece.is_empty(), "no frame for {piece:?}"),
            Some(received) => {
                assert!(!piece.is_empty(), "a frame out of an empty piece");
                report.received += 1;
                check_received(piece, received, &mut report);
            }
        }
        piece = pieces.next().unwrap_or_default();
    }
    report
}

/// One frame or fault against the layout.
fn check_received(piece: &[u8], received: Received<'_>, report: &mut Report) {
    match (link::expected(piece), received) {
        (Expected::Oversized(length), Received::Fault(FrameFault::Oversized { length: got })) => {
            assert_eq!(got, length, "oversized length")
        }
        (Expected::Cobs, Received::Fault(FrameFault::Cobs)) => {}
        (Expected::Short(length), Received::Frame(raw)) => {
            assert_eq!(raw.len(), usize::from(length));
            assert_eq!(
                frame::open(raw),
                Err(LinkError::Frame(FrameFault::Short { length }))
            );
        }
        (Expected::Crc(seq_as_read), Received::Frame(raw)) => {
            assert!(raw.len() <= MAX_RAW);
            assert_eq!(
                frame::open(raw),
                Err(LinkError::Frame(FrameFault::Crc { seq_as_read }))
            );
        }
        (Expected::Open { schema, seq, raw }, Received::Frame(got)) => {
            assert_eq!(got, &raw[..], "the raw frame");
            let (header, body) = frame::open(got).expect("a frame whose CRC holds opens");
            assert_eq!((header.schema, header.seq), (schema, seq), "header");
            assert_eq!(body, &raw[6..raw.len() - 4], "body");
            report.opened += 1;
            check_decode(schema, seq, body, report);
        }
        (expected, got) => panic!("{piece:?}: expected {expected:?}, the reader gave {got:?}"),
    }
}

/// `decode` and, for a request, its re-encoding.
fn check_decode(schema: u32, seq: u16, body: &[u8], report: &mut Report) {
    let decoded = frame::decode::<Request>(body);
    let request = match (postcard::take_from_bytes::<Request>(body), decoded) {
        (Ok((_, [])), Ok(request)) => request,
        (Ok((_, rest)), Err(LinkError::Frame(FrameFault::TrailingBytes { count }))) => {
            assert_eq!(usize::from(count), rest.len(), "trailing bytes");
            return;
        }
        (Err(_), Err(LinkError::Frame(FrameFault::Undecodable))) => return,
        (postcard, decoded) => panic!("postcard {postcard:?}, decode {decoded:?}"),
    };
    report.requests += 1;
    let mut out = [0u8; MAX_FRAME];
    let len = frame::encode(schema, seq, &request, &mut out)
        .unwrap_or_else(|e| panic!("{request:?} decoded but does not re-encode: {e:?}"));
    assert!(len <= MAX_FRAME, "re-encoded into {len} bytes");
    let canonical = link::body_of(&request);
    assert!(canonical.len() <= body.len());
    assert_eq!(
        out[..len],
        link::wire(schema, seq, &canonical)[..],
        "the link's encoding is the layout's"
    );
    let again: Request = frame::decode(&canonical).expect("a re-encoded request decodes");
    assert_eq!(link::body_of(&again), canonical, "postcard bytes stable");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::{op, Script};

    #[test]
    fn every_example_is_a_request_and_every_damage_a_fault() {
        let mut raw = vec![0u8];
        let mut script = Script::new();
        for (_, request) in link::examples() {
            raw.extend(link::wire(
                cuesight_link::SCHEMA_HASH,
                1,
                &link::body_of(request),
            ));
            script.send(request);
        }
        let n = link::examples().len();
        let report = run(&raw);
        assert_eq!((report.received, report.requests), (n, n));
        let mut with_script = vec![1u8];
        with_script.extend_from_slice(script.bytes());
        assert_eq!(run(&with_script).requests, n);
        let body = link::body_of(&link::examples()[1].1);
        for code in [op::TRUNCATE, op::FLIP, op::MERGE, op::OVERSIZED, op::SCHEMA] {
            let mut damaged = vec![1u8];
            damaged.extend_from_slice(Script::new().record(code, 9, 1, &body).bytes());
            let report = run(&damaged);
            assert!(report.received >= 1, "{code}: {report:?}");
        }
    }
}
