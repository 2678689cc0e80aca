//! What the streaming estimator reports: a stroke, or a typed fault.

use cuesight::strike::{strike, Cue, Strike, TipOffset};
use cuesight::Params;

use crate::stroke::StrokeError;

/// One report of [`super::StreamingEstimator::push`]. Sample indices count every sample
/// pushed since [`super::StreamingEstimator::new`] or the last
/// [`super::StreamingEstimator::finish`], from 0.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum StreamEvent {
    /// A stroke ended by a tip impact, reported on the sample that crossed the impact
    /// threshold.
    Stroke(StreamStroke),
    /// An impact that is not a measurable stroke, or a bad input.
    Fault(StreamFault),
    /// A reported stroke's follow-through (`docs/sensors.md` §11), reported once the cue
    /// is still again: on the sample after the second still 25 ms block after the stop,
    /// 50–75 ms after it. Only with [`super::StreamConfig::follow_through`]; none
    /// when the measurement is given up (no stop within 1.5 s of the contact, a
    /// full-scale sample after the contact's first 8 ms, a new impact, a new stroke).
    /// Only with the crate's `follow-through` feature.
    #[cfg(feature = "follow-through")]
    FollowThrough {
        /// The stroke's [`StreamStroke::impact_index`].
        impact: u64,
        /// How far the cue went forward from the tip contact until it stopped (m).
        length: f32,
        /// From the tip contact until the cue was slower than 0.02 m/s (s).
        time: f32,
    },
}

/// A detected stroke (the windowed [`crate::StrokeEstimate`]'s fields, with stream
/// indices).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StreamStroke {
    /// Cue speed just before the tip touched the ball (m/s).
    pub cue_speed: f32,
    /// First sample touched by the impact (excluded from the integral).
    pub impact_index: u64,
    /// First sample of the rest window the bias was taken from.
    pub rest_start: u64,
    /// One past the last sample of that window (where `v = 0` is imposed).
    pub rest_end: u64,
    /// Rest level removed from every sample: sensor offset + gravity along the cue
    /// (m/s²).
    pub bias: f32,
    /// Sensor noise at rest (m/s²): the root mean of the rest blocks' variances.
    pub rest_noise: f32,
    /// Integration time from the end of the rest to the impact (s).
    pub stroke_duration: f32,
    /// Change of cue elevation from the rest to the impact (rad), from the pitch rate;
    /// zero without one.
    pub tilt_at_impact: f32,
    /// The cue's acceleration just before the contact (m/s², bias removed): the mean
    /// of the 8 samples ending 4 samples before the impact crossing (1.2 ms at
    /// 6.66 kHz). Positive: still accelerating through the contact.
    pub accel_at_impact: f32,
    /// How far the cue went back from where it rested (m): the deepest point of the
    /// position integrated from the rest end (`docs/sensors.md` §11, stroke metrics).
    /// 0 for a stroke with no backswing.
    pub backswing_length: f32,
    /// Where the backswing starts: the end of the address rest (about 10 ms before the
    /// cue moves; the last rest before the backswing, which is not [`Self::rest_end`]
    /// when a long pause at the back became the speed's integration origin).
    pub backswing_start: u64,
    /// From [`Self::backswing_start`] to the start of the pause at the back (s).
    pub backswing_time: f32,
    /// The pause at the back (s): the time around the deepest point when the cue moves
    /// slower than 0.02 m/s. Without a held pause it is the reversal's own slow passage
    /// (about `0.04 / |a|` s at a reversal of `a` m/s²).
    pub pause: f32,
    /// From the end of that pause to the tip contact (s).
    pub forward_time: f32,
}

impl StreamStroke {
    /// The stroke's tempo: [`Self::backswing_time`] over [`Self::forward_time`]
    /// (dimensionless; coaches' "slow back, smooth through" is a tempo above 1). `None`
    /// when the forward time is zero.
    pub fn tempo(&self) -> Option<f32> {
        (self.forward_time > 0.0).then(|| self.backswing_time / self.forward_time)
    }

    /// Ball speed and spin for this cue speed (TP A.30, [`cuesight::strike::strike`]).
    pub fn strike(
        &self,
        params: &Params,
        cue: &Cue,
        tip: TipOffset,
    ) -> Result<Strike, StrokeError> {
        Ok(strike(params, cue, tip, self.cue_speed)?)
    }
}

/// Why an impact (or an input) gave no stroke. Every fault leaves the estimator ready
/// for the next stroke: it needs a new rest.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum StreamFault {
    /// An impact-sized deceleration with no rest of `min_rest` before it (a knock, or
    /// the cue moved for longer than `max_stroke` since its last rest).
    NotAtRest {
        /// The sample that crossed the impact threshold.
        index: u64,
    },
    /// A second impact within `double_hit_window` of a reported one (reported on its
    /// crossing sample). The first report stands: its speed is the cue's before the
    /// first contact.
    DoubleHit {
        /// First sample of the first impact.
        first: u64,
        /// The second impact's crossing sample.
        second: u64,
    },
    /// A sample between the rest and the impact reached the sensor's full scale: the
    /// integral is unknown. Reported at the impact.
    Saturated {
        /// A saturated sample (the first one after the motion test fired; with
        /// saturation in the 12 ms before it, the latest of those).
        index: u64,
        /// First sample of the impact.
        impact: u64,
    },
    /// The integrated speed is below `min_speed` (a knock during a rest, a wrong axis
    /// sign, no forward stroke).
    NotForward {
        /// First sample of the impact.
        impact: u64,
        /// The integrated speed (m/s).
        speed: f32,
    },
    /// A NaN or infinite sample (acceleration or pitch rate): the rest and any stroke
    /// in progress are dropped. Reported once per run of such samples.
    NotFinite {
        /// The first such sample.
        index: u64,
    },
    /// [`super::StreamingEstimator::finish`] while a stroke was being integrated.
    EndedMidStroke {
        /// Where that stroke's integration started.
        rest_end: u64,
        /// Samples pushed.
        samples: u64,
    },
}
