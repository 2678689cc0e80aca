//! The glitch detector (`find_glitch`, `src/glitch.rs`) on the repo's synthetic strokes:
//!
//! 1. no false positive on any clean window: the kinematic model of
//!    `tests/synthetic_strokes.rs` (copied here draw for draw: its seeded sets of 250
//!    strokes, 1/3/8 mg and the pendulum tilt, at 1, 1.67, 3.33 and 6.66 kHz, as the
//!    capture ring freezes them), the host generator of `host-tests/src/strokes.rs`
//!    (copied: `cuesight-host` depends on this crate; checked word for word against the
//!    demo session's stroke; the e2e strokes, the 1 kHz demo `(7, 1000, 2.5)`, 250 seeded
//!    strokes per rate) and piecewise-constant strokes of `tests/common`;
//! 2. a `−32768`, a `+32767` and ±2 g spikes injected before the impact onset are named
//!    (index, kind, word), ≥ 1,000 seeded injections per rate and kind at 1, 3.33 and
//!    6.66 kHz, every position of the demo stroke; the smallest spike found everywhere
//!    and the sample just before the onset are measured;
//! 3. no panic on any input (degenerate windows, rates and scales; a proptest).
//!
//! Figures (quoted in `src/glitch.rs`):
//!
//!     cargo test -p cuesight-sensors --release --test glitch -- --nocapture

mod common;

use cuesight_sensors::glitch::{CONTACT_MIN_S, GAP_S};
use cuesight_sensors::lsm6dsox::{ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB, STANDARD_GRAVITY};
use cuesight_sensors::{
    estimate_raw, find_glitch, Glitch, GlitchKind, ImpactTrigger, RingBuffer, StrokeConfig,
    StrokeError,
};
use proptest::prelude::*;
use proptest::test_runner::{contextualize_config, TestRunner};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::sync::OnceLock;

use common::thousands;

const G: f64 = 9.80665;

// ---------------------------------------------------------------------------------------
// Generator 1: the kinematic model of `tests/synthetic_strokes.rs`, copied verbatim (same
// random draws in the same order, so the same seeds give the same strokes).
// ---------------------------------------------------------------------------------------

const BALL_MASS: f64 = 0.17;
const RING: usize = 24_000;

#[derive(Clone, Debug)]
struct Stroke {
    speed: f64,
    settle: Option<(f64, f64)>,
    rest: f64,
    back: (f64, f64),
    pause: f64,
    forward: (f64, f64),
    contact: f64,
    delta_v: f64,
    ring: (f64, f64),
    follow: f64,
    elevation: f64,
    bias: f64,
    tilt_back: f64,
    gyro_bias: f64,
}

fn min_jerk_velocity(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance / duration * 30.0 * s * s * (1.0 - s) * (1.0 - s)
}

fn min_jerk_position(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
}

fn min_jerk_acceleration(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance / (duration * duration) * 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s)
}

impl Stroke {
    fn random(rng: &mut ChaCha8Rng) -> Self {
        let speed = (0.5f64.ln() + rng.random::<f64>() * (6.0f64 / 0.5).ln()).exp();
        let settle = if rng.random::<bool>() {
            let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
            Some((
                sign * rng.random_range(0.01..0.05),
                rng.random_range(0.3..0.6),
            ))
        } else {
            None
        };
        let back_distance = rng.random_range(0.05..0.10) + 0.008 * speed * speed;
        let back = (back_distance, rng.random_range(0.3..0.8));
        let travel = back_distance + rng.random_range(0.005..0.03);
        let w: f64 = rng.random();
        let mean_g = w / 3.0 + (1.0 - w) / 2.0;
        let forward = (travel / (speed * mean_g), w);
        let cue_mass = rng.random_range(0.50..0.60);
        let tip_e = rng.random_range(0.70..0.80);
        let b = 0.5 * rng.random::<f64>().sqrt();
        let ball = (1.0 + tip_e) * speed / (1.0 + BALL_MASS / cue_mass + 2.5 * b * b);
        let elevation = rng.random_range(2.0f64..12.0).to_radians();
        let bias = rng.random_range(-0.05..0.05) * G;
        Self {
            speed,
            settle,
            rest: rng.random_range(0.25..0.6),
            back,
            pause: rng.random_range(0.0..0.4),
            forward,
            contact: rng.random_range(0.8e-3..1.5e-3),
            delta_v: BALL_MASS * ball / cue_mass,
            ring: (
                rng.random_range(20.0..60.0) * G,
                rng.random_range(1000.0..2000.0),
            ),
            follow: rng.random_range(0.15..0.3),
            elevation,
            bias,
            tilt_back: 0.0,
            gyro_bias: rng.random_range(-1.0f64..1.0).to_radians(),
        }
    }

    fn position(&self, t: f64) -> f64 {
        let [_, back_start, back_end, forward_start, contact] = self.times();
        let (d, _) = self.back;
        if t < back_start {
            0.0
        } else if t < back_end {
            -min_jerk_position(d, self.back.1, t - back_start)
        } else if t < forward_start {
            -d
        } else {
            let s = ((t.min(contact) - forward_start) / self.forward.0).min(1.0);
            let w = self.forward.1;
            let g_int = w * s * s * s / 3.0 + (1.0 - w) * (s * s * s - 0.5 * s * s * s * s);
            -d + self.speed * self.forward.0 * g_int
        }
    }

