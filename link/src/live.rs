//! The live cue's messages (issue 15): the shot the player plans, set with `plan` and
//! kept by the device, and the report the device sends unprompted (sequence number
//! [`crate::frame::UNPROMPTED`]) when its IMU detects a stroke, an impact that is no
//! stroke, a sensor fault, or the end of an emulated trace. Units: SI, angles in
//! degrees in the keys ending in `_deg` (`docs/protocol.md`, `docs/sensors.md` §11).

use cuesight_sensors::StreamFault;
use serde::{Deserialize, Serialize};

use crate::error::LinkError;
use crate::shot::ShotAnswer;

/// One unprompted live report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
#[allow(clippy::large_enum_variant)]
pub enum LiveReport {
    /// A stroke, its metrics and the guidance for the planned shot.
    Stroke(LiveStroke),
    /// An impact that is no measurable stroke, or a bad input (the estimator's own
    /// report); sampling goes on.
    Fault(StreamFault),
    /// The IMU failed; sampling goes on.
    Sensor(SensorFault),
    /// The emulated IMU's trace ended (QEMU only).
    TraceEnd(TraceEnd),
    /// The cue's travel after a stroke's tip contact, once it has stopped (a later
    /// frame than the stroke's: the guidance does not wait for it).
    FollowThrough(FollowThrough),
}

/// A detected stroke.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct LiveStroke {
    /// Strokes reported since boot, this one included.
    pub stroke: u32,
    /// The first contact sample (0-based, counted from the trace's start).
    pub impact_sample: u64,
    /// Cue speed just before the tip contact (m/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub cue_speed: f32,
    /// Instructions from the start of the interrupt that delivered the sample on which
    /// the impact was detected to the guidance computed and this report composed
    /// (QEMU `-icount shift=0`: one instruction per virtual ns; resolution 40).
    pub latency_instructions: u32,
    /// What market smart cues report.
    pub metrics: StrokeMetrics,
    /// The planned shot played at this stroke's speed; `None` when no `plan` is set.
    pub guidance: Option<Result<ShotAnswer, LinkError>>,
}

/// Stroke metrics (`docs/sensors.md` §11 defines each and how it is measured).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct StrokeMetrics {
    /// How far the cue went back from the address (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub backswing_length: f32,
    /// Backswing duration (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub backswing_time: f32,
    /// Pause at the back (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub pause: f32,
    /// Forward stroke, from the pause to the contact (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub forward_time: f32,
    /// Backswing time over forward time; `None` without a forward time.
    pub tempo: Option<f32>,
    /// Acceleration just before the contact (m/s²): positive, still accelerating.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub accel_at_impact: f32,
    /// Cue elevation change from the address to the contact (degrees, butt up
    /// positive), from the gyro.
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub elevation_change_deg: f32,
    /// Side-to-side wobble: the RMS deviation of the yaw rate from its mean while the
    /// cue moved, from the start of the stroke's motion to the contact (°/s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub wobble_dps: f32,
}

/// A stroke's follow-through (`docs/sensors.md` defines it and how it is measured).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct FollowThrough {
    /// The stroke it follows ([`LiveStroke::stroke`]).
    pub stroke: u32,
    /// Forward travel of the cue from the tip contact until it stopped (m).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub length: f32,
    /// Time from the tip contact until the cue stopped (s).
    #[serde(serialize_with = "crate::wire::f32_field")]
    pub time: f32,
}

/// An IMU failure, with the sample count when it was seen.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
#[serde(rename_all = "snake_case")]
pub enum SensorFault {
    /// A bus read failed (the sample is lost; the stroke in progress is not).
    ReadFailed {
        /// Samples delivered before it.
        sample: u64,
    },
    /// Data-ready came without new data: the part stopped converting.
    Stalled {
        /// Samples delivered before it.
        sample: u64,
    },
    /// The part did not come up (chip id, reset, bus) or the rate is not one the
    /// estimator takes: no sampling until the next trace.
    NotStarted,
}

/// The end of an emulated trace.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct TraceEnd {
    /// Samples taken.
    pub samples: u64,
    /// The trace file ended before its header's sample count.
    pub truncated: bool,
    /// Per-sample work, the emulated bus excluded: the instructions of every sample
    /// (resolution 40 per sample)...
    pub work_instructions: u64,
    /// ...and the most of any one sampling interrupt...
    pub work_max_instructions: u32,
    /// ...and of any one report the sampling interrupt left to the resolving task (a
    /// stroke's figures, a follow-through: once per report, one priority below the
    /// sampling interrupt; in `work_instructions`, not in `work_max_instructions`).
    pub resolve_max_instructions: u32,
}

impl TraceEnd {
    /// The mean per-sample work (instructions).
    pub fn work_mean_instructions(&self) -> f64 {
        self.work_instructions as f64 / self.samples.max(1) as f64
    }
}
