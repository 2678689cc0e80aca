//! The schema's identity and the limits both ends share.

/// The schema's identity: FNV-1a (32 bits) of the postcard encoding of
/// `postcard-schema`'s description of [`crate::Request`] and [`crate::Response`]. Every frame carries
/// it; `tests/schema.rs` recomputes it and fails when the schema changed without it.
pub const SCHEMA_HASH: u32 = 0x632B_76BB;

/// Most raw samples in one stroke chunk. 128 keeps a request (568 B with 256) small on
/// the device's stack, which holds it a few times over while it is decoded.
pub const MAX_SAMPLES: usize = 128;

/// Most samples in one stroke, all chunks: 1.5 s at the LSM6DSOX's 3.33 kHz (0.75 s at
/// 6.66 kHz, 5 s at 1 kHz), 10 KB of `i16`, sized for the 16 KiB static RAM budget.
pub const STROKE_CAPACITY: usize = 5_000;

/// Most chunks in one stroke: room for [`STROKE_CAPACITY`] in chunks shorter than
/// [`MAX_SAMPLES`] (40 full ones hold it).
pub const MAX_CHUNKS: usize = 64;

/// Most object balls in a `shot` (the scene holds the cue ball and these).
pub const MAX_OBJECT_BALLS: usize = cuesight::table::MAX_BALLS - 1;
