//! What the reporting task of either live image does with a detection: the live report
//! frame's content (`cuesight_link::live::LiveReport`), the stroke numbering, the
//! defmt log line. The boards differ only in their clock (the latency) and their link.

use cuesight_link::live::{FollowThrough, LiveReport, LiveStroke};
use cuesight_sensors::StreamEvent;

use super::{metrics, Detected};

/// The strokes reported so far, and the last one's impact (its follow-through's key).
pub struct Reporter {
    strokes: u32,
    last_impact: u64,
}

impl Default for Reporter {
    fn default() -> Self {
        Self::new()
    }
}

impl Reporter {
    /// No stroke yet.
    pub const fn new() -> Self {
        Self {
            strokes: 0,
            last_impact: u64::MAX,
        }
    }

    /// The report for `detected`, `None` for a follow-through of a stroke that was not
    /// the last reported. `plan` plays the session's plan at a cue speed
    /// ([`cuesight_device::Session::plan_guidance`], under the session's lock);
    /// `latency` gives the instructions since the detecting interrupt began at `at`
    /// (the board's clock), taken after the guidance is computed.
    pub fn report(
        &mut self,
        detected: Detected,
        plan: impl FnOnce(f32) -> LiveGuidance,
        latency: impl FnOnce(u32) -> u32,
    ) -> Option<LiveReport> {
        Some(match detected {
            Detected::Event {
                event: StreamEvent::Stroke(stroke),
                at,
                lost,
                wobble,
            } => {
                self.strokes += 1;
                self.last_impact = stroke.impact_index;
                let guidance = plan(stroke.cue_speed);
                let latency = latency(at);
                defmt::info!(
                    "stroke {=u32}: cue {=f32} m/s, guidance after {=u32} instructions",
                    self.strokes,
                    stroke.cue_speed,
                    latency
                );
                LiveReport::Stroke(LiveStroke {
                    stroke: self.strokes,
                    impact_sample: stroke.impact_index + lost,
                    cue_speed: stroke.cue_speed,
                    latency_instructions: latency,
                    // 0.07 °/s per count at ±2000 dps (`cuesight_sensors::lsm6dsox`).
                    metrics: metrics(&stroke, wobble.rms(0.07)),
                    guidance,
                })
            }
            Detected::Event {
                event:
                    StreamEvent::FollowThrough {
                        impact,
                        length,
                        time,
                    },
                ..
            } => {
                // The estimator measures only the strokes it reports, so this is the
                // last one; a follow-through of another is not sent.
                if impact != self.last_impact {
                    return None;
                }
                LiveReport::FollowThrough(FollowThrough {
                    stroke: self.strokes,
                    length,
                    time,
                })
            }
            Detected::Event {
                event: StreamEvent::Fault(fault),
                ..
            } => LiveReport::Fault(fault),
            Detected::Sensor(fault) => LiveReport::Sensor(fault),
            Detected::End(end) => LiveReport::TraceEnd(end),
        })
    }
}

/// A stroke's guidance: the plan played at its speed (`None` without a plan).
pub type LiveGuidance = Option<Result<cuesight_link::shot::ShotAnswer, cuesight_link::LinkError>>;
