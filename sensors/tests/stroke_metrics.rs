//! The streaming estimator's stroke metrics (backswing length, time back, pause at the
//! back, forward time, tempo; `docs/sensors.md` §11) against the kinematic model's own
//! motion (`tests/common/kinematic.rs`): nothing expected here comes from the code under
//! test.
//!
//!     cargo test -p cuesight-sensors --release --test stroke_metrics -- --nocapture
//!
//! Truth per stroke, from the model's cue velocity `v(t)` and its phase times:
//! * backswing length: the backswing's distance (the model holds it through the pause);
//! * pause: the span around the model's pause at the back where `|v| < 0.02 m/s` (the
//!   metric's threshold), found on a 10 µs grid;
//! * time back: from the backswing start the estimator reports (an index: the metric is
//!   defined from it; it is checked against the model's start of motion on its own) to
//!   that span's start;
//! * forward time: from that span's end to the model's contact instant.

#[path = "common/kinematic.rs"]
mod kinematic;

use cuesight_sensors::{StreamConfig, StreamEvent, StreamStroke, StreamingEstimator};
use kinematic::{Stroke, Truth};

const FS: f64 = 6667.0;

/// The metrics' pause threshold (m/s), `REST_SPEED` of `sensors/src/streaming/integral.rs`.
const SLOW: f64 = 0.02;

/// The model's slow span at the back: `[start, end]` (s, the stroke's own clock).
fn slow_span(stroke: &Stroke) -> (f64, f64) {
    let [_, _, back_end, forward_start, _] = stroke.times();
    let step = 1e-5;
    let mut start = back_end;
    while stroke.velocity(start - step).abs() < SLOW {
        start -= step;
    }
    let mut end = forward_start;
    while stroke.velocity(end).abs() < SLOW {
        end += step;
    }
    (start, end)
}

#[derive(Default)]
struct Worst {
    /// The reported backswing start against the model's start of motion.
    start_s: f64,
    length_m: f64,
    back_s: f64,
    pause_s: f64,
    forward_s: f64,
    tempo: f64,
    count: usize,
    /// The stroke of the worst backswing length: its backswing (m), pause (s) and noise
    /// (mg RMS).
    length_stroke: (f64, f64, f64),
}

impl Worst {
    fn add(&mut self, s: &StreamStroke, t: &Truth, noise_mg: f64) {
        let stroke = &t.stroke;
        // The stroke's clock starts at stream sample `offset`.
        let offset = (t.contact - stroke.contact_sample(FS)) as f64 / FS;
        let (start, end) = slow_span(stroke);
        let rest_end = s.backswing_start as f64 / FS - offset;
        let contact = stroke.times()[4];
        let (back, forward) = (start - rest_end, contact - end);
        let length = f64::from(s.backswing_length) - stroke.back.0;
        let [_, back_start, ..] = stroke.times();
        self.start_s = self.start_s.max((rest_end - back_start).abs());
        let errors = [
            f64::from(s.backswing_time) - back,
            f64::from(s.pause) - (end - start),
            f64::from(s.forward_time) - forward,
        ];
        let tempo = f64::from(s.tempo().unwrap_or(f32::NAN)) / (back / forward) - 1.0;
        if length.abs() > self.length_m {
            self.length_stroke = (stroke.back.0, stroke.pause, noise_mg);
        }
        self.length_m = self.length_m.max(length.abs());
        self.back_s = self.back_s.max(errors[0].abs());
        self.pause_s = self.pause_s.max(errors[1].abs());
        self.forward_s = self.forward_s.max(errors[2].abs());
        // NaN (no tempo) is kept: `max` would drop it.
        self.tempo = if tempo.is_nan() {
            tempo
        } else {
            self.tempo.max(tempo.abs())
        };
        self.count += 1;
    }
}

/// The streaming acceptance set (120 strokes in 12 streams, 3 and 8 mg, the gyro on):
/// the backswing's start within 20 ms of the model's start of motion (the rest ends
/// 10 ms before the motion test fires), backswing length within 5 mm, time back, pause and forward time within 10 ms (two
/// orders finer than the tenths of a second and centimetres a coach reads), tempo within
/// 2 %.
#[test]
fn metrics_match_the_models_motion() {
    let mut worst = Worst::default();
    for stream in kinematic::acceptance_streams(FS) {
        let mut est = StreamingEstimator::new(&StreamConfig::new(FS as f32)).unwrap();
        let found: Vec<StreamStroke> = stream
            .accel
            .iter()
            .zip(&stream.pitch)
            .filter_map(|(&a, &p)| match est.push_raw(a, Some(p)) {
                Some(StreamEvent::Stroke(s)) => Some(s),
                _ => None,
            })
            .collect();
        assert_eq!(found.len(), stream.truth.len());
        for (s, t) in found.iter().zip(&stream.truth) {
            worst.add(s, t, stream.noise_mg);
        }
    }
    println!(
        "stroke metrics over {} strokes, worst: backswing start {:.1} ms from the model's, \
         backswing length {:.2} mm, time back {:.2} ms, pause {:.2} ms, forward time {:.2} ms, \
         tempo {:.3} %",
        worst.count,
        1e3 * worst.start_s,
        1e3 * worst.length_m,
        1e3 * worst.back_s,
        1e3 * worst.pause_s,
        1e3 * worst.forward_s,
        1e2 * worst.tempo
    );
    let (back, pause, noise) = worst.length_stroke;
    println!(
        "  worst backswing length: a {:.0} mm backswing, {pause:.2} s pause, {noise} mg",
        1e3 * back
    );
    for (key, value) in [
        (
            "sensors-metrics-start-ms",
            format!("{:.1}", 1e3 * worst.start_s),
        ),
        (
            "sensors-metrics-length-mm",
            format!("{:.2}", 1e3 * worst.length_m),
        ),
        (
            "sensors-metrics-length-backswing-mm",
            format!("{:.0}", 1e3 * back),
        ),
        ("sensors-metrics-length-pause-s", format!("{pause:.2}")),
        ("sensors-metrics-length-noise-mg", format!("{noise}")),
        (
            "sensors-metrics-back-ms",
            format!("{:.2}", 1e3 * worst.back_s),
        ),
        (
            "sensors-metrics-pause-ms",
            format!("{:.2}", 1e3 * worst.pause_s),
        ),
        (
            "sensors-metrics-forward-ms",
            format!("{:.2}", 1e3 * worst.forward_s),
        ),
        (
            "sensors-metrics-tempo-pct",
            format!("{:.3}", 1e2 * worst.tempo),
        ),
    ] {
        cuesight_figures::record!(key, "{value}");
    }
    assert_eq!(worst.count, 120);
    assert!(worst.start_s <= 0.020, "{} s", worst.start_s);
    assert!(worst.length_m <= 0.005, "{} m", worst.length_m);
    assert!(worst.back_s <= 0.010, "{} s", worst.back_s);
    assert!(worst.pause_s <= 0.010, "{} s", worst.pause_s);
    assert!(worst.forward_s <= 0.010, "{} s", worst.forward_s);
    assert!(worst.tempo <= 0.02, "{}", worst.tempo);
}
