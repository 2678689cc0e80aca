//! Text for people: a one-line [`Summary`] of every answer and a [`Sentence`] for every
//! error the device can send. The device sends data only (its errors are typed:
//! [`LinkError`]); the words, units and field names are added here, as defmt adds the
//! text of a log on the host.

use std::fmt;

use cuesight_link::error::{FrameFault, NoAim, SequenceFault, Unsupported};
use cuesight_link::frame::MAX_FRAME;
use cuesight_link::live::LiveReport;
use cuesight_link::names::{EndName, ShotMode};
use cuesight_link::shot::BallPart;
use cuesight_link::{LinkError, Response, UploadFault, MAX_CHUNKS, STROKE_CAPACITY};
use cuesight_sensors::{ConfigField, GlitchKind, StrokeError};

use crate::report::Friction;

/// `(x, y, z)` with three decimals.
struct Short<const N: usize>([f32; N]);

impl<const N: usize> fmt::Display for Short<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("(")?;
        for (i, c) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{c:.3}")?;
        }
        f.write_str(")")
    }
}

/// A schema hash as written in messages: `0x1234abcd`.
pub struct Schema(pub u32);

impl fmt::Display for Schema {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:#010x}", self.0)
    }
}

/// One line about an unprompted live report.
fn live_summary(f: &mut fmt::Formatter<'_>, report: &LiveReport) -> fmt::Result {
    match report {
        LiveReport::Stroke(s) => {
            write!(
                f,
                "live stroke {}: impact at sample {}, cue {:.3} m/s (backswing {:.3} m, pause {:.2} s, tempo {})",
                s.stroke,
                s.impact_sample,
                s.cue_speed,
                s.metrics.backswing_length,
                s.metrics.pause,
                s.metrics.tempo.map_or("-".to_string(), |t| format!("{t:.2}")),
            )?;
            match &s.guidance {
                None => f.write_str("; no plan set"),
                Some(Ok(answer)) => write!(f, "; {}", Summary(&Response::Shot(answer.clone()))),
                Some(Err(error)) => write!(f, "; the plan failed: {}", Sentence(error)),
            }
        }
        LiveReport::Fault(fault) => write!(f, "live: an impact that is no stroke: {fault:?}"),
        LiveReport::Sensor(fault) => write!(f, "live: IMU fault: {fault:?}"),
        LiveReport::FollowThrough(follow) => write!(
            f,
            "live stroke {}: follow-through {:.3} m in {:.3} s",
            follow.stroke, follow.length, follow.time
        ),
        LiveReport::TraceEnd(end) => {
            write!(
            f,
            "live: trace ended after {} samples{}; {:.0} instructions per sample (mean), {} (max), {} resolving a report (max)",
            end.samples,
            if end.truncated { " (the file was cut short)" } else { "" },
            end.work_mean_instructions(),
            end.work_max_instructions,
            end.resolve_max_instructions
        )
        }
    }
}

/// One line about an answer, no newline.
pub struct Summary<'a>(pub &'a Response);

