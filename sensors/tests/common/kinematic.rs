//! The kinematic stroke model (minimum-jerk phases, tip contact and ringing, pendulum
//! tilt, noise, bias; `tests/synthetic_strokes.rs` describes it), included by path by
//! `tests/synthetic_strokes.rs`, `tests/streaming.rs` and the live-trace generator
//! (`host-tests/src/live_trace.rs`). Beyond one stroke: samples up to any time (a
//! stroke followed by its follow-through and a pause, for continuous streams), a second
//! tip contact (a double hit), and the truth the tests compare with (contact sample,
//! speed). `tests/glitch.rs` keeps its own accelerometer-only copy: it draws the noise
//! without the gyro channel, so the same seeds give other samples there.
#![allow(dead_code)]

use cuesight_sensors::lsm6dsox::{ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

pub const G: f64 = 9.80665;
pub const BALL_MASS: f64 = 0.17;

/// One synthetic stroke.
#[derive(Clone, Debug)]
pub struct Stroke {
    pub speed: f64,
    pub settle: Option<(f64, f64)>, // (distance m, duration s)
    pub rest: f64,
    pub back: (f64, f64), // (distance m, duration s)
    pub pause: f64,
    pub forward: (f64, f64), // (duration s, w)
    pub contact: f64,        // s
    pub delta_v: f64,        // cue speed lost in the contact, m/s
    pub ring: (f64, f64),    // (amplitude m/s², frequency Hz)
    pub follow: f64,         // s
    pub elevation: f64,      // cue elevation at rest, rad
    pub bias: f64,           // accelerometer bias, m/s²
    pub tilt_back: f64,      // elevation gained at the back of the backswing, rad
    pub gyro_bias: f64,      // rad/s
    /// Addition: a second tip contact `(delay after the first s, Δv m/s)`, same shape.
    pub second_hit: Option<(f64, f64)>,
}

pub fn min_jerk_velocity(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance / duration * 30.0 * s * s * (1.0 - s) * (1.0 - s)
}

pub fn min_jerk_position(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
}

pub fn min_jerk_acceleration(distance: f64, duration: f64, t: f64) -> f64 {
    let s = t / duration;
    distance / (duration * duration) * 60.0 * s * (1.0 - s) * (1.0 - 2.0 * s)
}

impl Stroke {
    pub fn random(rng: &mut ChaCha8Rng) -> Self {
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
            second_hit: None,
        }
    }

    /// Cue displacement from address (m), zero before the backswing; held after contact.
    pub fn position(&self, t: f64) -> f64 {
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
    pub fn tilt(&self, t: f64) -> f64 {
        if self.tilt_back == 0.0 {
            return self.elevation;
        }
        let x = self.position(t);
        self.elevation + self.tilt_back * (x / self.back.0).powi(2)
    }

    /// Predicted accelerometer-only speed error (m/s) when the estimator takes the cue
    /// to be at rest up to sample `rest_end`: `−g ∫ (sin θ − sin θ_rest) dt` from there
    /// to contact, on the generator's sample grid.
    pub fn tilt_error(&self, rest_end: usize, fs: f64) -> f64 {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        let n = (contact * fs) as usize;
        let rest = self.tilt(rest_end as f64 * dt).sin();
        (rest_end..n)
            .map(|k| -G * (self.tilt((k as f64 + 0.5) * dt).sin() - rest) * dt)
            .sum()
    }

    /// Phase boundaries: (settle end, back start, back end, forward start, contact).
    pub fn times(&self) -> [f64; 5] {
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
    pub fn velocity(&self, t: f64) -> f64 {
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
    pub fn acceleration(&self, t: f64) -> f64 {
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
            let second = match self.second_hit {
                Some((delay, dv))
                    if u + self.contact >= delay && u + self.contact < delay + self.contact =>
                {
                    let w = u + self.contact - delay;
                    -dv * pi / (2.0 * self.contact) * (pi * w / self.contact).sin()
                }
                _ => 0.0,
            };
            ring + follow + second
        }
    }

    /// Raw accelerometer and pitch-rate words at `fs` until 100 ms after contact.
    pub fn samples(&self, fs: f64, noise_rms: f64, rng: &mut ChaCha8Rng) -> (Vec<i16>, Vec<i16>) {
        self.samples_to(self.times()[4] + 0.1, fs, noise_rms, rng)
    }

    /// Addition: as [`Self::samples`] (the same draws), up to time `end` (s).
    pub fn samples_to(
        &self,
        end: f64,
        fs: f64,
        noise_rms: f64,
        rng: &mut ChaCha8Rng,
    ) -> (Vec<i16>, Vec<i16>) {
        let contact = self.times()[4];
        let dt = 1.0 / fs;
        let n = (end * fs) as usize;
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
pub fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

// ---- Additions (not in `synthetic_strokes.rs`) ----

impl Stroke {
    /// The first sample touched by the tip contact: the one whose period holds its start.
    pub fn contact_sample(&self, fs: f64) -> usize {
        (self.times()[4] * fs) as usize
    }

    /// Time from the start of the stroke's samples to the end of its follow-through (s).
    pub fn end_of_follow_through(&self) -> f64 {
        self.times()[4] + self.contact + self.follow
    }

    /// How far the cue travels from the contact instant until it stops (m), from the
    /// model's motion in [`Self::acceleration`]: through the contact a half-sine
    /// deceleration from `speed` to `after = speed − delta_v` (mean velocity
    /// `(speed + after)/2`), then a half-sine deceleration from `after` to 0 over `follow`
    /// (mean velocity `after/2`). The ringing is taken as the tip's vibration, not as
    /// travel: its net velocity, `A ω / (ω² + τ⁻²)` ≈ 0.02–0.09 m/s for the model's
    /// amplitudes `A` and frequencies `ω` (`τ` = 3 ms), would otherwise never stop the cue.
    pub fn follow_through_length(&self) -> f64 {
        let after = self.speed - self.delta_v;
        0.5 * (self.speed + after) * self.contact + 0.5 * after * self.follow
    }

    /// Time from the contact instant until the cue is slower than `slow` (m/s): after the
    /// contact `v(u) = after (1 + cos(π u / follow)) / 2`, so `u = follow/π · acos(2 slow /
    /// after − 1)`.
    pub fn follow_through_time(&self, slow: f64) -> f64 {
        let after = self.speed - self.delta_v;
        let u = if after > slow {
            self.follow / std::f64::consts::PI * (2.0 * slow / after - 1.0).acos()
        } else {
            0.0
        };
        self.contact + u
    }
}

/// One stroke of a continuous stream, with the truth.
#[derive(Clone, Debug)]
pub struct Truth {
    pub stroke: Stroke,
    /// Stream index of the first contact sample.
    pub contact: usize,
    /// Cue speed at contact (m/s).
    pub speed: f64,
}

/// A continuous stream: the strokes' samples one after the other, each from its own
/// start (settling move or address) to `pause` seconds after its follow-through ends.
/// The accelerometer bias and gyro bias of the first stroke are used for all (one
/// sensor), and each stroke starts at the elevation the previous one ended with (one
/// cue, no step the gyro would not see).
pub fn stream(
    strokes: &[(Stroke, f64)],
    fs: f64,
    noise_rms: f64,
    rng: &mut ChaCha8Rng,
) -> (Vec<i16>, Vec<i16>, Vec<Truth>) {
    let (mut accel, mut pitch, mut truth) = (Vec::new(), Vec::new(), Vec::new());
    let (bias, gyro_bias) = strokes
        .first()
        .map_or((0.0, 0.0), |(s, _)| (s.bias, s.gyro_bias));
    let mut elevation = strokes.first().map_or(0.0, |(s, _)| s.elevation);
    for (stroke, pause) in strokes {
        let stroke = Stroke {
            bias,
            gyro_bias,
            elevation,
            ..stroke.clone()
        };
        elevation = stroke.tilt(stroke.end_of_follow_through());
        let offset = accel.len();
        let end = stroke.end_of_follow_through() + pause;
        let (a, p) = stroke.samples_to(end, fs, noise_rms, rng);
        accel.extend(a);
        pitch.extend(p);
        truth.push(Truth {
            contact: offset + stroke.contact_sample(fs),
            speed: stroke.speed,
            stroke,
        });
    }
    (accel, pitch, truth)
}

/// Silence the unused-import lint when a test uses only part of the model.
pub const SCALES: (f32, f32) = (ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB);

/// Draw `rng.random_range(lo..hi)` (a helper for the tests' own stroke variations).
pub fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    rng.random_range(lo..hi)
}

/// A stroke of the streaming acceptance sets (`tests/streaming.rs`,
/// `tests/stroke_metrics.rs`): the model's draw, then an address of 0.25–3 s, a pause at
/// the back of 0–1.5 s and a pendulum tilt of 0.5–2° (1–6 s per stroke), and the still
/// gap of 0.5–3 s after it.
pub fn acceptance_stroke(rng: &mut ChaCha8Rng) -> (Stroke, f64) {
    let mut stroke = Stroke::random(rng);
    stroke.rest = rng.random_range(0.25..3.0);
    stroke.pause = rng.random_range(0.0..1.5);
    stroke.tilt_back = rng.random_range(0.5f64..2.0).to_radians();
    let gap = rng.random_range(0.5..3.0);
    (stroke, gap)
}

/// One continuous stream of the streaming acceptance set, with its truth.
pub struct AcceptanceStream {
    /// RMS accelerometer noise (mg).
    pub noise_mg: f64,
    pub accel: Vec<i16>,
    pub pitch: Vec<i16>,
    pub truth: Vec<Truth>,
}

/// The streaming acceptance set at `fs` (`tests/streaming.rs`, `tests/stroke_metrics.rs`,
/// `tests/follow_through.rs`): 120 [`acceptance_stroke`]s in 12 continuous streams of
/// 10, six at 3 mg RMS noise and six at 8 mg, each half drawn from its own seed.
pub fn acceptance_streams(fs: f64) -> Vec<AcceptanceStream> {
    use rand::SeedableRng;
    let mut streams = Vec::new();
    for (noise_mg, seed) in [(3.0, 0x5712_0003u64), (8.0, 0x5712_0008)] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for _ in 0..6 {
            let strokes: Vec<_> = (0..10).map(|_| acceptance_stroke(&mut rng)).collect();
            let noise = noise_mg * 1e-3 * G;
            let (accel, pitch, truth) = stream(&strokes, fs, noise, &mut rng);
            streams.push(AcceptanceStream {
                noise_mg,
                accel,
                pitch,
                truth,
            });
        }
    }
    streams
}
