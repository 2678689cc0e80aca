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

use cuesight_link::live::{SensorFault, StrokeMetrics, TraceEnd};
use cuesight_sensors::{StreamEvent, StreamStroke};

/// What the sampling task hands to the reporting task.
#[derive(Clone, Copy)]
pub enum Detected {
    /// The estimator's report, and the board's clock (QEMU: TIMER0 ticks; nRF52840:
    /// DWT cycles) when the interrupt that delivered the detecting sample began.
    Event {
        /// The report.
        event: StreamEvent,
        /// When its interrupt began.
        at: u32,
        /// Samples lost before it (the estimator's indices do not count them).
        lost: u64,
        /// The stroke's yaw-rate statistics (its wobble, computed by the reporting
        /// task, not in the interrupt).
        wobble: cuesight_sensors::Wobble,
    },
    /// The IMU failed.
    Sensor(SensorFault),
    /// The trace ended.
    End(TraceEnd),
}

impl Detected {
    /// The estimator's `event`, detected on the sample whose interrupt began at `at`.
    #[inline(never)]
    pub fn event<P>(sampler: &sampler::Sampler<P>, event: StreamEvent, at: u32) -> Self {
        Detected::Event {
            event,
            at,
            lost: sampler.trace_index(0),
            wobble: sampler.wobble(),
        }
    }
}

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
