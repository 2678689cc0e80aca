//! Cue speed at the tip impact from the accelerometer axis along the cue.
//!
//! # Input contract
//!
//! `samples` is the specific force along the cue axis, **forward (towards the tip)
//! positive**, in m/s² (or raw words with a scale, [`estimate_raw`]), at a known, uniform
//! rate, oldest first. The window must contain a stretch of at least
//! [`StrokeConfig::min_rest`] (default 150 ms) in which the cue is held still — at
//! address before the backswing, or paused at the back — and then the tip impact, the
//! first impact-sized deceleration after that rest. The sensor's offset and gravity's
//! component along the cue are removed together as one constant; if the cue's elevation
//! changes during the stroke (a pendulum stroke tilts it by a degree or two) use the
//! gyro-aided [`estimate_with_pitch`], which integrates the pitch rate and puts the
//! gravity change back (`docs/sensors.md` has the figures).
//!
//! # Algorithm (a few passes over the window, no buffer, f32 with compensated sums)
//!
//! 1. **Rest.** Split the window into 25 ms blocks and take the longest run (ties: the
//!    later one), before the impact, of blocks whose standard deviation is below
//!    `rest_noise_limit` and whose means agree within `rest_level_tolerance`, lasting at
//!    least `min_rest`. A block holding an impact-sized deceleration before any run
//!    qualifies is a knock and restarts the search. Longest, because a slow, smooth move
//!    has stretches of nearly constant acceleration (around its acceleration peaks) that
//!    pass both tests for ~0.1 s; a real rest lasts longer.
//! 2. **Rest boundaries.** The level is the mean of the run's interior blocks. A 2.4 ms
//!    moving average departing from it by more than `max(6 σ/√W, motion_floor)` marks
//!    the end of the move before the rest (searched backwards) and the start of the
//!    stroke (forwards); the rest window keeps 10 ms clear of both, so the smooth,
//!    jerk-limited start of a backswing does not leak into the bias.
//! 3. **Bias.** The mean of the rest window (sensor offset + gravity along the cue).
//! 4. **Impact.** The first sample after the rest below `bias − impact_threshold`
//!    (default 8 g; the forward stroke accelerates, the impact decelerates at tens to
//!    hundreds of g and saturates a ±16 g part). The onset is refined backwards to the
//!    first sample lying `onset_drop` (1 g) below the pre-impact level, at most four
//!    samples back: samples touched by the spike are excluded from the integral.
//! 5. **Speed.** `V = Σ (a_i − bias) Δt` from the end of the rest window to the sample
//!    before the onset, i.e. the velocity with `v = 0` imposed at rest (plus the gravity
//!    correction of the tilt, with a pitch series). A sample at the sensor's full scale
//!    inside that span is refused (`Saturated`).
//!
//! The result feeds [`cuesight::strike::strike`] through [`StrokeEstimate::strike`].

use core::fmt;

use cuesight::strike::{strike, Cue, Strike, TipOffset};
use cuesight::Params;

use crate::lsm6dsox::STANDARD_GRAVITY;

/// Estimator settings. Start from [`StrokeConfig::new`]; every field is public so a
/// caller can tune one and keep the others.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrokeConfig {
    /// Sample rate (Hz), in `[500, 100 000]`. Use the part's trimmed ODR
    /// ([`crate::Lsm6dsox::odr_hz`]): a rate error is a speed error of the same size.
    pub sample_rate_hz: f32,
    /// Deceleration that marks the impact, below the rest level (m/s²). Default 8 g.
    pub impact_threshold: f32,
    /// Drop below the pre-impact level that marks a sample as touched by the impact
    /// (m/s²). Default 1 g.
    pub onset_drop: f32,
    /// Shortest accepted rest before the stroke (s). Default 0.15 s.
    pub min_rest: f32,
    /// Largest standard deviation of a rest block (m/s²). Default 0.3 m/s² (≈ 31 mg).
    pub rest_noise_limit: f32,
    /// Largest difference between rest-block means (m/s²). Default 0.05 m/s² (≈ 5 mg).
    pub rest_level_tolerance: f32,
    /// Smallest moving-average departure from rest taken as motion (m/s²). Default
    /// 0.03 m/s² (≈ 3 mg).
    pub motion_floor: f32,
    /// Sensor full scale (m/s²); a pre-impact sample at or beyond 99.9 % of it is
    /// refused. Default 16 g; `f32::INFINITY` disables the check.
    pub full_scale: f32,
    /// Cue elevation at rest (rad), used only by the gyro-aided estimators to scale the
    /// gravity correction (`g cos θ₀` per radian of pitch change). Default 0.1 rad
    /// (5.7°); an error of ±6° in it changes the correction by under 1.1 %.
    pub cue_elevation: f32,
}

