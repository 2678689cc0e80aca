//! Streaming stroke estimator: one sample at a time, constant memory, no sample window.
//!
//! The windowed estimator ([`crate::stroke`]) needs the whole stroke in a buffer (3.6 s,
//! 48 kB at 6.66 kHz). This one keeps block statistics, prefix sums and a 128-sample
//! ring of them ([`StreamingEstimator`] is 1,528 bytes, 1,624 with the follow-through),
//! and reports each stroke on the sample that crosses the impact threshold. The steps
//! are the windowed estimator's (`stroke.rs` module docs, `docs/sensors.md` §4),
//! rearranged so that each is decided when its last sample arrives:
//!
//! 1. **Rest** (`rest.rs`): 25 ms blocks; a run of blocks whose standard deviation is
//!    at most `rest_noise_limit` and whose means lie within `rest_level_tolerance` of
//!    the run's first block, holding no impact-sized or full-scale sample. Its level
//!    and noise come from the blocks after the first (the last 1–2 s of them).
//! 2. **Rest end**: once a run has two blocks, every sample tests the moving average of
//!    the last `W` samples (2.4 ms) against the level: a departure by more than
//!    `max(6 σ/√W, motion_floor)` is the start of motion, and the rest ends `guard`
//!    (10 ms) before that window. A run that fails its block tests without a departure
//!    ends at its last block, `guard` earlier (the windowed estimator's fallback).
//! 3. **Which rest**: a run of at least `min_rest` whose motion starts becomes the
//!    integration's origin if there is none, if it is at least as long as the current
//!    one (the windowed estimator's "longest, ties to the later"), if the current one
//!    is older than `max_stroke`, or if it is `trusted_rest` (1 s) long and the cue's
//!    speed at its end, integrated from the current origin, is under 0.02 m/s. Shorter
//!    runs are the acceleration plateaus and gentle ends of smooth moves (the last
//!    0.55 s of a 1.5 s backswing pass the rest tests at near-zero speed), not rests.
//! 4. **Bias** = the mean of the rest window (offset + gravity along the cue); the
//!    gyro's pitch-rate bias likewise.
//! 5. **Integration** (`integral.rs`) from the rest end: `V = Σ (a_i − bias) Δt`, exact
//!    integer sums of the raw words, the bias subtracted once at the impact; with a
//!    pitch rate, `g (cos θ₀ Δθ − sin θ₀ Δθ²/2)` added back per sample as in
//!    [`crate::estimate_with_pitch`].
//! 6. **Impact**: the first sample below `bias − impact_threshold` after the rest; the
//!    onset is moved back (at most 4 samples) to the first sample `onset_drop` below
//!    the mean of the 8 samples ending 4 before the crossing; samples from the onset on
//!    are left out of the integral. Crossings less than 5 ms apart are one impact (its
//!    ringing); a new one within `double_hit_window` is a double hit.
//! 7. **Follow-through** (`follow.rs`, the `follow-through` feature, with
//!    `StreamConfig::follow_through`): after a stroke's report, from 8 ms after its
//!    onset, exact sums `Σ a` and `Σ (i − c) a` until a rest shows the cue still; the
//!    velocity is integrated back from `v = 0` there (the contact is clipped at full
//!    scale), and `StreamEvent::FollowThrough` reported on the sample after that
//!    block end.
//!
//! Everything is per sample O(1): integer adds, a dozen f32 operations, no division,
//! no square root, no trigonometry, no loop; each block end (every 25 ms) adds a few
//! divisions, and the impact a loop of at most 5 steps. Indices into the ring are
//! `k & 127` into a 128-entry array: no panic path. Nothing is NaN: a non-finite input
//! is a [`StreamFault::NotFinite`] and is not used.
//!
//! **Cost on the device** (`docs/sensors.md` §11, `cargo xtask bench --stream-only`):
//! the per-sample path is one function with no call; block ends, rest ends and
//! crossings of the impact threshold are `#[inline(never)]` functions, so the common
//! sample saves and restores few registers. No 64-bit arithmetic per sample, no
//! `core::fmt`.
//!
//! **Sample indices** are `u32` inside (a `u64` costs two instructions per operation
//! and a library call per conversion to f32 on the Cortex-M4F): they wrap after 2³²
//! samples, 7.4 days of continuous sampling at 6.66 kHz. Every stored index is compared
//! through a wrapping difference with the current one, over a span the plan bounds (a
//! stroke at most `max_stroke` ≤ 60 s, a rest window at most 2 s and a block, 12 ms of
//! delay), so a wrap changes nothing; markers that could grow older than that (the last
//! crossing, impact and saturated sample) are dropped at a block end once they cannot
//! matter. The indices reported are `u64`: the index of the current block's first
//! sample is kept as a `u64` (one 64-bit add per block end), and a stored `u32` index is
//! widened by its signed distance from that block start.

