//! The device side of the protocol: session state and [`Session::serve`], which turns
//! one line into one answer line. Pure (no I/O), so the firmware's serial loop stays a
//! few lines and everything here is tested on the host.

#[cfg(feature = "shot")]
use cuesight::aim::AimError;
use cuesight::collide;
#[cfg(feature = "shot")]
use cuesight::guidance::{guide, Guidance};
use cuesight::strike::{Cue, TipOffset};
use cuesight_sensors::{estimate_raw, StrokeConfig, StrokeError, ACCEL_MPS2_PER_LSB};
use heapless::Vec;

use crate::answer::{
    Answer, CollideAnswer, ParamsAnswer, ShutdownAnswer, StrokeAnswer, StrokeChunkAnswer,
    VersionAnswer,
};
use crate::decode::{self, Kind};
use crate::json::Reader;
use crate::line::Event;
use crate::names::ModelName;
use crate::problem::{ErrorKind, Name, Problem};
use crate::request::{Defaults, Stroke};
#[cfg(feature = "shot")]
use crate::shot::{write_shot, PreparedShot};
use crate::{MAX_ANSWER, MAX_LINE, MAX_SAMPLES, PROTOCOL_VERSION, STROKE_CAPACITY};

/// An answer line: JSON and its `\n`.
pub type AnswerLine = Vec<u8, MAX_ANSWER>;

/// Who is answering, for `version`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Identity {
    /// Firmware name and version, e.g. `cuesight-firmware 0.1.0`.
    pub firmware: &'static str,
    /// Board name, e.g. `qemu-mps2-an386`.
    pub board: &'static str,
}

/// What the caller does after sending an answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Control {
    /// Keep reading lines.
    Continue,
    /// The session is over (`shutdown`): flush the answer and stop.
    Shutdown,
}

/// Outcome of serving one line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Served {
    /// The request's name, or `None` when the line was answered with an error.
    pub request: Option<&'static str>,
    /// The error class, when the answer is an error.
    pub error: Option<ErrorKind>,
    /// Whether to go on.
    pub control: Control,
}

/// One session: the defaults set by `params`, the samples of a `stroke` sent in chunks
/// (10 KB: keep the session in a static or on a large stack), and the counters
/// `shutdown` reports.
#[derive(Clone, Debug)]
pub struct Session {
    defaults: Defaults,
    identity: Identity,
    capture: Vec<i16, STROKE_CAPACITY>,
    requests: u32,
    errors: u32,
}

impl Session {
    /// A new session with [`Defaults::POOL`].
    pub const fn new(identity: Identity) -> Self {
        Self {
            defaults: Defaults::POOL,
            identity,
            capture: Vec::new(),
            requests: 0,
            errors: 0,
        }
    }

    /// The defaults in force.
    pub const fn defaults(&self) -> &Defaults {
        &self.defaults
    }

    /// Lines answered so far (errors included).
    pub const fn requests(&self) -> u32 {
        self.requests
    }

    /// Lines answered with an error so far.
    pub const fn errors(&self) -> u32 {
        self.errors
    }

    /// Answers one [`Event`] of a [`crate::LineReader`] into `out` (JSON and `\n`).
    ///
    /// Returns `None`, with `out` empty, for a blank line (only spaces or tabs), which
    /// gets no answer: an empty line on a terminal is not a request.
    pub fn serve(&mut self, event: Event<'_>, out: &mut AnswerLine) -> Option<Served> {
        out.clear();
        if let Event::Line(line) = event {
            if line.iter().all(|b| matches!(b, b' ' | b'\t')) {
                return None;
            }
        }
        self.requests = self.requests.saturating_add(1);
        let result = match event {
            Event::Line(line) => self.answer(line, out),
            Event::Overlong { length } => Err(Problem::LineTooLong {
                length,
                limit: MAX_LINE,
            }),
        };
        Some(match result {
            Ok((name, control)) => Served {
                request: Some(name),
                error: None,
                control,
            },
            Err(problem) => self.refuse(&problem, out),
        })
    }

