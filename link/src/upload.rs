//! A stroke upload: chunks checked for identity, order and count as they arrive, the
//! whole window checked for glitches, and only then estimated. Any fault drops the
//! upload, so nothing half-uploaded is ever estimated.

use cuesight::strike::{Cue, TipOffset};
use cuesight::Params;
use cuesight_sensors::{
    estimate_raw, find_glitch, GlitchKind, StrokeConfig, StrokeError, ACCEL_MPS2_PER_LSB,
};
use heapless::Vec;

use crate::error::{GlitchName, LinkError, UploadFault};
use crate::limits::{MAX_CHUNKS, STROKE_CAPACITY};
use crate::request::{StrokeChunk, StrokeSetup};
use crate::response::{plain, StrokeAnswer, StrokeProgress};

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
    pub(crate) fn push(&mut self, chunk: &StrokeChunk) -> Result<Step, UploadFault> {
        let StrokeChunk {
            stroke,
            index,
            count,
            ..
        } = *chunk;
        if count == 0 || usize::from(count) > MAX_CHUNKS || index >= count {
            return Err(UploadFault::BadChunk {
                chunk: index,
                count,
            });
        }
        if index == 0 {
            self.clear();
            self.stroke = stroke;
            self.count = count;
        } else if self.chunks.is_empty() || self.stroke != stroke {
            return Err(UploadFault::NotStarted {
                stroke,
                chunk: index,
            });
        }
        if count != self.count {
            return Err(UploadFault::CountChanged {
                stroke,
                count,
                expected: self.count,
            });
        }
        let expected = self.chunks.len() as u16;
        if index < expected {
            return Err(UploadFault::Duplicate {
                stroke,
                chunk: index,
            });
        }
        if index > expected {
            return Err(UploadFault::Missing {
                stroke,
                expected,
                chunk: index,
            });
        }
        if chunk.samples.is_empty() {
            return Err(UploadFault::Empty {
                stroke,
                chunk: index,
            });
        }
        let overflow = UploadFault::Overflow {
            stroke,
            chunk: index,
        };
        self.samples
            .extend_from_slice(&chunk.samples)
            .map_err(|()| overflow)?;
        self.chunks
            .push(self.samples.len() as u16)
            .map_err(|_| overflow)?;
        if index + 1 < count {
            return Ok(Step::Held(StrokeProgress {
                stroke,
                chunks: index + 1,
                count,
                samples: self.samples.len() as u16,
            }));
        }
        chunk
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
                kind: match glitch.kind {
                    GlitchKind::Rail => GlitchName::Rail,
                    GlitchKind::Spike => GlitchName::Spike,
                },
                value: glitch.value,
            }));
        }
        let cue = Cue::new(
            setup.cue_mass.unwrap_or(Cue::TYPICAL.mass()),
            setup
                .tip_restitution
                .unwrap_or(Cue::TYPICAL.tip_restitution()),
        )?;
        let [side, height] = setup.tip_offset.unwrap_or([0.0; 2]);
        let tip = TipOffset::new(side, height)?;
        let mut config = StrokeConfig::new(setup.rate_hz);
        // A raw word saturates at ±32768: the full scale follows the scale.
        config.full_scale = 32768.0 * if scale < 0.0 { -scale } else { scale };
        let estimate = estimate_raw(&self.samples, scale, &config)?;
        let hit = estimate
            .strike(params, &cue, tip)
            .map_err(|error| match error {
                StrokeError::Strike(error) => LinkError::Invalid(error),
                other => LinkError::from(other),
            })?;
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
