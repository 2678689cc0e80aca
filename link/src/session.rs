//! The device's side of the link: one frame in, one answer frame out, and the state
//! kept between them (the session defaults, the stroke upload, the frame count).

use cuesight::collide;

use crate::error::{LinkError, SequenceFault, Unsupported};
use crate::frame::{self, Received, MAX_FRAME};
use crate::limits::{MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY};
use crate::request::{Collide, Defaults, Request, StrokeChunk};
use crate::response::{
    CollideAnswer, InputEcho, ParamsAnswer, Response, ShutdownAnswer, VersionAnswer,
};
use crate::upload::{Step, Upload};

/// The sequence number of a frame the device sends unprompted (its `version` at boot):
/// not an answer to any request.
pub const UNPROMPTED: u16 = u16::MAX;

/// Who the device is, for `version`.
#[derive(Clone, Copy, Debug)]
pub struct Identity {
    /// Firmware name and version.
    pub firmware: &'static str,
    /// Board.
    pub board: &'static str,
}

/// What to do after an answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Keep serving.
    Continue,
    /// The answer was to `shutdown`: send it, then exit.
    Shutdown,
}

/// One answered frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Served {
    /// Bytes of the answer frame written to `out`.
    pub len: usize,
    /// The request's name, or the error it got.
    pub outcome: Result<&'static str, LinkError>,
    /// What next.
    pub control: Control,
}

/// A session: the defaults in force, the stroke upload in progress, the frame count.
pub struct Session {
    defaults: Defaults,
    identity: Identity,
    upload: Upload,
    last_seq: Option<u16>,
    requests: u32,
    errors: u32,
}

impl Session {
    /// A new session with [`Defaults::POOL`].
    pub const fn new(identity: Identity) -> Self {
        Self {
            defaults: Defaults::POOL,
            identity,
            upload: Upload::new(),
            last_seq: None,
            requests: 0,
            errors: 0,
        }
    }

    /// Frames answered so far (errors included).
    pub const fn requests(&self) -> u32 {
        self.requests
    }

    /// Frames answered with an error so far.
    pub const fn errors(&self) -> u32 {
        self.errors
    }

    /// The `version` answer, as a frame sent unprompted at boot, into `out`.
    pub fn hello(&self, out: &mut [u8]) -> usize {
        let answer = Response::Version(self.version());
        frame::encode(SCHEMA_HASH, UNPROMPTED, &answer, out).unwrap_or(0)
    }

    /// Answers one received frame (from a [`crate::frame::FrameReader`]) into `out`,
    /// which should hold [`MAX_FRAME`] bytes.
    pub fn serve(&mut self, received: Received<'_>, out: &mut [u8]) -> Served {
        self.requests = self.requests.saturating_add(1);
        let (seq, result) = self.answer(received);
        let (response, outcome, control) = match result {
            Ok((response, name)) => {
                let control = if matches!(response, Response::Shutdown(_)) {
                    Control::Shutdown
                } else {
                    Control::Continue
                };
                (response, Ok(name), control)
            }
            Err(error) => {
                self.errors = self.errors.saturating_add(1);
                // The frame may have been a chunk of the stroke in progress: drop the
                // upload rather than estimate a window with a hole.
                self.upload.clear();
                (Response::Error(error), Err(error), Control::Continue)
            }
        };
        let len = match frame::encode(SCHEMA_HASH, seq, &response, out) {
            Ok(len) => len,
            Err(error) => {
                frame::encode(SCHEMA_HASH, seq, &Response::Error(error), out).unwrap_or(0)
            }
        };
        Served {
            len,
            outcome,
            control,
        }
    }

