//! Stroke estimator on synthetic strokes from a kinematic model, end to end through the
//! capture path (raw i16 words → ring buffer + impact trigger → `estimate_raw`).
//!
//! Run with the figures printed (release: the generator sub-samples the impact):
//!
//!     cargo test -p cuesight-sensors --release --test synthetic_strokes -- --nocapture
//!
//! The model (f64, independent of the estimator):
//!
//! * optional settling move (half the strokes): 1–5 cm minimum-jerk move in 0.3–0.6 s;
//! * rest at address 0.25–0.6 s;
//! * backswing, minimum-jerk, 5–10 cm + 0.8 cm·(V/(m/s))², in 0.3–0.8 s;
//! * pause at the back 0–0.4 s;
//! * forward stroke over backswing + 0.5–3 cm, velocity `V·g(s)`, `g = w s² + (1−w)(3s² −
//!   2s³)`, `w ∈ [0, 1]` (still accelerating at impact for `w > 0`), reaching `V` at
//!   contact; `V` log-uniform in 0.5–6 m/s;
//! * tip contact: half-sine deceleration of 0.8–1.5 ms removing `Δv = M v_ball / m_c`
//!   (TP A.30 with a random cue 0.50–0.60 kg, e_t 0.70–0.80, tip offset ≤ 0.5 R), then a
//!   20–60 g cue vibration at 1–2 kHz (3 ms decay) and a 0.15–0.3 s follow-through stop;
//! * sensor: specific force = acceleration − g·sin(elevation), elevation 2–12°, plus a
//!   constant bias uniform in ±50 mg, clipped at ±16 g, averaged over each sample period
//!   (exact velocity differences before contact, 32 sub-samples from contact on), white
//!   Gaussian noise of the stated RMS, quantised to 0.488 mg and the i16 range; ODR
//!   6667 Hz.
//!
//! The last test adds what the accelerometer-only model leaves out: a pendulum stroke
//! tilts the cue (the grip hand rises on its arc away from address), `Δθ = k x²` with
//! `x` the cue's displacement from address and 0.5–2° at the back of the backswing,
//! and a gyro channel (pitch rate, bias ±1 dps, 0.29 dps RMS white noise, 70 mdps LSB)
//! for the gyro-aided estimator.

use cuesight_sensors::lsm6dsox::{ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB, STANDARD_GRAVITY};
use cuesight_sensors::{
    estimate_raw, estimate_raw_with_pitch, ImpactTrigger, RingBuffer, StrokeConfig, StrokeEstimate,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The LSM6DSOX's 6.66 kHz ODR.
const FS: f64 = 6667.0;
const G: f64 = 9.80665;
const BALL_MASS: f64 = 0.17;
/// Ring capacity: 3.6 s at 6.67 kHz, 48 kB of i16.
const RING: usize = 24_000;

/// One synthetic stroke.
#[derive(Clone, Debug)]
struct Stroke {
    speed: f64,
    settle: Option<(f64, f64)>, // (distance m, duration s)
    rest: f64,
    back: (f64, f64), // (distance m, duration s)
    pause: f64,
    forward: (f64, f64), // (duration s, w)
    contact: f64,        // s
    delta_v: f64,        // cue speed lost in the contact, m/s
    ring: (f64, f64),    // (amplitude m/s², frequency Hz)
    follow: f64,         // s
    elevation: f64,      // cue elevation at rest, rad
    bias: f64,           // accelerometer bias, m/s²
    tilt_back: f64,      // elevation gained at the back of the backswing, rad
    gyro_bias: f64,      // rad/s
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
        // TP A.30, written out here independently of the crate.
        let cue_mass = rng.random_range(0.50..0.60);
        let tip_e = rng.random_range(0.70..0.80);
        let b = 0.5 * rng.random::<f64>().sqrt(); // |b|/R, uniform over the disc
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

    /// Cue displacement from address (m), zero before the backswing; held after contact.
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

    /// Cue elevation (rad): the pendulum tilt `k x²`, `k` set by the tilt at the back.
    fn tilt(&self, t: f64) -> f64 {
        if self.tilt_back == 0.0 {
            return self.elevation;
        }
        let x = self.position(t);
        self.elevation + self.tilt_back * (x / self.back.0).powi(2)
    }

    /// Predicted accelerometer-only speed error (m/s) when the estimator takes the cue
    /// to be at rest up to sample `rest_end`: `−g ∫ (sin θ − sin θ_rest) dt` from there
    /// to contact, on the generator's sample grid.
    fn tilt_error(&self, rest_end: usize, fs: f64) -> f64 {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        let n = (contact * fs) as usize;
        let rest = self.tilt(rest_end as f64 * dt).sin();
        (rest_end..n)
            .map(|k| -G * (self.tilt((k as f64 + 0.5) * dt).sin() - rest) * dt)
            .sum()
    }

    /// Phase boundaries: (settle end, back start, back end, forward start, contact).
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

    /// Cue velocity before contact (m/s).
    fn velocity(&self, t: f64) -> f64 {
        let [settle_end, back_start, back_end, forward_start, contact] = self.times();
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
            debug_assert!(t <= contact + 1e-12);
            self.speed * g
        }
    }

    /// Cue acceleration at any time (m/s²).
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

    /// Raw accelerometer and pitch-rate words at `fs` until 100 ms after contact.
    fn samples(&self, fs: f64, noise_rms: f64, rng: &mut ChaCha8Rng) -> (Vec<i16>, Vec<i16>) {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        let n = ((contact + 0.1) * fs) as usize;
        let rail = 16.0 * G;
        let lsb = f64::from(ACCEL_MPS2_PER_LSB);
        let gyro_lsb = f64::from(GYRO_RADPS_PER_LSB);
        let gyro_noise = 0.29f64.to_radians();
        let mut accel = Vec::with_capacity(n);
        let mut pitch = Vec::with_capacity(n);
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
            let rate = rate + gyro_noise * gaussian(rng);
            pitch.push((rate / gyro_lsb).round().clamp(-32768.0, 32767.0) as i16);
        }
        (accel, pitch)
    }
}

