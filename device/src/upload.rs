//! A stroke upload: chunks checked for identity, order and count as they arrive, the
//! whole window checked for glitches, and only then estimated. Any fault drops the
//! upload, so nothing half-uploaded is ever estimated.

use cuesight::strike::TipOffset;
use cuesight::Params;
use cuesight_sensors::{estimate_raw, find_glitch, StrokeConfig, ACCEL_MPS2_PER_LSB};
use heapless::Vec;

use cuesight_link::error::{LinkError, UploadFault};
use cuesight_link::request::{cue, StrokeChunk, StrokeSetup};
use cuesight_link::response::{plain, StrokeAnswer, StrokeProgress};
use cuesight_link::{MAX_CHUNKS, STROKE_CAPACITY};

/// The stroke being uploaded: 10 KB of samples, all zero when new (see
/// [`crate::Session::with_upload`]).
pub struct Upload {
    /// Stroke id; meaningful while `chunks` is not empty.
    stroke: u16,
    /// Chunk count announced by chunk 0.
    count: u16,
    /// Where each received chunk ends in `samples`.
    chunks: Vec<u16, MAX_CHUNKS>,
    samples: Vec<i16, STROKE_CAPACITY>,
}

/// What a chunk did.
pub(crate) enum Step {
    /// Held; more chunks to come.
    Held(StrokeProgress),
    /// The last chunk: the whole stroke, ready for [`Upload::estimate`].
    Complete(StrokeSetup),
}

impl Default for Upload {
    fn default() -> Self {
        Self::new()
    }
}

impl Upload {
    /// No upload in progress.
    pub const fn new() -> Self {
        Self {
            stroke: 0,
            count: 0,
            chunks: Vec::new(),
            samples: Vec::new(),
        }
    }

    /// Drops the upload in progress.
    pub(crate) fn clear(&mut self) {
        self.chunks.clear();
        self.samples.clear();
    }

    /// Takes one chunk. Errors drop the upload (the caller clears on every error).
    pub(crate) fn push(&mut self, request: &StrokeChunk) -> Result<Step, UploadFault> {
        let (stroke, chunk, count) = (request.stroke, request.index, request.count);
        if count == 0 || usize::from(count) > MAX_CHUNKS || chunk >= count {
            return Err(UploadFault::BadChunk { chunk, count });
        }
        if chunk == 0 {
            self.clear();
            (self.stroke, self.count) = (stroke, count);
        } else if self.chunks.is_empty() || self.stroke != stroke {
            return Err(UploadFault::NotStarted { stroke, chunk });
        }
        let expected = self.count;
        if count != expected {
            return Err(UploadFault::CountChanged {
                stroke,
                count,
                expected,
            });
        }
        let expected = self.chunks.len() as u16;
        if chunk < expected {
            return Err(UploadFault::Duplicate { stroke, chunk });
        }
        if chunk > expected {
            return Err(UploadFault::Missing {
                stroke,
                expected,
                chunk,
            });
        }
        if request.samples.is_empty() {
            return Err(UploadFault::Empty { stroke, chunk });
        }
        let overflow = UploadFault::Overflow { stroke, chunk };
        self.samples
            .extend_from_slice(&request.samples)
            .map_err(|()| overflow)?;
        let samples = self.samples.len() as u16;
        self.chunks.push(samples).map_err(|_| overflow)?;
        if chunk + 1 < count {
            let chunks = chunk + 1;
            return Ok(Step::Held(StrokeProgress {
                stroke,
                chunks,
                count,
                samples,
            }));
        }
        request
            .setup
            .map(Step::Complete)
            .ok_or(UploadFault::NoSetup { stroke })
    }

    /// The chunk holding sample `index` of the stroke, and its index in that chunk.
    fn locate(&self, index: usize) -> (u16, u16) {
        let mut start = 0usize;
        for (chunk, &end) in self.chunks.iter().enumerate() {
            let end = usize::from(end);
            if index < end {
                return (chunk as u16, (index - start) as u16);
            }
            start = end;
        }
        (self.chunks.len() as u16, 0)
    }

    /// Checks the complete stroke for glitches, then estimates the cue speed and the
    /// struck ball with the session's `params`. Not inlined: the estimator's frame is
    /// gone before the answer is encoded.
    #[inline(never)]
    pub fn estimate(
        &self,
        setup: &StrokeSetup,
        params: &Params,
    ) -> Result<StrokeAnswer, LinkError> {
        let scale = setup.scale.unwrap_or(ACCEL_MPS2_PER_LSB);
        if let Some(glitch) = find_glitch(&self.samples, setup.rate_hz, scale) {
            let (chunk, sample) = self.locate(glitch.index);
            return Err(LinkError::Upload(UploadFault::Glitch {
                stroke: self.stroke,
                chunk,
                sample,
                kind: glitch.kind,
                value: glitch.value,
            }));
        }
        let cue = cue(setup.cue_mass, setup.tip_restitution)?;
        let [side, height] = setup.tip_offset.unwrap_or([0.0; 2]);
        let tip = TipOffset::new(side, height)?;
        let mut config = StrokeConfig::new(setup.rate_hz);
        // A raw word saturates at ±32768: the full scale follows the scale.
        config.full_scale = 32768.0 * if scale < 0.0 { -scale } else { scale };
        let estimate = estimate_raw(&self.samples, scale, &config)?;
        let hit = estimate.strike(params, &cue, tip)?;
        Ok(StrokeAnswer {
            stroke: self.stroke,
            cue_speed: estimate.cue_speed,
            ball_speed: hit.speed,
            ball_spin: plain(hit.spin),
            samples: self.samples.len() as u16,
            impact_index: estimate.impact_index as u16,
            stroke_duration: estimate.stroke_duration,
            rest_noise: estimate.rest_noise,
        })
    }
}
