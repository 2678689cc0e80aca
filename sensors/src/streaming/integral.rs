//! Integration from the rest end, impact onset and the stroke report (steps 4–6 of the
//! module docs).

use super::config::ceil;
use super::phases::Phases;
use super::{at_or_after, StreamingEstimator};
use crate::lsm6dsox::STANDARD_GRAVITY;

/// Largest speed (m/s) at which a later, shorter run may replace the integration's
/// origin: a pause at the back integrates to ~0 (0.005 m/s of noise and bias error at
/// 8 mg), a smooth move's acceleration plateau to its speed there (0.83 d/T for a
/// minimum-jerk move of `d` in `T`: 0.08 m/s for 15 cm in 1.5 s).
pub(super) const REST_SPEED: f32 = 0.02;

/// The stroke being integrated (counts unless stated).
#[derive(Clone, Copy, Debug)]
pub(super) struct Stroke {
    /// A rest has ended and no impact has come yet.
    pub(super) active: bool,
    /// The rest window `[rest_start, rest_end)` and the run's length in blocks.
    pub(super) rest_start: u32,
    pub(super) rest_end: u32,
    pub(super) rest_blocks: u32,
    /// Rest mean, its nearest integer and the difference; the pitch-rate rest mean.
    pub(super) bias: f32,
    bias_round: i32,
    bias_fraction: f32,
    pub(super) gyro_bias: f32,
    /// Rest noise (m/s²).
    pub(super) noise: f32,
    /// A sample below `bias − impact_threshold` is an impact: a count `a` is when
    /// `a < limit`, this being `⌈bias − impact_threshold⌉` ([`ceil`]); between strokes
    /// `plan.knock`, the threshold for a cue at rest (one comparison per sample).
    pub(super) limit: i32,
    /// `Σ a` over `[rest_end, k)` (exact) and `fold = P(k)`, `k` the last block end.
    sum: i64,
    fold: i32,
    /// Elevation change since the rest end, `Σ (p − gyro_bias)` (counts·samples: times
    /// `pitch_scale · Δt` it is radians), and the sums `Σ A`, `Σ A²` of the mid-sample
    /// change `A = T + q/2`: folded totals and the current block's.
    pub(super) tilt: f32,
    pub(super) lin: f32,
    pub(super) lin_block: f32,
    pub(super) quad: f32,
    pub(super) quad_block: f32,
    /// First sample integrated per sample (after the rest end's delay).
    pub(super) live_from: u32,
    /// A full-scale sample after the rest end.
    pub(super) first_saturated: Option<u32>,
    /// Velocity and position, for the stroke metrics.
    pub(super) phases: Phases,
}

impl Stroke {
    /// No stroke; `knock` is the plan's.
    pub const fn new(knock: i32) -> Self {
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
            limit: knock,
            sum: 0,
            fold: 0,
            tilt: 0.0,
            lin: 0.0,
            lin_block: 0.0,
            quad: 0.0,
            quad_block: 0.0,
            live_from: 0,
            first_saturated: None,
            phases: Phases::new(),
        }
    }

    /// The stroke is over (impact, fault, too long): between strokes.
    pub fn end(&mut self, plan: &super::Plan) {
        self.active = false;
        self.limit = plan.knock;
    }
}

impl StreamingEstimator {
    /// Start integrating from `rest_end` (prefix sums `p`, `c` there) at sample `n`,
    /// the run of `blocks` that ends there being still in `self.run`: step 4's bias over
    /// the rest window, and the sums over `[rest_end, n]`, which the motion test saw
    /// only after the fact, from the prefix sums.
    pub(super) fn anchor(&mut self, n: u32, rest_end: u32, p: i32, c: i32, blocks: u32) {
        let (rest_start, p_start, c_start) = self.run.window_start();
        let count = rest_end.wrapping_sub(rest_start) as f32;
        let bias = p.wrapping_sub(p_start) as f32 / count;
        let gyro_bias = c.wrapping_sub(c_start) as f32 / count;
        let bias_round = if bias >= 0.0 { bias + 0.5 } else { bias - 0.5 } as i32;
        let span = n.wrapping_add(1).wrapping_sub(rest_end) as f32;
        // Elevation change over the span: exact. Its mid-sample sums over the span are
        // taken as for a change growing linearly from 0 (the span is the end of the rest
        // and the first W samples of motion, 12 ms at most; `docs/sensors.md` §11).
        let tilt = self.c.wrapping_sub(c) as f32 - gyro_bias * span;
        let noise = cuesight::math::sqrt(self.run.variance) * self.plan.scale;
        let limit = ceil(bias - self.plan.impact);
        let first_saturated = self.last_saturated.filter(|&s| at_or_after(s, rest_end));
        // A later rest replacing the origin of a stroke in progress (the address after a
        // settling move, or a long pause at the back): the phases decide at the impact.
        let reanchor = self.stroke.active;
        // Field by field: a struct literal is built on the stack and copied.
        let s = &mut self.stroke;
        s.active = true;
        s.rest_start = rest_start;
        s.rest_end = rest_end;
        s.rest_blocks = blocks;
        s.bias = bias;
        s.bias_round = bias_round;
        s.bias_fraction = bias - bias_round as f32;
        s.gyro_bias = gyro_bias;
        s.noise = noise;
        s.limit = limit;
        s.sum = i64::from(self.p.wrapping_sub(p));
        s.fold = self.p;
        s.tilt = tilt;
        s.lin = 0.5 * tilt * span;
        s.lin_block = 0.0;
        s.quad = tilt * tilt * span / 3.0;
        s.quad_block = 0.0;
        s.live_from = n.wrapping_add(1);
        s.first_saturated = first_saturated;
        self.start_phases(n, rest_end, p, reanchor);
    }