/// Standard normal deviate (Box–Muller).
fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// Push the streams through the capture path as the firmware would; `aided` selects
/// the gyro-aided estimator. Also returns the stream index of the ring's first sample.
fn capture(accel: &[i16], pitch: &[i16], fs: f64, aided: bool) -> Option<(StrokeEstimate, usize)> {
    let mut ring = Box::new(RingBuffer::<i16, RING>::new(0));
    let mut pitch_ring = Box::new(RingBuffer::<i16, RING>::new(0));
    // Keep 50 ms after the trigger.
    let mut trigger = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, (0.05 * fs) as usize).unwrap();
    let mut done = false;
    let mut pushed = 0;
    for (&word, &rate) in accel.iter().zip(pitch) {
        pushed += 1;
        ring.push(word);
        pitch_ring.push(rate);
        if trigger.push(f32::from(word) * ACCEL_MPS2_PER_LSB) {
            done = true;
            break;
        }
    }
    assert!(done, "the trigger never completed");
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
    match result {
        Ok(e) => Some((e, pushed - ring.len())),
        Err(e) => {
            println!("  estimator error: {e:?}");
            None
        }
    }
}

struct Figures {
    count: usize,
    max_abs: f64,
    rms: f64,
    mean: f64,
    worst: Option<Stroke>,
    band_max: [f64; 4],
    failures: usize,
}

/// Speed errors over `strokes` seeded strokes. `tilt_back` (degrees range) adds the
/// pendulum tilt; `aided` uses the pitch channel. Each stroke, its speed error (m/s)
/// and the stream index where the estimator's rest ended go to `check`.
fn run(
    fs: f64,
    noise_mg: f64,
    strokes: usize,
    seed: u64,
    tilt_deg: Option<(f64, f64)>,
    aided: bool,
    mut check: impl FnMut(&Stroke, f64, usize),
) -> Figures {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = noise_mg * 1e-3 * G;
    let (mut sum, mut sum_sq, mut max_abs) = (0.0, 0.0, 0.0f64);
    let mut worst = None;
    let mut band_max = [0.0f64; 4];
    let mut failures = 0;
    for _ in 0..strokes {
        let mut stroke = Stroke::random(&mut rng);
        if let Some((lo, hi)) = tilt_deg {
            stroke.tilt_back = rng.random_range(lo..hi).to_radians();
        }
        let (accel, pitch) = stroke.samples(fs, noise, &mut rng);
        let Some((est, offset)) = capture(&accel, &pitch, fs, aided) else {
            failures += 1;
            println!("  failed stroke: {stroke:?}");
            continue;
        };
        let rel = (f64::from(est.cue_speed) - stroke.speed) / stroke.speed;
        check(
            &stroke,
            f64::from(est.cue_speed) - stroke.speed,
            est.rest_end + offset,
        );
        sum += rel;
        sum_sq += rel * rel;
        let band = match stroke.speed {
            v if v < 1.0 => 0,
            v if v < 2.0 => 1,
            v if v < 4.0 => 2,
            _ => 3,
        };
        band_max[band] = band_max[band].max(rel.abs());
        if rel.abs() > max_abs {
            max_abs = rel.abs();
            worst = Some(stroke);
        }
    }
    let ok = (strokes - failures).max(1) as f64;
    Figures {
        count: strokes,
        max_abs,
        rms: (sum_sq / ok).sqrt(),
        mean: sum / ok,
        worst,
        band_max,
        failures,
    }
}

