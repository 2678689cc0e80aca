//! Settings of the streaming estimator, their validation and the sample counts derived
//! from them (all computed once, in a `const fn`).

use core::fmt;

use crate::lsm6dsox::{ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB};
use crate::stroke::{ConfigField, StrokeConfig};

/// Samples of history the estimator keeps (prefix sums, [`super::StreamingEstimator`]).
/// A power of two: every ring index is `k & (RING − 1)`, in range by construction.
pub(crate) const RING: usize = 128;

/// Highest accepted sample rate (Hz): the rest boundary lies `W + guard` = 12.4 ms of
/// samples behind the motion test, and that delay must fit in the ring (124 samples at
/// 10 kHz). The LSM6DSOX's highest ODR is 6.66 kHz (7.9 kHz at the largest trim).
pub const MAX_STREAM_RATE_HZ: f32 = 10_000.0;

/// Streaming estimator settings. The stroke detection settings are the windowed
/// estimator's ([`StrokeConfig`], same meaning and defaults); the rest are the raw
/// words' scales and what a stream needs beyond one window.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StreamConfig {
    /// Rate, thresholds, rest tests, full scale and cue elevation, as for the windowed
    /// estimator; the rate must be in `[500, 10 000]` Hz here.
    pub stroke: StrokeConfig,
    /// Acceleration per raw word (m/s² per LSB), negative if the sensor's axis points
    /// away from the tip. Default [`ACCEL_MPS2_PER_LSB`] (±16 g).
    pub accel_scale: f32,
    /// Pitch rate per raw word (rad/s per LSB), with the sign that makes a rising butt
    /// positive. Default [`GYRO_RADPS_PER_LSB`] (±2000 dps).
    pub pitch_scale: f32,
    /// A rest at least this long (s) replaces an earlier, longer one as the start of the
    /// integration, if the cue's integrated speed at its end is near zero. Default 1 s:
    /// the gentle end of a slow backswing (1.5 s) passes the rest tests for up to
    /// 0.55 s at near-zero speed (`docs/sensors.md` §11); shorter runs are compared by
    /// length, as the windowed estimator does.
    pub trusted_rest: f32,
    /// Longest accepted stroke, from the end of the rest to the impact (s). An
    /// integration running longer is dropped. Default 10 s; at most 60 s.
    pub max_stroke: f32,
    /// A second impact starting within this time (s) of the first is reported as a
    /// double hit. Default 0.1 s.
    pub double_hit_window: f32,
    /// Slowest cue speed reported as a stroke (m/s); a slower or backward integral is
    /// [`super::StreamFault::NotForward`]. Default 0.05 m/s.
    pub min_speed: f32,
    /// Measure each stroke's follow-through and report it as
    /// [`super::StreamEvent::FollowThrough`] once the cue is still again (`follow.rs`).
    /// Default `false`: a consumer that does not handle the event gets exactly the
    /// events it got before. Only with the crate's `follow-through` feature.
    #[cfg(feature = "follow-through")]
    pub follow_through: bool,
    /// Defer the costly work (a stroke's impact, a follow-through's report, a block
    /// end's rest tests, a rest's end with the rest of its sample's step) out of the
    /// sample that finds it: that sample's push returns
    /// `None` and sets [`super::StreamingEstimator::deferred`], and
    /// [`super::StreamingEstimator::resolve`] does it. For a sampling
    /// interrupt that must stay short, with the report computed at a lower priority
    /// before the next sample (`docs/sensors.md` §11). Default `false`.
    pub defer_reports: bool,
}

impl StreamConfig {
    /// Defaults for a sample rate in Hz (LSM6DSOX at ±16 g and ±2000 dps).
    pub const fn new(sample_rate_hz: f32) -> Self {
        Self {
            stroke: StrokeConfig::new(sample_rate_hz),
            accel_scale: ACCEL_MPS2_PER_LSB,
            pitch_scale: GYRO_RADPS_PER_LSB,
            trusted_rest: 1.0,
            max_stroke: 10.0,
            double_hit_window: 0.1,
            min_speed: 0.05,
            #[cfg(feature = "follow-through")]
            follow_through: false,
            defer_reports: false,
        }
    }
}