    fn tilt(&self, t: f64) -> f64 {
        if self.tilt_back == 0.0 {
            return self.elevation;
        }
        let x = self.position(t);
        self.elevation + self.tilt_back * (x / self.back.0).powi(2)
    }

    fn times(&self) -> [f64; 5] {
        let settle_end = self.settle.map_or(0.0, |(_, d)| d);
        let back_start = settle_end + self.rest;
        let back_end = back_start + self.back.1;
        let forward_start = back_end + self.pause;
        [
            settle_end,
            back_start,
            back_end,
            forward_start,
            forward_start + self.forward.0,
        ]
    }

    fn velocity(&self, t: f64) -> f64 {
        let [settle_end, back_start, back_end, forward_start, _] = self.times();
        if t < settle_end {
            let (d, dur) = self.settle.unwrap_or((0.0, 1.0));
            min_jerk_velocity(d, dur, t)
        } else if t < back_start {
            0.0
        } else if t < back_end {
            -min_jerk_velocity(self.back.0, self.back.1, t - back_start)
        } else if t < forward_start {
            0.0
        } else {
            let s = ((t - forward_start) / self.forward.0).min(1.0);
            let w = self.forward.1;
            let g = w * s * s + (1.0 - w) * (3.0 * s * s - 2.0 * s * s * s);
            self.speed * g
        }
    }

    fn acceleration(&self, t: f64) -> f64 {
        let [settle_end, back_start, back_end, forward_start, contact] = self.times();
        if t < settle_end {
            let (d, dur) = self.settle.unwrap_or((0.0, 1.0));
            min_jerk_acceleration(d, dur, t)
        } else if t < back_start {
            0.0
        } else if t < back_end {
            -min_jerk_acceleration(self.back.0, self.back.1, t - back_start)
        } else if t < forward_start {
            0.0
        } else if t < contact {
            let s = (t - forward_start) / self.forward.0;
            let w = self.forward.1;
            self.speed / self.forward.0 * (2.0 * w * s + (1.0 - w) * (6.0 * s - 6.0 * s * s))
        } else if t < contact + self.contact {
            let u = t - contact;
            let pi = std::f64::consts::PI;
            -self.delta_v * pi / (2.0 * self.contact) * (pi * u / self.contact).sin()
        } else {
            let u = t - contact - self.contact;
            let pi = std::f64::consts::PI;
            let (amp, freq) = self.ring;
            let ring = amp * (-u / 3e-3).exp() * (2.0 * pi * freq * u).sin();
            let after = self.speed - self.delta_v;
            let follow = if u < self.follow {
                -after * pi / (2.0 * self.follow) * (pi * u / self.follow).sin()
            } else {
                0.0
            };
            ring + follow
        }
    }

    /// Raw accelerometer words at `fs` until 100 ms after contact (the pitch channel is
    /// drawn and dropped, to keep the random stream of the original).
    fn samples(&self, fs: f64, noise_rms: f64, rng: &mut ChaCha8Rng) -> Vec<i16> {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        let n = ((contact + 0.1) * fs) as usize;
        let rail = 16.0 * G;
        let lsb = f64::from(ACCEL_MPS2_PER_LSB);
        let gyro_noise = 0.29f64.to_radians();
        let mut accel = Vec::with_capacity(n);
        for k in 0..n {
            let (t0, t1) = (k as f64 * dt, (k + 1) as f64 * dt);
            let gravity = -G * self.tilt(0.5 * (t0 + t1)).sin();
            let mean = if t1 <= contact {
                let a = (self.velocity(t1) - self.velocity(t0)) / dt;
                assert!(a.abs() < 12.0 * G, "model stroke too violent: {a} m/s²");
                a + gravity + self.bias
            } else {
                let sub = 32;
                (0..sub)
                    .map(|j| {
                        let t = t0 + (j as f64 + 0.5) * dt / sub as f64;
                        (self.acceleration(t) + gravity + self.bias).clamp(-rail, rail)
                    })
                    .sum::<f64>()
                    / sub as f64
            };
            let measured = mean + noise_rms * gaussian(rng);
            accel.push((measured / lsb).round().clamp(-32768.0, 32767.0) as i16);
            let rate = (self.tilt(t1) - self.tilt(t0)) / dt + self.gyro_bias;
            let _ = rate + gyro_noise * gaussian(rng);
            let _ = GYRO_RADPS_PER_LSB;
        }
        accel
    }
}

fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// The window the firmware's capture loop freezes: ring of 24,000 words, impact trigger at
/// 8 g, 50 ms kept after it (as `tests/synthetic_strokes.rs` captures), and the stream
/// index of its first word. `None` when the trigger never completes (at 1 kHz the
/// one-sample average of a slow stroke's impact can stay above −8 g).
fn capture(accel: &[i16], fs: f64) -> Option<(Vec<i16>, usize)> {
    let mut ring = Box::new(RingBuffer::<i16, RING>::new(0));
    let mut trigger = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, (0.05 * fs) as usize).unwrap();
    for (pushed, &word) in accel.iter().enumerate() {
        ring.push(word);
        if trigger.push(f32::from(word) * ACCEL_MPS2_PER_LSB) {
            return Some((ring.make_contiguous().to_vec(), pushed + 1 - ring.len()));
        }
    }
    None
}