    /// The stroke's phases start at `rest_end` (acceleration prefix sum `p` there),
    /// integrated through sample `n` with the current bias; `within_stroke` as
    /// [`Phases::start`].
    pub(super) fn start_phases(&mut self, n: u32, rest_end: u32, p: i32, within_stroke: bool) {
        let span = n.wrapping_add(1).wrapping_sub(rest_end);
        // Over the span (12 ms at most) the elevation change is taken as the current
        // one: at a rest within the stroke (a pause at the back) the cue is tilted.
        let s = &mut self.stroke;
        let level = s.bias - self.tilt_gain * s.tilt;
        let velocity = self.p.wrapping_sub(p) as f32 - span as f32 * level;
        s.phases
            .start(rest_end, n, velocity, span as f32, within_stroke);
    }

    /// `Σ (a − bias)` over the first `count` samples from the rest end, `p` being the
    /// acceleration prefix sum after them: the exact integer sum less `count` times
    /// the rounded bias, then the bias's fraction in f32.
    pub(super) fn counts(&self, count: u32, p: i32) -> f32 {
        let s = &self.stroke;
        let total =
            s.sum + i64::from(p.wrapping_sub(s.fold)) - i64::from(count) * i64::from(s.bias_round);
        // The same value as `total as f32`, without the library call when it fits.
        let total = match i32::try_from(total) {
            Ok(t) => t as f32,
            Err(_) => total as f32,
        };
        total - count as f32 * s.bias_fraction
    }

    /// Cue speed (m/s) from the integrated counts and the tilt sums `Σ A`, `Σ A²`.
    pub(super) fn speed(&self, counts: f32, lin: f32, quad: f32) -> f32 {
        let plan = &self.plan;
        let (g_cos, g_sin) = self.gravity.unwrap_or((STANDARD_GRAVITY, 0.0));
        let angle = plan.pitch_scale * plan.dt; // rad per count·sample
        let correction = plan.dt * angle * (g_cos * lin - 0.5 * g_sin * angle * quad);
        counts * plan.scale * plan.dt + correction
    }

    /// The integrated cue speed at `index` (acceleration prefix sum `p` there) is below
    /// [`REST_SPEED`]. The tilt correction is taken through the current sample (the
    /// motion test fires `W + guard` samples after `index`; the cue has barely moved).
    pub(super) fn at_rest(&self, index: u32, p: i32) -> bool {
        let s = &self.stroke;
        if !at_or_after(index, s.live_from) {
            return false;
        }
        let counts = self.counts(index.wrapping_sub(s.rest_end), p);
        let speed = self.speed(counts, s.lin + s.lin_block, s.quad + s.quad_block);
        cuesight::math::abs(speed) < REST_SPEED
    }

    /// Per-sample tilt sums (step 5, gyro-aided part): `A = T + q/2` is the elevation
    /// change at mid-sample, `T` before it, `q` the bias-free pitch rate.
    #[inline(always)]
    pub(super) fn integrate(&mut self, n: u32, a: i32, p: i32) {
        let s = &mut self.stroke;
        self.recent_tilt[n as usize & 7] = s.tilt;
        let q = p as f32 - s.gyro_bias;
        let mid = s.tilt + 0.5 * q;
        s.lin_block += mid;
        s.quad_block += mid * mid;
        s.tilt += q;
        s.phases
            .step(n, a as f32 - s.bias, self.tilt_gain * mid, self.plan.slow);
    }

    /// Block end: fold the block's sums into the totals (f32 sums stay block-sized);
    /// drop an integration older than `max_stroke`.
    pub(super) fn fold(&mut self, n: u32) {
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
        if n.wrapping_add(1).wrapping_sub(s.rest_end) > self.plan.max_stroke {
            s.end(&self.plan);
        }
    }
}