impl StrokeConfig {
    /// Defaults (see each field) for a sample rate in Hz.
    pub const fn new(sample_rate_hz: f32) -> Self {
        Self {
            sample_rate_hz,
            impact_threshold: 8.0 * STANDARD_GRAVITY,
            onset_drop: STANDARD_GRAVITY,
            min_rest: 0.15,
            rest_noise_limit: 0.3,
            rest_level_tolerance: 0.05,
            motion_floor: 0.03,
            full_scale: 16.0 * STANDARD_GRAVITY,
            cue_elevation: 0.1,
        }
    }

    fn validate(&self) -> Result<Plan, StrokeError> {
        let positive = |x: f32| cuesight::math::is_finite(x) && x > 0.0;
        let rate = self.sample_rate_hz;
        if !(positive(rate) && (500.0..=100_000.0).contains(&rate)) {
            return Err(StrokeError::InvalidConfig(ConfigField::SampleRate));
        }
        let checks = [
            (self.impact_threshold, ConfigField::ImpactThreshold),
            (self.onset_drop, ConfigField::OnsetDrop),
            (self.rest_noise_limit, ConfigField::RestNoiseLimit),
            (self.rest_level_tolerance, ConfigField::RestLevelTolerance),
            (self.motion_floor, ConfigField::MotionFloor),
        ];
        for (value, field) in checks {
            if !positive(value) {
                return Err(StrokeError::InvalidConfig(field));
            }
        }
        if !(positive(self.min_rest) && self.min_rest <= 10.0) {
            return Err(StrokeError::InvalidConfig(ConfigField::MinRest));
        }
        // NaN-safe: only a full scale strictly above the threshold is accepted.
        let above = self.full_scale.partial_cmp(&self.impact_threshold);
        if above != Some(core::cmp::Ordering::Greater) {
            return Err(StrokeError::InvalidConfig(ConfigField::FullScale));
        }
        let elevation = self.cue_elevation;
        if !(cuesight::math::is_finite(elevation) && (-1.2..=1.2).contains(&elevation)) {
            return Err(StrokeError::InvalidConfig(ConfigField::CueElevation));
        }
        // Sample counts; the float-to-int casts saturate and the values are bounded by
        // the checks above (rate ≤ 1e5, min_rest ≤ 10 s).
        let samples = |seconds: f32, at_least: usize| {
            let n = (seconds * rate + 0.5) as usize;
            if n < at_least {
                at_least
            } else {
                n
            }
        };
        let block = samples(0.025, 8);
        let min_rest = samples(self.min_rest, block);
        Ok(Plan {
            dt: 1.0 / rate,
            block,
            // At least three blocks: the level is taken from the interior ones.
            rest_blocks: min_rest.div_ceil(block).max(3),
            window: samples(0.0024, 4),
            guard: samples(0.010, 2),
        })
    }
}

/// Sample counts derived from a validated [`StrokeConfig`].
struct Plan {
    dt: f32,
    block: usize,
    rest_blocks: usize,
    window: usize,
    guard: usize,
}

/// A [`StrokeConfig`] field that failed validation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum ConfigField {
    /// `sample_rate_hz` not in `[500, 100 000]`.
    SampleRate,
    /// `impact_threshold` not finite and positive.
    ImpactThreshold,
    /// `onset_drop` not finite and positive.
    OnsetDrop,
    /// `min_rest` not in `(0, 10]` s.
    MinRest,
    /// `rest_noise_limit` not finite and positive.
    RestNoiseLimit,
    /// `rest_level_tolerance` not finite and positive.
    RestLevelTolerance,
    /// `motion_floor` not finite and positive.
    MotionFloor,
    /// `full_scale` not above `impact_threshold`.
    FullScale,
    /// `cue_elevation` not in `[−1.2, 1.2]` rad.
    CueElevation,
}

impl ConfigField {
    /// The [`StrokeConfig`] field's name, as written in the source.
    pub const fn name(&self) -> &'static str {
        match self {
            ConfigField::SampleRate => "sample_rate_hz",
            ConfigField::ImpactThreshold => "impact_threshold",
            ConfigField::OnsetDrop => "onset_drop",
            ConfigField::MinRest => "min_rest",
            ConfigField::RestNoiseLimit => "rest_noise_limit",
            ConfigField::RestLevelTolerance => "rest_level_tolerance",
            ConfigField::MotionFloor => "motion_floor",
            ConfigField::FullScale => "full_scale",
            ConfigField::CueElevation => "cue_elevation",
        }
    }

    /// What the field must be, in words (the check [`StrokeConfig`] validation makes).
    pub const fn valid_range(&self) -> &'static str {
        match self {
            ConfigField::SampleRate => "in [500, 100000] Hz",
            ConfigField::ImpactThreshold
            | ConfigField::OnsetDrop
            | ConfigField::RestNoiseLimit
            | ConfigField::RestLevelTolerance
            | ConfigField::MotionFloor => "a finite number > 0 (m/s^2)",
            ConfigField::MinRest => "in (0, 10] s",
            ConfigField::FullScale => {
                "above impact_threshold (m/s^2; +inf disables the saturation check)"
            }
            ConfigField::CueElevation => "in [-1.2, 1.2] rad",
        }
    }
}