mod config;
mod event;
#[cfg(feature = "follow-through")]
mod follow;
mod impact;
mod integral;
mod phases;
mod rest;
#[cfg(test)]
mod tests;
mod wobble;

pub use config::{CheckedConfig, StreamConfig, StreamConfigError, StreamPlan, MAX_STREAM_RATE_HZ};
pub use event::{StreamEvent, StreamFault, StreamStroke};
pub use wobble::Wobble;

use config::{Plan, RING};
#[cfg(feature = "follow-through")]
use follow::Follow;
use integral::Stroke;
use rest::{Block, Run};

/// `k & MASK` is a ring index.
const MASK: usize = RING - 1;

/// Streaming cue-speed estimator. Feed every sample in order with [`Self::push_raw`]
/// (raw words) or [`Self::push`] (SI units); call [`Self::finish`] when the stream ends.
#[derive(Clone, Debug)]
#[repr(C)]
pub struct StreamingEstimator {
    plan: Plan,
    /// Index of the current block's first sample, unwrapped (`block.start` is its low
    /// 32 bits): every reported index is this plus a signed `u32` distance.
    block_base: u64,
    /// Prefix sums of the acceleration and pitch-rate counts through the last sample
    /// (wrapping: only differences over a bounded span are used).
    p: i32,
    c: i32,
    block: Block,
    run: Run,
    stroke: Stroke,
    /// The follow-through after the last reported stroke (`follow.rs`).
    #[cfg(feature = "follow-through")]
    follow: Follow,
    /// Elevation change from the rest (counts·samples) before each of the last 8 samples.
    recent_tilt: [f32; 8],
    /// Latest sample below the impact threshold (dropped at a block end once more than
    /// `gap` old).
    last_crossing: Option<u32>,
    /// The last reported impact's onset, and the last sample a double hit may start
    /// (dropped at a block end after that).
    last_impact: Option<(u64, u32)>,
    /// Latest sample at full scale (dropped at a block end once too old for any rest
    /// end to come).
    last_saturated: Option<u32>,
    /// The previous sample was not finite.
    not_finite: bool,
    /// `(g cos θ₀, g sin θ₀)` (m/s²), computed at the first block end.
    gravity: Option<(f32, f32)>,
    /// The stroke metrics' first-order tilt correction, `g cos θ₀ · pitch_scale · Δt /
    /// scale`: velocity counts per count·sample of mid-sample elevation change (set
    /// with `gravity`; `phases.rs`).
    tilt_gain: f32,
    /// `ring[k & MASK] = [P(k), C(k)]`, the prefix sums before sample `k`, for the last
    /// `RING` values of `k` (last: the fields before it stay within the Cortex-M4F's
    /// 1,020-byte reach of a floating-point load from the estimator's address).
    ring: [[i32; 2]; RING],
    /// A report deferred by [`StreamConfig::defer_reports`], for [`Self::resolve`].
    deferred: Deferred,
}