impl fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Response::Version(v) => write!(
                f,
                "schema {}, {} on {}; frames up to {} bytes, strokes up to {} samples in chunks of {}; shot {}",
                Schema(v.schema),
                v.firmware,
                v.board,
                v.max_frame,
                v.stroke_capacity,
                v.max_samples,
                if v.shot { "served" } else { "not served" }
            ),
            Response::Collide(c) => write!(
                f,
                "{} {}: object v {} m/s, throw {:.2} deg; cue v {} m/s, w {} rad/s, deflection {:.2} deg",
                c.model.name(),
                c.regime.name(),
                Short(c.object.v),
                c.throw_deg,
                Short(c.cue.v),
                Short(c.cue.w),
                c.cue_deflection_deg
            ),
            Response::Params(p) => write!(
                f,
                "defaults now: model {}, {}, e* {}, mu_s {}, R {} m, M {} kg",
                p.model.name(),
                Friction {
                    mu: p.mu,
                    mu_b: p.mu_b,
                    mu_c: p.mu_c
                },
                p.restitution,
                p.mu_s,
                p.radius,
                p.mass
            ),
            Response::Plan(true) => f.write_str("plan set: each stroke the cue detects plays it"),
            Response::Plan(false) => f.write_str("no plan: strokes are reported without guidance"),
            Response::Live(report) => live_summary(f, report),
            Response::StrokeChunk(p) => write!(
                f,
                "stroke {}: {} of {} chunks held, {} samples",
                p.stroke, p.chunks, p.count, p.samples
            ),
            Response::Stroke(s) => write!(
                f,
                "stroke {}: cue {:.3} m/s at the tip -> ball {:.3} m/s, w {} rad/s ({} samples, impact at #{}, {:.3} s of stroke, rest noise {:.3} m/s2)",
                s.stroke,
                s.cue_speed,
                s.ball_speed,
                Short(s.ball_spin),
                s.samples,
                s.impact_index,
                s.stroke_duration,
                s.rest_noise
            ),
            Response::Shot(s) => {
                match (s.mode, &s.solve) {
                    (ShotMode::Solve, Some(solve)) => write!(
                        f,
                        "solved: aim {:.2} deg to pocket ball {} in pocket {} ({:+.2} deg from the ghost-ball aim, cut {:.1} deg)",
                        solve.aim_deg, solve.object, solve.pocket, solve.correction_deg, solve.cut_deg
                    )?,
                    _ => write!(f, "played: aim {:.2} deg", s.stroke.aim_deg)?,
                }
                write!(f, ", cue {:.2} m/s", s.stroke.cue_speed)?;
                match &s.contact {
                    Some(c) => write!(
                        f,
                        "; hits ball {} at {:.3} s, {} {}, throw {:.2} deg",
                        c.ball,
                        c.time,
                        c.model_used.name(),
                        c.regime.name(),
                        c.throw_deg
                    )?,
                    None => f.write_str("; hits no ball")?,
                }
                if let Some(object) = &s.object_ball {
                    write!(f, "; ball {} {}", object.ball, End(object))?;
                }
                write!(f, "; cue ball {}", End(&s.cue_ball))?;
                if let Some(t) = &s.target {
                    match (t.pocketed, t.miss) {
                        (true, _) => write!(f, "; target: pocketed")?,
                        (false, Some(miss)) => {
                            write!(f, "; target: missed by {:.1} mm", 1e3 * miss)?
                        }
                        (false, None) => write!(f, "; target: does not reach the pocket")?,
                    }
                }
                Ok(())
            }
            Response::Shutdown(s) => write!(
                f,
                "session over: {} requests answered, {} with an error",
                s.requests, s.errors
            ),
            Response::Error(e) => write!(f, "error: {}", Sentence(e)),
        }
    }
}

/// How a ball's path ends, in words.
struct End<'a>(&'a BallPart);

impl fmt::Display for End<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0;
        match (b.end, b.pocket) {
            (EndName::Pocket, Some(pocket)) => {
                write!(f, "drops in pocket {pocket} at {:.2} s", b.end_time)
            }
            (EndName::Pocket, None) => write!(f, "drops in a pocket at {:.2} s", b.end_time),
            (EndName::Rest, _) => write!(
                f,
                "rests at {} m at {:.2} s",
                Short(b.end_position),
                b.end_time
            ),
            (EndName::Cushion, _) => write!(
                f,
                "reaches a cushion at {} m at {:.2} s",
                Short(b.end_position),
                b.end_time
            ),
        }
    }
}

/// A sentence about an error the device sent, no newline, no `error: ` prefix.
pub struct Sentence<'a>(pub &'a LinkError);

