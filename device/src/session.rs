//! The device's side of the link: one frame in, one answer frame out, and the state
//! kept between them (the session defaults, the stroke upload, the frame count).

use core::borrow::BorrowMut;

use cuesight::collide;

use cuesight_link::error::{LinkError, SequenceFault, Unsupported};
use cuesight_link::frame::{self, next_seq, Received, MAX_FRAME, UNPROMPTED};
use cuesight_link::live::LiveReport;
use cuesight_link::request::{Collide, Defaults, Request, ShotRequest, StrokeChunk};
use cuesight_link::response::{
    CollideAnswer, InputEcho, ParamsAnswer, Response, ShutdownAnswer, VersionAnswer,
};
use cuesight_link::{ShotAnswer, MAX_SAMPLES, SCHEMA_HASH, STROKE_CAPACITY};

#[cfg(feature = "upload")]
use crate::upload::Step;
use crate::upload::Upload;

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
///
/// It owns its [`Upload`] (10 KB: [`Session::new`]), or borrows one
/// ([`Session::with_upload`]): a device keeps the upload in a static of its own, whose
/// initial value is all zero (`.bss`), so the session is built without a 10 KB
/// temporary on the stack.
pub struct Session<U: BorrowMut<Upload> = Upload> {
    defaults: Defaults,
    /// The live cue's planned shot (`plan`; never set without the `shot` feature).
    #[cfg_attr(not(feature = "shot"), allow(dead_code))]
    plan: Option<ShotRequest>,
    identity: Identity,
    upload: U,
    last_seq: Option<u16>,
    requests: u32,
    errors: u32,
}

impl Session {
    /// A new session with [`Defaults::POOL`] and an upload of its own.
    pub const fn new(identity: Identity) -> Self {
        Session::with_upload(identity, Upload::new())
    }
}