    /// The error answer for `problem`.
    #[inline(never)]
    fn refuse(&mut self, problem: &Problem, out: &mut AnswerLine) -> Served {
        self.errors = self.errors.saturating_add(1);
        // The line may have been a chunk of the stroke in progress: drop it rather
        // than estimate from a window with a hole.
        self.capture.clear();
        Answer::Error(problem.to_answer()).write(out);
        Served {
            request: None,
            error: Some(problem.kind()),
            control: Control::Continue,
        }
    }

    /// Answers one line (without its newline): [`Session::serve`] for a line that fit.
    pub fn serve_line(&mut self, line: &[u8], out: &mut AnswerLine) -> Option<Served> {
        if line.len() > MAX_LINE {
            return self.serve(Event::Overlong { length: line.len() }, out);
        }
        self.serve(Event::Line(line), out)
    }

    /// Decodes and answers one line into `out`. Each request is answered by its own
    /// function, which reads the request's body (so only that body is on the stack:
    /// the firmware's peak stack is a budget) and writes the answer.
    fn answer(
        &mut self,
        line: &[u8],
        out: &mut AnswerLine,
    ) -> Result<(&'static str, Control), Problem> {
        let (kind, mut reader) = decode::open(line)?;
        let r = &mut reader;
        let mut control = Control::Continue;
        match kind {
            Kind::Collide => self.collide(r, out)?,
            Kind::Params => self.set_params(r, out)?,
            Kind::Stroke => self.stroke(r, out)?,
            #[cfg(feature = "shot")]
            Kind::Shot => self.shot(r, out)?,
            Kind::Version => {
                decode::read_empty(r, "version")?;
                decode::close(r)?;
                Answer::Version(self.version()).write(out);
            }
            Kind::Shutdown => {
                decode::read_empty(r, "shutdown")?;
                decode::close(r)?;
                let answer = ShutdownAnswer {
                    requests: self.requests,
                    errors: self.errors,
                };
                Answer::Shutdown(answer).write(out);
                control = Control::Shutdown;
            }
        }
        Ok((kind.name(), control))
    }

    #[inline(never)]
    fn collide(&self, r: &mut Reader<'_>, out: &mut AnswerLine) -> Result<(), Problem> {
        let request = decode::read_collide(r)?;
        decode::close(r)?;
        let prepared = request.prepare(&self.defaults)?;
        let model = core_model(prepared.model)?;
        let outcome = collide(&prepared.params, &prepared.impact, model)?;
        let answer = CollideAnswer::new(prepared.model, prepared.input, &outcome);
        Answer::Collide(answer).write(out);
        Ok(())
    }

    /// `shot`, answered into `out` here rather than through [`Answer`], which stays
    /// small, and written by hand ([`crate::shot::write_shot`]). The request is read
    /// and validated, the guidance computed and the answer written each in a frame of
    /// its own: the shot's solve is the firmware's deepest stack (issue 6's 8 KiB).
    #[cfg(feature = "shot")]
    #[inline(never)]
    fn shot(&self, r: &mut Reader<'_>, out: &mut AnswerLine) -> Result<(), Problem> {
        // The prepared shot and the guidance are read where they lie: moved out of
        // their `Result`s, each (a few hundred bytes) would be copied, and be on this
        // frame twice.
        let prepared = self.prepare_shot(r);
        let (prepared, speed, tip) = match prepared {
            Ok(ref prepared) => prepared,
            Err(problem) => return Err(problem),
        };
        let guidance = run_guide(prepared, *speed);
        let guidance = match guidance {
            Ok(ref guidance) => guidance,
            Err(error) => return Err(error.into()),
        };
        write_shot(out, *tip, prepared.model, guidance);
        Ok(())
    }

    /// The `shot` request, validated; in its own frame, which is gone before the
    /// guidance runs.
    #[cfg(feature = "shot")]
    #[inline(never)]
    fn prepare_shot(&self, r: &mut Reader<'_>) -> Result<(PreparedShot, f32, [f32; 2]), Problem> {
        let request = decode::read_shot(r)?;
        decode::close(r)?;
        let prepared = request.prepare(&self.defaults)?;
        Ok((prepared, request.speed, request.tip))
    }