fn report(label: &str, noise_mg: f64, f: &Figures) {
    println!(
        "{label}: noise {noise_mg} mg RMS, {} strokes: speed error max {:.3} %, RMS {:.3} %, mean {:+.3} %, \
         failures {}",
        f.count,
        100.0 * f.max_abs,
        100.0 * f.rms,
        100.0 * f.mean,
        f.failures
    );
    println!(
        "  max by V band: [0.5,1) {:.3} %  [1,2) {:.3} %  [2,4) {:.3} %  [4,6] {:.3} %",
        100.0 * f.band_max[0],
        100.0 * f.band_max[1],
        100.0 * f.band_max[2],
        100.0 * f.band_max[3]
    );
    if let Some(w) = &f.worst {
        println!("  worst stroke: {w:?}");
    }
}

const STROKES: usize = 250;

/// The brief's figure: ~1 mg RMS at ODR/2.
#[test]
fn speed_error_within_3_percent_at_1_mg_noise() {
    let f = run(FS, 1.0, STROKES, 0x5EED_0001, None, false, |_, _, _| {});
    report("6667 Hz, accelerometer only", 1.0, &f);
    assert_eq!(f.failures, 0);
    assert!(f.max_abs <= 0.03, "max error {:.3} %", 100.0 * f.max_abs);
}

/// ST's LSM6DSO datasheet (DS12140 Rev 2, p. 10): 3.0 mg RMS at ±16 g, BW = ODR/2
/// (normal/low-power mode figure; the only one verified for this family here).
#[test]
fn speed_error_within_3_percent_at_3_mg_noise() {
    let f = run(FS, 3.0, STROKES, 0x5EED_0003, None, false, |_, _, _| {});
    report("6667 Hz, accelerometer only", 3.0, &f);
    assert_eq!(f.failures, 0);
    assert!(f.max_abs <= 0.03, "max error {:.3} %", 100.0 * f.max_abs);
}

/// Pessimistic: 130 µg/√Hz over 3.33 kHz ≈ 7.5 mg, rounded up.
#[test]
fn speed_error_within_3_percent_at_8_mg_noise() {
    let f = run(FS, 8.0, STROKES, 0x5EED_0008, None, false, |_, _, _| {});
    report("6667 Hz, accelerometer only", 8.0, &f);
    assert_eq!(f.failures, 0);
    assert!(f.max_abs <= 0.03, "max error {:.3} %", 100.0 * f.max_abs);
}

/// A pendulum stroke tilts the cue by 0.5–2° at the back. Accelerometer-only: the
/// error must be the predicted `−g ∫ (sin θ − sin θ_rest) dt` from the rest the
/// estimator chose (within 10 % + 0.5 % of V), which is far above 3 % for slow
/// strokes. Gyro-aided: back within 3 %.
#[test]
fn pendulum_tilt_needs_the_gyro() {
    let tilt = Some((0.5, 2.0));
    let mut worst_unexplained = 0.0f64;
    let plain = run(
        FS,
        8.0,
        STROKES,
        0x5EED_7117,
        tilt,
        false,
        |stroke, err, rest_end| {
            let predicted = stroke.tilt_error(rest_end, FS);
            let unexplained =
                (err - predicted).abs() / (0.1 * predicted.abs() + 0.005 * stroke.speed);
            worst_unexplained = worst_unexplained.max(unexplained);
        },
    );
    report(
        "6667 Hz, pendulum tilt 0.5-2 deg, accelerometer only",
        8.0,
        &plain,
    );
    assert_eq!(plain.failures, 0);
    assert!(
        worst_unexplained <= 1.0,
        "tilt error not explained by the first-order model: {worst_unexplained}"
    );
    let aided = run(FS, 8.0, STROKES, 0x5EED_7117, tilt, true, |_, _, _| {});
    report("6667 Hz, pendulum tilt 0.5-2 deg, gyro-aided", 8.0, &aided);
    assert_eq!(aided.failures, 0);
    assert!(
        aided.max_abs <= 0.03,
        "max error {:.3} %",
        100.0 * aided.max_abs
    );
    // The same strokes without tilt through the gyro-aided path (gyro noise and bias
    // only): the pitch channel must not cost accuracy.
    let flat = run(FS, 8.0, STROKES, 0x5EED_0008, None, true, |_, _, _| {});
    report("6667 Hz, no tilt, gyro-aided", 8.0, &flat);
    assert!(
        flat.max_abs <= 0.03,
        "max error {:.3} %",
        100.0 * flat.max_abs
    );
}

/// The same strokes sampled at 3333 Hz (the lowest rate the issue allows) and 1667 Hz:
/// the estimator's windows scale with the rate; the error grows with the sample period
/// (the impact onset is located to one sample).
#[test]
fn lower_sample_rates() {
    for (fs, limit) in [(3333.0, 0.03), (1667.0, 0.03)] {
        let f = run(fs, 8.0, STROKES, 0x5EED_0008, None, false, |_, _, _| {});
        report(&format!("{fs} Hz, accelerometer only"), 8.0, &f);
        assert_eq!(f.failures, 0);
        assert!(
            f.max_abs <= limit,
            "{fs} Hz: max error {:.3} %",
            100.0 * f.max_abs
        );
    }
}
