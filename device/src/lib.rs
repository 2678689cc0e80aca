//! The cuesight device's side of the link (no_std, no heap): what the firmware runs on
//! the schema and frames of `cuesight-link`.
//!
//! * [`Session`]: the session that answers frames: one frame in, one answer frame out,
//!   and the state kept between them (the session defaults, the frame count).
//! * [`Upload`]: the stroke upload: chunks checked for identity, order and count as they
//!   arrive, the whole window checked for glitches, and only then estimated.
//! * The shot guidance (`guide`, with the `shot` feature, on by default): a `shot`
//!   request validated, played or solved by `cuesight::guidance::guide`, and answered;
//!   without the feature the session answers `shot` with `unsupported`.
//!
//! The host runs the same session in process (the console's loopback device, the
//! end-to-end tests' mirror of the firmware).
//!
//! ```
//! use cuesight_device::{Identity, Session};
//! use cuesight_link::frame::{self, FrameReader, Received, MAX_FRAME};
//! use cuesight_link::{Collide, Request, Response, SCHEMA_HASH};
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

#[cfg(feature = "shot")]
mod guide;
mod session;
#[cfg(feature = "upload")]
mod upload;
#[cfg(not(feature = "upload"))]
#[path = "no_upload.rs"]
mod upload;

pub use session::{live_frame, Control, Identity, Served, Session};
pub use upload::Upload;