    #[inline(never)]
    fn set_params(&mut self, r: &mut Reader<'_>, out: &mut AnswerLine) -> Result<(), Problem> {
        let overrides = decode::read_params(r)?;
        decode::close(r)?;
        let defaults = overrides.apply(&self.defaults)?;
        core_model(defaults.model)?;
        self.defaults = defaults;
        Answer::Params(ParamsAnswer::from(&self.defaults)).write(out);
        Ok(())
    }

    /// Adds a chunk to the capture; on the last chunk, estimates and clears it.
    #[inline(never)]
    fn stroke(&mut self, r: &mut Reader<'_>, out: &mut AnswerLine) -> Result<(), Problem> {
        let stroke = decode::read_stroke(r)?;
        decode::close(r)?;
        if self.capture.extend_from_slice(&stroke.samples).is_err() {
            self.capture.clear();
            return Err(Problem::TooMany {
                field: "samples",
                limit: STROKE_CAPACITY,
            });
        }
        if stroke.more {
            let answer = StrokeChunkAnswer {
                samples: self.capture.len() as u32,
                capacity: STROKE_CAPACITY as u32,
            };
            Answer::StrokeChunk(answer).write(out);
            return Ok(());
        }
        let result = self.estimate(&stroke);
        self.capture.clear();
        Answer::Stroke(result?).write(out);
        Ok(())
    }

    fn estimate(&self, stroke: &Stroke) -> Result<StrokeAnswer, Problem> {
        // Checked by the decoder: the last chunk has a rate.
        let rate_hz = stroke.rate_hz.unwrap_or(f32::NAN);
        let scale = stroke.scale.unwrap_or(ACCEL_MPS2_PER_LSB);
        let cue = Cue::new(
            stroke.cue_mass.unwrap_or(Cue::TYPICAL.mass()),
            stroke
                .tip_restitution
                .unwrap_or(Cue::TYPICAL.tip_restitution()),
        )?;
        let [side, height] = stroke.tip_offset.unwrap_or([0.0; 2]);
        let tip = TipOffset::new(side, height)?;
        let mut config = StrokeConfig::new(rate_hz);
        // A raw word saturates at ±32768: the full scale follows the scale.
        config.full_scale = 32768.0 * if scale < 0.0 { -scale } else { scale };
        let estimate = estimate_raw(&self.capture, scale, &config).map_err(Problem::Stroke)?;
        let hit = estimate
            .strike(&self.defaults.params, &cue, tip)
            .map_err(|e| match e {
                StrokeError::Strike(error) => Problem::Value(error),
                other => Problem::Stroke(other),
            })?;
        Ok(StrokeAnswer {
            cue_speed: estimate.cue_speed,
            ball_speed: hit.speed,
            ball_spin: hit.spin.to_array().map(|c| c + 0.0),
            samples: self.capture.len() as u32,
            impact_index: estimate.impact_index as u32,
            stroke_duration: estimate.stroke_duration,
            rest_noise: estimate.rest_noise,
        })
    }

    fn version(&self) -> VersionAnswer {
        VersionAnswer {
            protocol: PROTOCOL_VERSION,
            firmware: Name::of(self.identity.firmware),
            board: Name::of(self.identity.board),
            max_line: MAX_LINE as u32,
            max_samples: MAX_SAMPLES as u32,
            stroke_capacity: STROKE_CAPACITY as u32,
        }
    }
}

/// [`guide`] on a prepared shot, in its own frame.
#[cfg(feature = "shot")]
#[inline(never)]
fn run_guide(prepared: &PreparedShot, speed: f32) -> Result<Guidance, AimError> {
    guide(
        &prepared.scene,
        speed,
        prepared.tip,
        prepared.aim,
        &prepared.setup,
    )
}

/// The core model for `name`; `reference` is host-only.
fn core_model(name: ModelName) -> Result<cuesight::Model, Problem> {
    name.core().ok_or(Problem::Unsupported {
        field: "model",
        reason: "reference runs on the host only (cuesight collide --model reference)",
    })
}