impl StreamingEstimator {
    /// A validated estimator, at sample index 0.
    pub const fn new(config: &StreamConfig) -> Result<Self, StreamConfigError> {
        match Plan::new(config) {
            Ok(plan) => Ok(Self::from_plan(plan)),
            Err(e) => Err(e),
        }
    }

    /// An estimator at sample index 0 on a config validated before
    /// ([`StreamPlan::new`]; in a `const` item, at compile time: a device that samples
    /// at a few known rates then carries no validation code).
    pub const fn with_plan(plan: &StreamPlan) -> Self {
        Self::from_plan(plan.0)
    }

    const fn from_plan(plan: Plan) -> Self {
        Self {
            plan,
            block_base: 0,
            p: 0,
            c: 0,
            ring: [[0; 2]; RING],
            block: Block::new(),
            run: Run::new(),
            stroke: Stroke::new(plan.knock),
            #[cfg(feature = "follow-through")]
            follow: Follow::new(),
            recent_tilt: [0.0; 8],
            last_crossing: None,
            last_impact: None,
            last_saturated: None,
            not_finite: false,
            deferred: Deferred::Nothing,
            gravity: None,
            tilt_gain: 0.0,
        }
    }

    /// One sample of raw words: the accelerometer's cue axis and, for the gyro-aided
    /// estimate, the pitch-rate axis (`None`: no gyro, a zero rate). The words are
    /// scaled by the config's `accel_scale` and `pitch_scale`.
    pub fn push_raw(&mut self, accel: i16, pitch: Option<i16>) -> Option<StreamEvent> {
        let a = i32::from(accel) * self.plan.accel_sign;
        let p = match pitch {
            Some(w) => i32::from(w) * self.plan.pitch_sign,
            None => 0,
        };
        self.step(a, p, true)
    }

    /// One sample in SI units: specific force along the cue, forward positive (m/s²),
    /// and the pitch rate, butt rising positive (rad/s). Each is quantised to the
    /// config's scale (the sensor's own resolution) and clipped to the i16 range, where
    /// it counts as saturated. A NaN or infinite value gives
    /// [`StreamFault::NotFinite`] (once per run of them).
    pub fn push(&mut self, accel_mps2: f32, pitch_rate_radps: Option<f32>) -> Option<StreamEvent> {
        let pitch = pitch_rate_radps.unwrap_or(0.0);
        if !(cuesight::math::is_finite(accel_mps2) && cuesight::math::is_finite(pitch)) {
            return self.step(0, 0, false);
        }
        let a = quantise(accel_mps2 * self.plan.inv_scale);
        let p = quantise(pitch * self.plan.inv_pitch_scale);
        self.step(a, p, true)
    }

    /// End of the stream: a stroke being integrated is reported as
    /// [`StreamFault::EndedMidStroke`]. The estimator is then as new (index 0).
    pub fn finish(&mut self) -> Option<StreamEvent> {
        let event = self
            .stroke
            .active
            .then_some(StreamEvent::Fault(StreamFault::EndedMidStroke {
                rest_end: self.unwrap_index(self.stroke.rest_end),
                samples: self.samples(),
            }));
        *self = Self::from_plan(self.plan);
        event
    }

    /// Samples pushed so far (the index the next one gets).
    pub const fn samples(&self) -> u64 {
        self.block_base + self.block.pos as u64
    }

    /// `true` while a stroke is being integrated (a rest has ended, no impact yet; an
    /// impact whose report is deferred ends it).
    pub const fn in_stroke(&self) -> bool {
        self.stroke.active && !matches!(self.deferred, Deferred::Impact(_))
    }

    /// Where the stroke being integrated starts: the end of the rest its speed is
    /// integrated from (`None` between strokes). It moves when a later rest replaces
    /// that one (step 3 of the module docs).
    pub fn rest_end(&self) -> Option<u64> {
        self.stroke
            .active
            .then(|| self.unwrap_index(self.stroke.rest_end))
    }

