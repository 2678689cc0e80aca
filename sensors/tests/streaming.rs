//! The streaming estimator (`sensors/src/streaming/`) against the kinematic model's truth
//! and against the windowed estimator on the same strokes.
//!
//! Figures (printed; seeded, so they repeat exactly):
//!
//!     cargo test -p cuesight-sensors --release --test streaming -- --nocapture --test-threads 1
//!
//! Truth is the model's (`tests/common/kinematic.rs`, a draw-for-draw copy of
//! `tests/synthetic_strokes.rs`): the cue speed at contact and the first sample whose
//! period holds the contact's start. Nothing expected here comes from the code under
//! test.

mod common;
#[path = "common/kinematic.rs"]
mod kinematic;

use cuesight_sensors::lsm6dsox::{ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB, STANDARD_GRAVITY};
use cuesight_sensors::{
    estimate_raw, estimate_raw_with_pitch, ConfigField, ImpactTrigger, RingBuffer, StreamConfig,
    StreamConfigError, StreamEvent, StreamFault, StreamStroke, StreamingEstimator, StrokeConfig,
};
use kinematic::Stroke;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const FS: f64 = 6667.0;

fn estimator(fs: f64) -> StreamingEstimator {
    StreamingEstimator::new(&StreamConfig::new(fs as f32)).unwrap()
}

/// Every event of a stream of raw words, with the `finish` report last (if any).
fn events(est: &mut StreamingEstimator, accel: &[i16], pitch: Option<&[i16]>) -> Vec<StreamEvent> {
    let mut out = Vec::new();
    for (i, &a) in accel.iter().enumerate() {
        let p = pitch.map(|p| p[i]);
        out.extend(est.push_raw(a, p));
    }
    out
}

fn strokes_of(events: &[StreamEvent]) -> Vec<StreamStroke> {
    events
        .iter()
        .filter_map(|e| match e {
            StreamEvent::Stroke(s) => Some(*s),
            StreamEvent::Fault(_) => None,
        })
        .collect()
}

/// The windowed estimator through the capture path of `tests/synthetic_strokes.rs`
/// (24,000-word ring, 8 g trigger, 50 ms after it): cue speed and the impact index in
/// the stream.
fn windowed(accel: &[i16], pitch: &[i16], fs: f64, aided: bool) -> Option<(f32, usize)> {
    const RING: usize = 24_000;
    let mut ring = Box::new(RingBuffer::<i16, RING>::new(0));
    let mut pitch_ring = Box::new(RingBuffer::<i16, RING>::new(0));
    let mut trigger = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, (0.05 * fs) as usize).unwrap();
    let mut pushed = 0;
    for (&word, &rate) in accel.iter().zip(pitch) {
        pushed += 1;
        ring.push(word);
        pitch_ring.push(rate);
        if trigger.push(f32::from(word) * ACCEL_MPS2_PER_LSB) {
            break;
        }
    }
    let config = StrokeConfig::new(fs as f32);
    let result = if aided {
        estimate_raw_with_pitch(
            ring.make_contiguous(),
            ACCEL_MPS2_PER_LSB,
            pitch_ring.make_contiguous(),
            GYRO_RADPS_PER_LSB,
            &config,
        )
    } else {
        estimate_raw(ring.make_contiguous(), ACCEL_MPS2_PER_LSB, &config)
    };
    result
        .ok()
        .map(|e| (e.cue_speed, e.impact_index + pushed - ring.len()))
}

#[derive(Default)]
struct Errors {
    count: usize,
    max: f64,
    sum: f64,
    failures: usize,
}

impl Errors {
    fn add(&mut self, rel: f64) {
        self.count += 1;
        self.max = self.max.max(rel.abs());
        self.sum += rel.abs();
    }
    fn mean(&self) -> f64 {
        self.sum / self.count.max(1) as f64
    }
    fn line(&self) -> String {
        format!(
            "max {:.3} %, mean {:.4} % ({} strokes, {} failed)",
            100.0 * self.max,
            100.0 * self.mean(),
            self.count,
            self.failures
        )
    }
}

