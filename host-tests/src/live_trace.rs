//! Six-axis IMU traces of continuous stroke sessions for the live cue (issue 15, item 4):
//! the format of `cuesight_sensors::trace`, written from the synthetic-stroke model, with
//! the truth per stroke beside it. `cargo run --release -p cuesight-host --example
//! live_trace -- --help`; the shipped traces and their commands: `firmware/traces/`.
//!
//! # Model
//!
//! The kinematic stroke model lives in the sensors crate's tests
//! (`sensors/tests/common/kinematic.rs`, itself a draw-for-draw copy of
//! `tests/synthetic_strokes.rs`); it is compiled in here from that file (`#[path]`), not
//! copied, so the traces are the streams `sensors/tests/streaming.rs` measures. Per
//! stroke, [`Stroke::random`] (speed 0.5–6 m/s log-uniform, settling move, backswing,
//! forward stroke, tip contact, vibration, follow-through, elevation 2–12°, accelerometer
//! bias ±50 mg, gyro bias ±1 dps), then as the acceptance streams of `streaming.rs` draw
//! them: the address (rest), the pause at the back, the pendulum tilt at the back, the
//! still gap after the follow-through (ranges in [`TraceConfig`]). `kinematic::stream`
//! joins them (one sensor: the first stroke's biases for all; each stroke starts at the
//! elevation the previous one ended at) and gives `ax` (cue axis, gravity `−g sin θ`,
//! bias, noise, clipped at ±16 g) and the pitch rate (`gy`, bias, 0.29 dps RMS noise).
//!
//! Added here, with a second random stream (seed `seed ^ 0x5EED_A1E5`) so that `ax` and
//! `gy` stay exactly the model's draws: `az = g cos θ` + bias + noise (`z` up, in the
//! cue's vertical plane), `ay` = bias + noise, `gx`, `gz` = bias + noise; biases ±50 mg
//! and ±1 dps, noise as the model's. The cue moves along `x` only, so nothing else
//! reaches `y` and `z`.
//!
//! Truth per stroke: the index of its first contact sample (the sample whose period
//! holds the contact's start), the cue speed at that instant (m/s), and the phases.
//! Options put a second contact 20 ms after the first ([`TraceConfig::double_hits`]),
//! or 2 ms at the +16 g rail 40 ms before the contact ([`TraceConfig::saturated`]), as
//! the streaming estimator's bad-input tests do.

use std::io::{self, Write};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

#[path = "../../sensors/tests/common/kinematic.rs"]
mod kinematic;

pub use kinematic::{Stroke, G};

/// Accelerometer and gyroscope LSB (m/s², rad/s) at ±16 g and ±2000 dps.
const ACCEL_LSB: f64 = 0.488e-3 * G;
const GYRO_LSB: f64 = 70e-3 * std::f64::consts::PI / 180.0;

/// What to generate. Ranges are `(low, high)`, drawn uniformly; `low == high` is that
/// value (and draws nothing).
#[derive(Clone, Debug, PartialEq)]
pub struct TraceConfig {
    /// Seed of everything (ChaCha8).
    pub seed: u64,
    /// Strokes in the trace.
    pub strokes: usize,
    /// Output data rate (Hz).
    pub odr_hz: f64,
    /// Accelerometer white noise (mg RMS), all three axes.
    pub noise_mg: f64,
    /// Still at address before the backswing (s).
    pub address_s: (f64, f64),
    /// Pause at the back of the backswing (s).
    pub pause_s: (f64, f64),
    /// Still after each follow-through (s).
    pub gap_s: (f64, f64),
    /// Pendulum tilt gained at the back of the backswing (degrees).
    pub tilt_deg: (f64, f64),
    /// Strokes (0-based) given a second tip contact 20 ms after the first (Δv half the first's).
    pub double_hits: Vec<usize>,
    /// Strokes (0-based) whose `ax` sits at the +16 g rail for 2 ms, 40 ms before contact.
    pub saturated: Vec<usize>,
}