impl fmt::Display for ConfigField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why no cue speed could be estimated. Counts and sample indices are `u32` (the device's
/// word; a fixed width on the link, where the device sends this error as it is), saturated
/// at `u32::MAX` for a window longer than that.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum StrokeError {
    /// A configuration value is out of range.
    InvalidConfig(ConfigField),
    /// Fewer samples than the rest window and the detectors need.
    TooShort {
        /// Samples given.
        len: u32,
        /// Samples needed at this rate.
        min: u32,
    },
    /// A sample is NaN or infinite; from the raw estimators also a scale that is not a
    /// finite, non-zero number (reported as index 0).
    NotFinite {
        /// Its index.
        index: u32,
    },
    /// No rest of `min_rest` before an impact: the capture did not start with the cue
    /// held still. Also when the rest's level or spread is not representable in f32
    /// (only possible with limits far beyond any accelerometer's range).
    NotAtRest,
    /// No impact-sized deceleration after the rest.
    NoImpact,
    /// A sample between the rest and the impact reached the sensor's full scale.
    Saturated {
        /// Its index.
        index: u32,
    },
    /// The integrated speed at impact is not positive (wrong axis sign, or no stroke).
    NotForward {
        /// The integrated speed (m/s).
        speed: f32,
    },
    /// The pitch-rate series is not as long as the acceleration series.
    LengthMismatch {
        /// Acceleration samples.
        accel: u32,
        /// Pitch-rate samples.
        pitch: u32,
    },
    /// The strike model refused the estimate (e.g. above its 20 m/s range).
    Strike(cuesight::Error),
}

impl fmt::Display for StrokeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StrokeError::InvalidConfig(field) => write!(
                f,
                "stroke config: {} must be {}",
                field.name(),
                field.valid_range()
            ),
            StrokeError::TooShort { len, min } => write!(
                f,
                "window too short: {len} samples, at least {min} are needed at this sample rate"
            ),
            StrokeError::NotFinite { index } => write!(
                f,
                "sample {index} is not a finite number (or the raw scale is not a finite, \
                 non-zero number)"
            ),
            StrokeError::NotAtRest => {
                f.write_str("no rest of min_rest (the cue held still) before the impact")
            }
            StrokeError::NoImpact => {
                f.write_str("no impact (a deceleration beyond impact_threshold) after the rest")
            }
            StrokeError::Saturated { index } => write!(
                f,
                "sample {index}, between the rest and the impact, is at the sensor's full scale"
            ),
            StrokeError::NotForward { speed } => write!(
                f,
                "the cue speed at impact integrates to {speed} m/s, not forward (> 0): wrong \
                 axis sign or no stroke"
            ),
            StrokeError::LengthMismatch { accel, pitch } => write!(
                f,
                "length mismatch: {accel} acceleration samples but {pitch} pitch-rate samples"
            ),
            StrokeError::Strike(error) => write!(f, "strike model: {error}"),
        }
    }
}

/// ```
/// use cuesight_sensors::{estimate, StrokeConfig};
///
/// fn cue_speed(samples: &[f32]) -> Result<f32, Box<dyn std::error::Error>> {
///     Ok(estimate(samples, &StrokeConfig::new(1000.0))?.cue_speed)
/// }
///
/// // 10 ms of samples at 1 kHz: not even the rest before the stroke.
/// let error = cue_speed(&[0.0; 10]).unwrap_err();
/// assert!(error.to_string().starts_with("window too short: 10 samples"));
/// ```
impl core::error::Error for StrokeError {}

impl From<cuesight::Error> for StrokeError {
    fn from(e: cuesight::Error) -> Self {
        StrokeError::Strike(e)
    }
}

/// What the estimator found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrokeEstimate {
    /// Cue speed just before the tip touched the ball (m/s).
    pub cue_speed: f32,
    /// First sample touched by the impact (excluded from the integral).
    pub impact_index: usize,
    /// First sample of the rest window.
    pub rest_start: usize,
    /// One past the last sample of the rest window (where `v = 0` is imposed).
    pub rest_end: usize,
    /// Rest level removed from every sample: sensor offset + gravity along the cue
    /// (m/s²).
    pub bias: f32,
    /// Standard deviation of the rest window (m/s²): the sensor noise as seen.
    pub rest_noise: f32,
    /// Integration time from the end of the rest to the impact (s).
    pub stroke_duration: f32,
    /// Change of cue elevation from the rest to the impact (rad), from the pitch rate;
    /// zero for the accelerometer-only estimators.
    pub tilt_at_impact: f32,
}

