//! The cuesight device link: one schema, compiled into the firmware and the host.
//!
//! * [`Request`] and [`Response`] (with the typed [`LinkError`]) derive serde and are the
//!   only schema: postcard on the wire, and the JSON a person types into `cuesight
//!   device` (the field names of `cuesight collide` and `cuesight shot`).
//! * [`frame`]: each message in a COBS frame with the schema hash, a sequence number and
//!   a CRC-32. The device never writes text; the host turns answers into sentences.
//! * [`Session`]: the device's side (no_std, no heap): one frame in, one answer out.
//!
//! ```
//! use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME};
//! use cuesight_link::{Collide, Identity, Request, Response, Session, SCHEMA_HASH};
//!
//! let mut device = Session::new(Identity { firmware: "doc 0", board: "none" });
//! let mut wire = [0u8; MAX_FRAME];
//! let len = frame::encode(SCHEMA_HASH, 0, &Request::Collide(Collide::new(2.0, 30.0)), &mut wire).unwrap();
//! let mut reader = FrameReader::new();
//! let mut answer = [0u8; MAX_FRAME];
//! for &byte in &wire[..len] {
//!     if let Some(received) = reader.push(byte) {
//!         let served = device.serve(received, &mut answer);
//!         let mut host = FrameReader::new();
//!         let raw = answer[..served.len].iter().find_map(|&b| match host.push(b) {
//!             Some(Received::Frame(raw)) => Some(raw.to_vec()),
//!             _ => None,
//!         }).unwrap();
//!         let (header, body) = frame::open(&raw).unwrap();
//!         assert_eq!(header.seq, 0);
//!         assert!(matches!(frame::decode::<Response>(body), Ok(Response::Collide(_))));
//!     }
//! }
//! ```
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod error;
pub mod frame;
#[cfg(feature = "shot")]
mod guide;
mod limits;
pub mod names;
pub mod request;
pub mod response;
mod session;
pub mod shot;
mod upload;

pub use error::{LinkError, UploadFault};
pub use frame::{next_seq, UNPROMPTED};
pub use limits::{MAX_CHUNKS, MAX_OBJECT_BALLS, MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY};
pub use names::{ModelName, RegimeName, TableName};
pub use request::{
    Collide, Defaults, Empty, Overrides, Request, ShotRequest, StrokeChunk, StrokeSetup,
};
pub use response::{CollideAnswer, Response, StrokeAnswer, VersionAnswer};
pub use session::{Control, Identity, Served, Session};
pub use shot::ShotAnswer;
pub use upload::Upload;