impl Default for TraceConfig {
    /// The acceptance streams of `sensors/tests/streaming.rs`: 3 mg, address 0.25–3 s,
    /// pause 0–1.5 s, gap 0.5–3 s, tilt 0.5–2°, at 6667 Hz; three strokes.
    fn default() -> Self {
        Self {
            seed: 1,
            strokes: 3,
            odr_hz: 6667.0,
            noise_mg: 3.0,
            address_s: (0.25, 3.0),
            pause_s: (0.0, 1.5),
            gap_s: (0.5, 3.0),
            tilt_deg: (0.5, 2.0),
            double_hits: Vec::new(),
            saturated: Vec::new(),
        }
    }
}

impl TraceConfig {
    /// `Err` naming the first field out of its domain.
    pub fn check(&self) -> Result<(), String> {
        let range = |name: &str, (lo, hi): (f64, f64), min: f64| {
            if lo.is_finite() && hi.is_finite() && min <= lo && lo <= hi {
                Ok(())
            } else {
                Err(format!(
                    "{name} = {lo},{hi}: need {min} <= low <= high, finite"
                ))
            }
        };
        if !(self.odr_hz.is_finite() && (500.0..=100_000.0).contains(&self.odr_hz)) {
            return Err(format!("odr = {} Hz: need 500 ..= 100000", self.odr_hz));
        }
        if !(self.noise_mg.is_finite() && (0.0..=100.0).contains(&self.noise_mg)) {
            return Err(format!("noise = {} mg: need 0 ..= 100", self.noise_mg));
        }
        if self.strokes == 0 {
            return Err("strokes = 0: need at least one".into());
        }
        range("address", self.address_s, 0.2)?;
        range("pause", self.pause_s, 0.0)?;
        range("gap", self.gap_s, 0.2)?;
        range("tilt", self.tilt_deg, 0.0)?;
        for (name, list) in [
            ("double-hit", &self.double_hits),
            ("saturate", &self.saturated),
        ] {
            if let Some(i) = list.iter().find(|&&i| i >= self.strokes) {
                return Err(format!("{name} {i}: strokes are 0..{}", self.strokes));
            }
        }
        Ok(())
    }
}

/// The speed below which the cue counts as stopped for the follow-through's time
/// (m/s): the estimator's (`cuesight_sensors::streaming`, `REST_SPEED`).
const FOLLOW_SLOW_MPS: f64 = 0.02;

/// The truth of one stroke.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrokeTruth {
    /// 0-based stroke number.
    pub stroke: usize,
    /// 0-based index of the first contact sample in the trace.
    pub impact_sample: usize,
    /// Cue speed just before the tip contact (m/s).
    pub cue_speed_mps: f64,
    /// First sample of the stroke (its settling move or address).
    pub start_sample: usize,
    /// Still at address (s).
    pub address_s: f64,
    /// Backswing length (m).
    pub backswing_m: f64,
    /// Backswing duration (s).
    pub backswing_s: f64,
    /// Pause at the back (s).
    pub pause_s: f64,
    /// Forward stroke, end of the pause to contact (s).
    pub forward_s: f64,
    /// Cue elevation at address (degrees).
    pub elevation_deg: f64,
    /// Elevation gained at the back of the backswing (degrees).
    pub tilt_back_deg: f64,
    /// Cue speed lost in the contact (m/s).
    pub contact_delta_v_mps: f64,
    /// Follow-through: the cue's travel from the contact until it stops (m), and the
    /// time until it is slower than 0.02 m/s (s), from the model's motion
    /// (`kinematic.rs`, `follow_through_length` / `_time`).
    pub follow_through_m: f64,
    pub follow_through_s: f64,
    /// Index of the second contact's first sample, for a double hit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub second_impact_sample: Option<usize>,
    /// First `ax` sample forced to the rail, for a saturated stroke (2 ms of them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub saturated_from_sample: Option<usize>,
}

/// A generated trace.
#[derive(Clone, Debug)]
pub struct LiveTrace {
    /// The configuration it came from.
    pub config: TraceConfig,
    /// `[ax, ay, az, gx, gy, gz]` raw LSB, one per sample.
    pub samples: Vec<[i16; 6]>,
    /// One per stroke, in time order.
    pub strokes: Vec<StrokeTruth>,
    /// Accelerometer bias of `x`, `y`, `z` (mg).
    pub accel_bias_mg: [f64; 3],
    /// Gyroscope bias of `x`, `y`, `z` (dps).
    pub gyro_bias_dps: [f64; 3],
}