impl fmt::Display for Sentence<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            LinkError::Frame(fault) => frame_fault(f, fault),
            LinkError::SchemaMismatch { device, host } => write!(
                f,
                "device speaks schema {}, this host {}",
                Schema(*device),
                Schema(*host)
            ),
            LinkError::Sequence(fault) => sequence_fault(f, fault),
            // The core's sentence: the field's name, the value and the range with units
            // (`speed = -1 is outside (0, 100] m/s`).
            LinkError::Invalid(error) => write!(f, "{error}"),
            LinkError::SpinAndRoll => f.write_str(
                "spin and roll were both given: give one (roll derives the spin from the speed)",
            ),
            LinkError::MissingAim => f.write_str(
                "shot needs an aim (aim, degrees) or a pocket to solve the aim for",
            ),
            LinkError::Unsupported(Unsupported::ReferenceModel) => f.write_str(
                "model reference (the f64 reference solver) runs on the host only: cuesight collide --model reference",
            ),
            LinkError::Unsupported(Unsupported::Shot) => {
                f.write_str("this firmware is built without shot guidance (feature shot)")
            }
            LinkError::Unsupported(Unsupported::Upload) => f.write_str(
                "this firmware takes no stroke uploads (the live cue's image: its IMU measures the strokes)",
            ),
            LinkError::NoAim(NoAim::ObjectBallNotHit) => f.write_str(
                "no aim: at the ghost-ball aim the cue ball does not hit the object ball first",
            ),
            LinkError::NoAim(NoAim::PocketUnreachable) => f.write_str(
                "no aim: the object ball stops, or passes the mouth, before the pocket",
            ),
            LinkError::NoAim(NoAim::NotConverged) => {
                f.write_str("no aim: the solver did not converge (the cut may be too thin)")
            }
            LinkError::Stroke(rejected) => stroke_rejected(f, rejected),
            LinkError::Upload(fault) => upload_fault(f, fault),
            LinkError::AnswerTooLarge => f.write_str(
                "the device's answer did not fit a frame (a firmware bug, please report it)",
            ),
        }
    }
}

/// What is wrong with a frame the device sent (or a request too large to send).
pub struct Unreadable<'a>(pub &'a LinkError);

impl fmt::Display for Unreadable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            LinkError::Frame(FrameFault::Cobs) => {
                f.write_str("unreadable answer: not valid COBS (bytes lost)")
            }
            LinkError::Frame(FrameFault::Oversized { length }) => write!(
                f,
                "unreadable answer: {length} bytes, longer than {MAX_FRAME}"
            ),
            LinkError::Frame(FrameFault::Short { length }) => write!(
                f,
                "unreadable answer: {length} bytes, shorter than a header and a CRC"
            ),
            LinkError::Frame(FrameFault::Crc { .. }) => {
                f.write_str("unreadable answer: its CRC-32 does not match (bytes changed)")
            }
            LinkError::Frame(FrameFault::Undecodable) => {
                f.write_str("unreadable answer: its body is no answer of this schema")
            }
            LinkError::Frame(FrameFault::TrailingBytes { count }) => write!(
                f,
                "unreadable answer: {count} bytes left over after the answer"
            ),
            LinkError::AnswerTooLarge => {
                f.write_str("the request does not fit one frame; not sent")
            }
            other => write!(f, "unreadable answer: {}", Sentence(other)),
        }
    }
}

fn frame_fault(f: &mut fmt::Formatter<'_>, fault: &FrameFault) -> fmt::Result {
    match fault {
        FrameFault::Cobs => f.write_str(
            "the device received a frame that is not valid COBS (bytes lost on the way); not acted on",
        ),
        FrameFault::Oversized { length } => write!(
            f,
            "the device received a frame of {length} bytes, longer than {MAX_FRAME}; skipped"
        ),
        FrameFault::Short { length } => write!(
            f,
            "the device received a frame of {length} bytes, shorter than a header and a CRC (10 bytes)"
        ),
        FrameFault::Crc { seq_as_read } => write!(
            f,
            "the device received a frame whose CRC-32 does not match (bytes changed on the way; seq read as {seq_as_read}); not acted on"
        ),
        FrameFault::Undecodable => f.write_str(
            "the device could not decode the frame's body as a request of its schema",
        ),
        FrameFault::TrailingBytes { count } => write!(
            f,
            "the frame's body is a request with {count} bytes left over; not acted on"
        ),
    }
}

fn sequence_fault(f: &mut fmt::Formatter<'_>, fault: &SequenceFault) -> fmt::Result {
    match fault {
        SequenceFault::Duplicate { seq } => {
            write!(f, "frame {seq} was received twice; the copy was not acted on")
        }
        SequenceFault::Stale { seq, expected } => write!(
            f,
            "frame {seq} is older than frame {expected}, the one expected (reordered or replayed); not acted on"
        ),
        SequenceFault::Gap { seq, expected } => write!(
            f,
            "frame {seq} arrived where frame {expected} was expected: {} frame(s) lost; not acted on",
            seq.wrapping_sub(*expected)
        ),
    }
}