    /// `true` when the last push deferred work ([`StreamConfig::defer_reports`]: a
    /// report, a block end or a rest's end, which may change [`Self::in_stroke`]): call
    /// [`Self::resolve`] before the next push.
    pub fn deferred(&self) -> bool {
        !matches!(self.deferred, Deferred::Nothing)
    }

    /// The work the last push deferred, done now: its report (a stroke or one of its
    /// faults, a follow-through), exactly what that push would have returned without
    /// [`StreamConfig::defer_reports`], or a block end's rest tests or a rest's end
    /// (`None`, unless the sample that ended the rest also ends something). `None`
    /// when nothing waits.
    ///
    /// Call it before the next push: the report is computed from the estimator's state
    /// at the sample that found it, which the next sample changes (the firmware's
    /// resolving task runs at the priority just below the sampling interrupt's, so it
    /// always comes first).
    pub fn resolve(&mut self) -> Option<StreamEvent> {
        match core::mem::replace(&mut self.deferred, Deferred::Nothing) {
            Deferred::Nothing => None,
            Deferred::Impact(n) => self.new_impact(n),
            Deferred::BlockEnd(n) => {
                self.end_block(n);
                None
            }
            Deferred::Depart(n, a) => {
                // The rest of `step` after the motion test (its report, if any, now).
                self.depart(n);
                if a < self.stroke.limit && self.new_crossing(n) {
                    return self.new_impact(n);
                }
                #[cfg(feature = "follow-through")]
                if self.follow_due(n, a) {
                    return self.follow_report();
                }
                if self.block.pos == self.plan.block {
                    self.end_block(n);
                }
                None
            }
            #[cfg(feature = "follow-through")]
            Deferred::Follow => self.follow_report(),
        }
    }

    /// The unwrapped index of sample `k` (within 2³¹ samples of the current block).
    fn unwrap_index(&self, k: u32) -> u64 {
        let distance = k.wrapping_sub(self.block.start) as i32;
        self.block_base.wrapping_add_signed(i64::from(distance))
    }

    /// The per-sample step on counts (forward positive); `finite` is false for a
    /// non-finite SI input (then `a = p = 0`).
    ///
    /// The sample ends in one of the `#[inline(never)]` functions when something
    /// happens (an impact, a non-finite input); they build the event last, directly in
    /// the caller's return slot (an event returned from a call and then moved is copied
    /// twice, 48 bytes through `memcpy` each time, on the Cortex-M4F).
    fn step(&mut self, a: i32, p: i32, finite: bool) -> Option<StreamEvent> {
        let n = self.block.start.wrapping_add(self.block.pos);
        let report_non_finite = if finite {
            self.not_finite = false;
            false
        } else {
            self.non_finite()
        };
        self.p = self.p.wrapping_add(a);
        self.c = self.c.wrapping_add(p);
        let next = n.wrapping_add(1);
        self.ring[next as usize & MASK] = [self.p, self.c];
        // The sum of the last W samples, `P(n+1) − P(n+1−W)`: the block's W-sum
        // extremes and the motion test.
        let w_sum = self
            .p
            .wrapping_sub(self.prefix(next.wrapping_sub(self.plan.window)));
        self.block_sample(a, w_sum);
        if (a.wrapping_sub(self.plan.normal)) as u32 >= self.plan.normal_span {
            self.extreme(a, n);
        }
        // Integrate before the motion test: a rest end found now already covers `n`.
        if self.stroke.active {
            self.integrate(n, a, p);
        }
        if self.run.armed && self.moved(w_sum) {
            // (Never on a non-finite sample: `non_finite` abandoned the run.)
            if self.plan.defer {
                // The rest of the step after the rest's end too (`resolve`).
                self.deferred = Deferred::Depart(n, a);
                return None;
            }
            self.depart(n);
        }
        // The impact threshold: `stroke.limit` is `plan.knock` between strokes.
        if finite && a < self.stroke.limit && self.new_crossing(n) {
            if self.plan.defer {
                self.deferred = Deferred::Impact(n);
                return None;
            }
            return self.new_impact(n);
        }
        if report_non_finite {
            return self.report_non_finite(n);
        }
        // The follow-through's sums (`follow.rs`): one comparison when none is measured.
        // After the impact and non-finite reports: each ends a measurement, and the
        // costliest samples (impacts) do not pay for it.
        #[cfg(feature = "follow-through")]
        if self.follow_due(n, a) {
            return self.report_follow();
        }
        if self.block.pos == self.plan.block {
            if self.plan.defer {
                self.deferred = Deferred::BlockEnd(n);
            } else {
                self.end_block(n);
            }
        }
        None
    }