/// One of `synthetic_strokes.rs`'s sets (same seed, same draws): the streaming estimator
/// and the windowed one on each stroke. Returns (streaming, windowed) errors and the
/// largest impact-index distance from the truth (streaming).
fn compare_set(
    noise_mg: f64,
    seed: u64,
    tilt_deg: Option<(f64, f64)>,
    aided: bool,
) -> (Errors, Errors, usize) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = noise_mg * 1e-3 * kinematic::G;
    let (mut stream, mut window) = (Errors::default(), Errors::default());
    let mut worst_index = 0;
    for _ in 0..250 {
        let mut stroke = Stroke::random(&mut rng);
        if let Some((lo, hi)) = tilt_deg {
            stroke.tilt_back = rng.random_range(lo..hi).to_radians();
        }
        let (accel, pitch) = stroke.samples(FS, noise, &mut rng);
        let contact = stroke.contact_sample(FS);
        match windowed(&accel, &pitch, FS, aided) {
            Some((v, _)) => window.add((f64::from(v) - stroke.speed) / stroke.speed),
            None => window.failures += 1,
        }
        let mut est = estimator(FS);
        let events = events(&mut est, &accel, aided.then_some(&pitch[..]));
        let found = strokes_of(&events);
        assert_eq!(
            (found.len(), events.len()),
            (1, 1),
            "one stroke and nothing else expected: {events:?}\n{stroke:?}"
        );
        let s = found[0];
        worst_index =
            worst_index.max((s.impact_index as i64 - contact as i64).unsigned_abs() as usize);
        stream.add((f64::from(s.cue_speed) - stroke.speed) / stroke.speed);
        assert_eq!(est.finish(), None);
    }
    (stream, window, worst_index)
}

/// The streaming estimator is at least as accurate as the windowed one (max and mean
/// |Δv|/v) on every set of `synthetic_strokes.rs`, finds every stroke, nothing else, and
/// the impact within 2 samples.
#[test]
fn at_least_as_accurate_as_the_windowed_estimator() {
    let sets: [(&str, f64, u64, Option<(f64, f64)>, bool); 5] = [
        ("1 mg", 1.0, 0x5EED_0001, None, false),
        ("3 mg", 3.0, 0x5EED_0003, None, false),
        ("8 mg", 8.0, 0x5EED_0008, None, false),
        ("8 mg, gyro-aided, no tilt", 8.0, 0x5EED_0008, None, true),
        (
            "8 mg, pendulum tilt 0.5-2 deg, gyro-aided",
            8.0,
            0x5EED_7117,
            Some((0.5, 2.0)),
            true,
        ),
    ];
    let results: Vec<_> = sets
        .iter()
        .map(|&(label, noise, seed, tilt, aided)| {
            let (stream, window, worst_index) = compare_set(noise, seed, tilt, aided);
            println!(
                "{label}: streaming {}; windowed {}; impact within {worst_index} samples",
                stream.line(),
                window.line()
            );
            (label, stream, window, worst_index)
        })
        .collect();
    for (label, stream, window, worst_index) in results {
        assert_eq!(stream.failures, 0);
        assert!(
            worst_index <= 2,
            "{label}: impact {worst_index} samples off"
        );
        // Both evaluate the same sum in f32 (the windowed one with Kahan sums, this one
        // with exact integer sums): where they pick the same rest, the results may
        // differ by an ulp or two of the speed, so 4 ulps (4 ε relative) are allowed.
        assert!(
            stream.max <= window.max + 4.0 * f64::from(f32::EPSILON),
            "{label}: max {} vs windowed {}",
            stream.max,
            window.max
        );
        assert!(
            stream.mean() <= window.mean(),
            "{label}: mean {} vs windowed {}",
            stream.mean(),
            window.mean()
        );
        assert!(
            stream.max <= 0.01,
            "{label}: max {:.3} %",
            100.0 * stream.max
        );
    }
}