impl Stroke {
    /// Stream index of the first sample the tip contact touches (the generator's own
    /// test: the sample ending after the contact time).
    fn contact_sample(&self, fs: f64) -> usize {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        (0..).find(|&k| (k + 1) as f64 * dt > contact).unwrap()
    }
}

// ---------------------------------------------------------------------------------------
// Generator 2: `host-tests/src/strokes.rs` (the demo session's and the e2e test's strokes),
// copied verbatim: cuesight-host depends on this crate, so its tests cannot use it.
// ---------------------------------------------------------------------------------------

fn host_stroke(seed: u64, rate_hz: f64, cue_speed: f64) -> Vec<i16> {
    host_stroke_of(seed, rate_hz, cue_speed, None)
}

/// `synthetic_stroke_of`: exactly `count` samples when given.
fn host_stroke_of(seed: u64, rate_hz: f64, cue_speed: f64, count: Option<usize>) -> Vec<i16> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scale = f64::from(ACCEL_MPS2_PER_LSB);
    let (rest, back, pause, forward) = (0.4, 0.45, 0.12, 0.3);
    let backswing = 0.12;
    let (impact, follow, stop) = (0.0015, 0.06, 0.2);
    let total = rest + back + pause + forward + impact + follow;
    let bias = G * 5f64.to_radians().sin() + 0.02 * G;
    let count = count.unwrap_or((total * rate_hz).round() as usize);
    let pi = std::f64::consts::PI;
    (0..count)
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
            let (u1, u2): (f64, f64) = (rng.random_range(1e-12..1.0), rng.random());
            let noise = 0.008 * G * (-2.0 * u1.ln()).sqrt() * (2.0 * pi * u2).cos();
            ((a + bias + noise) / scale)
                .round()
                .clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// The demo session's stroke, as committed in firmware/demo/session.jsonl
// ---------------------------------------------------------------------------------------

/// The stroke of `firmware/demo/session.jsonl`: its words (every `"samples"` array, in
/// order), its rate (`"rate_hz"`) and the arguments of the `## Generated by:` command
/// above it (`stroke_session -- SEED RATE_HZ SPEED_M_S [SAMPLES [ID]]`).
fn demo_session() -> (Vec<i16>, f64, Vec<f64>) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../firmware/demo/session.jsonl"
    );
    let text = std::fs::read_to_string(path).expect("firmware/demo/session.jsonl");
    let (mut words, mut rate, mut args) = (Vec::new(), None, Vec::new());
    for line in text.lines() {
        if let Some(command) = line.strip_prefix("## Generated by:") {
            let tail = command
                .split(" -- ")
                .nth(1)
                .expect("stroke_session -- ARGS");
            args = tail
                .split_whitespace()
                .map(|a| a.parse().unwrap())
                .collect();
        }
        if line.starts_with('#') {
            continue;
        }
        if let Some((_, rest)) = line.split_once("\"samples\":[") {
            let list = &rest[..rest.find(']').expect("a closed samples array")];
            words.extend(
                list.split(',')
                    .map(|w| w.trim().parse::<i16>().expect("an i16")),
            );
        }
        if let Some((_, rest)) = line.split_once("\"rate_hz\":") {
            let end = rest.find([',', '}']).expect("a number");
            rate = Some(rest[..end].trim().parse::<f64>().expect("a rate"));
        }
    }
    (words, rate.expect("a rate_hz"), args)
}

// ---------------------------------------------------------------------------------------
// Windows
// ---------------------------------------------------------------------------------------

/// A clean synthetic window with its true impact onset (first sample the tip contact
/// touches; `None` for strokes the estimator cannot use).
#[derive(Clone, Debug)]
struct Window {
    label: String,
    rate: f64,
    samples: Vec<i16>,
    onset: Option<usize>,
}

/// A set of `tests/synthetic_strokes.rs` (same seeds, same draws), as captured; strokes
/// whose capture never triggers (only at 1 kHz) are kept whole, with no onset.
fn kinematic_set(
    fs: f64,
    noise_mg: f64,
    strokes: usize,
    seed: u64,
    tilt: Option<(f64, f64)>,
) -> Vec<Window> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = noise_mg * 1e-3 * G;
    let mut out = Vec::new();
    for k in 0..strokes {
        let mut stroke = Stroke::random(&mut rng);
        if let Some((lo, hi)) = tilt {
            stroke.tilt_back = rng.random_range(lo..hi).to_radians();
        }
        let accel = stroke.samples(fs, noise, &mut rng);
        let label = format!(
            "kinematic {fs} Hz {noise_mg} mg seed {seed:#x} #{k} (V {:.2} m/s)",
            stroke.speed
        );
        let contact = stroke.contact_sample(fs);
        let window = match capture(&accel, fs) {
            Some((samples, offset)) => Window {
                label,
                rate: fs,
                samples,
                onset: Some(contact - offset),
            },
            None => Window {
                label,
                rate: fs,
                samples: accel,
                onset: None,
            },
        };
        out.push(window);
    }
    out
}

/// `strokes` host-generator strokes (`host-tests/src/strokes.rs`) from seeds `seed..`,
/// speeds log-uniform in 0.5–6 m/s.
fn host_set(fs: f64, strokes: u64, seed: u64) -> Vec<Window> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0xD3A0);
    (0..strokes)
        .map(|k| {
            let speed = (0.5f64.ln() + rng.random::<f64>() * (6.0f64 / 0.5).ln()).exp();
            host_window(seed + k, fs, speed)
        })
        .collect()
}