/// A [`StreamConfig`] field that failed validation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum StreamConfigError {
    /// A field of `stroke` other than the rate, with the windowed estimator's range.
    Stroke(ConfigField),
    /// `stroke.sample_rate_hz` not in `[500, 10 000]` Hz.
    SampleRate,
    /// `accel_scale` not a finite, non-zero number.
    AccelScale,
    /// `pitch_scale` not a finite, non-zero number.
    PitchScale,
    /// `trusted_rest` not in `[min_rest, 60]` s.
    TrustedRest,
    /// `max_stroke` not in `(0, 60]` s.
    MaxStroke,
    /// `double_hit_window` not in `(0, 1]` s.
    DoubleHitWindow,
    /// `min_speed` not a finite number ≥ 0.
    MinSpeed,
}

impl fmt::Display for StreamConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (name, range) = match self {
            StreamConfigError::Stroke(field) => (field.name(), field.valid_range()),
            StreamConfigError::SampleRate => ("sample_rate_hz", "in [500, 10000] Hz"),
            StreamConfigError::AccelScale => ("accel_scale", "a finite, non-zero number"),
            StreamConfigError::PitchScale => ("pitch_scale", "a finite, non-zero number"),
            StreamConfigError::TrustedRest => ("trusted_rest", "in [min_rest, 60] s"),
            StreamConfigError::MaxStroke => ("max_stroke", "in (0, 60] s"),
            StreamConfigError::DoubleHitWindow => ("double_hit_window", "in (0, 1] s"),
            StreamConfigError::MinSpeed => ("min_speed", "a finite number >= 0 (m/s)"),
        };
        write!(f, "stream config: {name} must be {range}")
    }
}

impl core::error::Error for StreamConfigError {}

/// A validated [`StreamConfig`], with everything [`super::StreamingEstimator`] derives
/// from it: [`super::StreamingEstimator::with_plan`] starts an estimator from it.
#[derive(Clone, Copy, Debug)]
pub struct StreamPlan(pub(super) Plan);

impl StreamPlan {
    /// Validates `config` (the checks of [`super::StreamingEstimator::new`]).
    pub const fn new(config: &StreamConfig) -> Result<Self, StreamConfigError> {
        match Plan::new(config) {
            Ok(plan) => Ok(Self(plan)),
            Err(e) => Err(e),
        }
    }
}

/// A [`StreamConfig`] whose settings were all validated ([`StreamPlan::new`]), for a
/// device whose sample rate is known only at run time (a part's trimmed output data
/// rate): [`Self::plan_at`] checks the rate alone. In a `const` item, every other check
/// is made at compile time, and the image carries none of their code.
#[derive(Clone, Copy, Debug)]
pub struct CheckedConfig(StreamConfig);

impl CheckedConfig {
    /// Validates `config` (the checks of [`StreamPlan::new`]).
    pub const fn new(config: &StreamConfig) -> Result<Self, StreamConfigError> {
        match check(config) {
            Ok(()) => Ok(Self(*config)),
            Err(e) => Err(e),
        }
    }

    /// [`StreamPlan::new`] of the config with its `stroke.sample_rate_hz` replaced by
    /// `rate_hz`: the same plan, or the same [`StreamConfigError::SampleRate`]. No other
    /// check depends on the rate, and they all held for [`Self::new`].
    pub const fn plan_at(&self, rate_hz: f32) -> Result<StreamPlan, StreamConfigError> {
        let mut config = self.0;
        config.stroke.sample_rate_hz = rate_hz;
        if !(rate_hz >= 500.0 && rate_hz <= MAX_STREAM_RATE_HZ) {
            return Err(StreamConfigError::SampleRate);
        }
        Ok(StreamPlan(Plan::derive(&config)))
    }
}

