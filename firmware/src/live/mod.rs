//! The live cue (issue 15): IMU samples in, strokes out. [`feed`] decodes the trace
//! the QEMU board receives, [`sampler`] runs the part, the driver and the streaming
//! estimator, [`report`] turns what it detects into the live report; the RTIC apps
//! (`app.rs` on QEMU, `app_nrf52840.rs` on the nRF52840) pace them and send the reports.

pub mod feed;
#[cfg(feature = "live-cue")]
pub mod report;
pub mod sampler;
#[cfg(feature = "live-cue")]
pub mod tasks;

use cuesight_link::live::StrokeMetrics;
use cuesight_sensors::StreamStroke;

pub use sampler::Detected;

/// A stroke's metrics for the live report (`docs/sensors.md` §11).
pub fn metrics(stroke: &StreamStroke, wobble_dps: f32) -> StrokeMetrics {
    StrokeMetrics {
        backswing_length: stroke.backswing_length,
        backswing_time: stroke.backswing_time,
        pause: stroke.pause,
        forward_time: stroke.forward_time,
        tempo: stroke.tempo(),
        accel_at_impact: stroke.accel_at_impact,
        elevation_change_deg: stroke.tilt_at_impact * (180.0 / core::f32::consts::PI),
        wobble_dps,
    }
}