fn host_window(seed: u64, fs: f64, speed: f64) -> Window {
    host_window_of(seed, fs, speed, None)
}

fn host_window_of(seed: u64, fs: f64, speed: f64, count: Option<usize>) -> Window {
    let samples = host_stroke_of(seed, fs, speed, count);
    // The impact is the only stretch at −50 g (clipped to the rail).
    let onset = samples.iter().position(|&w| w == i16::MIN);
    Window {
        label: format!("host seed {seed} {fs} Hz {speed:.3} m/s"),
        rate: fs,
        samples,
        onset,
    }
}

/// Piecewise-constant strokes of `tests/common` (noise-free, f32 → words): one push at
/// `a` m/s² for 40–200 ms from a level within ±1 g, or two to four moves.
fn piecewise_set(fs: f64, strokes: usize, seed: u64) -> Vec<Window> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let rate = fs as f32;
    (0..strokes)
        .map(|k| {
            let level = rng.random_range(-1.0f32..1.0) * STANDARD_GRAVITY;
            let p = if k % 2 == 0 {
                let a = rng.random_range(1.0f32..50.0);
                let push = (rng.random_range(0.04..0.2) * fs) as usize;
                common::step(rate, level, a, push)
            } else {
                let moves: Vec<(f32, usize)> = (0..rng.random_range(2..5))
                    .map(|_| {
                        (
                            rng.random_range(-50.0f32..50.0),
                            (rng.random_range(0.002..0.2) * fs) as usize + 2,
                        )
                    })
                    .collect();
                let coast = (rng.random_range(0.0..0.03) * fs) as usize;
                common::piecewise(rate, level, (0.3 * fs) as usize, &moves, coast)
            };
            Window {
                label: format!("piecewise {fs} Hz #{k}"),
                rate: fs,
                samples: common::to_raw(&p.samples, ACCEL_MPS2_PER_LSB),
                onset: Some(p.impact),
            }
        })
        .collect()
}

/// Every clean set, by name (generated once per test process).
fn clean_sets() -> &'static [(String, Vec<Window>)] {
    static SETS: OnceLock<Vec<(String, Vec<Window>)>> = OnceLock::new();
    SETS.get_or_init(build_clean_sets)
}

fn build_clean_sets() -> Vec<(String, Vec<Window>)> {
    let mut sets: Vec<(String, Vec<Window>)> = Vec::new();
    // tests/synthetic_strokes.rs: its six sets (6667 Hz at 1, 3 and 8 mg, the pendulum
    // tilt at 8 mg, 3333 and 1667 Hz at 8 mg), and the same seeds at the other rates.
    for fs in [1000.0, 1667.0, 3333.0, 6667.0] {
        for (noise, seed) in [(1.0, 0x5EED_0001), (3.0, 0x5EED_0003), (8.0, 0x5EED_0008)] {
            sets.push((
                format!("kinematic {fs} Hz, {noise} mg"),
                kinematic_set(fs, noise, 250, seed, None),
            ));
        }
        sets.push((
            format!("kinematic {fs} Hz, 8 mg, pendulum tilt"),
            kinematic_set(fs, 8.0, 250, 0x5EED_7117, Some((0.5, 2.0))),
        ));
    }
    // host-tests/src/strokes.rs: the e2e test's four, its own test's three, the brief's
    // 1 kHz demo and the session's 5,000-sample window (also at the other rates: 5 s at
    // 1 kHz, 0.75 s at 6.67 kHz, cut before the impact), and 250 seeded strokes per rate.
    let listed = [
        (11, 3333.0, 1.5),
        (12, 3333.0, 3.0),
        (13, 3333.0, 5.0),
        (14, 1000.0, 0.8),
        (1, 6667.0, 2.0),
        (2, 3333.0, 4.0),
        (3, 1000.0, 1.0),
        (7, 1000.0, 2.5),
    ];
    sets.push((
        "host generator: e2e, its own test, demo, 5,000-sample windows".into(),
        listed
            .iter()
            .map(|&(seed, fs, v)| host_window(seed, fs, v))
            .chain([1000.0, 3333.0, 6667.0].map(|fs| host_window_of(7, fs, 2.5, Some(5000))))
            .collect(),
    ));
    for fs in [1000.0, 3333.0, 6667.0] {
        sets.push((format!("host generator {fs} Hz"), host_set(fs, 250, 1000)));
        sets.push((format!("piecewise {fs} Hz"), piecewise_set(fs, 100, 0x9137)));
    }
    sets
}

// ---------------------------------------------------------------------------------------
// 1. No false positives
// ---------------------------------------------------------------------------------------

/// The committed demo session's stroke is the host generator's (the replica here is
/// exact) and clean; so is the brief's 1 kHz demo stroke (`stroke_session -- 7 1000 2.5`
/// before the window became 5,000 samples: `synthetic_stroke(7, 1000, 2.5)`).
#[test]
fn the_demo_strokes_are_clean() {
    let (words, rate, args) = demo_session();
    let [seed, speed] = [args[0], args[2]];
    assert_eq!(args[1], rate);
    let count = args.get(3).map(|&n| n as usize);
    let replica = host_stroke_of(seed as u64, rate, speed, count);
    assert_eq!(
        words, replica,
        "the replica of host-tests/src/strokes.rs drifted"
    );
    for (words, rate) in [(words, rate), (host_stroke(7, 1000.0, 2.5), 1000.0)] {
        assert_eq!(find_glitch(&words, rate as f32, ACCEL_MPS2_PER_LSB), None);
        // As the firmware estimates it (full scale at the i16 range): the impact is the
        // first rail word.
        let mut config = StrokeConfig::new(rate as f32);
        config.full_scale = 32768.0 * ACCEL_MPS2_PER_LSB;
        let e = estimate_raw(&words, ACCEL_MPS2_PER_LSB, &config).unwrap();
        assert_eq!(
            words.iter().position(|&w| w == i16::MIN),
            Some(e.impact_index)
        );
    }
}