/// Sample counts and unit conversions derived from a validated [`StreamConfig`]. Every
/// acceleration is in raw counts (`m/s² / |accel_scale|`), forward positive.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plan {
    /// Sample period (s).
    pub dt: f32,
    /// |accel_scale| (m/s² per count) and its inverse.
    pub scale: f32,
    pub inv_scale: f32,
    /// The raw accelerometer word's sign: −1 if it is negated (axis pointing to the
    /// butt), else 1 (a multiplication, where a test and a negation take four
    /// instructions).
    pub accel_sign: i32,
    /// |pitch_scale| (rad/s per count), its inverse, and the word's sign.
    pub pitch_scale: f32,
    pub inv_pitch_scale: f32,
    pub pitch_sign: i32,
    /// Block length (25 ms), and its inverse; the position in a block where the guard
    /// mark is taken (`block − guard`).
    pub block: u32,
    pub inv_block: f32,
    pub guard_pos: u32,
    /// Blocks a rest needs (`min_rest`, at least 3) and blocks of a trusted rest.
    pub rest_blocks: u32,
    pub trusted_blocks: u32,
    /// Rest-window bucket (blocks, ~1 s): the bias is the mean of the last 1–2 s of rest.
    pub bucket: u32,
    /// Moving-average window `W` (2.4 ms), guard (10 ms), delay `W + guard`.
    pub window: u32,
    pub guard: u32,
    pub delay: u32,
    /// Impact crossings closer than this (5 ms) belong to one impact.
    pub gap: u32,
    /// `double_hit_window` and `max_stroke` in samples.
    pub double_hit: u32,
    pub max_stroke: u32,
    /// Thresholds in counts: impact, onset drop, rest level tolerance; the rest-noise
    /// limit and `W · motion_floor`, squared.
    pub impact: f32,
    pub onset_drop: f32,
    pub level_tolerance: f32,
    pub noise_limit_sq: f32,
    pub floor_sq: f32,
    /// A word at or beyond this magnitude is at the sensor's full scale.
    pub rail: i32,
    /// `⌈−impact⌉`: a count `a` is below the impact threshold of a still cue,
    /// `(a as f32) < −impact`, exactly when `a < knock` (see [`ceil`]).
    pub knock: i32,
    /// Counts `a` with `(a − normal) as u32 < normal_span` (`normal ≤ a < rail`, `normal`
    /// the larger of `knock` and `1 − rail`) are neither at full scale nor below the
    /// knock threshold: one comparison per sample for both tests.
    pub normal: i32,
    pub normal_span: u32,
    /// Slowest reported speed (m/s) and cue elevation at rest (rad).
    pub min_speed: f32,
    pub elevation: f32,
    /// The stroke metrics' pause threshold, `REST_SPEED` in velocity counts
    /// (counts·samples: times `scale · dt` it is m/s).
    pub slow: f32,
    /// Follow-through (`follow.rs`): the contact window left out of its sums (samples
    /// from the onset), and how many samples after that window its sums may run before
    /// it is given up (0: not measured).
    #[cfg(feature = "follow-through")]
    pub follow_skip: u32,
    #[cfg(feature = "follow-through")]
    pub follow_span: u32,
    /// [`StreamConfig::defer_reports`].
    pub defer: bool,
}

/// `round(seconds · rate)`, at least `at_least` (casts saturate; inputs are bounded).
/// Out of line where a plan is derived at run time (the nRF52840's trimmed rate): its
/// eleven inlined copies were larger than their calls. A `const` plan is unaffected.
#[inline(never)]
const fn samples(seconds: f32, rate: f32, at_least: u32) -> u32 {
    let n = (seconds * rate + 0.5) as u32;
    if n < at_least {
        at_least
    } else {
        n
    }
}

/// `⌈x⌉` for a finite `x` within the `i32` range: for every integer `a` (exact in f32,
/// `|a| < 2²⁴`), `(a as f32) < x` exactly when `a < ⌈x⌉`, so a count is compared with
/// an f32 threshold in one integer comparison.
pub(crate) const fn ceil(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) < x {
        t + 1
    } else {
        t
    }
}

/// The smallest positive f32 (a subnormal): `x ≥ TINY` is `x > 0`.
const TINY: f32 = f32::from_bits(1);

/// `|x|`, NaN for NaN (a `const` comparison).
const fn magnitude(x: f32) -> f32 {
    if x < 0.0 {
        -x
    } else {
        x
    }
}

/// Validate `config` (the windowed estimator's checks, then the stream's own).
const fn check(config: &StreamConfig) -> Result<(), StreamConfigError> {
    let s = &config.stroke;
    let rate = s.sample_rate_hz;
    use ConfigField as F;
    use StreamConfigError as E;
    // Every check is `low ≤ x ≤ high`, false for NaN, in the order the errors are
    // reported: a table and one loop are a third of the code of fifteen tests. "> 0
    // and finite" is `[TINY, MAX]`; "above the impact threshold" `≥` the next float.
    let above_threshold = f32::from_bits(s.impact_threshold.to_bits().wrapping_add(1));
    #[rustfmt::skip]
    let checks: [(f32, f32, f32, StreamConfigError); 15] = [
        (rate, 500.0, MAX_STREAM_RATE_HZ, E::SampleRate),
        (s.impact_threshold, TINY, f32::MAX, E::Stroke(F::ImpactThreshold)),
        (s.onset_drop, TINY, f32::MAX, E::Stroke(F::OnsetDrop)),
        (s.rest_noise_limit, TINY, f32::MAX, E::Stroke(F::RestNoiseLimit)),
        (s.rest_level_tolerance, TINY, f32::MAX, E::Stroke(F::RestLevelTolerance)),
        (s.motion_floor, TINY, f32::MAX, E::Stroke(F::MotionFloor)),
        (s.min_rest, TINY, 10.0, E::Stroke(F::MinRest)),
        (s.full_scale, above_threshold, f32::INFINITY, E::Stroke(F::FullScale)),
        (s.cue_elevation, -1.2, 1.2, E::Stroke(F::CueElevation)),
        (magnitude(config.accel_scale), TINY, f32::MAX, E::AccelScale),
        (magnitude(config.pitch_scale), TINY, f32::MAX, E::PitchScale),
        (config.trusted_rest, s.min_rest, 60.0, E::TrustedRest),
        (config.max_stroke, TINY, 60.0, E::MaxStroke),
        (config.double_hit_window, TINY, 1.0, E::DoubleHitWindow),
        (config.min_speed, 0.0, f32::MAX, E::MinSpeed),
    ];
    let mut i = 0;
    while i < checks.len() {
        let (x, low, high, error) = checks[i];
        if !(x >= low && x <= high) {
            return Err(error);
        }
        i += 1;
    }
    Ok(())
}