impl StrokeEstimate {
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

/// No pitch series (accelerometer-only estimators).
type NoPitch = fn(usize) -> f32;

/// Estimate the cue speed at impact from samples in m/s² (forward positive).
pub fn estimate(samples: &[f32], config: &StrokeConfig) -> Result<StrokeEstimate, StrokeError> {
    // `get` keeps the indexing free of panic paths (indices are always in range).
    run(
        samples.len(),
        |i| samples.get(i).map_or(f32::NAN, |&a| a),
        None::<NoPitch>,
        config,
    )
}

/// As [`estimate`] from raw sensor words: sample `i` is `samples[i] · scale` m/s² (for
/// the LSM6DSOX at ±16 g, `scale = ACCEL_MPS2_PER_LSB`, negated if the sensor's axis
/// points away from the tip).
pub fn estimate_raw(
    samples: &[i16],
    scale: f32,
    config: &StrokeConfig,
) -> Result<StrokeEstimate, StrokeError> {
    if !cuesight::math::is_finite(scale) || scale == 0.0 {
        return Err(StrokeError::NotFinite { index: 0 });
    }
    let raw = Raw { samples, scale };
    run(samples.len(), |i| raw.at(i), None::<NoPitch>, config)
}

/// Raw accelerometer words and their scale, read one sample at a time.
struct Raw<'a> {
    samples: &'a [i16],
    scale: f32,
}

impl Raw<'_> {
    /// Sample `i` in m/s² (NaN past the end). Out of line: the estimator reads samples
    /// in eight places, and each inlined copy cost flash on the device.
    #[inline(never)]
    fn at(&self, i: usize) -> f32 {
        self.samples
            .get(i)
            .map_or(f32::NAN, |&a| f32::from(a) * self.scale)
    }
}

/// Gyro-aided [`estimate`]: `pitch_rate[i]` (rad/s, same instants as `accel[i]`) is the
/// rate of change of the cue's elevation, **positive when the butt rises** (the tip
/// dips). Its mean over the rest window is removed as gyro bias, it is integrated from
/// the end of the rest into the elevation change `Δθ`, and the gravity component that
/// change adds along the cue, `g (cos θ₀ Δθ − sin θ₀ Δθ²/2)`, is put back before the
/// acceleration is integrated. This removes the error of a cue that pivots during the
/// stroke (see `docs/sensors.md`: ~1° of pitch costs ~0.1 m/s).
pub fn estimate_with_pitch(
    accel: &[f32],
    pitch_rate: &[f32],
    config: &StrokeConfig,
) -> Result<StrokeEstimate, StrokeError> {
    if pitch_rate.len() != accel.len() {
        return Err(StrokeError::LengthMismatch {
            accel: saturated_u32(accel.len()),
            pitch: saturated_u32(pitch_rate.len()),
        });
    }
    run(
        accel.len(),
        |i| accel.get(i).map_or(f32::NAN, |&a| a),
        Some(|i| pitch_rate.get(i).map_or(f32::NAN, |&p: &f32| p)),
        config,
    )
}

/// [`estimate_with_pitch`] from raw words: acceleration `accel[i] · accel_scale` (m/s²)
/// and pitch rate `pitch[i] · pitch_scale` (rad/s; for the LSM6DSOX at ±2000 dps
/// `GYRO_RADPS_PER_LSB`, with the sign that makes a rising butt positive).
pub fn estimate_raw_with_pitch(
    accel: &[i16],
    accel_scale: f32,
    pitch: &[i16],
    pitch_scale: f32,
    config: &StrokeConfig,
) -> Result<StrokeEstimate, StrokeError> {
    let finite = |x: f32| cuesight::math::is_finite(x) && x != 0.0;
    if !finite(accel_scale) || !finite(pitch_scale) {
        return Err(StrokeError::NotFinite { index: 0 });
    }
    if pitch.len() != accel.len() {
        return Err(StrokeError::LengthMismatch {
            accel: saturated_u32(accel.len()),
            pitch: saturated_u32(pitch.len()),
        });
    }
    run(
        accel.len(),
        |i| {
            accel
                .get(i)
                .map_or(f32::NAN, |&a| f32::from(a) * accel_scale)
        },
        Some(|i| {
            pitch
                .get(i)
                .map_or(f32::NAN, |&p: &i16| f32::from(p) * pitch_scale)
        }),
        config,
    )
}

/// Kahan–Babuška compensated sum: keeps an f32 sum of ~10⁴ terms to a few ulps.
#[derive(Clone, Copy, Default)]
struct Sum {
    sum: f32,
    carry: f32,
}

impl Sum {
    /// Out of line: called in eight places, each inlined copy cost flash on the device
    /// (260 B of the release image), and a call per sample is nothing next to the
    /// estimate's one pass over the window.
    #[inline(never)]
    fn add(&mut self, x: f32) {
        let t = self.sum + x;
        if cuesight::math::abs(self.sum) >= cuesight::math::abs(x) {
            self.carry += (self.sum - t) + x;
        } else {
            self.carry += (x - t) + self.sum;
        }
        self.sum = t;
    }

