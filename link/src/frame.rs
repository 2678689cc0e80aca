//! Frames: how one message travels over a byte stream (a UART, a TCP socket).
//!
//! ```text
//! on the wire:  COBS(raw) 0x00
//! raw:          schema u32 LE | seq u16 LE | body (postcard) | crc u32 LE
//! ```
//!
//! * **COBS** (consistent overhead byte stuffing, the `cobs` crate, as postcard's own
//!   COBS flavour uses): the encoded frame has no zero byte, so `0x00` ends every frame
//!   and a receiver that joins mid-stream, or loses bytes, is back in step at the next
//!   zero.
//! * **schema**: [`crate::SCHEMA_HASH`] of the sender. Fixed width and first, so that a
//!   peer with another schema can still read it and say so instead of decoding garbage.
//! * **seq**: the host numbers its requests ([`next_seq`]); the device answers with the
//!   number of the request it answers, or [`UNPROMPTED`] (the device's session checks the
//!   order: duplicates, gaps, reordering).
//! * **body**: the message in postcard (varint integers, `f32` as 4 bytes LE).
//! * **crc**: CRC-32/ISO-HDLC (the Ethernet/zlib CRC, the `crc` crate, table-free) over
//!   schema, seq and body. Catches every burst error up to 32 bits and all odd numbers of
//!   bit flips.
//!
//! Limits: a raw frame is at most [`MAX_RAW`] bytes, so an encoded one at most
//! [`MAX_FRAME`] with its zero.

use crc::{Crc, NoTable, CRC_32_ISO_HDLC};
use serde::{Deserialize, Serialize};

use crate::error::{FrameFault, LinkError};

/// Longest raw frame (header, body and CRC), in bytes. A full `stroke` chunk
/// ([`crate::MAX_SAMPLES`] samples, at most 3 bytes each, and its setup: at most 435
/// bytes) fits, and so does the largest answer (`shot`'s, at most about 400;
/// `tests/roundtrip.rs` encodes arbitrary values of every message within it).
pub const MAX_RAW: usize = 512;

/// Longest encoded frame: COBS adds one byte per 254 and one more, and the zero ends it.
pub const MAX_FRAME: usize = MAX_RAW + MAX_RAW / 254 + 2;

/// Bytes of the header (schema and seq).
pub const HEADER: usize = 6;

/// Bytes of the CRC.
const CRC_LEN: usize = 4;

/// The sequence number of a frame the device sends unprompted (its `version` at boot):
/// not an answer to any request. Hosts never number a request with it ([`next_seq`]).
pub const UNPROMPTED: u16 = u16::MAX;

/// The number after `seq` in a host's count: 0, 1, ..., 0xFFFE, then 0 again
/// ([`UNPROMPTED`] is skipped, so no answer can be taken for an unprompted frame).
pub const fn next_seq(seq: u16) -> u16 {
    if seq >= UNPROMPTED - 1 {
        0
    } else {
        seq + 1
    }
}

/// CRC-32/ISO-HDLC, computed bit by bit (no 1 KB table in flash; a 1 KB frame costs a
/// few tens of thousands of instructions, next to the UART's 90 ms at 115,200 baud).
///
/// A `static`, not a `const`: [`encode`] is generic, so it is compiled in the crate that
/// calls it (the device's session is another crate), and a `const` gave each crate its
/// own copy of the parameters; with one address for every caller, LTO folds them into
/// the one checksum, which with two copies was compiled for any CRC (126 B more flash).
static CRC32: Crc<u32, NoTable> = Crc::<u32, NoTable>::new(&CRC_32_ISO_HDLC);

/// The header of a frame whose CRC held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// The sender's schema hash.
    pub schema: u32,
    /// The sequence number.
    pub seq: u16,
}