#[test]
fn no_false_positive_on_any_synthetic_stroke() {
    let mut total = 0;
    let mut per_rate = BTreeMap::new();
    let mut failures = Vec::new();
    for (name, set) in clean_sets() {
        for w in set {
            total += 1;
            *per_rate.entry(w.rate as u32).or_insert(0) += 1;
            // Both axis polarities: words negated with the scale.
            let flipped: Vec<i16> = w.samples.iter().map(|&x| x.saturating_neg()).collect();
            let found = [
                find_glitch(&w.samples, w.rate as f32, ACCEL_MPS2_PER_LSB),
                find_glitch(&flipped, w.rate as f32, -ACCEL_MPS2_PER_LSB),
            ];
            for g in found.into_iter().flatten() {
                failures.push(format!("{name}: {}: {g:?}", w.label));
            }
        }
        println!("{name}: {} windows", set.len());
    }
    println!("{total} clean windows, {} false positives", failures.len());
    assert!(
        failures.is_empty(),
        "false positives:\n{}",
        failures.join("\n")
    );
    cuesight_figures::record!("sensors-glitch-clean-windows", "{}", thousands(total));
    for (rate, windows) in per_rate {
        let key = format!("sensors-glitch-clean-windows-{rate}hz");
        cuesight_figures::record!(&key, "{}", thousands(windows));
    }
}

// ---------------------------------------------------------------------------------------
// 2. Detection
// ---------------------------------------------------------------------------------------

/// What is injected.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Injection {
    /// The rail in the deceleration direction (−32768 at a positive scale).
    DecelRail,
    /// The rail in the forward direction (+32767).
    ForwardRail,
    /// `g` added to one sample (either sign), in words at the scale.
    Spike(f64),
}

/// The word `what` puts at `samples[at]`, and the glitch it must be reported as.
fn injected(samples: &[i16], at: usize, what: Injection) -> Glitch {
    let (value, kind) = match what {
        Injection::DecelRail => (i16::MIN, GlitchKind::Rail),
        Injection::ForwardRail => (i16::MAX, GlitchKind::Rail),
        Injection::Spike(g) => {
            let lsb = (g * G / f64::from(ACCEL_MPS2_PER_LSB)).round();
            let v = (f64::from(samples[at]) + lsb).clamp(-32767.0, 32766.0) as i16;
            (v, GlitchKind::Spike)
        }
    };
    Glitch {
        index: at,
        kind,
        value,
    }
}

/// `samples` with `what` injected at `at`, and the glitch it must be reported as.
fn inject(samples: &[i16], at: usize, what: Injection) -> (Vec<i16>, Glitch) {
    let expected = injected(samples, at, what);
    let mut s = samples.to_vec();
    s[at] = expected.value;
    (s, expected)
}

/// The positions a detector must cover: every sample before the onset, except, for an
/// injection in the deceleration direction, the one sample just before it (it reads as
/// the impact starting one sample earlier; see the module documentation).
fn limit(onset: usize, what: Injection) -> usize {
    match what {
        Injection::ForwardRail => onset,
        Injection::Spike(g) if g > 0.0 => onset,
        _ => onset.saturating_sub(1),
    }
}

/// Below 2.5 kHz (`CONTACT_MIN_S · rate < 2`) a tip contact can fall into one sample,
/// and a lone sample deeper than everything after it in the impact's group is the
/// impact: a deceleration-rail glitch within `GAP_S` (10 ms) before an impact that does
/// not reach the rail reads as the impact. The zone in samples (0 at 2.5 kHz and above).
fn ambiguity_zone(fs: f64) -> usize {
    if f64::from(CONTACT_MIN_S) * fs < 2.0 {
        (f64::from(GAP_S) * fs) as usize + 1
    } else {
        0
    }
}

/// The first 100 strokes of each kinematic set at `fs` (the three noise levels and the
/// tilt) that the estimator takes (at 1 kHz a slow stroke's impact can average to less
/// than 8 g: NoImpact, nothing to protect), and the 250 host-generator strokes at `fs`.
fn injection_windows(fs: f64) -> (Vec<&'static Window>, Vec<&'static Window>) {
    let (mut kinematic, mut host) = (Vec::new(), Vec::new());
    for (name, set) in clean_sets() {
        if name.starts_with(&format!("kinematic {fs} Hz,")) {
            kinematic.extend(set.iter().take(100).filter(|w| {
                let config = StrokeConfig::new(w.rate as f32);
                w.onset.is_some() && estimate_raw(&w.samples, ACCEL_MPS2_PER_LSB, &config).is_ok()
            }));
        }
        if *name == format!("host generator {fs} Hz") {
            host.extend(set.iter());
        }
    }
    (kinematic, host)
}