fn draw(rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)) -> f64 {
    if hi > lo {
        rng.random_range(lo..hi)
    } else {
        lo
    }
}

fn word(value: f64, lsb: f64) -> i16 {
    (value / lsb).round().clamp(-32768.0, 32767.0) as i16
}

/// Generate the trace `config` describes (call [`TraceConfig::check`] first: the model
/// panics on out-of-domain values).
pub fn generate(config: &TraceConfig) -> LiveTrace {
    let fs = config.odr_hz;
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
    let strokes: Vec<(Stroke, f64)> = (0..config.strokes)
        .map(|i| {
            let mut stroke = Stroke::random(&mut rng);
            stroke.rest = draw(&mut rng, config.address_s);
            stroke.pause = draw(&mut rng, config.pause_s);
            stroke.tilt_back = draw(&mut rng, config.tilt_deg).to_radians();
            let gap = draw(&mut rng, config.gap_s);
            if config.double_hits.contains(&i) {
                stroke.second_hit = Some((0.020, 0.5 * stroke.delta_v));
            }
            (stroke, gap)
        })
        .collect();
    let noise = config.noise_mg * 1e-3 * G;
    let (mut accel, pitch, truth) = kinematic::stream(&strokes, fs, noise, &mut rng);

    // The other four axes, from their own stream.
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed ^ 0x5EED_A1E5);
    let accel_bias = [
        truth[0].stroke.bias,
        rng.random_range(-0.05..0.05) * G,
        rng.random_range(-0.05..0.05) * G,
    ];
    let gyro_bias = [
        rng.random_range(-1.0f64..1.0).to_radians(),
        truth[0].stroke.gyro_bias,
        rng.random_range(-1.0f64..1.0).to_radians(),
    ];
    let gyro_noise = 0.29f64.to_radians();
    let starts: Vec<usize> = truth
        .iter()
        .map(|t| t.contact - t.stroke.contact_sample(fs))
        .collect();
    let mut strokes_out = Vec::new();
    for (i, t) in truth.iter().enumerate() {
        let s = &t.stroke;
        let start = starts[i];
        let saturated_from = config.saturated.contains(&i).then(|| {
            let at = t.contact - (0.040 * fs) as usize;
            let end = (at + (0.002 * fs).round() as usize).min(accel.len());
            accel[at..end].fill(i16::MAX);
            at
        });
        strokes_out.push(StrokeTruth {
            stroke: i,
            impact_sample: t.contact,
            cue_speed_mps: t.speed,
            start_sample: start,
            address_s: s.rest,
            backswing_m: s.back.0,
            backswing_s: s.back.1,
            pause_s: s.pause,
            forward_s: s.forward.0,
            elevation_deg: s.elevation.to_degrees(),
            tilt_back_deg: s.tilt_back.to_degrees(),
            contact_delta_v_mps: s.delta_v,
            follow_through_m: s.follow_through_length(),
            follow_through_s: s.follow_through_time(FOLLOW_SLOW_MPS),
            second_impact_sample: s
                .second_hit
                .map(|(delay, _)| start + ((s.times()[4] + delay) * fs) as usize),
            saturated_from_sample: saturated_from,
        });
    }
    let samples = (0..accel.len())
        .map(|k| {
            // The stroke this sample belongs to, and its time within it (mid-sample).
            let i = starts.partition_point(|&s| s <= k) - 1;
            let t = (k - starts[i]) as f64 / fs + 0.5 / fs;
            let theta = truth[i].stroke.tilt(t);
            let mut gauss = || kinematic::gaussian(&mut rng);
            let ay = accel_bias[1] + noise * gauss();
            let az = G * theta.cos() + accel_bias[2] + noise * gauss();
            let gx = gyro_bias[0] + gyro_noise * gauss();
            let gz = gyro_bias[2] + gyro_noise * gauss();
            [
                accel[k],
                word(ay, ACCEL_LSB),
                word(az, ACCEL_LSB),
                word(gx, GYRO_LSB),
                pitch[k],
                word(gz, GYRO_LSB),
            ]
        })
        .collect();
    LiveTrace {
        config: config.clone(),
        samples,
        strokes: strokes_out,
        accel_bias_mg: accel_bias.map(|b| b / G * 1e3),
        gyro_bias_dps: gyro_bias.map(f64::to_degrees),
    }
}