    fn value(&self) -> f32 {
        self.sum + self.carry
    }
}

/// A length or index as [`StrokeError`] carries it (saturated at `u32::MAX`).
fn saturated_u32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Mean and standard deviation of `at(start..end)` (two passes; `end > start`).
fn mean_std(at: &impl Fn(usize) -> f32, start: usize, end: usize) -> (f32, f32) {
    let count = (end - start) as f32;
    let mut s = Sum::default();
    for i in start..end {
        s.add(at(i));
    }
    let mean = s.value() / count;
    let mut q = Sum::default();
    for i in start..end {
        let d = at(i) - mean;
        q.add(d * d);
    }
    (mean, cuesight::math::sqrt(q.value() / count))
}

fn run<P: Fn(usize) -> f32>(
    n: usize,
    at: impl Fn(usize) -> f32,
    pitch: Option<P>,
    config: &StrokeConfig,
) -> Result<StrokeEstimate, StrokeError> {
    let plan = config.validate()?;
    let (b, w) = (plan.block, plan.window);
    let min = b * plan.rest_blocks + w + 8;
    if n < min {
        return Err(StrokeError::TooShort {
            len: saturated_u32(n),
            min: saturated_u32(min),
        });
    }
    if let Some(index) = (0..n).find(|&i| !cuesight::math::is_finite(at(i))) {
        return Err(StrokeError::NotFinite {
            index: saturated_u32(index),
        });
    }
    if let Some(p) = &pitch {
        if let Some(index) = (0..n).find(|&i| !cuesight::math::is_finite(p(i))) {
            return Err(StrokeError::NotFinite {
                index: saturated_u32(index),
            });
        }
    }
    let coarse_impact = -config.impact_threshold;

    // 1. The longest run of still, level blocks (at least min_rest) before the impact;
    //    ties go to the later run. A block holding an impact-sized deceleration ends
    //    the search once a run qualifies, and restarts it before that (a knock).
    let mut best: Option<(usize, usize)> = None; // (first block, one past the last)
    let mut run_start = 0usize; // block index
    let mut run_len = 0usize;
    let mut run_level = 0.0f32;
    let mut impact_seen = false;
    let mut block_index = 0usize;
    let consider = |start: usize, len: usize, best: &mut Option<(usize, usize)>| {
        let longest = best.is_none_or(|(s, e)| len >= e - s);
        if len >= plan.rest_blocks && longest {
            *best = Some((start, start + len));
        }
    };
    while (block_index + 1) * b <= n {
        let (start, end) = (block_index * b, (block_index + 1) * b);
        let (mean, std) = mean_std(&at, start, end);
        let knock = (start..end).any(|i| at(i) < coarse_impact);
        let still = !knock && std <= config.rest_noise_limit;
        let level_ok =
            run_len == 0 || cuesight::math::abs(mean - run_level) <= config.rest_level_tolerance;
        if still && level_ok {
            if run_len == 0 {
                run_start = block_index;
                run_level = mean;
            }
            run_len += 1;
        } else {
            consider(run_start, run_len, &mut best);
            // A still block that only failed the level test starts a new run.
            (run_start, run_level, run_len) = (block_index, mean, usize::from(still));
            if knock && best.is_some() {
                impact_seen = true;
                break;
            }
        }
        block_index += 1;
    }
    if !impact_seen {
        // Still blocks up to the end of the window: no impact after them.
        consider(run_start, run_len, &mut best);
    }
    let Some((run_start, run_end)) = best else {
        return Err(StrokeError::NotAtRest);
    };
    // The run's first and last blocks may hold the tail of the move before the rest or
    // the start of the backswing; the level comes from the interior blocks only.
    let first = run_start * b;
    let last = run_end * b;
    let (core_start, core_end) = (first + b, last - b);
    let (level, spread) = mean_std(&at, core_start, core_end);

    // 2. Rest boundaries: a moving average of W samples leaving the level, looked for
    //    backwards from the interior (end of the earlier move) and forwards (motion start).
    let threshold = cuesight::math::max(
        6.0 * spread / cuesight::math::sqrt(w as f32),
        config.motion_floor,
    );
    let departs = |window: &Sum| cuesight::math::abs(window.value() / w as f32 - level) > threshold;

    // Backwards: window [i − W, i) for i from core_start down to first + W.
    let mut window = Sum::default();
    for i in core_start - w..core_start {
        window.add(at(i));
    }
    let mut rest_start = first;
    let mut i = core_start;
    loop {
        if departs(&window) {
            rest_start = i + plan.guard;
            break;
        }
        if i <= first + w {
            break;
        }
        i -= 1;
        window.add(at(i - w));
        window.add(-at(i));
    }

    // Forwards: window [i − W, i) for i from core_start + W up to a block past the run.
    let scan_end = if last + b < n { last + b } else { n };
    let mut window = Sum::default();
    for i in core_start..core_start + w {
        window.add(at(i));
    }
    let mut motion = last;
    let mut i = core_start + w;
    loop {
        if departs(&window) {
            motion = i - w;
            break;
        }
        if i >= scan_end {
            break;
        }
        window.add(at(i));
        window.add(-at(i - w));
        i += 1;
    }
    let rest_end = motion.saturating_sub(plan.guard);
    if rest_end < rest_start + b / 2 {
        // Less than half a block (12 ms) of clean rest survives the guards.
        return Err(StrokeError::NotAtRest);
    }

    // 3. Bias over the rest window. Its blocks passed the stillness tests, but with
    //    limits far beyond any sensor's range the spread over several blocks can still
    //    overflow f32: that is no rest.
    let (bias, rest_noise) = mean_std(&at, rest_start, rest_end);
    if !(cuesight::math::is_finite(bias) && cuesight::math::is_finite(rest_noise)) {
        return Err(StrokeError::NotAtRest);
    }

    // 4. Impact crossing and onset.
    let limit = bias - config.impact_threshold;
    let crossing = (rest_end..n)
        .find(|&i| at(i) < limit)
        .ok_or(StrokeError::NoImpact)?;
    let pre_start = crossing.saturating_sub(12).max(rest_end);
    let pre_end = crossing.saturating_sub(4).max(rest_end);
    let pre_level = if pre_end > pre_start {
        mean_std(&at, pre_start, pre_end).0
    } else {
        bias
    };
    let mut onset = crossing;
    while onset > rest_end && onset + 4 > crossing && at(onset - 1) < pre_level - config.onset_drop
    {
        onset -= 1;
    }

    // 5. Integrate from rest to the onset, v(rest_end) = 0; with a pitch series, add
    //    back the gravity change of the tilt integrated from the rest.
    let rail = 0.999 * config.full_scale;
    let gravity_cos = STANDARD_GRAVITY * cuesight::math::cos(config.cue_elevation);
    let gravity_sin = STANDARD_GRAVITY * cuesight::math::sin(config.cue_elevation);
    let gyro_bias = pitch.as_ref().map(|p| mean_std(p, rest_start, rest_end).0);
    let mut velocity = Sum::default();
    let mut tilt = Sum::default(); // Δθ / Δt at the start of the current sample
    for i in rest_end..onset {
        let a = at(i);
        if cuesight::math::abs(a) >= rail {
            return Err(StrokeError::Saturated {
                index: saturated_u32(i),
            });
        }
        let mut correction = 0.0;
        if let (Some(p), Some(bias)) = (&pitch, gyro_bias) {
            let rate = p(i) - bias;
            // Mid-sample elevation change (rad).
            let angle = (tilt.value() + 0.5 * rate) * plan.dt;
            correction = gravity_cos * angle - 0.5 * gravity_sin * angle * angle;
            tilt.add(rate);
        }
        velocity.add(a - bias + correction);
    }
    let cue_speed = velocity.value() * plan.dt;
    if !cuesight::math::is_finite(cue_speed) {
        return Err(StrokeError::NotFinite {
            index: saturated_u32(onset),
        });
    }
    if cue_speed <= 0.0 {
        return Err(StrokeError::NotForward { speed: cue_speed });
    }
    Ok(StrokeEstimate {
        cue_speed,
        impact_index: onset,
        rest_start,
        rest_end,
        bias,
        rest_noise,
        stroke_duration: (onset - rest_end) as f32 * plan.dt,
        tilt_at_impact: tilt.value() * plan.dt,
    })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::vec;
    use std::vec::Vec;

    use super::*;

    const FS: f32 = 6667.0;

    /// Piecewise-constant acceleration: rest at `level`, then `accel` for `push` samples,
    /// then coast, then a −40 g spike. Exact answer: accel · push / FS.
    fn step_stroke(level: f32, accel: f32, push: usize) -> Vec<f32> {
        let mut s = vec![level; 2000];
        s.extend(core::iter::repeat_n(level + accel, push));
        s.extend(core::iter::repeat_n(level, 300));
        s.extend(core::iter::repeat_n(level - 40.0 * STANDARD_GRAVITY, 6));
        s.extend(core::iter::repeat_n(level, 200));
        s
    }

    #[test]
    fn noise_free_step_is_exact() {
        let s = step_stroke(1.3, 20.0, 1000);
        let est = estimate(&s, &StrokeConfig::new(FS)).unwrap();
        let expected = 20.0 * 1000.0 / FS;
        assert!(
            (est.cue_speed - expected).abs() < 1e-4 * expected,
            "{} vs {expected}",
            est.cue_speed
        );
        assert!((est.bias - 1.3).abs() < 1e-6);
        assert_eq!(est.impact_index, 2000 + 1000 + 300);
        assert_eq!(est.rest_start, 0);
        // The first 16-sample window holding the step (sample 2000) starts at 1985; the
        // rest ends 10 ms (67 samples) before that.
        assert_eq!(est.rest_end, 1985 - 67);
    }

    #[test]
    fn raw_words_give_the_same_answer() {
        let s = step_stroke(0.0, 20.0, 1000);
        let scale = crate::ACCEL_MPS2_PER_LSB;
        let raw: Vec<i16> = s
            .iter()
            .map(|&a| (a / scale).round().clamp(-32768.0, 32767.0) as i16)
            .collect();
        let cfg = StrokeConfig::new(FS);
        let a = estimate(&s, &cfg).unwrap().cue_speed;
        let b = estimate_raw(&raw, scale, &cfg).unwrap().cue_speed;
        assert!((a - b).abs() < 2e-3 * a, "{a} vs {b}");
        assert_eq!(
            estimate_raw(&raw, f32::NAN, &cfg),
            Err(StrokeError::NotFinite { index: 0 })
        );
    }

    #[test]
    fn empty_and_short_inputs_are_refused() {
        let cfg = StrokeConfig::new(FS);
        assert!(matches!(
            estimate(&[], &cfg),
            Err(StrokeError::TooShort { len: 0, .. })
        ));
        assert!(matches!(
            estimate(&[0.0; 500], &cfg),
            Err(StrokeError::TooShort { len: 500, .. })
        ));
    }

    #[test]
    fn no_spike_means_no_impact() {
        let mut s = step_stroke(0.5, 20.0, 1000);
        s.truncate(2000 + 1000 + 300);
        assert_eq!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::NoImpact)
        );
        // Rest only.
        assert_eq!(
            estimate(&[0.2; 5000], &StrokeConfig::new(FS)),
            Err(StrokeError::NoImpact)
        );
    }

    #[test]
    fn moving_from_the_start_is_not_at_rest() {
        // A 3 Hz swing of ±5 m/s² throughout, then a spike.
        let mut s: Vec<f32> = (0..6000)
            .map(|i| 5.0 * (2.0 * core::f32::consts::PI * 3.0 * i as f32 / FS).sin())
            .collect();
        s.extend(core::iter::repeat_n(-50.0 * STANDARD_GRAVITY, 5));
        assert_eq!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::NotAtRest)
        );
    }

    #[test]
    fn a_knock_before_the_rest_is_skipped() {
        let mut s = vec![-30.0 * STANDARD_GRAVITY; 4];
        s.extend(step_stroke(0.0, 10.0, 800));
        let est = estimate(&s, &StrokeConfig::new(FS)).unwrap();
        let expected = 10.0 * 800.0 / FS;
        assert!((est.cue_speed - expected).abs() < 1e-4 * expected);
        assert!(est.rest_start > 4);
    }

    #[test]
    fn the_longest_rest_wins() {
        // 0.2 s at a constant 0.5 m/s² (a move's acceleration plateau: still and level,
        // but not at rest), then 0.4 s of true rest, then the stroke.
        let mut s = vec![0.5f32; 1333];
        s.extend(core::iter::repeat_n(0.0, 667));
        s.extend(step_stroke(0.0, 10.0, 800));
        let est = estimate(&s, &StrokeConfig::new(FS)).unwrap();
        let expected = 10.0 * 800.0 / FS;
        assert!(est.rest_start > 1333, "{est:?}");
        assert!(
            (est.cue_speed - expected).abs() < 1e-4 * expected,
            "{} vs {expected}",
            est.cue_speed
        );
    }

    #[test]
    fn non_finite_samples_are_located() {
        let mut s = step_stroke(0.0, 10.0, 800);
        s[1234] = f32::NAN;
        assert_eq!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::NotFinite { index: 1234 })
        );
        s[1234] = f32::NEG_INFINITY;
        assert_eq!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::NotFinite { index: 1234 })
        );
    }

    #[test]
    fn backward_only_motion_is_not_forward() {
        let s = step_stroke(0.0, -10.0, 800);
        assert!(matches!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::NotForward { .. })
        ));
    }

    #[test]
    fn saturated_stroke_is_refused() {
        let s = step_stroke(0.0, 16.0 * STANDARD_GRAVITY, 100);
        assert!(matches!(
            estimate(&s, &StrokeConfig::new(FS)),
            Err(StrokeError::Saturated { index: 2000 })
        ));
    }

    #[test]
    fn bad_configs_are_named() {
        let s = step_stroke(0.0, 10.0, 800);
        let base = StrokeConfig::new(FS);
        let cases = [
            (StrokeConfig::new(f32::NAN), ConfigField::SampleRate),
            (StrokeConfig::new(100.0), ConfigField::SampleRate),
            (
                StrokeConfig {
                    impact_threshold: -1.0,
                    ..base
                },
                ConfigField::ImpactThreshold,
            ),
            (
                StrokeConfig {
                    min_rest: 0.0,
                    ..base
                },
                ConfigField::MinRest,
            ),
            (
                StrokeConfig {
                    full_scale: 50.0,
                    ..base
                },
                ConfigField::FullScale,
            ),
            (
                StrokeConfig {
                    motion_floor: f32::INFINITY,
                    ..base
                },
                ConfigField::MotionFloor,
            ),
        ];
        for (cfg, field) in cases {
            assert_eq!(estimate(&s, &cfg), Err(StrokeError::InvalidConfig(field)));
        }
    }

    /// Step stroke on a cue whose elevation rises at 0.2 rad/s while it is pushed:
    /// specific force `b + a − g sin(θ₀ + Δθ)`, samples at mid-interval. Returns the
    /// acceleration and pitch-rate series.
    fn tilting_stroke() -> (Vec<f32>, Vec<f32>) {
        let (theta0, bias, g) = (0.1f64, 0.3f64, f64::from(STANDARD_GRAVITY));
        let dt = 1.0 / f64::from(FS);
        let (mut accel, mut pitch) = (Vec::new(), Vec::new());
        let mut theta = theta0;
        let phases: [(usize, f64, f64); 4] = [
            (2000, 0.0, 0.0),  // rest
            (1000, 10.0, 0.2), // push, tilting
            (300, 0.0, 0.0),   // coast, tilted
            (6, -400.0, 0.0),  // impact
        ];
        for (count, a, rate) in phases {
            for _ in 0..count {
                let mid = theta + 0.5 * rate * dt;
                accel.push((bias + a - g * mid.sin()) as f32);
                pitch.push(rate as f32 + 0.01); // with a 0.01 rad/s gyro bias
                theta += rate * dt;
            }
        }
        (accel, pitch)
    }

    #[test]
    fn pitch_rate_removes_the_tilt_error() {
        let (accel, pitch) = tilting_stroke();
        let cfg = StrokeConfig::new(FS);
        let truth = 10.0 * 1000.0 / f64::from(FS);
        let plain = f64::from(estimate(&accel, &cfg).unwrap().cue_speed);
        // First-order prediction of the accelerometer-only error, worked by hand:
        // −g cos θ₀ (Δθ_max · T_push / 2 + Δθ_max · T_coast), Δθ_max = 0.2 · 0.15 rad.
        let g_cos = 9.80665 * 0.1f64.cos();
        let (t_push, t_coast) = (1000.0 / 6667.0, 300.0 / 6667.0);
        let predicted = -g_cos * 0.2 * t_push * (t_push / 2.0 + t_coast);
        assert!(
            ((plain - truth) - predicted).abs() < 0.05 * predicted.abs(),
            "accel-only error {} vs predicted {predicted}",
            plain - truth
        );
        let aided = estimate_with_pitch(&accel, &pitch, &cfg).unwrap();
        let err = f64::from(aided.cue_speed) - truth;
        assert!(err.abs() < 1e-3 * truth, "gyro-aided error {err}");
        assert!((f64::from(aided.tilt_at_impact) - 0.03).abs() < 1e-4);
    }

    #[test]
    fn pitch_series_is_checked() {
        let (accel, mut pitch) = tilting_stroke();
        let cfg = StrokeConfig::new(FS);
        assert_eq!(
            estimate_with_pitch(&accel, &pitch[1..], &cfg),
            Err(StrokeError::LengthMismatch {
                accel: accel.len() as u32,
                pitch: accel.len() as u32 - 1
            })
        );
        pitch[77] = f32::INFINITY;
        assert_eq!(
            estimate_with_pitch(&accel, &pitch, &cfg),
            Err(StrokeError::NotFinite { index: 77 })
        );
        let raw = [0i16; 4000];
        assert_eq!(
            estimate_raw_with_pitch(&raw, 1.0, &raw[..10], 1.0, &cfg),
            Err(StrokeError::LengthMismatch {
                accel: 4000,
                pitch: 10
            })
        );
        assert_eq!(
            estimate_raw_with_pitch(&raw, 1.0, &raw, 0.0, &cfg),
            Err(StrokeError::NotFinite { index: 0 })
        );
    }

    #[test]
    fn estimate_feeds_the_strike_model() {
        let s = step_stroke(0.0, 12.0, 1111);
        let est = estimate(&s, &StrokeConfig::new(FS)).unwrap();
        let hit = est
            .strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE)
            .unwrap();
        // (1 + 0.75) V / (1 + 0.17/0.54), V = 12 · 1111 / 6667.
        let v = 12.0 * 1111.0 / 6667.0 * 1.75 / (1.0 + 0.17 / 0.54);
        assert!((hit.speed - v).abs() < 1e-3 * v);
        let too_far = TipOffset::new(0.02, 0.0).unwrap();
        assert!(matches!(
            est.strike(&Params::POOL, &Cue::TYPICAL, too_far),
            Err(StrokeError::Strike(_))
        ));
    }
}