/// Tally of injections.
#[derive(Default)]
struct Tally {
    hit: usize,
    total: usize,
    /// Misses that found nothing (the glitch read as the impact).
    none: usize,
    misses: Vec<String>,
}

impl Tally {
    fn rate(&self) -> f64 {
        100.0 * self.hit as f64 / self.total.max(1) as f64
    }
}

/// Injects `what` at each of `positions` of `w` and tallies exact detections (index,
/// kind and value).
fn tally(t: &mut Tally, w: &Window, what: Injection, positions: impl IntoIterator<Item = usize>) {
    let mut s = w.samples.clone();
    for at in positions {
        let expected = injected(&w.samples, at, what);
        s[at] = expected.value;
        let got = find_glitch(&s, w.rate as f32, ACCEL_MPS2_PER_LSB);
        s[at] = w.samples[at];
        t.total += 1;
        if got == Some(expected) {
            t.hit += 1;
        } else {
            t.none += usize::from(got.is_none());
            if t.misses.len() < 5 {
                t.misses.push(format!(
                    "{}: {what:?} at {at} (onset {:?}): {got:?}",
                    w.label, w.onset
                ));
            }
        }
    }
}

/// `per_window` random positions in `[lo, hi)` plus both ends.
fn positions(rng: &mut ChaCha8Rng, lo: usize, hi: usize, per_window: usize) -> Vec<usize> {
    if hi <= lo {
        return Vec::new();
    }
    let mut p: Vec<usize> = (0..per_window).map(|_| rng.random_range(lo..hi)).collect();
    p.extend([lo, hi - 1]);
    p
}

const INJECTIONS: [Injection; 4] = [
    Injection::DecelRail,
    Injection::ForwardRail,
    Injection::Spike(2.0),
    Injection::Spike(-2.0),
];