/// Write `samples` as a trace: the header, then one line per sample.
pub fn write_csv(samples: &[[i16; 6]], out: &mut impl Write) -> io::Result<()> {
    writeln!(out, "{}", cuesight_sensors::trace::HEADER)?;
    for [ax, ay, az, gx, gy, gz] in samples {
        writeln!(out, "{ax},{ay},{az},{gx},{gy},{gz}")?;
    }
    Ok(())
}

#[derive(Serialize)]
struct TruthFile<'a> {
    trace: &'a str,
    generated_by: &'a str,
    odr_hz: f64,
    samples: usize,
    seed: u64,
    noise_mg: f64,
    accel_bias_mg: [f64; 3],
    gyro_bias_dps: [f64; 3],
    strokes: &'a [StrokeTruth],
}

/// The truth file (JSON) of `trace`, naming the trace file and the command that made it.
pub fn truth_json(trace: &LiveTrace, trace_name: &str, command: &str) -> String {
    let file = TruthFile {
        trace: trace_name,
        generated_by: command,
        odr_hz: trace.config.odr_hz,
        samples: trace.samples.len(),
        seed: trace.config.seed,
        noise_mg: trace.config.noise_mg,
        accel_bias_mg: trace.accel_bias_mg,
        gyro_bias_dps: trace.gyro_bias_dps,
        strokes: &trace.strokes,
    };
    // Plain data: serialisation cannot fail.
    serde_json::to_string_pretty(&file).unwrap_or_default() + "\n"
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight_sensors::trace::parse_trace;
    use cuesight_sensors::{StreamConfig, StreamEvent, StreamFault, StreamingEstimator};

    fn short(seed: u64, strokes: usize) -> TraceConfig {
        TraceConfig {
            seed,
            strokes,
            address_s: (0.3, 0.6),
            pause_s: (0.0, 0.2),
            gap_s: (0.3, 0.5),
            ..TraceConfig::default()
        }
    }

    fn events(samples: &[[i16; 6]], fs: f64) -> Vec<StreamEvent> {
        let mut est = StreamingEstimator::new(&StreamConfig::new(fs as f32)).unwrap();
        let mut out: Vec<StreamEvent> = samples
            .iter()
            .filter_map(|s| est.push_raw(s[0], Some(s[4])))
            .collect();
        out.extend(est.finish());
        out
    }

    /// The CSV the generator writes parses back to its samples, and the streaming
    /// estimator, reading `ax` and `gy` from the parsed trace, finds each stroke where
    /// the truth says, at the truth's speed: within 2 samples, and 1 % at 6667 Hz (the
    /// issue's bounds). At 3333 Hz the bound is 1.5 %: docs/sensors.md §3 gives 0.95 %
    /// for the windowed estimator there, and the streaming one is 1.17 % off on the first
    /// stroke of seed 12 below. A wrong column or sign would be off by far more.
    #[test]
    fn written_traces_parse_back_and_hold_their_truth() {
        for (seed, odr, bound) in [(11, 6667.0, 0.01), (12, 3333.0, 0.015)] {
            let config = TraceConfig {
                odr_hz: odr,
                ..short(seed, 3)
            };
            let trace = generate(&config);
            let mut csv = Vec::new();
            write_csv(&trace.samples, &mut csv).unwrap();
            let mut parsed = Vec::new();
            let n = parse_trace(&csv, |i, s| {
                assert_eq!(i as usize, parsed.len());
                parsed.push(s);
            })
            .unwrap();
            assert_eq!(n as usize, trace.samples.len());
            assert_eq!(parsed, trace.samples);

            let events = events(&parsed, odr);
            assert_eq!(events.len(), 3, "{events:?}");
            for (event, truth) in events.iter().zip(&trace.strokes) {
                let StreamEvent::Stroke(s) = event else {
                    panic!("{event:?}")
                };
                let off = (s.impact_index as i64 - truth.impact_sample as i64).abs();
                let err = (f64::from(s.cue_speed) - truth.cue_speed_mps) / truth.cue_speed_mps;
                assert!(off <= 2 && err.abs() <= bound, "{s:?} vs {truth:?}");
            }
        }
    }

    /// `az` at address reads `g cos θ` of the truth's elevation (within the ±50 mg bias
    /// and 4σ of the mean's noise); `ay`, `gx`, `gz` sit at their bias.
    #[test]
    fn the_other_axes_carry_gravity_and_bias() {
        let trace = generate(&short(5, 1));
        let s = &trace.strokes[0];
        let n = 1000;
        let mean = |axis: usize| -> f64 {
            trace.samples[..n]
                .iter()
                .map(|x| f64::from(x[axis]))
                .sum::<f64>()
                / n as f64
        };
        // Settling moves are along x only; the elevation is the address elevation.
        let expected_az = s.elevation_deg.to_radians().cos() / 0.488e-3; // LSB
        let bias_bound = 0.050 / 0.488e-3 + 4.0 * 3.0 / 0.488 / (n as f64).sqrt();
        assert!(
            (mean(2) - expected_az).abs() <= bias_bound,
            "{} vs {expected_az}",
            mean(2)
        );
        assert!(mean(1).abs() <= bias_bound, "ay {}", mean(1));
        let gyro_bound = 1.0 / 0.070 + 4.0 * 0.29 / 0.070 / (n as f64).sqrt();
        for axis in [3, 5] {
            assert!(
                mean(axis).abs() <= gyro_bound,
                "axis {axis}: {}",
                mean(axis)
            );
        }
    }

    /// The bad-input options give the streaming estimator's faults at the truth's samples.
    #[test]
    fn double_hits_and_saturation_are_where_the_truth_says() {
        let config = TraceConfig {
            double_hits: vec![1],
            saturated: vec![2],
            ..short(21, 3)
        };
        let trace = generate(&config);
        let events = events(&trace.samples, config.odr_hz);
        assert_eq!(events.len(), 4, "{events:?}");
        let second = trace.strokes[1].second_impact_sample.unwrap();
        let first = trace.strokes[1].impact_sample;
        // 20 ms at 6667 Hz is 133.3 sample periods.
        assert!((133..=134).contains(&(second - first)), "{first} {second}");
        let StreamEvent::Fault(StreamFault::DoubleHit { second: found, .. }) = events[2] else {
            panic!("{events:?}")
        };
        assert!(
            (found as i64 - second as i64).abs() <= 4,
            "{found} vs {second}"
        );
        let at = trace.strokes[2].saturated_from_sample.unwrap();
        // 40 ms before the contact at 6667 Hz: 266.7 periods; 2 ms: 13.3.
        assert_eq!(at, trace.strokes[2].impact_sample - 266);
        assert!(trace.samples[at..at + 13].iter().all(|s| s[0] == i16::MAX));
        let StreamEvent::Fault(StreamFault::Saturated { index, .. }) = events[3] else {
            panic!("{events:?}")
        };
        assert_eq!(index, at as u64);
        assert!(trace.strokes[0].second_impact_sample.is_none());
    }

    #[test]
    fn bad_configs_are_named() {
        assert!(TraceConfig::default().check().is_ok());
        for (config, word) in [
            (
                TraceConfig {
                    odr_hz: 0.0,
                    ..Default::default()
                },
                "odr",
            ),
            (
                TraceConfig {
                    strokes: 0,
                    ..Default::default()
                },
                "strokes",
            ),
            (
                TraceConfig {
                    noise_mg: f64::NAN,
                    ..Default::default()
                },
                "noise",
            ),
            (
                TraceConfig {
                    gap_s: (1.0, 0.5),
                    ..Default::default()
                },
                "gap",
            ),
            (
                TraceConfig {
                    address_s: (0.0, 1.0),
                    ..Default::default()
                },
                "address",
            ),
            (
                TraceConfig {
                    double_hits: vec![3],
                    ..Default::default()
                },
                "double-hit",
            ),
        ] {
            let err = config.check().unwrap_err();
            assert!(err.starts_with(word), "{err}");
        }
    }
}
