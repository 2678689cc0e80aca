//! Integration from the rest end, impact onset and the stroke report (steps 4–6 of the
//! module docs).

use super::{StreamEvent, StreamFault, StreamStroke, StreamingEstimator};
use crate::lsm6dsox::STANDARD_GRAVITY;

use super::rest::Run;

/// Largest speed (m/s) at which a later, shorter run may replace the integration's
/// origin: a pause at the back integrates to ~0 (0.005 m/s of noise and bias error at
/// 8 mg), a smooth move's acceleration plateau to its speed there (0.83 d/T for a
/// minimum-jerk move of `d` in `T`: 0.08 m/s for 15 cm in 1.5 s).
pub(super) const REST_SPEED: f32 = 0.02;

/// The stroke being integrated (counts unless stated).
#[derive(Clone, Copy, Debug)]
pub(super) struct Stroke {
    /// A rest has ended and no impact has come yet.
    pub active: bool,
    /// The rest window `[rest_start, rest_end)` and the run's length in blocks.
    rest_start: u64,
    pub rest_end: u64,
    pub rest_blocks: u32,
    /// Rest mean, its nearest integer and the difference; the pitch-rate rest mean.
    bias: f32,
    bias_round: i32,
    bias_fraction: f32,
    gyro_bias: f32,
    /// Rest noise (m/s²).
    noise: f32,
    /// A sample below this is an impact: `bias − impact_threshold`.
    pub limit: f32,
    /// `Σ a` over `[rest_end, k)` (exact) and `fold = P(k)`, `k` the last block end.
    sum: i64,
    fold: i32,
    /// Elevation change since the rest end, `Σ (p − gyro_bias)` (counts·samples: times
    /// `pitch_scale · Δt` it is radians), and the sums `Σ A`, `Σ A²` of the mid-sample
    /// change `A = T + q/2`: folded totals and the current block's.
    tilt: f32,
    lin: f32,
    lin_block: f32,
    quad: f32,
    quad_block: f32,
    /// First sample integrated per sample (after the rest end's delay).
    live_from: u64,
    /// A full-scale sample after the rest end.
    pub first_saturated: Option<u64>,
}

impl Stroke {
    pub const fn new() -> Self {
        Self {
            active: false,
            rest_start: 0,
            rest_end: 0,
            rest_blocks: 0,
            bias: 0.0,
            bias_round: 0,
            bias_fraction: 0.0,
            gyro_bias: 0.0,
            noise: 0.0,
            limit: 0.0,
            sum: 0,
            fold: 0,
            tilt: 0.0,
            lin: 0.0,
            lin_block: 0.0,
            quad: 0.0,
            quad_block: 0.0,
            live_from: 0,
            first_saturated: None,
        }
    }
}

impl StreamingEstimator {
    /// Start integrating from `rest_end` (prefix sums `p`, `c` there) at sample `n`:
    /// step 4's bias over the rest window, and the sums over `[rest_end, n]`, which the
    /// motion test saw only after the fact, from the prefix sums.
    pub(super) fn anchor(&mut self, n: u64, rest_end: u64, p: i32, c: i32, run: &Run) {
        let (rest_start, p_start, c_start) = run.window_start();
        let count = (rest_end - rest_start) as f32;
        let bias = p.wrapping_sub(p_start) as f32 / count;
        let gyro_bias = c.wrapping_sub(c_start) as f32 / count;
        let bias_round = if bias >= 0.0 { bias + 0.5 } else { bias - 0.5 } as i32;
        let span = (n + 1 - rest_end) as f32;
        // Elevation change over the span: exact. Its mid-sample sums over the span are
        // taken as for a change growing linearly from 0 (the span is the end of the rest
        // and the first W samples of motion, 12 ms at most; `docs/sensors.md` §11).
        let tilt = self.c.wrapping_sub(c) as f32 - gyro_bias * span;
        self.stroke = Stroke {
            active: true,
            rest_start,
            rest_end,
            rest_blocks: run.blocks,
            bias,
            bias_round,
            bias_fraction: bias - bias_round as f32,
            gyro_bias,
            noise: cuesight::math::sqrt(run.variance) * self.plan.scale,
            limit: bias - self.plan.impact,
            sum: i64::from(self.p.wrapping_sub(p)),
            fold: self.p,
            tilt,
            lin: 0.5 * tilt * span,
            lin_block: 0.0,
            quad: tilt * tilt * span / 3.0,
            quad_block: 0.0,
            live_from: n + 1,
            first_saturated: self.last_saturated.filter(|&s| s >= rest_end),
        };
        if self.gravity.is_none() {
            let (sin, cos) = cuesight::math::sin_cos(self.plan.elevation);
            self.gravity = Some((STANDARD_GRAVITY * cos, STANDARD_GRAVITY * sin));
        }
    }

    /// The integrated cue speed at `index` (acceleration prefix sum `p` there) is below
    /// [`REST_SPEED`]. The tilt correction is taken through the current sample (the
    /// motion test fires `W + guard` samples after `index`; the cue has barely moved).
    pub(super) fn at_rest(&self, index: u64, p: i32) -> bool {
        let s = &self.stroke;
        if index < s.live_from {
            return false;
        }
        let count = index - s.rest_end;
        let total =
            s.sum + i64::from(p.wrapping_sub(s.fold)) - count as i64 * i64::from(s.bias_round);
        let counts = total as f32 - count as f32 * s.bias_fraction;
        let (g_cos, g_sin) = self.gravity.unwrap_or((STANDARD_GRAVITY, 0.0));
        let angle = self.plan.pitch_scale * self.plan.dt;
        let (lin, quad) = (s.lin + s.lin_block, s.quad + s.quad_block);
        let correction = self.plan.dt * angle * (g_cos * lin - 0.5 * g_sin * angle * quad);
        let speed = counts * self.plan.scale * self.plan.dt + correction;
        cuesight::math::abs(speed) < REST_SPEED
    }

