//! The IMU trace as it arrives on the QEMU board's second UART: the host (`cargo
//! xtask live`) reads the CSV trace (`firmware/traces/README.md`), checks it with
//! `cuesight_sensors::trace::TraceParser`, and streams it in binary, so the device
//! parses no text:
//!
//! | bytes | content |
//! |---|---|
//! | 4 | magic `CUE1` |
//! | 2 | output data rate (Hz, `u16` little-endian): 3333 or 6667 |
//! | 4 | samples that follow (`u32` little-endian) |
//! | 12 each | `[ax, ay, az, gx, gy, gz]`, raw LSB, `i16` little-endian |
//!
//! After a segment's last sample another header may follow: `CUE1`, a new trace (the
//! estimator starts over), or `CUEF`, more samples of the same trace delivered with
//! the emulated part's faults set by its `u16` (bit 0: every bus transaction fails,
//! bit 1: the part is stalled, no conversion; 0: none) for a failed bus read or a
//! stalled sensor (issue 15's bad inputs). The trace ends with the file. [`Feed`] takes
//! the bytes one at a time, with no buffer beyond one sample.

/// A trace's header's magic.
pub const MAGIC: [u8; 4] = *b"CUE1";
/// A fault segment's header's magic.
pub const FAULT_MAGIC: [u8; 4] = *b"CUEF";
/// Header bytes.
pub const HEADER_LEN: usize = 10;
/// Bytes per sample.
pub const SAMPLE_LEN: usize = 12;

/// What a byte completed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, defmt::Format)]
pub enum Fed {
    /// A header: the trace's rate and sample count.
    Header {
        /// Output data rate (Hz).
        rate_hz: u16,
        /// Samples that follow.
        samples: u32,
    },
    /// A fault segment's header: the faults set for the samples that follow.
    Faults {
        /// Every bus transaction fails.
        bus_failing: bool,
        /// The part converts nothing.
        stalled: bool,
        /// Samples that follow.
        samples: u32,
    },
    /// A header whose magic is wrong (the bytes up to it are dropped; the feed looks
    /// for a header again).
    BadMagic,
    /// A sample, `[ax, ay, az, gx, gy, gz]` in raw LSB.
    Sample([i16; 6]),
}

/// The byte decoder.
pub struct Feed {
    bytes: [u8; SAMPLE_LEN],
    filled: usize,
    /// Samples still to come in the current trace (0: a header is next).
    left: u32,
}

impl Feed {
    /// A feed waiting for a header.
    pub const fn new() -> Self {
        Self {
            bytes: [0; SAMPLE_LEN],
            filled: 0,
            left: 0,
        }
    }

    /// Samples still to come in the current trace.
    pub const fn left(&self) -> u32 {
        self.left
    }

    /// Takes one byte.
    pub fn push(&mut self, byte: u8) -> Option<Fed> {
        let want = if self.left == 0 {
            HEADER_LEN
        } else {
            SAMPLE_LEN
        };
        if let Some(slot) = self.bytes.get_mut(self.filled) {
            *slot = byte;
        }
        self.filled += 1;
        if self.filled < want {
            return None;
        }
        self.filled = 0;
        let b = self.bytes;
        if self.left == 0 {
            let word = u16::from_le_bytes([b[4], b[5]]);
            let samples = u32::from_le_bytes([b[6], b[7], b[8], b[9]]);
            self.left = samples;
            return Some(match [b[0], b[1], b[2], b[3]] {
                MAGIC => Fed::Header {
                    rate_hz: word,
                    samples,
                },
                FAULT_MAGIC => Fed::Faults {
                    bus_failing: word & 1 != 0,
                    stalled: word & 2 != 0,
                    samples,
                },
                _ => {
                    self.left = 0;
                    Fed::BadMagic
                }
            });
        }
        self.left -= 1;
        let word = |i: usize| i16::from_le_bytes([b[2 * i], b[2 * i + 1]]);
        Some(Fed::Sample([
            word(0),
            word(1),
            word(2),
            word(3),
            word(4),
            word(5),
        ]))
    }
}

impl Default for Feed {
    fn default() -> Self {
        Self::new()
    }
}