    /// A non-finite input: the rest and any stroke are dropped. `true` for the first of
    /// a run of them (reported).
    #[inline(never)]
    fn non_finite(&mut self) -> bool {
        let first = !self.not_finite;
        self.not_finite = true;
        self.stroke.end(&self.plan);
        self.run.abandon();
        #[cfg(feature = "follow-through")]
        {
            self.follow.span = 0;
        }
        self.block.bad = true;
        first
    }

    /// The end of a step whose sample `n` is the first of a run of non-finite ones.
    #[inline(never)]
    fn report_non_finite(&mut self, n: u32) -> Option<StreamEvent> {
        if self.block.pos == self.plan.block {
            self.end_block(n);
        }
        Some(StreamEvent::Fault(StreamFault::NotFinite {
            index: self.unwrap_index(n),
        }))
    }

    /// Sample `n`, `a` counts, is at the sensor's full scale or below the impact
    /// threshold of a cue at rest (a knock): not a rest block.
    #[inline(never)]
    fn extreme(&mut self, a: i32, n: u32) {
        if a >= self.plan.rail || a <= -self.plan.rail {
            self.block.bad = true;
            self.last_saturated = Some(n);
            if self.stroke.active && self.stroke.first_saturated.is_none() {
                self.stroke.first_saturated = Some(n);
            }
        }
        if a < self.plan.knock {
            self.block.bad = true;
        }
    }

    /// Prefix sum of the acceleration before sample `k` (`k` within the ring's reach).
    fn prefix(&self, k: u32) -> i32 {
        self.ring[k as usize & MASK][0]
    }

    /// Sample `i` in counts, from the prefix ring.
    fn sample(&self, i: u32) -> f32 {
        self.prefix(i.wrapping_add(1)).wrapping_sub(self.prefix(i)) as f32
    }
}

/// What [`StreamingEstimator::resolve`] has to compute.
#[derive(Clone, Copy, Debug)]
enum Deferred {
    Nothing,
    /// The impact crossing at this sample ([`StreamingEstimator::new_impact`]).
    Impact(u32),
    /// The block ending at this sample (every 25 ms: the rest tests, `rest.rs`). It
    /// reports nothing itself.
    BlockEnd(u32),
    /// The motion test fired at this sample, of these counts: the rest's end (which
    /// may start a stroke or re-anchor one) and the rest of the step.
    Depart(u32, i32),
    /// The follow-through's report.
    #[cfg(feature = "follow-through")]
    Follow,
}

/// `a` is at or after `b`, for two sample indices less than 2³¹ apart.
fn at_or_after(a: u32, b: u32) -> bool {
    a.wrapping_sub(b) as i32 >= 0
}

/// Nearest integer (ties away from zero), clipped to the i16 range.
fn quantise(x: f32) -> i32 {
    let r = if x >= 0.0 { x + 0.5 } else { x - 0.5 };
    (r as i32).clamp(i32::from(i16::MIN), i32::from(i16::MAX))
}