    /// The answer to a frame, and the sequence number it goes out with.
    #[inline(never)]
    fn answer(
        &mut self,
        received: Received<'_>,
    ) -> (u16, Result<(Response, &'static str), LinkError>) {
        let raw = match received {
            Received::Frame(raw) => raw,
            Received::Fault(fault) => return (UNPROMPTED, Err(LinkError::Frame(fault))),
        };
        let (header, body) = match frame::open(raw) {
            Ok(opened) => opened,
            Err(error) => return (UNPROMPTED, Err(error)),
        };
        let seq = header.seq;
        if header.schema != SCHEMA_HASH {
            let mismatch = LinkError::SchemaMismatch {
                device: SCHEMA_HASH,
                host: header.schema,
            };
            return (seq, Err(mismatch));
        }
        let request = decode_request(body);
        let restarts = matches!(request, Ok(Request::Version(_)));
        if let Err(fault) = self.check_sequence(seq, restarts) {
            return (seq, Err(LinkError::Sequence(fault)));
        }
        let result = request.and_then(|request| {
            let name = request.name();
            self.dispatch(&request).map(|response| (response, name))
        });
        (seq, result)
    }

    /// Accepts `seq` if it follows the last frame's (any number after boot, or when
    /// `restarts`); a gap is refused but moves the count on, so the host can go on.
    fn check_sequence(&mut self, seq: u16, restarts: bool) -> Result<(), SequenceFault> {
        let Some(last) = self.last_seq.filter(|_| !restarts) else {
            self.last_seq = Some(seq);
            return Ok(());
        };
        let expected = last.wrapping_add(1);
        if seq == expected {
            self.last_seq = Some(seq);
            Ok(())
        } else if seq == last {
            Err(SequenceFault::Duplicate { seq })
        } else if expected.wrapping_sub(seq) < 0x8000 {
            Err(SequenceFault::Stale { seq, expected })
        } else {
            self.last_seq = Some(seq);
            Err(SequenceFault::Gap { seq, expected })
        }
    }

    #[inline(never)]
    fn dispatch(&mut self, request: &Request) -> Result<Response, LinkError> {
        Ok(match request {
            Request::Version(_) => Response::Version(self.version()),
            Request::Collide(collide) => Response::Collide(self.collide(collide)?),
            Request::Params(overrides) => {
                let defaults = overrides.apply(&self.defaults)?;
                defaults
                    .model
                    .core()
                    .ok_or(LinkError::Unsupported(Unsupported::ReferenceModel))?;
                self.defaults = defaults;
                Response::Params(ParamsAnswer::from(&self.defaults))
            }
            Request::Stroke(chunk) => self.stroke(chunk)?,
            Request::Shot(shot) => Response::Shot(self.shot(shot)?),
            Request::Shutdown(_) => Response::Shutdown(ShutdownAnswer {
                requests: self.requests,
                errors: self.errors,
            }),
        })
    }

    #[inline(never)]
    fn collide(&self, request: &Collide) -> Result<CollideAnswer, LinkError> {
        let prepared = request.prepare(&self.defaults)?;
        let model = prepared
            .model
            .core()
            .ok_or(LinkError::Unsupported(Unsupported::ReferenceModel))?;
        let outcome = collide(&prepared.params, &prepared.impact, model)?;
        let input = InputEcho::new(
            request.speed,
            request.cut,
            request.roll,
            &prepared.params,
            &prepared.impact,
        );
        Ok(CollideAnswer::new(prepared.model, input, &outcome))
    }

    #[cfg(feature = "shot")]
    fn shot(&self, request: &crate::request::ShotRequest) -> Result<crate::shot::ShotAnswer, LinkError> {
        crate::shot::answer(request, &self.defaults)
    }

    #[cfg(not(feature = "shot"))]
    fn shot(&self, _: &crate::request::ShotRequest) -> Result<crate::shot::ShotAnswer, LinkError> {
        Err(LinkError::Unsupported(Unsupported::Shot))
    }

    /// Adds a chunk to the upload; on the last one, estimates and clears it.
    #[inline(never)]
    fn stroke(&mut self, chunk: &StrokeChunk) -> Result<Response, LinkError> {
        match self.upload.push(chunk).map_err(LinkError::Upload)? {
            Step::Held(progress) => Ok(Response::StrokeChunk(progress)),
            Step::Complete(setup) => {
                let answer = self.upload.estimate(&setup, &self.defaults.params);
                self.upload.clear();
                Ok(Response::Stroke(answer?))
            }
        }
    }

    fn version(&self) -> VersionAnswer {
        VersionAnswer {
            schema: SCHEMA_HASH,
            firmware: short_name(self.identity.firmware),
            board: short_name(self.identity.board),
            max_frame: MAX_FRAME as u16,
            max_samples: MAX_SAMPLES as u16,
            stroke_capacity: STROKE_CAPACITY as u16,
            shot: cfg!(feature = "shot"),
        }
    }
}

/// `text` as a short name; empty if it does not fit (the names are the firmware's own
/// constants, well within [`crate::response::NAME_LEN`]).
fn short_name<const N: usize>(text: &str) -> heapless::String<N> {
    heapless::String::try_from(text).unwrap_or_default()
}

/// The request in a frame's body. Not inlined, nor are [`Session::answer`] and
/// [`Session::dispatch`]: in one frame with the serial loop they cost 2.3 KB more flash
/// (measured on the release image).
#[inline(never)]
fn decode_request(body: &[u8]) -> Result<Request, LinkError> {
    frame::decode::<Request>(body)
}