impl<U: BorrowMut<Upload>> Session<U> {
    /// A new session with [`Defaults::POOL`], its stroke upload kept in `upload`.
    pub const fn with_upload(identity: Identity, upload: U) -> Self {
        Self {
            defaults: Defaults::POOL,
            plan: None,
            identity,
            upload,
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

    /// Answers one received frame (from a [`cuesight_link::frame::FrameReader`]) into `out`,
    /// which should hold [`MAX_FRAME`] bytes.
    ///
    /// Each answer is encoded where it is computed, in the frame of the function that
    /// computed it, so no answer is copied up the call chain: the device's stack holds
    /// one at a time (its peak stack is a budget).
    #[inline(never)]
    pub fn serve(&mut self, received: Received<'_>, out: &mut [u8]) -> Served {
        self.requests = self.requests.saturating_add(1);
        let (seq, result) = self.answer(received, out);
        match result {
            Ok((len, name, control)) => Served {
                len,
                outcome: Ok(name),
                control,
            },
            Err(error) => {
                self.errors = self.errors.saturating_add(1);
                // The frame may have been a chunk of the stroke in progress: drop the
                // upload rather than estimate a window with a hole.
                self.upload.borrow_mut().clear();
                Served {
                    len: send(seq, &Response::Error(error), out).unwrap_or(0),
                    outcome: Err(error),
                    control: Control::Continue,
                }
            }
        }
    }

    /// Answers a frame into `out`: the sequence number the answer goes out with, and
    /// the answer's length, the request's name and what next, or the error to send.
    #[inline(never)]
    fn answer(&mut self, received: Received<'_>, out: &mut [u8]) -> (u16, Answered) {
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
        let result = request.and_then(|mut request| self.dispatch(&mut request, seq, out));
        (seq, result)
    }

    /// Accepts `seq` if it follows the last frame's (any number after boot, or when
    /// `restarts`); a gap is refused but moves the count on, so the host can go on.
    fn check_sequence(&mut self, seq: u16, restarts: bool) -> Result<(), SequenceFault> {
        let Some(last) = self.last_seq.filter(|_| !restarts) else {
            self.last_seq = Some(seq);
            return Ok(());
        };
        let expected = next_seq(last);
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

    /// Runs `request` and encodes its answer into `out` (a `plan` is moved out of it:
    /// a clone costs flash).
    #[inline(never)]
    fn dispatch(&mut self, request: &mut Request, seq: u16, out: &mut [u8]) -> Answered {
        let name = request.name();
        let mut control = Control::Continue;
        let len = match request {
            Request::Version(_) => send(seq, &Response::Version(self.version()), out)?,
            Request::Collide(collide) => self.collide(collide, seq, out)?,
            Request::Params(overrides) => {
                let defaults = overrides.apply(&self.defaults)?;
                defaults
                    .model
                    .core()
                    .ok_or(LinkError::Unsupported(Unsupported::ReferenceModel))?;
                self.defaults = defaults;
                send(
                    seq,
                    &Response::Params(ParamsAnswer::from(&self.defaults)),
                    out,
                )?
            }
            Request::Stroke(chunk) => self.stroke(chunk, seq, out)?,
            Request::Shot(shot) => self.shot(shot, seq, out)?,
            Request::Plan(plan) => self.plan(plan, seq, out)?,
            Request::Shutdown(_) => {
                control = Control::Shutdown;
                let counts = ShutdownAnswer {
                    requests: self.requests,
                    errors: self.errors,
                };
                send(seq, &Response::Shutdown(counts), out)?
            }
        };
        Ok((len, name, control))
    }

    #[inline(never)]
    fn collide(&self, request: &Collide, seq: u16, out: &mut [u8]) -> Result<usize, LinkError> {
        let prepared = request.prepare(&self.defaults)?;
        let model = prepared
            .model
            .core()
            .ok_or(LinkError::Unsupported(Unsupported::ReferenceModel))?;
        let outcome = collide(&prepared.params, &prepared.impact, model)?;
        let answer =
            CollideAnswer::new(prepared.model, InputEcho::of(request, &prepared), &outcome);
        send(seq, &Response::Collide(answer), out)
    }

    /// `shot`, guided and encoded in a frame of its own (the guidance is the deepest
    /// stack the device has).
    #[cfg(feature = "shot")]
    #[inline(never)]
    fn shot(&self, request: &ShotRequest, seq: u16, out: &mut [u8]) -> Result<usize, LinkError> {
        // Read where it lies: moved out of its `Result`, the answer would be copied.
        match crate::guide::answer(request, &self.defaults) {
            Ok(ref response) => send(seq, response, out),
            Err(error) => Err(error),
        }
    }

    #[cfg(not(feature = "shot"))]
    fn shot(&self, _: &ShotRequest, _: u16, _: &mut [u8]) -> Result<usize, LinkError> {
        Err(LinkError::Unsupported(Unsupported::Shot))
    }

    /// `plan`: checked (the scene, the parameters, the tip, the aim or pocket; not its
    /// speed, which each stroke replaces) against the defaults in force, then kept;
    /// `None` forgets it.
    #[cfg(feature = "shot")]
    #[inline(never)]
    fn plan(
        &mut self,
        plan: &mut Option<ShotRequest>,
        seq: u16,
        out: &mut [u8],
    ) -> Result<usize, LinkError> {
        if let Some(plan) = plan {
            crate::guide::check(plan, &self.defaults)?;
        }
        self.plan = plan.take();
        send(seq, &Response::Plan(self.plan.is_some()), out)
    }

    #[cfg(not(feature = "shot"))]
    fn plan(
        &mut self,
        _: &mut Option<ShotRequest>,
        _: u16,
        _: &mut [u8],
    ) -> Result<usize, LinkError> {
        Err(LinkError::Unsupported(Unsupported::Shot))
    }

    /// The planned shot played at `cue_speed` (a stroke the live cue measured), with
    /// the defaults in force; `None` when no plan is set.
    #[cfg(feature = "shot")]
    #[inline(never)]
    pub fn plan_guidance(&self, cue_speed: f32) -> Option<Result<ShotAnswer, LinkError>> {
        let plan = self.plan.as_ref()?;
        Some(crate::guide::play_plan(plan, cue_speed, &self.defaults))
    }

    /// Without the `shot` feature there is no plan.
    #[cfg(not(feature = "shot"))]
    pub fn plan_guidance(&self, _: f32) -> Option<Result<ShotAnswer, LinkError>> {
        None
    }

    /// Without the `upload` feature no stroke is taken.
    #[cfg(not(feature = "upload"))]
    fn stroke(&mut self, _: &StrokeChunk, _: u16, _: &mut [u8]) -> Result<usize, LinkError> {
        Err(LinkError::Unsupported(Unsupported::Upload))
    }

    /// Adds a chunk to the upload; on the last one, estimates and clears it.
    #[cfg(feature = "upload")]
    #[inline(never)]
    fn stroke(
        &mut self,
        chunk: &StrokeChunk,
        seq: u16,
        out: &mut [u8],
    ) -> Result<usize, LinkError> {
        let upload = self.upload.borrow_mut();
        let response = match upload.push(chunk).map_err(LinkError::Upload)? {
            Step::Held(progress) => Response::StrokeChunk(progress),
            Step::Complete(setup) => {
                let answer = upload.estimate(&setup, &self.defaults.params);
                upload.clear();
                Response::Stroke(answer?)
            }
        };
        send(seq, &response, out)
    }

    fn version(&self) -> VersionAnswer {
        VersionAnswer {
            schema: SCHEMA_HASH,
            firmware: short_name(self.identity.firmware),
            board: short_name(self.identity.board),
            max_frame: MAX_FRAME as u16,
            max_samples: MAX_SAMPLES as u16,
            // No uploads without the `upload` feature: room for none.
            stroke_capacity: if cfg!(feature = "upload") {
                STROKE_CAPACITY as u16
            } else {
                0
            },
            shot: cfg!(feature = "shot"),
        }
    }
}

/// `text` as a short name; empty if it does not fit (the names are the firmware's own
/// constants, well within [`cuesight_link::response::NAME_LEN`]). Out of line: the
/// version answer's two names share one copy (36 B of flash).
#[inline(never)]
fn short_name<const N: usize>(text: &str) -> heapless::String<N> {
    heapless::String::try_from(text).unwrap_or_default()
}

/// What [`Session::answer`] did: the answer's length, the request's name and what
/// next; or the error to send.
type Answered = Result<(usize, &'static str, Control), LinkError>;

/// A live report as an unprompted frame, into `out` ([`MAX_FRAME`] bytes); 0 if it
/// does not fit.
pub fn live_frame(report: LiveReport, out: &mut [u8]) -> usize {
    send(UNPROMPTED, &Response::Live(report), out).unwrap_or(0)
}

/// Encodes `response` as the answer to frame `seq`.
fn send(seq: u16, response: &Response, out: &mut [u8]) -> Result<usize, LinkError> {
    frame::encode(SCHEMA_HASH, seq, response, out)
}

/// The request in a frame's body. Not inlined, nor are [`Session::answer`] and
/// [`Session::dispatch`]: in one frame with the serial loop they cost 2.3 KB more flash
/// (measured on the release image).
#[inline(never)]
fn decode_request(body: &[u8]) -> Result<Request, LinkError> {
    frame::decode::<Request>(body)
}
