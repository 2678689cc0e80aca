//! Shared by the sensors crate's reliability suites (`extremes`, `validation`,
//! `properties`): piecewise-constant strokes with their exact speed, f32 neighbours, the
//! checks every `Ok` estimate must pass, and the fixed proptest configuration.
#![allow(dead_code)]

// Not every test target that includes this module formats figures.
#[allow(unused_imports)]
pub use cuesight_figures::{signed, thousands};
use cuesight_sensors::lsm6dsox::STANDARD_GRAVITY;
use cuesight_sensors::{StrokeConfig, StrokeEstimate};

/// f32 unit roundoff, 2⁻²⁴.
pub const EPS32: f64 = 5.960_464_477_539_063e-8;

/// Standard gravity in f64 (m/s²).
pub const G: f64 = 9.806_65;

/// The LSM6DSOX's nominal 6.66 kHz ODR.
pub const FS: f32 = 6667.0;

/// The next f32 towards +∞ (`f32::next_up` is newer than the crate's MSRV).
pub fn next_up(x: f32) -> f32 {
    if x.is_nan() || x == f32::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f32::from_bits(1);
    }
    let bits = x.to_bits();
    f32::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next f32 towards −∞.
pub fn next_down(x: f32) -> f32 {
    -next_up(-x)
}

/// A piecewise-constant stroke: `rest` samples at `level`, then each `(a, count)`
/// segment at `level + a`, `coast` samples at `level`, six samples of a −40 g tip impact
/// below `level`, then 20 samples at `level`.
#[derive(Clone, Debug)]
pub struct Piecewise {
    pub samples: Vec<f32>,
    /// Index of the first impact sample.
    pub impact: usize,
    /// End of the rest (first stroke sample).
    pub rest_end: usize,
    /// `Σ (s_i − level) / rate` over the stroke samples as stored in f32, in f64: the
    /// speed the estimator's step 5 integrates, from first principles (`v = 0` at rest).
    pub speed: f64,
}

pub fn piecewise(
    rate: f32,
    level: f32,
    rest: usize,
    segments: &[(f32, usize)],
    coast: usize,
) -> Piecewise {
    let mut samples = vec![level; rest];
    let mut speed = 0.0f64;
    for &(a, count) in segments {
        let s = level + a;
        speed += (f64::from(s) - f64::from(level)) * count as f64 / f64::from(rate);
        samples.extend(std::iter::repeat_n(s, count));
    }
    samples.extend(std::iter::repeat_n(level, coast));
    let impact = samples.len();
    samples.extend(std::iter::repeat_n(level - 40.0 * STANDARD_GRAVITY, 6));
    samples.extend(std::iter::repeat_n(level, 20));
    Piecewise {
        samples,
        impact,
        rest_end: rest,
        speed,
    }
}

/// `rest` = 0.3 s, one push of `a` m/s² for `push` samples, 45 ms of coasting (300
/// samples at 6667 Hz; the coast must stay shorter than the rest, or it would be the
/// longest still stretch and taken for the rest).
pub fn step(rate: f32, level: f32, a: f32, push: usize) -> Piecewise {
    let coast = ((0.045 * rate) as usize).max(12);
    piecewise(rate, level, (0.3 * rate) as usize, &[(a, push)], coast)
}

/// Raw words `round(s / scale)`, clamped to the i16 range (as the part clips).
pub fn to_raw(samples: &[f32], scale: f32) -> Vec<i16> {
    samples
        .iter()
        .map(|&a| {
            (f64::from(a) / f64::from(scale))
                .round()
                .clamp(-32768.0, 32767.0) as i16
        })
        .collect()
}

/// What every `Ok` estimate of a window of `n` samples must satisfy (the documented
/// contract): every field finite, a forward speed, `rest_start < rest_end ≤
/// impact_index < n`, the duration `(impact_index − rest_end) / rate`, noise ≥ 0, no tilt
/// from the accelerometer-only estimators.
pub fn check_estimate(
    e: &StrokeEstimate,
    n: usize,
    rate: f32,
    with_pitch: bool,
) -> Result<(), String> {
    let numbers = [
        e.cue_speed,
        e.bias,
        e.rest_noise,
        e.stroke_duration,
        e.tilt_at_impact,
    ];
    if numbers.iter().any(|x| !x.is_finite()) {
        return Err(format!("non-finite output: {e:?}"));
    }
    if e.cue_speed <= 0.0 {
        return Err(format!("Ok with a speed that is not forward: {e:?}"));
    }
    if !(e.rest_start < e.rest_end && e.rest_end <= e.impact_index && e.impact_index < n) {
        return Err(format!("indices out of order (n = {n}): {e:?}"));
    }
    if e.rest_noise < 0.0 {
        return Err(format!("negative noise: {e:?}"));
    }
    let duration = (e.impact_index - e.rest_end) as f64 / f64::from(rate);
    if (f64::from(e.stroke_duration) - duration).abs() > 4.0 * EPS32 * duration {
        return Err(format!("duration {duration} s expected: {e:?}"));
    }
    if !with_pitch && e.tilt_at_impact != 0.0 {
        return Err(format!("tilt without a pitch series: {e:?}"));
    }
    Ok(())
}

/// Step 5 recomputed in f64 from the estimate's own rest end, impact index and bias:
/// `Σ (a_i − bias) / rate` over `[rest_end, impact_index)`, and the rounding bound of
/// the estimator's f32 evaluation, `8ε Σ (|a_i| + |bias|) / rate + 4ε |V|` (each
/// difference rounds once, the compensated sum adds a few ulps of its result).
pub fn step5(samples: &[f32], e: &StrokeEstimate, rate: f32) -> (f64, f64) {
    let bias = f64::from(e.bias);
    let dt = 1.0 / f64::from(rate);
    let (mut v, mut scale) = (0.0f64, 0.0f64);
    for &a in &samples[e.rest_end..e.impact_index] {
        v += (f64::from(a) - bias) * dt;
        scale += (f64::from(a).abs() + bias.abs()) * dt;
    }
    (v, 8.0 * EPS32 * scale + 4.0 * EPS32 * v.abs())
}

/// A configuration with every acceleration setting multiplied by `factor`.
pub fn scaled(config: &StrokeConfig, factor: f32) -> StrokeConfig {
    StrokeConfig {
        impact_threshold: config.impact_threshold * factor,
        onset_drop: config.onset_drop * factor,
        rest_noise_limit: config.rest_noise_limit * factor,
        rest_level_tolerance: config.rest_level_tolerance * factor,
        motion_floor: config.motion_floor * factor,
        full_scale: config.full_scale * factor,
        ..*config
    }
}

/// Fixed proptest configuration: XorShift with a fixed seed (CI is deterministic;
/// `PROPTEST_RNG_SEED` / `PROPTEST_CASES` override), failures persisted next to the
/// test source (`<test>.proptest-regressions`).
pub fn config(cases: u32, seed: u64) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, FileFailurePersistence, RngAlgorithm, RngSeed};
    Config {
        cases,
        rng_algorithm: RngAlgorithm::XorShift,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        max_shrink_iters: 4096,
        ..Config::default()
    }
}