/// Encodes `message` with `schema` and `seq` into `out` as one frame, its `0x00`
/// included; returns the frame's length. Fails ([`LinkError::AnswerTooLarge`]) when
/// the message does not fit [`MAX_RAW`] or `out`.
pub fn encode<T: Serialize>(
    schema: u32,
    seq: u16,
    message: &T,
    out: &mut [u8],
) -> Result<usize, LinkError> {
    let too_large = LinkError::AnswerTooLarge;
    let mut raw = [0u8; MAX_RAW];
    let (head, rest) = raw.split_first_chunk_mut::<HEADER>().ok_or(too_large)?;
    let [s0, s1, s2, s3] = schema.to_le_bytes();
    let [q0, q1] = seq.to_le_bytes();
    *head = [s0, s1, s2, s3, q0, q1];
    let body_room = rest
        .get_mut(..MAX_RAW - HEADER - CRC_LEN)
        .ok_or(too_large)?;
    let writer = Out {
        buf: body_room,
        len: 0,
        overflowed: false,
    };
    let body = postcard::serialize_with_flavor(message, writer).map_err(|_| too_large)?;
    let end = HEADER + body;
    let crc = CRC32.checksum(raw.get(..end).unwrap_or_default());
    let crc_slot = raw.get_mut(end..end + CRC_LEN).ok_or(too_large)?;
    crc_slot.copy_from_slice(&crc.to_le_bytes());
    let raw = raw.get(..end + CRC_LEN).unwrap_or_default();
    let written = cobs::try_encode(raw, out).map_err(|_| too_large)?;
    let zero = out.get_mut(written).ok_or(too_large)?;
    *zero = 0;
    Ok(written + 1)
}

/// Checks a raw (COBS-decoded) frame's length and CRC and returns its header and body.
/// The schema is *not* compared here: the caller decides what a foreign schema means.
pub fn open(raw: &[u8]) -> Result<(Header, &[u8]), LinkError> {
    let short = LinkError::Frame(FrameFault::Short {
        length: raw.len() as u16,
    });
    let (content, crc) = raw.split_last_chunk::<CRC_LEN>().ok_or(short)?;
    let (head, body) = content.split_first_chunk::<HEADER>().ok_or(short)?;
    let [s0, s1, s2, s3, q0, q1] = *head;
    let seq = u16::from_le_bytes([q0, q1]);
    if CRC32.checksum(content) != u32::from_le_bytes(*crc) {
        return Err(LinkError::Frame(FrameFault::Crc { seq_as_read: seq }));
    }
    let schema = u32::from_le_bytes([s0, s1, s2, s3]);
    Ok((Header { schema, seq }, body))
}

/// Decodes a body as `T`; every byte must be used.
pub fn decode<'a, T: Deserialize<'a>>(body: &'a [u8]) -> Result<T, LinkError> {
    let mut reader = postcard::Deserializer::from_flavor(In { rest: body });
    match T::deserialize(&mut reader) {
        Ok(message) => match reader.finalize() {
            Ok([]) => Ok(message),
            Ok(rest) => Err(LinkError::Frame(FrameFault::TrailingBytes {
                count: rest.len() as u16,
            })),
            Err(_) => Err(LinkError::Frame(FrameFault::Undecodable)),
        },
        Err(_) => Err(LinkError::Frame(FrameFault::Undecodable)),
    }
}

/// What [`FrameReader::push`] found at a frame's end.
#[derive(Debug, PartialEq, Eq)]
pub enum Received<'a> {
    /// A whole frame, COBS-decoded (header, body and CRC; see [`open`]).
    Frame(&'a [u8]),
    /// A frame that could not be taken: too long, or not valid COBS.
    Fault(FrameFault),
}

/// Collects bytes into frames: feed it every byte received; at each `0x00` it hands
/// out the frame that ended there. Never more than [`MAX_RAW`] bytes are kept: a longer
/// frame is skipped to its end and reported as [`FrameFault::Oversized`].
pub struct FrameReader {
    buf: [u8; MAX_RAW],
    len: usize,
    /// Encoded bytes of the frame in progress (for the oversize report).
    seen: u32,
    state: cobs::DecoderState,
    /// The frame in progress is longer than [`MAX_RAW`].
    oversized: bool,
    /// A zero cut a COBS block short.
    broken: bool,
}

impl Default for FrameReader {
    fn default() -> Self {
        Self::new()
    }
}

impl FrameReader {
    /// An empty reader, waiting for the first frame.
    pub const fn new() -> Self {
        Self {
            buf: [0; MAX_RAW],
            len: 0,
            seen: 0,
            state: cobs::DecoderState::Idle,
            oversized: false,
            broken: false,
        }
    }