impl Plan {
    /// Validate `config` ([`check`]) and derive its plan.
    pub const fn new(config: &StreamConfig) -> Result<Plan, StreamConfigError> {
        match check(config) {
            Ok(()) => Ok(Self::derive(config)),
            Err(e) => Err(e),
        }
    }

    /// The plan of a valid `config` ([`check`]).
    const fn derive(config: &StreamConfig) -> Plan {
        let s = &config.stroke;
        let rate = s.sample_rate_hz;
        let scale = magnitude(config.accel_scale);
        let pitch_scale = magnitude(config.pitch_scale);
        // The windowed estimator's sample counts (`stroke.rs`, `StrokeConfig::validate`).
        let block = samples(0.025, rate, 8);
        let min_rest = samples(s.min_rest, rate, block);
        let rest_blocks = {
            let n = min_rest.div_ceil(block);
            if n < 3 {
                3
            } else {
                n
            }
        };
        let trusted_blocks = samples(config.trusted_rest, rate, block).div_ceil(block);
        let window = samples(0.0024, rate, 4);
        let guard = samples(0.010, rate, 2);
        let motion_floor = s.motion_floor / scale * window as f32;
        let noise_limit = s.rest_noise_limit / scale;
        // 0.999 of full scale, in whole counts, never above the i16 rail (a clipped
        // word is saturated whatever the configured full scale).
        let rail = {
            let r = 0.999 * s.full_scale / scale;
            if r >= 32_767.0 {
                32_767
            } else {
                let t = r as i32;
                if (t as f32) < r {
                    t + 1
                } else {
                    t
                }
            }
        };
        let knock = ceil(-(s.impact_threshold / scale));
        let normal = if knock > 1 - rail { knock } else { 1 - rail };
        Plan {
            dt: 1.0 / rate,
            scale,
            inv_scale: 1.0 / scale,
            accel_sign: if config.accel_scale < 0.0 { -1 } else { 1 },
            pitch_scale,
            inv_pitch_scale: 1.0 / pitch_scale,
            pitch_sign: if config.pitch_scale < 0.0 { -1 } else { 1 },
            block,
            inv_block: 1.0 / block as f32,
            guard_pos: block - guard,
            rest_blocks,
            trusted_blocks,
            bucket: samples(1.0, rate, 1).div_ceil(block),
            window,
            guard,
            delay: window + guard,
            gap: samples(0.005, rate, 2),
            double_hit: samples(config.double_hit_window, rate, 1),
            max_stroke: samples(config.max_stroke, rate, 1),
            impact: s.impact_threshold / scale,
            onset_drop: s.onset_drop / scale,
            level_tolerance: s.rest_level_tolerance / scale,
            noise_limit_sq: noise_limit * noise_limit,
            floor_sq: motion_floor * motion_floor,
            rail,
            knock,
            normal,
            normal_span: (rail - normal) as u32,
            min_speed: config.min_speed,
            elevation: s.cue_elevation,
            slow: super::integral::REST_SPEED * rate / scale,
            #[cfg(feature = "follow-through")]
            follow_skip: samples(super::follow::SKIP, rate, 1),
            #[cfg(feature = "follow-through")]
            follow_span: if config.follow_through {
                samples(super::follow::BOUND - super::follow::SKIP, rate, 1)
            } else {
                0
            },
            defer: config.defer_reports,
        }
    }
}