/// The estimator's error, in the words of the `stroke` request (its `rate_hz` and
/// `scale`, sample indices over all chunks).
fn stroke_rejected(f: &mut fmt::Formatter<'_>, rejected: &StrokeError) -> fmt::Result {
    match rejected {
        StrokeError::InvalidConfig(ConfigField::SampleRate) => {
            f.write_str("stroke: rate_hz is outside [500, 100000] Hz")
        }
        StrokeError::InvalidConfig(ConfigField::FullScale) => f.write_str(
            "stroke: scale makes the full scale (32768 |scale| m/s2) no larger than the impact threshold",
        ),
        StrokeError::InvalidConfig(_) => write!(f, "stroke: {rejected} (a device default; a firmware bug, please report it)"),
        StrokeError::TooShort { len, min } => write!(
            f,
            "stroke: {len} samples, {min} needed at this rate (150 ms of rest, then the stroke and the impact)"
        ),
        StrokeError::NotFinite { .. } | StrokeError::LengthMismatch { .. } => {
            f.write_str("stroke: scale must be a finite, non-zero number (m/s2 per LSB)")
        }
        StrokeError::NotAtRest => f.write_str(
            "stroke: no 150 ms rest before the impact (the capture must start with the cue still)",
        ),
        StrokeError::NoImpact => {
            f.write_str("stroke: no impact-sized deceleration after the rest")
        }
        StrokeError::Saturated { index } => write!(
            f,
            "stroke: sample {index} (counted over all chunks), between the rest and the impact, is at the sensor's full scale"
        ),
        StrokeError::NotForward { speed } => write!(
            f,
            "stroke: the integrated speed at the impact is {speed:.3} m/s, not forward (wrong axis sign, or no stroke)"
        ),
        StrokeError::Strike(error) => write!(
            f,
            "stroke: the strike model refused the estimated stroke: {error}"
        ),
    }
}