    /// Per-sample tilt sums (step 5, gyro-aided part): `A = T + q/2` is the elevation
    /// change at mid-sample, `T` before it, `q` the bias-free pitch rate.
    pub(super) fn integrate(&mut self, n: u64, p: i32) {
        let s = &mut self.stroke;
        self.recent_tilt[n as usize & 7] = s.tilt;
        let q = p as f32 - s.gyro_bias;
        let mid = s.tilt + 0.5 * q;
        s.lin_block += mid;
        s.quad_block += mid * mid;
        s.tilt += q;
    }

    /// Block end: fold the block's sums into the totals (f32 sums stay block-sized);
    /// drop an integration older than `max_stroke`.
    pub(super) fn fold(&mut self, n: u64) {
        let s = &mut self.stroke;
        if !s.active {
            return;
        }
        s.sum += i64::from(self.p.wrapping_sub(s.fold));
        s.fold = self.p;
        s.lin += s.lin_block;
        s.quad += s.quad_block;
        s.lin_block = 0.0;
        s.quad_block = 0.0;
        if n + 1 - s.rest_end > u64::from(self.plan.max_stroke) {
            s.active = false;
        }
    }

    /// Sample `n` is below the impact threshold. Crossings closer than `gap` are one
    /// impact; a new impact ends the stroke, or is a double hit or a knock.
    pub(super) fn crossing(&mut self, n: u64) -> Option<StreamEvent> {
        let new = self
            .last_crossing
            .is_none_or(|last| n - last > u64::from(self.plan.gap));
        self.last_crossing = Some(n);
        if !new {
            return None;
        }
        if self.stroke.active {
            return Some(self.impact(n));
        }
        let fault = match self.last_impact {
            Some((first, until)) if n <= until => StreamFault::DoubleHit { first, second: n },
            _ => StreamFault::NotAtRest { index: n },
        };
        Some(StreamEvent::Fault(fault))
    }

    /// Step 6 at the crossing sample `c`: onset, speed, report.
    fn impact(&mut self, c: u64) -> StreamEvent {
        let s = self.stroke;
        self.stroke.active = false;
        let plan = self.plan;
        let rest_end = s.rest_end;
        // Pre-impact level: mean of [c − 12, c − 4), clipped to the stroke.
        let pre_start = c.saturating_sub(12).max(rest_end);
        let pre_end = c.saturating_sub(4).max(rest_end);
        let pre_level = if pre_end > pre_start {
            self.prefix(pre_end).wrapping_sub(self.prefix(pre_start)) as f32
                / (pre_end - pre_start) as f32
        } else {
            s.bias
        };
        let mut onset = c;
        while onset > rest_end
            && onset + 4 > c
            && self.sample(onset - 1) < pre_level - plan.onset_drop
        {
            onset -= 1;
        }
        // Σ (a − bias) over [rest_end, onset): exact integers, then the bias's fraction.
        let count = onset - rest_end;
        let total = s.sum + i64::from(self.prefix(onset).wrapping_sub(s.fold))
            - count as i64 * i64::from(s.bias_round);
        let counts = total as f32 - count as f32 * s.bias_fraction;
        // Tilt sums over [rest_end, onset): remove the samples from the onset on.
        let (mut lin, mut quad) = (s.lin + s.lin_block, s.quad + s.quad_block);
        let tilt;
        if onset >= s.live_from {
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
                i -= 1;
            }
            tilt = after;
        } else {
            // An impact within the rest end's delay: no tilt correction.
            (lin, quad, tilt) = (0.0, 0.0, 0.0);
        }
        let (g_cos, g_sin) = self.gravity.unwrap_or((STANDARD_GRAVITY, 0.0));
        let angle = plan.pitch_scale * plan.dt; // rad per count·sample
        let correction = plan.dt * angle * (g_cos * lin - 0.5 * g_sin * angle * quad);
        let speed = counts * plan.scale * plan.dt + correction;
        self.last_impact = Some((onset, c + u64::from(plan.double_hit)));
        if let Some(index) = s.first_saturated.filter(|&i| i < onset) {
            return StreamEvent::Fault(StreamFault::Saturated {
                index,
                impact: onset,
            });
        }
        if !(speed > plan.min_speed && cuesight::math::is_finite(speed)) {
            let speed = if cuesight::math::is_finite(speed) {
                speed
            } else {
                0.0
            };
            return StreamEvent::Fault(StreamFault::NotForward {
                impact: onset,
                speed,
            });
        }
        StreamEvent::Stroke(StreamStroke {
            cue_speed: speed,
            impact_index: onset,
            rest_start: s.rest_start,
            rest_end,
            bias: s.bias * plan.scale,
            rest_noise: s.noise,
            stroke_duration: count as f32 * plan.dt,
            tilt_at_impact: tilt * angle,
            accel_at_impact: (pre_level - s.bias) * plan.scale,
        })
    }
}
