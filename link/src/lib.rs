//! The cuesight device link: one schema, compiled into the firmware and the host.
//!
//! * [`Request`] and [`Response`] (with the typed [`LinkError`]) derive serde and are the
//!   only schema: postcard on the wire, and the JSON a person types into `cuesight
//!   device` (the field names of `cuesight collide` and `cuesight shot`).
//! * [`frame`]: each message in a COBS frame with the schema hash, a sequence number and
//!   a CRC-32. The device never writes text; the host turns answers into sentences.
//!
//! The device's side (the session that answers frames, the stroke upload, the shot
//! guidance) is the `cuesight-device` crate, built on this one.
//!
//! ```
//! use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME};
//! use cuesight_link::{Collide, Request, SCHEMA_HASH};
//!
//! let request = Request::Collide(Collide::new(2.0, 30.0));
//! let mut wire = [0u8; MAX_FRAME];
//! let len = frame::encode(SCHEMA_HASH, 7, &request, &mut wire).unwrap();
//! let mut reader = FrameReader::new();
//! let raw = wire[..len].iter().find_map(|&b| match reader.push(b) {
//!     Some(Received::Frame(raw)) => Some(raw.to_vec()),
//!     _ => None,
//! }).unwrap();
//! let (header, body) = frame::open(&raw).unwrap();
//! assert_eq!((header.schema, header.seq), (SCHEMA_HASH, 7));
//! assert_eq!(frame::decode::<Request>(body), Ok(request));
//! ```
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod error;
pub mod frame;
mod limits;
pub mod live;
pub mod names;
pub mod request;
pub mod response;
pub mod shot;
mod wire;

pub use error::{LinkError, UploadFault};
pub use frame::{next_seq, UNPROMPTED};
pub use limits::{MAX_CHUNKS, MAX_OBJECT_BALLS, MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY};
pub use names::{ModelName, RegimeName, TableName};
pub use request::{
    Collide, Defaults, Empty, Overrides, Request, ShotRequest, StrokeChunk, StrokeSetup,
};
pub use response::{CollideAnswer, Response, StrokeAnswer, VersionAnswer};
pub use shot::ShotAnswer;
