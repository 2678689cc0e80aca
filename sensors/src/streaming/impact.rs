//! The impact: a new crossing of the impact threshold, its onset, the stroke's speed and
//! its report (step 6 of the module docs).

use super::{at_or_after, StreamEvent, StreamFault, StreamStroke, StreamingEstimator};

impl StreamingEstimator {
    /// Sample `n` is below the impact threshold: `true` if it starts a new impact
    /// (crossings closer than `gap` are one impact, its ringing).
    #[inline(always)]
    pub(super) fn new_crossing(&mut self, n: u32) -> bool {
        let new = self
            .last_crossing
            .is_none_or(|last| n.wrapping_sub(last) > self.plan.gap);
        self.last_crossing = Some(n);
        new
    }

    /// The end of a step whose sample `n` starts a new impact: it ends the stroke, or
    /// is a double hit or a knock. The block end comes after the report's figures, the
    /// event last (built in the caller's return slot).
    /// With [`super::StreamConfig::defer_reports`] it is only marked, for
    /// [`Self::resolve`].
    #[inline(never)]
    pub(super) fn new_impact(&mut self, n: u32) -> Option<StreamEvent> {
        let r = if self.stroke.active {
            self.impact(n)
        } else {
            let index = self.unwrap_index(n);
            match self.last_impact {
                Some((first, until)) if at_or_after(until, n) => Report {
                    kind: Kind::DoubleHit,
                    index: first,
                    other: index,
                    ..Report::default()
                },
                _ => Report {
                    kind: Kind::NotAtRest,
                    index,
                    ..Report::default()
                },
            }
        };
        if self.block.pos == self.plan.block {
            self.end_block(n);
        }
        Some(match r.kind {
            Kind::Stroke => {
                // The phases only for a stroke (a knock's report stays short).
                let phases = self.stroke.phases.report();
                let dt = self.plan.dt;
                let onset = r.index as u32;
                let seconds = |from: u32, to: u32| to.wrapping_sub(from) as f32 * dt;
                StreamEvent::Stroke(StreamStroke {
                    cue_speed: r.speed,
                    impact_index: r.index,
                    rest_start: r.other,
                    rest_end: r.rest_end,
                    bias: r.bias,
                    rest_noise: r.noise,
                    stroke_duration: r.duration,
                    tilt_at_impact: r.tilt,
                    accel_at_impact: r.accel,
                    backswing_length: phases.depth * self.plan.scale * dt * dt,
                    backswing_start: self.unwrap_index(phases.origin),
                    backswing_time: seconds(phases.origin, phases.pause_start),
                    pause: seconds(phases.pause_start, phases.pause_end),
                    // The pause ends before the onset (a forward stroke is faster than
                    // `slow`); `min` keeps a degenerate stroke's figure finite and short.
                    forward_time: seconds(phases.pause_end, onset).min(r.duration),
                })
            }
            Kind::Saturated => StreamEvent::Fault(StreamFault::Saturated {
                index: r.other,
                impact: r.index,
            }),
            Kind::NotForward => StreamEvent::Fault(StreamFault::NotForward {
                impact: r.index,
                speed: r.speed,
            }),
            Kind::DoubleHit => StreamEvent::Fault(StreamFault::DoubleHit {
                first: r.index,
                second: r.other,
            }),
            Kind::NotAtRest => StreamEvent::Fault(StreamFault::NotAtRest { index: r.index }),
        })
    }

    /// Step 6 at the crossing sample `c`: onset, speed, report.
    #[inline(always)]
    fn impact(&mut self, c: u32) -> Report {
        self.stroke.end(&self.plan);
        let s = &self.stroke;
        let plan = &self.plan;
        let rest_end = s.rest_end;
        // Samples from the rest end to the crossing (the stroke is at most `max_stroke`).
        let back = c.wrapping_sub(rest_end);
        // Pre-impact level: mean of [c − 12, c − 4), clipped to the stroke.
        let (pre_start, pre_end) = (c.wrapping_sub(back.min(12)), c.wrapping_sub(back.min(4)));
        let pre_level = if back > 4 {
            self.prefix(pre_end).wrapping_sub(self.prefix(pre_start)) as f32
                / (back.min(12) - 4) as f32
        } else {
            s.bias
        };
        // The onset: back from the crossing (at most 4 samples, not past the rest end)
        // while the sample before lies `onset_drop` below the pre-impact level.
        let mut before = 0; // samples the onset lies before the crossing
        while before < back
            && before < 4
            && self.sample(c.wrapping_sub(before + 1)) < pre_level - plan.onset_drop
        {
            before += 1;
        }
        let onset = c.wrapping_sub(before);
        // Σ (a − bias) over [rest_end, onset): exact integers, then the bias's fraction.
        let count = back - before;
        let counts = self.counts(count, self.prefix(onset));
        // Tilt sums over [rest_end, onset): remove the samples from the onset on.
        let (mut lin, mut quad) = (s.lin + s.lin_block, s.quad + s.quad_block);
        let tilt;
        if at_or_after(onset, s.live_from) {
            let mut after = s.tilt;
            let mut i = c;
            loop {
                let before = self.recent_tilt[i as usize & 7];
                let mid = 0.5 * (before + after);
                lin -= mid;
                quad -= mid * mid;
                after = before;
                if i == onset {
                    break;
                }
                i = i.wrapping_sub(1);
            }
            tilt = after;
        } else {
            // An impact within the rest end's delay: no tilt correction.
            (lin, quad, tilt) = (0.0, 0.0, 0.0);
        }
        let speed = self.speed(counts, lin, quad);
        let angle = plan.pitch_scale * plan.dt;
        let onset_index = self.unwrap_index(onset);
        let first_saturated = s.first_saturated.filter(|&i| !at_or_after(i, onset));
        let report = Report {
            kind: Kind::Stroke,
            speed,
            index: onset_index,
            other: self.unwrap_index(s.rest_start),
            rest_end: self.unwrap_index(rest_end),
            bias: s.bias * plan.scale,
            noise: s.noise,
            duration: count as f32 * plan.dt,
            tilt: tilt * angle,
            accel: (pre_level - s.bias) * plan.scale,
        };
        self.last_impact = Some((onset_index, c.wrapping_add(plan.double_hit)));
        if let Some(index) = first_saturated {
            return Report {
                kind: Kind::Saturated,
                other: self.unwrap_index(index),
                ..report
            };
        }
        if !(speed > plan.min_speed && cuesight::math::is_finite(speed)) {
            let speed = if cuesight::math::is_finite(speed) {
                speed
            } else {
                0.0
            };
            return Report {
                kind: Kind::NotForward,
                speed,
                ..report
            };
        }
        #[cfg(feature = "follow-through")]
        self.start_follow(onset, tilt, speed);
        report
    }
}

/// What an impact reports, as scalars (see [`StreamingEstimator::new_impact`]).
#[derive(Clone, Copy, Default)]
struct Report {
    kind: Kind,
    /// The onset (stroke, saturated, not forward), the first impact (double hit), the
    /// crossing (not at rest).
    index: u64,
    /// The rest start (stroke), the saturated sample, the second crossing (double hit).
    other: u64,
    rest_end: u64,
    speed: f32,
    bias: f32,
    noise: f32,
    duration: f32,
    tilt: f32,
    accel: f32,
}

#[derive(Clone, Copy, Default)]
enum Kind {
    Stroke,
    Saturated,
    NotForward,
    DoubleHit,
    #[default]
    NotAtRest,
}
