//! Seeded synthetic strokes as raw accelerometer words, for the `stroke` request in the
//! end-to-end test and the demo session.
//!
//! Kinematics along the cue axis (forward positive): still at address, a half-cosine
//! backswing of 12 cm, a short pause (under the estimator's 150 ms rest), a half-cosine
//! forward stroke whose speed peaks at the tip impact, a 1.5 ms impact at −50 g
//! (clipped at the ±16 g full scale), then a follow-through. The specific force adds
//! gravity along a cue raised 5° and a 20 mg offset, plus 8 mg RMS white noise; words
//! are rounded at the LSM6DSOX ±16 g scale. (The sensors crate's own tests use a richer
//! model with bias drift and tilt; this one only has to be a plausible input.)

use cuesight_link::{Request, StrokeChunk, StrokeSetup, MAX_SAMPLES};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Standard gravity (m/s²).
const G: f64 = 9.806_65;

/// A synthetic stroke.
#[derive(Clone, Debug)]
pub struct SyntheticStroke {
    /// Sample rate (Hz).
    pub rate_hz: f32,
    /// Raw words of the cue-axis accelerometer, oldest first.
    pub samples: Vec<i16>,
    /// The cue speed at the impact that generated them (m/s).
    pub cue_speed: f64,
}

/// A stroke reaching `cue_speed` (m/s) at the impact, sampled at `rate_hz`: 1.33 s of
/// motion (0.4 s of rest first).
pub fn synthetic_stroke(seed: u64, rate_hz: f64, cue_speed: f64) -> SyntheticStroke {
    synthetic_stroke_of(seed, rate_hz, cue_speed, None)
}

/// [`synthetic_stroke`] with exactly `count` samples when given: the follow-through is
/// cut or lengthened (the cue stops 0.2 s after the impact and stays still), so the
/// window can be filled to its last sample.
pub fn synthetic_stroke_of(
    seed: u64,
    rate_hz: f64,
    cue_speed: f64,
    count: Option<usize>,
) -> SyntheticStroke {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scale = f64::from(cuesight_sensors::ACCEL_MPS2_PER_LSB);
    let (rest, back, pause, forward) = (0.4, 0.45, 0.12, 0.3);
    let backswing = 0.12; // m
    let (impact, follow, stop) = (0.0015, 0.06, 0.2);
    let total = rest + back + pause + forward + impact + follow;
    let bias = G * 5f64.to_radians().sin() + 0.02 * G;
    let count = count.unwrap_or((total * rate_hz).round() as usize);
    let pi = std::f64::consts::PI;
    let samples = (0..count)
        .map(|i| {
            let t = i as f64 / rate_hz;
            let hit = rest + back + pause + forward;
            let a = if t < rest {
                0.0
            } else if t < rest + back {
                let u = t - rest;
                -backswing * pi * pi / (2.0 * back * back) * (pi * u / back).cos()
            } else if t < rest + back + pause {
                0.0
            } else if t < hit {
                let u = t - rest - back - pause;
                cue_speed * pi / (2.0 * forward) * (pi * u / forward).sin()
            } else if t < hit + impact {
                -50.0 * G
            } else if t < hit + impact + stop {
                -cue_speed / stop
            } else {
                0.0
            };
            // Box–Muller: 8 mg RMS.
            let (u1, u2): (f64, f64) = (rng.random_range(1e-12..1.0), rng.random());
            let noise = 0.008 * G * (-2.0 * u1.ln()).sqrt() * (2.0 * pi * u2).cos();
            ((a + bias + noise) / scale)
                .round()
                .clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
        })
        .collect();
    SyntheticStroke {
        rate_hz: rate_hz as f32,
        samples,
        cue_speed,
    }
}

/// The chunks that upload `stroke` as stroke `id`, at most `chunk` samples each (and at
/// most [`MAX_SAMPLES`]); the last carries the setup (the rate, defaults for the rest).
pub fn stroke_chunks(stroke: &SyntheticStroke, id: u16, chunk: usize) -> Vec<StrokeChunk> {
    let parts: Vec<&[i16]> = stroke.samples.chunks(chunk.clamp(1, MAX_SAMPLES)).collect();
    let count = parts.len() as u16;
    parts
        .iter()
        .enumerate()
        .map(|(i, part)| {
            let mut samples = heapless::Vec::new();
            for &word in part.iter() {
                // At most MAX_SAMPLES by the clamp above.
                let _ = samples.push(word);
            }
            StrokeChunk {
                stroke: id,
                index: i as u16,
                count,
                samples,
                setup: (i + 1 == parts.len()).then_some(StrokeSetup {
                    rate_hz: stroke.rate_hz,
                    ..StrokeSetup::default()
                }),
            }
        })
        .collect()
}

/// [`stroke_chunks`] of stroke 1, as `stroke` requests.
pub fn stroke_requests(stroke: &SyntheticStroke, chunk: usize) -> Vec<Request> {
    stroke_chunks(stroke, 1, chunk)
        .into_iter()
        .map(Request::Stroke)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimator_recovers_the_speed() {
        for (seed, rate, speed) in [(1, 6667.0, 2.0), (2, 3333.0, 4.0), (3, 1000.0, 1.0)] {
            let stroke = synthetic_stroke(seed, rate, speed);
            let scale = cuesight_sensors::ACCEL_MPS2_PER_LSB;
            let mut config = cuesight_sensors::StrokeConfig::new(stroke.rate_hz);
            config.full_scale = 32768.0 * scale;
            let estimate = cuesight_sensors::estimate_raw(&stroke.samples, scale, &config).unwrap();
            let error = (f64::from(estimate.cue_speed) - speed).abs() / speed;
            assert!(error < 0.03, "{rate} Hz, {speed} m/s: {estimate:?}");
        }
    }

    #[test]
    fn a_full_window_is_forty_chunks_and_estimates() {
        let stroke = synthetic_stroke_of(7, 3333.0, 2.5, Some(cuesight_link::STROKE_CAPACITY));
        assert_eq!(stroke.samples.len(), 5_000);
        let chunks = stroke_chunks(&stroke, 9, 125);
        assert_eq!(chunks.len(), 40);
        for (i, chunk) in chunks.iter().enumerate() {
            assert_eq!((chunk.stroke, chunk.index, chunk.count), (9, i as u16, 40));
            assert_eq!(chunk.samples.len(), 125);
            assert_eq!(chunk.setup.is_some(), i == 39);
        }
        let scale = cuesight_sensors::ACCEL_MPS2_PER_LSB;
        let mut config = cuesight_sensors::StrokeConfig::new(stroke.rate_hz);
        config.full_scale = 32768.0 * scale;
        let estimate = cuesight_sensors::estimate_raw(&stroke.samples, scale, &config).unwrap();
        assert!(
            (f64::from(estimate.cue_speed) - 2.5).abs() < 0.075,
            "{estimate:?}"
        );
    }
}