    /// Takes one byte; returns what ended with it, if it was a frame's `0x00`. Empty
    /// frames (two zeros in a row) are skipped.
    pub fn push(&mut self, byte: u8) -> Option<Received<'_>> {
        if byte != 0 {
            self.seen = self.seen.saturating_add(1);
        }
        let fed = self.state.feed(byte);
        match fed {
            Ok(cobs::DecodeResult::NoData) => None,
            Ok(cobs::DecodeResult::DataContinue(data)) => {
                match self.buf.get_mut(self.len) {
                    Some(slot) => {
                        *slot = data;
                        self.len += 1;
                    }
                    None => self.oversized = true,
                }
                None
            }
            Ok(cobs::DecodeResult::DataComplete) => Some(self.finish()),
            // Only a zero can be invalid: it cut a COBS block short.
            Err(_) => {
                self.broken = true;
                Some(self.finish())
            }
        }
    }

    /// The frame that just ended, and a fresh start for the next.
    fn finish(&mut self) -> Received<'_> {
        let len = core::mem::take(&mut self.len);
        let seen = core::mem::take(&mut self.seen);
        let broken = core::mem::take(&mut self.broken);
        if core::mem::take(&mut self.oversized) {
            Received::Fault(FrameFault::Oversized { length: seen })
        } else if broken {
            Received::Fault(FrameFault::Cobs)
        } else {
            Received::Frame(self.buf.get(..len).unwrap_or_default())
        }
    }
}

/// postcard's output over a slice (as its `Slice` flavour), with the two writers out of
/// line: inlined, every field of every answer carried its own bounds check and copy
/// (260 B more flash on the release image). The writers never fail: a byte past the
/// end is dropped and remembered, and [`Out::finalize`] reports it. The compiler sees
/// that they always return `Ok` and drops the error check after every field of every
/// answer (about 10 bytes of code each; 1,000 B of the release image).
struct Out<'a> {
    buf: &'a mut [u8],
    len: usize,
    overflowed: bool,
}

impl postcard::ser_flavors::Flavor for Out<'_> {
    type Output = usize;

    #[inline(never)]
    fn try_push(&mut self, byte: u8) -> postcard::Result<()> {
        match self.buf.get_mut(self.len) {
            Some(slot) => {
                *slot = byte;
                self.len += 1;
            }
            None => self.overflowed = true,
        }
        Ok(())
    }

    #[inline(never)]
    fn try_extend(&mut self, data: &[u8]) -> postcard::Result<()> {
        for &byte in data {
            self.try_push(byte)?;
        }
        Ok(())
    }

    fn finalize(self) -> postcard::Result<usize> {
        if self.overflowed {
            Err(postcard::Error::SerializeBufferFull)
        } else {
            Ok(self.len)
        }
    }
}

/// postcard's input over a slice (as its `Slice` flavour), with the readers out of
/// line, for the same reason as [`Out`] (88 B of the release image).
struct In<'de> {
    rest: &'de [u8],
}

impl<'de> In<'de> {
    /// The next `count` bytes, or `None` if fewer are left.
    #[inline(never)]
    fn take(&mut self, count: usize) -> Option<&'de [u8]> {
        let (taken, rest) = (self.rest.get(..count)?, self.rest.get(count..)?);
        self.rest = rest;
        Some(taken)
    }
}

impl<'de> postcard::de_flavors::Flavor<'de> for In<'de> {
    type Remainder = &'de [u8];
    type Source = &'de [u8];

    #[inline(never)]
    fn pop(&mut self) -> postcard::Result<u8> {
        let (&byte, rest) = self
            .rest
            .split_first()
            .ok_or(postcard::Error::DeserializeUnexpectedEnd)?;
        self.rest = rest;
        Ok(byte)
    }

    /// The take itself is out of line ([`In::take`]); the re-slice here, inlined, shows
    /// the compiler the slice's length, so postcard's fixed-size copies keep no
    /// length-mismatch panic.
    #[inline(always)]
    fn try_take_n(&mut self, count: usize) -> postcard::Result<&'de [u8]> {
        self.take(count)
            .and_then(|taken| taken.get(..count))
            .ok_or(postcard::Error::DeserializeUnexpectedEnd)
    }

    fn finalize(self) -> postcard::Result<&'de [u8]> {
        Ok(self.rest)
    }
}