/// Acceptance 2: a rail word of either sign, or a ±2 g single-sample spike, injected
/// before the impact onset (the generator's first contact sample) is reported with its
/// index, kind and word: every position of the covered range (`limit`), ≥ 1,000
/// injections per rate and kind. At 1 kHz the kinematic model's deceleration-rail
/// injections inside the ambiguity zone are tallied apart and must find nothing rather
/// than a wrong sample.
#[test]
fn rails_and_2g_spikes_before_the_impact_are_found() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x6117C4);
    let mut failures = Vec::new();
    for fs in [1000.0, 3333.0, 6667.0] {
        let (kinematic, host) = injection_windows(fs);
        assert!(
            kinematic.len() >= 250,
            "{fs} Hz: {} kinematic windows",
            kinematic.len()
        );
        let zone = ambiguity_zone(fs);
        let mut totals = Vec::new();
        for what in INJECTIONS {
            let (mut main, mut zoned) = (Tally::default(), Tally::default());
            for &w in &host {
                let end = limit(w.onset.unwrap(), what);
                tally(&mut main, w, what, positions(&mut rng, 0, end, 2));
            }
            for &w in &kinematic {
                let end = limit(w.onset.unwrap(), what);
                let cut = if what == Injection::DecelRail {
                    end.saturating_sub(zone)
                } else {
                    end
                };
                tally(&mut main, w, what, positions(&mut rng, 0, cut, 2));
                tally(&mut zoned, w, what, cut..end);
            }
            println!(
                "{fs} Hz, {what:?}: {}/{} detected ({:.2} %) in {} host + {} kinematic windows",
                main.hit,
                main.total,
                main.rate(),
                host.len(),
                kinematic.len()
            );
            if zoned.total > 0 {
                println!(
                    "  ambiguity zone (last {zone} samples, kinematic): {}/{} detected \
                     ({:.2} %), {} read as the impact",
                    zoned.hit,
                    zoned.total,
                    zoned.rate(),
                    zoned.none
                );
                let found = format!("sensors-glitch-zone-found-{fs}hz");
                cuesight_figures::record!(&found, "{}", thousands(zoned.hit));
                let injections = format!("sensors-glitch-zone-injections-{fs}hz");
                cuesight_figures::record!(&injections, "{}", thousands(zoned.total));
            }
            totals.push(main.total);
            assert!(main.total >= 1000);
            if main.hit != main.total {
                failures.push(format!(
                    "{fs} Hz {what:?}: {}/{}: {:?}",
                    main.hit, main.total, main.misses
                ));
            }
            if zoned.hit + zoned.none != zoned.total {
                failures.push(format!("{fs} Hz {what:?} zone: {:?}", zoned.misses));
            }
        }
        // Injections per kind: one figure when every kind had as many.
        let (fewest, most) = (totals.iter().min().unwrap(), totals.iter().max().unwrap());
        let per_kind = if fewest == most {
            thousands(*most)
        } else {
            format!("{}–{}", thousands(*fewest), thousands(*most))
        };
        cuesight_figures::record!(&format!("sensors-glitch-injections-{fs}hz"), "{per_kind}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every position of the demo stroke, every injection.
#[test]
fn every_position_of_the_demo_stroke() {
    let words = host_stroke(7, 1000.0, 2.5);
    let onset = words.iter().position(|&w| w == i16::MIN).unwrap();
    for what in [
        Injection::DecelRail,
        Injection::ForwardRail,
        Injection::Spike(2.0),
        Injection::Spike(-2.0),
    ] {
        for at in 0..limit(onset, what) {
            let (s, expected) = inject(&words, at, what);
            assert_eq!(
                find_glitch(&s, 1000.0, ACCEL_MPS2_PER_LSB),
                Some(expected),
                "{what:?} at {at}"
            );
        }
    }
}

/// The smallest spike found at every sampled position (one random position per window
/// and both ends of the covered range, kinematic and host windows), on a 0.05 g grid,
/// and what the one position left out (a deceleration just before the onset) gives.
#[test]
fn smallest_reliable_spike_and_the_sample_before_the_onset() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5A11);
    for fs in [1000.0, 3333.0, 6667.0] {
        let (mut windows, host) = injection_windows(fs);
        windows.extend(host);
        let mut smallest_by_sign = Vec::new();
        for sign in [1.0, -1.0] {
            let mut smallest = None;
            for step in (10..=40).rev() {
                let g = sign * f64::from(step) * 0.05;
                let mut t = Tally::default();
                for &w in &windows {
                    let end = limit(w.onset.unwrap(), Injection::Spike(g));
                    tally(
                        &mut t,
                        w,
                        Injection::Spike(g),
                        positions(&mut rng, 0, end, 1),
                    );
                }
                if t.hit < t.total {
                    println!(
                        "{fs} Hz: {g:+.2} g spikes: {}/{} found, e.g. {:?}",
                        t.hit,
                        t.total,
                        t.misses.first()
                    );
                    break;
                }
                smallest = Some(g);
            }
            println!(
                "{fs} Hz: smallest spike found at every sampled position: {smallest:+.2?} g \
                 ({} windows)",
                windows.len()
            );
            let smallest = smallest.expect("2 g is found");
            assert!(smallest.abs() <= 1.5, "{fs} Hz: {smallest} g");
            smallest_by_sign.push(smallest.abs());
        }
        // As docs/sensors.md §9 prints it: ±1.10, or +1.35 / −1.25.
        let [up, down] = [smallest_by_sign[0], smallest_by_sign[1]].map(|g| format!("{g:.2}"));
        let smallest = if up == down {
            format!("±{up}")
        } else {
            format!("+{up} / \u{2212}{down}")
        };
        cuesight_figures::record!(
            &format!("sensors-glitch-smallest-spike-{fs}hz"),
            "{smallest}"
        );
        // The sample just before the onset, deceleration direction: how often it is
        // still reported (never as another sample).
        for what in [Injection::DecelRail, Injection::Spike(-2.0)] {
            let mut t = Tally::default();
            for &w in &windows {
                tally(&mut t, w, what, [w.onset.unwrap() - 1]);
            }
            println!(
                "{fs} Hz, {what:?} at onset - 1: {} reported, {} read as the impact, of {}",
                t.hit, t.none, t.total
            );
            assert_eq!(t.hit + t.none, t.total, "{:?}", t.misses);
            if what == Injection::DecelRail {
                let reported = format!("sensors-glitch-before-onset-reported-{fs}hz");
                cuesight_figures::record!(&reported, "{}", thousands(t.hit));
                let windows = format!("sensors-glitch-before-onset-windows-{fs}hz");
                cuesight_figures::record!(&windows, "{}", thousands(t.total));
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Why: what one glitch does to the estimate
// ---------------------------------------------------------------------------------------

/// One rail word in the middle of the demo stroke's forward swing changes the estimated
/// speed (or the estimator takes it for the impact); `find_glitch` names it.
#[test]
fn a_glitch_moves_the_estimate_and_is_named() {
    let words = host_stroke(7, 1000.0, 2.5);
    let mut config = StrokeConfig::new(1000.0);
    config.full_scale = 32768.0 * ACCEL_MPS2_PER_LSB;
    let clean = estimate_raw(&words, ACCEL_MPS2_PER_LSB, &config).unwrap();
    let middle = (clean.rest_end + clean.impact_index) / 2;
    cuesight_figures::record!("sensors-glitch-demo-clean-speed", "{:.2}", clean.cue_speed);
    for (what, word) in [("-32768", i16::MIN), ("+32767", i16::MAX)] {
        let mut bad = words.clone();
        bad[middle] = word;
        let est = estimate_raw(&bad, ACCEL_MPS2_PER_LSB, &config);
        println!(
            "demo stroke, {what} at {middle}: estimate {:?} m/s (clean {} m/s)",
            est.map(|e| e.cue_speed),
            clean.cue_speed
        );
        // The −32768 is taken for the impact: a stroke going backwards.
        if let Err(StrokeError::NotForward { speed }) = est {
            let speed = common::signed(f64::from(speed), 2);
            cuesight_figures::record!("sensors-glitch-demo-rail-not-forward", "{speed}");
        }
        assert_eq!(
            find_glitch(&bad, 1000.0, ACCEL_MPS2_PER_LSB),
            Some(Glitch {
                index: middle,
                kind: GlitchKind::Rail,
                value: word
            })
        );
    }
}

// ---------------------------------------------------------------------------------------
// 3. Robustness
// ---------------------------------------------------------------------------------------

/// Degenerate inputs: named answers, no panic.
#[test]
fn degenerate_inputs() {
    let s = ACCEL_MPS2_PER_LSB;
    let rail = |index, value| {
        Some(Glitch {
            index,
            kind: GlitchKind::Rail,
            value,
        })
    };
    assert_eq!(find_glitch(&[], 1000.0, s), None);
    assert_eq!(find_glitch(&[0], 1000.0, s), None);
    assert_eq!(find_glitch(&[0, 0], 1000.0, s), None);
    // A forward rail word is never an impact; a deceleration rail alone is one.
    assert_eq!(find_glitch(&[i16::MAX], 1000.0, s), rail(0, i16::MAX));
    assert_eq!(find_glitch(&[i16::MIN], 1000.0, s), None);
    assert_eq!(find_glitch(&[i16::MIN], 1000.0, -s), rail(0, i16::MIN));
    assert_eq!(find_glitch(&[0, i16::MAX], 1000.0, s), rail(1, i16::MAX));
    // All rails: the deceleration rail is one long impact; the forward one is a rail.
    for n in [1, 2, 3, 24_000] {
        assert_eq!(find_glitch(&vec![i16::MIN; n], 6667.0, s), None);
        assert_eq!(
            find_glitch(&vec![i16::MAX; n], 6667.0, s),
            rail(0, i16::MAX)
        );
    }
    // Alternating rails: the first forward rail before the impact.
    let alternating: Vec<i16> = (0..1000)
        .map(|i| if i % 2 == 0 { i16::MAX } else { i16::MIN })
        .collect();
    assert_eq!(find_glitch(&alternating, 3333.0, s), rail(0, i16::MAX));
    // A rate or scale that is not a finite number above zero (scale: non-zero): None.
    let stroke = {
        let mut w = host_stroke(7, 1000.0, 2.5);
        w[500] = i16::MIN;
        w
    };
    assert_eq!(find_glitch(&stroke, 1000.0, s), rail(500, i16::MIN));
    for rate in [
        0.0,
        -0.0,
        -1000.0,
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ] {
        assert_eq!(find_glitch(&stroke, rate, s), None, "rate {rate}");
    }
    for scale in [0.0, -0.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert_eq!(find_glitch(&stroke, 1000.0, scale), None, "scale {scale}");
    }
    // Extreme but valid rates and scales: the rail is still a rail.
    for rate in [f32::MIN_POSITIVE, 1e-30, 1.0, 1e9, f32::MAX] {
        assert_eq!(
            find_glitch(&stroke, rate, s),
            rail(500, i16::MIN),
            "rate {rate}"
        );
    }
    for scale in [f32::from_bits(1), f32::MIN_POSITIVE, 1e-30, 1e30, f32::MAX] {
        let found = find_glitch(&stroke, 1000.0, scale);
        assert!(
            found.is_none_or(|g| g.index < stroke.len()),
            "scale {scale}"
        );
    }
}

fn word() -> impl Strategy<Value = i16> {
    prop_oneof![
        3 => any::<i16>(),
        2 => Just(i16::MIN),
        2 => Just(i16::MAX),
        3 => -300i16..300,
    ]
}

fn number() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => prop_oneof![
            Just(1000.0f32),
            Just(3333.0),
            Just(6667.0),
            Just(ACCEL_MPS2_PER_LSB),
            Just(-ACCEL_MPS2_PER_LSB),
        ],
        2 => prop_oneof![
            Just(0.0f32),
            Just(-0.0),
            Just(f32::NAN),
            Just(f32::INFINITY),
            Just(f32::NEG_INFINITY),
            Just(f32::MAX),
            Just(f32::MIN),
            Just(f32::MIN_POSITIVE),
            Just(f32::from_bits(1)),
            Just(-f32::from_bits(1)),
        ],
        3 => any::<f32>(),
        2 => -1e5f32..1e5,
    ]
}

/// Any window (0–400 words, rails weighted up; or a kinematic-model stroke with random
/// words overwritten), any rate and scale (every special f32): no panic; `Some` only
/// for a finite rate above zero and a finite non-zero scale, naming a sample of the
/// window with its word, `Rail` exactly for a rail word.
#[test]
fn never_panics_and_names_a_sample_of_the_window() {
    let strokes: Vec<Vec<i16>> = (0..4)
        .map(|k| host_stroke(k, [1000.0, 3333.0][k as usize % 2], 0.5 + k as f64))
        .collect();
    let windows = prop_oneof![
        3 => prop::collection::vec(word(), 0..400),
        1 => (0..strokes.len(), prop::collection::vec((any::<prop::sample::Index>(), word()), 0..4))
            .prop_map(move |(k, edits)| {
                let mut w = strokes[k].clone();
                for (at, value) in edits {
                    let i = at.index(w.len());
                    w[i] = value;
                }
                w
            }),
    ];
    let mut config = contextualize_config(common::config(20_000, 0x6117));
    config.source_file = Some(file!());
    config.test_name = Some("never_panics_and_names_a_sample_of_the_window");
    let mut runner = TestRunner::new(config);
    runner
        .run(&(windows, number(), number()), |(raw, rate, scale)| {
            let found = find_glitch(&raw, rate, scale);
            let valid = rate.is_finite() && rate > 0.0 && scale.is_finite() && scale != 0.0;
            if let Some(g) = found {
                prop_assert!(valid, "a glitch at rate {rate}, scale {scale}");
                prop_assert!(g.index < raw.len());
                prop_assert_eq!(g.value, raw[g.index]);
                let rail = g.value == i16::MIN || g.value == i16::MAX;
                prop_assert_eq!(g.kind == GlitchKind::Rail, rail);
            }
            Ok(())
        })
        .unwrap();
}