fn upload_fault(f: &mut fmt::Formatter<'_>, fault: &UploadFault) -> fmt::Result {
    match fault {
        UploadFault::NotStarted { stroke, chunk } => write!(
            f,
            "stroke {stroke}, chunk {chunk}: chunk 0 of this stroke was not received (or an earlier error dropped the upload)"
        ),
        UploadFault::Missing {
            stroke,
            expected,
            chunk,
        } => write!(
            f,
            "stroke {stroke}: chunk {chunk} arrived where chunk {expected} was expected (chunks lost or reordered); upload dropped"
        ),
        UploadFault::Duplicate { stroke, chunk } => write!(
            f,
            "stroke {stroke}: chunk {chunk} was already received; upload dropped"
        ),
        UploadFault::CountChanged {
            stroke,
            count,
            expected,
        } => write!(
            f,
            "stroke {stroke}: a chunk says {count} chunks, chunk 0 said {expected}; upload dropped"
        ),
        UploadFault::BadChunk { chunk, count } => write!(
            f,
            "stroke chunk {chunk} of {count}: the count must be 1 to {MAX_CHUNKS} and the index below it"
        ),
        UploadFault::Empty { stroke, chunk } => {
            write!(f, "stroke {stroke}, chunk {chunk}: no samples; upload dropped")
        }
        UploadFault::Overflow { stroke, chunk } => write!(
            f,
            "stroke {stroke}, chunk {chunk}: the stroke would hold more than {STROKE_CAPACITY} samples; upload dropped"
        ),
        UploadFault::NoSetup { stroke } => write!(
            f,
            "stroke {stroke}: the last chunk carries no setup (rate_hz is needed); upload dropped"
        ),
        UploadFault::Glitch {
            stroke,
            chunk,
            sample,
            kind,
            value,
        } => {
            write!(f, "stroke {stroke}, chunk {chunk}, sample {sample}: ")?;
            match kind {
                GlitchKind::Rail => write!(
                    f,
                    "raw value {value} is at the sensor's rail before the impact"
                )?,
                GlitchKind::Spike => write!(
                    f,
                    "raw value {value} is a single-sample spike (its neighbours agree)"
                )?,
            }
            f.write_str("; upload dropped, nothing estimated")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight::{Error, Field};

    #[test]
    fn a_value_error_names_field_value_range_and_unit() {
        let error = LinkError::Invalid(Error::OutOfRange {
            field: Field::Speed,
            value: -1.0,
        });
        assert_eq!(
            Sentence(&error).to_string(),
            "speed = -1 is outside (0, 100] m/s"
        );
        assert_eq!(
            Summary(&Response::Error(error)).to_string(),
            "error: speed = -1 is outside (0, 100] m/s"
        );
    }

    #[test]
    fn schema_mismatch_names_both_hashes() {
        let error = LinkError::SchemaMismatch {
            device: 0x1234_abcd,
            host: 0xffe5_b4dd,
        };
        assert_eq!(
            Sentence(&error).to_string(),
            "device speaks schema 0x1234abcd, this host 0xffe5b4dd"
        );
    }

    #[test]
    fn a_glitch_names_stroke_chunk_and_sample() {
        let error = LinkError::Upload(UploadFault::Glitch {
            stroke: 3,
            chunk: 7,
            sample: 12,
            kind: GlitchKind::Rail,
            value: -32768,
        });
        let text = Sentence(&error).to_string();
        assert!(
            text.starts_with("stroke 3, chunk 7, sample 12: raw value -32768"),
            "{text}"
        );
    }

    #[test]
    fn no_sentence_is_empty_or_multiline() {
        let errors = [
            LinkError::Frame(FrameFault::Cobs),
            LinkError::Frame(FrameFault::Oversized { length: 2000 }),
            LinkError::Frame(FrameFault::Short { length: 3 }),
            LinkError::Frame(FrameFault::Crc { seq_as_read: 4 }),
            LinkError::Frame(FrameFault::Undecodable),
            LinkError::Frame(FrameFault::TrailingBytes { count: 2 }),
            LinkError::Sequence(SequenceFault::Duplicate { seq: 1 }),
            LinkError::Sequence(SequenceFault::Stale {
                seq: 1,
                expected: 3,
            }),
            LinkError::Sequence(SequenceFault::Gap {
                seq: 5,
                expected: 3,
            }),
            LinkError::Invalid(Error::NotFinite {
                field: Field::Friction,
            }),
            LinkError::Invalid(Error::NumericalFailure),
            LinkError::SpinAndRoll,
            LinkError::MissingAim,
            LinkError::Unsupported(Unsupported::ReferenceModel),
            LinkError::Unsupported(Unsupported::Shot),
            LinkError::Unsupported(Unsupported::Upload),
            LinkError::NoAim(NoAim::ObjectBallNotHit),
            LinkError::NoAim(NoAim::PocketUnreachable),
            LinkError::NoAim(NoAim::NotConverged),
            LinkError::Stroke(StrokeError::InvalidConfig(ConfigField::SampleRate)),
            LinkError::Stroke(StrokeError::InvalidConfig(ConfigField::FullScale)),
            LinkError::Stroke(StrokeError::InvalidConfig(ConfigField::MinRest)),
            LinkError::Stroke(StrokeError::TooShort { len: 10, min: 600 }),
            LinkError::Stroke(StrokeError::NotFinite { index: 0 }),
            LinkError::Stroke(StrokeError::NotAtRest),
            LinkError::Stroke(StrokeError::NoImpact),
            LinkError::Stroke(StrokeError::Saturated { index: 99 }),
            LinkError::Stroke(StrokeError::NotForward { speed: -0.5 }),
            LinkError::Stroke(StrokeError::Strike(Error::NumericalFailure)),
            LinkError::Upload(UploadFault::NotStarted {
                stroke: 1,
                chunk: 2,
            }),
            LinkError::Upload(UploadFault::Missing {
                stroke: 1,
                expected: 2,
                chunk: 3,
            }),
            LinkError::Upload(UploadFault::Duplicate {
                stroke: 1,
                chunk: 2,
            }),
            LinkError::Upload(UploadFault::CountChanged {
                stroke: 1,
                count: 3,
                expected: 2,
            }),
            LinkError::Upload(UploadFault::BadChunk { chunk: 5, count: 0 }),
            LinkError::Upload(UploadFault::Empty {
                stroke: 1,
                chunk: 0,
            }),
            LinkError::Upload(UploadFault::Overflow {
                stroke: 1,
                chunk: 20,
            }),
            LinkError::Upload(UploadFault::NoSetup { stroke: 1 }),
            LinkError::Upload(UploadFault::Glitch {
                stroke: 1,
                chunk: 2,
                sample: 3,
                kind: GlitchKind::Spike,
                value: 9000,
            }),
            LinkError::AnswerTooLarge,
        ];
        for error in errors {
            let text = Sentence(&error).to_string();
            assert!(
                !text.is_empty() && !text.contains('\n'),
                "{error:?}: {text}"
            );
        }
    }
}
