//! Property tests (proptest) of the sensors crate over its valid domain (issue 6, item 3).
//!
//! 1. `ring_behaves_like_a_bounded_deque`: capacities 0, 1, 2, 7 and 64 under random
//!    push / try_push / clear / make_contiguous / get / copy_to sequences, against
//!    `VecDeque` kept to the last N values: the same values in the same order through
//!    every accessor, the same evictions.
//! 2. `ring_holds_the_last_n_pushed`: 0 to 3N values into rings of 1, 3, 16 and 24,000
//!    (the capture ring): exactly the last `min(n, N)` in push order, also after
//!    `make_contiguous`.
//! 3. `trigger_fires_iff_the_threshold_is_crossed`: random thresholds (1e-3–1e3 m/s²
//!    log-uniform, the smallest subnormal, 8 g, `f32::MAX`), post-impact counts (0–40,
//!    `usize::MAX`) and sample sequences that dwell on `−threshold` and its f32
//!    neighbours, NaN and ±∞, with re-arming: `push` is `true` exactly from the
//!    `post`-th sample after the first one strictly below `−threshold`, `is_triggered`
//!    from that first one (the model is written here from the documentation).
//! 4. `driver_decodes_any_bytes`: random output bytes, status byte, reset-poll count
//!    (1–100) and trim byte through the mock bus: words are the little-endian i16 at
//!    their documented registers, SI values are word × sensitivity, the ODR is
//!    `6667 × (1 + 0.0015 × (i8)trim)`.
//! 5. `estimator_answers_any_window_within_its_contract`: random raw windows (stroke-like
//!    — rest, up to five moves, an impact — or arbitrary words, rails included), rates
//!    500 Hz–100 kHz, scales of either sign, every valid configuration, with and
//!    without a pitch series: no panic; never `InvalidConfig`, `NotFinite` or
//!    `LengthMismatch` (the inputs are valid); `TooShort` exactly below the minimum
//!    length; an `Ok` estimate passes the documented contract: every field finite, a
//!    speed > 0, `rest_start < rest_end ≤ impact_index < n`, the duration, no sample
//!    before the impact below `bias − impact_threshold` and one within the four after
//!    it (step 4), none at the 99.9 % rail (step 5), the bias and rest noise the mean and
//!    standard deviation of the rest window (f64, to rounding) and, accelerometer-only,
//!    the speed `Σ (a_i − bias) Δt` over `[rest_end, impact_index)` (f64, to the f32
//!    rounding bound); the strike model takes every speed up to 20 m/s and refuses
//!    beyond it.
//! 6. `estimator_recovers_piecewise_strokes_exactly`: random piecewise-constant strokes
//!    (level ±2 g, rest 0.25–0.5 s, one to four moves of ±50 m/s² — backwards,
//!    forwards, pauses — no move longer than the rest, a coast or none, a 10–60 g impact)
//!    at 500 Hz–100 kHz, in f32 and as raw words: the speed is the exact
//!    `Σ (a_i − level) Δt` of the stored samples to the f32 rounding bound, the impact
//!    index is the impact's first sample, the rest ends before the stroke; `NotForward`
//!    exactly when that speed is negative; the gyro-aided estimators with a zero pitch
//!    rate give bit for bit the same answer.
//! 7. `raw_estimate_is_exactly_scale_covariant`: the windows of 5 with the scale and every
//!    acceleration setting multiplied by 2^k (k in −10…10): the same answer with the
//!    speed, bias and noise multiplied by 2^k bit for bit (every step of the estimator
//!    commutes with a power-of-two scaling when nothing overflows or goes subnormal),
//!    the same indices, the same error.
//! 8. `constant_pitch_rate_is_removed_as_gyro_bias`: the windows of 6 with a constant
//!    pitch rate up to ±2000 dps: the same indices as without it, the speed within the
//!    rounding of the gyro bias, `8ε g |ω| T²`.
//!
//! Cases are drawn as uniform `u32` arrays and decoded in test code (as in `core/tests`):
//! shrinking still works on the integers. Seeds are fixed; `PROPTEST_CASES` /
//! `PROPTEST_RNG_SEED` override; failures persist to
//! `tests/properties.proptest-regressions`. `-- --nocapture` prints the figures.

mod common;

use common::*;
use cuesight::strike::{Cue, TipOffset};
use cuesight::{Error as CoreError, Field, Params};
use cuesight_figures::thousands;
use cuesight_sensors::lsm6dsox::{trimmed_odr_hz, DataReady, STANDARD_GRAVITY};
use cuesight_sensors::{
    estimate, estimate_raw, estimate_raw_with_pitch, estimate_with_pitch, Axis, ImpactTrigger,
    Lsm6dsox, RingBuffer, StrokeConfig, StrokeError, StrokeEstimate, ACCEL_MPS2_PER_LSB,
    GYRO_RADPS_PER_LSB,
};
use embedded_hal_mock::eh1::i2c::{Mock, Transaction};
use proptest::prelude::*;
use proptest::test_runner::{contextualize_config, TestCaseError, TestRunner};
use std::cell::RefCell;
use std::collections::{BTreeMap, VecDeque};

const RING_CASES: u32 = 10_000;
const RING_LAST_CASES: u32 = 1_000;
const TRIGGER_CASES: u32 = 50_000;
const DRIVER_CASES: u32 = 10_000;
const WINDOW_CASES: u32 = 30_000;
const PIECEWISE_CASES: u32 = 12_000;
const COVARIANCE_CASES: u32 = 10_000;
const PITCH_CASES: u32 = 4_000;

type Raw = [u32; 16];

fn unit(x: u32) -> f64 {
    x as f64 / 4_294_967_296.0
}

fn uniform(x: u32, lo: f64, hi: f64) -> f64 {
    lo + unit(x) * (hi - lo)
}

fn log_uniform(x: u32, lo: f64, hi: f64) -> f64 {
    (lo.ln() + unit(x) * (hi.ln() - lo.ln())).exp()
}

/// Pick an index by weights.
fn pick(x: u32, weights: &[u32]) -> usize {
    let total: u32 = weights.iter().sum();
    let mut u = (unit(x) * total as f64) as u32;
    for (i, &w) in weights.iter().enumerate() {
        if u < w {
            return i;
        }
        u -= w;
    }
    weights.len() - 1
}

/// 64-bit LCG for the bulk content of a case, seeded from the draw.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 32) as u32
    }

    /// Uniform integer in `[-amplitude, amplitude]`.
    fn noise(&mut self, amplitude: i32) -> i32 {
        if amplitude == 0 {
            return 0;
        }
        (self.next() % (2 * amplitude as u32 + 1)) as i32 - amplitude
    }
}

fn runner(test: &'static str, cases: u32, seed: u64) -> TestRunner {
    let mut config = contextualize_config(config(cases, seed));
    config.source_file = Some(file!());
    config.test_name = Some(test);
    TestRunner::new(config)
}

fn fail(message: String) -> TestCaseError {
    TestCaseError::fail(message)
}

// ---------------------------------------------------------------------------------------
// 1–2. Ring buffer
// ---------------------------------------------------------------------------------------

/// One ring operation.
#[derive(Clone, Copy, Debug)]
enum Op {
    Push(i32),
    TryPush(i32),
    Clear,
    MakeContiguous,
    Get(usize),
    CopyTo(usize),
}

fn op(x: u32, y: u32) -> Op {
    match pick(x, &[60, 15, 3, 8, 8, 6]) {
        0 => Op::Push(y as i32),
        1 => Op::TryPush(y as i32),
        2 => Op::Clear,
        3 => Op::MakeContiguous,
        4 => Op::Get((y % 80) as usize),
        _ => Op::CopyTo((y % 80) as usize),
    }
}

fn ring_against_model<const N: usize>(ops: &[Op]) -> Result<(), TestCaseError> {
    let mut ring = RingBuffer::<i32, N>::new(i32::MIN);
    let mut model: VecDeque<i32> = VecDeque::new();
    for (k, &op) in ops.iter().enumerate() {
        let at = |what: &str| format!("N = {N}, op {k} {op:?}: {what}");
        match op {
            Op::Push(v) => {
                let want = if N == 0 {
                    Some(v)
                } else {
                    model.push_back(v);
                    if model.len() > N {
                        model.pop_front()
                    } else {
                        None
                    }
                };
                prop_assert_eq!(ring.push(v), want, "{}", at("eviction"));
            }
            Op::TryPush(v) => {
                let room = model.len() < N;
                if room {
                    model.push_back(v);
                }
                prop_assert_eq!(
                    ring.try_push(v),
                    if room { Ok(()) } else { Err(v) },
                    "{}",
                    at("")
                );
            }
            Op::Clear => {
                ring.clear();
                model.clear();
            }
            Op::MakeContiguous => {
                let got = ring.make_contiguous().to_vec();
                prop_assert_eq!(got, model.iter().copied().collect::<Vec<_>>(), "{}", at(""));
                prop_assert!(ring.as_slices().1.is_empty(), "{}", at("second slice"));
            }
            Op::Get(i) => prop_assert_eq!(ring.get(i), model.get(i).copied(), "{}", at("")),
            Op::CopyTo(len) => {
                let mut out = vec![0x5A5A; len];
                let n = ring.copy_to(&mut out);
                prop_assert_eq!(n, len.min(model.len()), "{}", at("count"));
                prop_assert!(
                    out[..n].iter().eq(model.iter().take(n))
                        && out[n..].iter().all(|&x| x == 0x5A5A),
                    "{}",
                    at("contents")
                );
            }
        }
        prop_assert_eq!(ring.len(), model.len(), "{}", at("len"));
        prop_assert_eq!(ring.is_empty(), model.is_empty());
        prop_assert_eq!(ring.is_full(), model.len() == N);
        prop_assert_eq!(ring.latest(), model.back().copied(), "{}", at("latest"));
        let (a, b) = ring.as_slices();
        prop_assert!(
            a.iter().chain(b).eq(model.iter()) && ring.iter().eq(model.iter().copied()),
            "{}",
            at("contents")
        );
    }
    Ok(())
}

#[test]
fn ring_behaves_like_a_bounded_deque() {
    let name = "ring_behaves_like_a_bounded_deque";
    let mut runner = runner(name, RING_CASES, 0x7269_6e67_0001);
    let strategy = (
        0u32..5,
        proptest::collection::vec(any::<(u32, u32)>(), 0..300),
    );
    let started = std::time::Instant::now();
    let result = runner.run(&strategy, |(capacity, draws)| {
        let ops: Vec<Op> = draws.iter().map(|&(x, y)| op(x, y)).collect();
        match capacity {
            0 => ring_against_model::<0>(&ops),
            1 => ring_against_model::<1>(&ops),
            2 => ring_against_model::<2>(&ops),
            3 => ring_against_model::<7>(&ops),
            _ => ring_against_model::<64>(&ops),
        }
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    println!(
        "{name}: {RING_CASES} cases in {:.2} s",
        started.elapsed().as_secs_f64()
    );
}

fn last_n<const N: usize>(count: usize, seed: u64) -> Result<(), TestCaseError> {
    let mut ring = Box::new(RingBuffer::<i16, N>::new(0));
    let mut rng = Lcg(seed);
    let pushed: Vec<i16> = (0..count).map(|_| rng.next() as i16).collect();
    for &w in &pushed {
        ring.push(w);
    }
    let keep = count.min(N);
    let want = &pushed[count - keep..];
    prop_assert!(
        ring.iter().eq(want.iter().copied()),
        "N = {N}, {count} pushed"
    );
    prop_assert_eq!(ring.make_contiguous(), want, "N = {}, {} pushed", N, count);
    Ok(())
}

#[test]
fn ring_holds_the_last_n_pushed() {
    let name = "ring_holds_the_last_n_pushed";
    let mut runner = runner(name, RING_LAST_CASES, 0x7269_6e67_0002);
    let started = std::time::Instant::now();
    let result = runner.run(
        &(0u32..4, any::<u32>(), any::<u64>()),
        |(which, x, seed)| {
            let fraction = unit(x) * 3.0;
            match which {
                0 => last_n::<1>((fraction * 1.0) as usize + (x % 2) as usize, seed),
                1 => last_n::<3>((fraction * 3.0) as usize, seed),
                2 => last_n::<16>((fraction * 16.0) as usize, seed),
                _ => last_n::<24_000>((fraction * 24_000.0) as usize, seed),
            }
        },
    );
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    println!(
        "{name}: {RING_LAST_CASES} cases in {:.2} s",
        started.elapsed().as_secs_f64()
    );
}

// ---------------------------------------------------------------------------------------
// 3. Impact trigger
// ---------------------------------------------------------------------------------------

#[test]
fn trigger_fires_iff_the_threshold_is_crossed() {
    let name = "trigger_fires_iff_the_threshold_is_crossed";
    let mut runner = runner(name, TRIGGER_CASES, 0x7472_6967_0001);
    let fired = RefCell::new([0usize; 2]);
    let started = std::time::Instant::now();
    let strategy = (
        any::<[u32; 3]>(),
        proptest::collection::vec(any::<(u32, u32)>(), 0..120),
    );
    let result = runner.run(&strategy, |(head, draws)| {
        let threshold = match pick(head[0], &[8, 1, 1, 1]) {
            0 => log_uniform(head[1], 1e-3, 1e3) as f32,
            1 => f32::from_bits(1),
            2 => 8.0 * STANDARD_GRAVITY,
            _ => f32::MAX,
        };
        let post = match pick(head[2], &[3, 3, 10, 1]) {
            0 => 0,
            1 => 1,
            2 => (head[2] % 41) as usize,
            _ => usize::MAX,
        };
        let mut trigger = ImpactTrigger::new(threshold, post)
            .map_err(|e| fail(format!("valid threshold refused: {e}")))?;
        // The model: the index of the first sample strictly below −threshold since the
        // last re-arm; complete from `post` samples after it.
        let mut first: Option<usize> = None;
        let mut since = 0usize; // samples since the last re-arm
        for &(x, y) in &draws {
            if x % 97 == 0 {
                trigger.reset();
                first = None;
                since = 0;
                prop_assert!(!trigger.is_triggered());
                continue;
            }
            let t = -threshold;
            let sample = match pick(x, &[4, 4, 4, 6, 1, 1, 1, 2]) {
                0 => t,
                1 => next_up(t),
                2 => next_down(t),
                3 => (uniform(y, -2.0, 2.0) * f64::from(threshold)) as f32,
                4 => f32::NAN,
                5 => f32::INFINITY,
                6 => f32::NEG_INFINITY,
                _ => 0.0,
            };
            if first.is_none() && sample < t {
                first = Some(since);
            }
            let want = first.is_some_and(|k| since - k >= post);
            let got = trigger.push(sample);
            prop_assert_eq!(
                got,
                want,
                "threshold {:e}, post {}, sample {:e} at {} (first crossing {:?})",
                threshold,
                post,
                sample,
                since,
                first
            );
            prop_assert_eq!(trigger.is_triggered(), first.is_some());
            since += 1;
        }
        fired.borrow_mut()[usize::from(first.is_some())] += 1;
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    let [quiet, triggered] = fired.into_inner();
    println!(
        "{name}: {TRIGGER_CASES} cases in {:.2} s ({triggered} ended triggered, {quiet} not)",
        started.elapsed().as_secs_f64()
    );
    assert!(triggered > 1000 && quiet > 100);
}

// ---------------------------------------------------------------------------------------
// 4. Driver
// ---------------------------------------------------------------------------------------

#[test]
fn driver_decodes_any_bytes() {
    let name = "driver_decodes_any_bytes";
    let mut runner = runner(name, DRIVER_CASES, 0x696d_7500_0001);
    let started = std::time::Instant::now();
    let strategy = (
        any::<[u8; 12]>(),
        any::<[u8; 2]>(),
        0usize..3,
        any::<u8>(),
        1usize..=100,
        any::<u8>(),
        any::<bool>(),
    );
    let result = runner.run(
        &strategy,
        |(block, word, axis, status, polls, trim, high)| {
            let address = if high { 0x6B } else { 0x6A };
            let axis_reg = [0x28u8, 0x2A, 0x2C][axis];
            let mut t = vec![
                Transaction::write_read(address, vec![0x0F], vec![0x6C]),
                Transaction::write(address, vec![0x12, 0x01]),
            ];
            // SW_RESET (bit 0) still set on every poll but the last; other bits random.
            for k in 0..polls {
                let bit = u8::from(k + 1 < polls);
                t.push(Transaction::write_read(
                    address,
                    vec![0x12],
                    vec![(status & 0xFE) | bit],
                ));
            }
            t.extend([
                Transaction::write(address, vec![0x12, 0x44]),
                Transaction::write(address, vec![0x18, 0xE2]),
                Transaction::write(address, vec![0x10, 0xA4]),
                Transaction::write(address, vec![0x11, 0xAC]),
                Transaction::write_read(address, vec![0x63], vec![trim]),
                Transaction::write_read(address, vec![0x22], block.to_vec()),
                Transaction::write_read(address, vec![axis_reg], word.to_vec()),
                Transaction::write_read(address, vec![0x1E], vec![status]),
            ]);
            let mut i2c = Mock::new(&t);
            let mut imu = Lsm6dsox::new(i2c.clone(), address);
            imu.init().map_err(|e| fail(format!("init: {e}")))?;
            let odr = 6667.0 * (1.0 + 0.0015 * f64::from(trim as i8));
            prop_assert!((f64::from(imu.odr_hz()) - odr).abs() <= 4.0 * EPS32 * odr);
            prop_assert_eq!(imu.odr_hz(), trimmed_odr_hz(trim));
            let raw = imu.read_raw().map_err(|e| fail(format!("{e}")))?;
            let w = |i: usize| i16::from_le_bytes([block[2 * i], block[2 * i + 1]]);
            prop_assert_eq!(raw.gyro, [w(0), w(1), w(2)]);
            prop_assert_eq!(raw.accel, [w(3), w(4), w(5)]);
            let si = raw.to_si();
            for i in 0..3 {
                let (g, a) = (f64::from(raw.gyro[i]), f64::from(raw.accel[i]));
                let g_want = g * 70.0e-3 * std::f64::consts::PI / 180.0;
                let a_want = a * 0.488e-3 * G;
                prop_assert!((f64::from(si.gyro[i]) - g_want).abs() <= 2.0 * EPS32 * g_want.abs());
                prop_assert!((f64::from(si.accel[i]) - a_want).abs() <= 2.0 * EPS32 * a_want.abs());
            }
            let got = imu
                .read_accel_axis_raw([Axis::X, Axis::Y, Axis::Z][axis])
                .map_err(|e| fail(format!("{e}")))?;
            prop_assert_eq!(got, i16::from_le_bytes(word));
            let ready = imu.data_ready().map_err(|e| fail(format!("{e}")))?;
            prop_assert_eq!(
                ready,
                DataReady {
                    accel: status & 1 != 0,
                    gyro: status & 2 != 0,
                    temperature: status & 4 != 0
                }
            );
            i2c.done();
            Ok(())
        },
    );
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    println!(
        "{name}: {DRIVER_CASES} cases in {:.2} s",
        started.elapsed().as_secs_f64()
    );
}

// ---------------------------------------------------------------------------------------
// 5, 7. Arbitrary windows
// ---------------------------------------------------------------------------------------

/// A raw window from the valid domain.
#[derive(Clone, Debug)]
struct Window {
    rate: f32,
    scale: f32,
    pitch_scale: f32,
    config: StrokeConfig,
    accel: Vec<i16>,
    pitch: Vec<i16>,
}

/// At most this many samples per window (about 1.8 s at 6667 Hz).
const MAX_WINDOW: usize = 12_000;

impl Window {
    /// Rate: 6667 or 3333 Hz, or log-uniform 500 Hz–100 kHz; scale the LSM6DSOX's, its
    /// negative, or 1e-4–1e-1 m/s² per LSB of either sign; configuration the defaults
    /// (with the full scale following the scale, as the firmware sets it, or +∞), or
    /// every setting drawn within physical ranges. Content: stroke-like (a rest of
    /// 0–0.6 s at a level within ±2 g with 0–40 LSB of noise, one to five moves of
    /// 2–250 ms at any word or at a rail with noise, an impact 8–60 g below the level
    /// most of the time, a tail), or up to eight arbitrary segments (constant, noise,
    /// ramps, alternating rails, random words). Pitch: none, zero, constant, noise or
    /// random words.
    fn decode(r: Raw) -> Window {
        let rate = match pick(r[0], &[3, 2, 5]) {
            0 => 6667.0,
            1 => 3333.0,
            _ => log_uniform(r[1], 500.0, 100_000.0) as f32,
        };
        let scale = match pick(r[2], &[6, 2, 2]) {
            0 => ACCEL_MPS2_PER_LSB,
            1 => -ACCEL_MPS2_PER_LSB,
            _ => {
                let s = log_uniform(r[3], 1e-4, 1e-1) as f32;
                if r[3] & 1 == 0 {
                    s
                } else {
                    -s
                }
            }
        };
        let mut config = StrokeConfig::new(rate);
        match pick(r[4], &[4, 2, 4]) {
            0 => config.full_scale = 32768.0 * scale.abs(),
            1 => config.full_scale = f32::INFINITY,
            _ => {
                let mut x = Lcg(u64::from(r[4]) << 32 | u64::from(r[5]));
                let g = f64::from(STANDARD_GRAVITY);
                config.impact_threshold = (uniform(x.next(), 2.0, 15.0) * g) as f32;
                config.onset_drop = (uniform(x.next(), 0.1, 3.0) * g) as f32;
                config.min_rest = uniform(x.next(), 0.05, 0.3) as f32;
                config.rest_noise_limit = log_uniform(x.next(), 0.05, 2.0) as f32;
                config.rest_level_tolerance = log_uniform(x.next(), 0.01, 0.5) as f32;
                config.motion_floor = log_uniform(x.next(), 0.005, 0.2) as f32;
                config.cue_elevation = uniform(x.next(), -1.2, 1.2) as f32;
                config.full_scale = match x.next() % 3 {
                    0 => f32::INFINITY,
                    1 => 32768.0 * scale.abs(),
                    _ => (uniform(x.next(), 4.0, 32.0) * g) as f32,
                };
            }
        }
        if config.full_scale.partial_cmp(&config.impact_threshold)
            != Some(std::cmp::Ordering::Greater)
        {
            config.full_scale = f32::INFINITY;
        }
        let samples = |seconds: f64| ((seconds * f64::from(rate)) as usize).max(1);
        let lsb = |m_s2: f64| (m_s2 / f64::from(scale)).round().clamp(-32768.0, 32767.0) as i32;
        let mut rng = Lcg(u64::from(r[6]) << 32 | u64::from(r[7]));
        let mut accel: Vec<i16> = Vec::new();
        let push = |accel: &mut Vec<i16>, word: i32, count: usize| {
            for _ in 0..count.min(MAX_WINDOW.saturating_sub(accel.len())) {
                accel.push(word.clamp(-32768, 32767) as i16);
            }
        };
        if pick(r[8], &[7, 3]) == 0 {
            let g = f64::from(STANDARD_GRAVITY);
            let level = lsb(uniform(r[9], -2.0, 2.0) * g);
            let noise = (r[10] % 41) as i32;
            for _ in 0..samples(uniform(r[11], 0.0, 0.6)) {
                let w = level + rng.noise(noise);
                push(&mut accel, w, 1);
            }
            for _ in 0..1 + r[12] % 5 {
                let count = samples(uniform(rng.next(), 0.002, 0.25));
                let target = match rng.next() % 6 {
                    0 => 32767,
                    1 => -32768,
                    _ => level + lsb(uniform(rng.next(), -8.0, 8.0) * g),
                };
                let jitter = (rng.next() % 300) as i32;
                for _ in 0..count {
                    let w = target + rng.noise(jitter);
                    push(&mut accel, w, 1);
                }
            }
            if r[13] % 5 != 0 {
                let depth = lsb(-uniform(rng.next(), 8.0, 60.0) * g);
                let count = 3 + (rng.next() % 8) as usize;
                push(&mut accel, level + depth, count);
            }
            let tail = samples(uniform(rng.next(), 0.0, 0.05));
            for _ in 0..tail {
                let w = level + rng.noise(2000);
                push(&mut accel, w, 1);
            }
        } else {
            for _ in 0..1 + r[9] % 8 {
                let count = (rng.next() % 3000) as usize;
                let base = rng.next() as i16 as i32;
                match rng.next() % 5 {
                    0 => push(&mut accel, base, count),
                    1 => {
                        let a = (rng.next() % 3000) as i32;
                        for _ in 0..count {
                            let w = base + rng.noise(a);
                            push(&mut accel, w, 1);
                        }
                    }
                    2 => {
                        for k in 0..count {
                            push(&mut accel, base + (k as i32 * 37) % 20_000, 1);
                        }
                    }
                    3 => {
                        for k in 0..count {
                            push(&mut accel, if k % 2 == 0 { -32768 } else { 32767 }, 1);
                        }
                    }
                    _ => {
                        for _ in 0..count {
                            let w = rng.next() as i16 as i32;
                            push(&mut accel, w, 1);
                        }
                    }
                }
            }
        }
        let n = accel.len();
        let pitch = match pick(r[14], &[3, 2, 2, 1]) {
            0 => vec![0; n],
            1 => vec![(r[15] % 2001) as i16 - 1000; n],
            2 => (0..n).map(|_| rng.noise(50) as i16).collect(),
            _ => (0..n).map(|_| rng.next() as i16).collect(),
        };
        Window {
            rate,
            scale,
            pitch_scale: GYRO_RADPS_PER_LSB,
            config,
            accel,
            pitch,
        }
    }

    /// The f32 samples the estimator sees.
    fn samples(&self) -> Vec<f32> {
        self.accel
            .iter()
            .map(|&w| f32::from(w) * self.scale)
            .collect()
    }
}

/// Outcome counts for the report.
#[derive(Default, Debug)]
struct Outcomes {
    counts: BTreeMap<&'static str, usize>,
    worst_step5: f64,
}

fn kind(r: &Result<StrokeEstimate, StrokeError>) -> &'static str {
    match r {
        Ok(_) => "ok",
        Err(StrokeError::InvalidConfig(_)) => "InvalidConfig",
        Err(StrokeError::TooShort { .. }) => "TooShort",
        Err(StrokeError::NotFinite { .. }) => "NotFinite",
        Err(StrokeError::NotAtRest) => "NotAtRest",
        Err(StrokeError::NoImpact) => "NoImpact",
        Err(StrokeError::Saturated { .. }) => "Saturated",
        Err(StrokeError::NotForward { .. }) => "NotForward",
        Err(StrokeError::LengthMismatch { .. }) => "LengthMismatch",
        Err(StrokeError::Strike(_)) => "Strike",
    }
}

/// The documented contract of an answer for a valid window (see the module docs, 5).
fn check_answer(
    w: &Window,
    samples: &[f32],
    got: &Result<StrokeEstimate, StrokeError>,
    min: usize,
    with_pitch: bool,
    out: &mut Outcomes,
) -> Result<(), TestCaseError> {
    let n = samples.len();
    let c = &w.config;
    match got {
        Err(StrokeError::TooShort { len, min: m }) => {
            prop_assert!(
                *len as usize == n && *m as usize == min && n < min,
                "{:?}",
                got
            )
        }
        _ if n < min => return Err(fail(format!("{n} < {min} samples not TooShort: {got:?}"))),
        Err(StrokeError::NotForward { speed }) => {
            prop_assert!(speed.is_finite() && *speed <= 0.0, "{:?}", got)
        }
        Err(StrokeError::NotAtRest | StrokeError::NoImpact) => {}
        Err(StrokeError::Saturated { index }) => {
            let rail = 0.999 * c.full_scale;
            let index = *index as usize;
            prop_assert!(index < n && samples[index].abs() >= rail, "{:?}", got);
        }
        Err(e) => return Err(fail(format!("a valid input refused: {e:?}"))),
        Ok(e) => {
            check_estimate(e, n, w.rate, with_pitch).map_err(fail)?;
            // Step 4: the first sample below bias − threshold after the rest, the onset
            // at most four samples before it.
            let limit = e.bias - c.impact_threshold;
            let before = &samples[e.rest_end..e.impact_index];
            prop_assert!(
                before.iter().all(|&a| a >= limit),
                "a crossing before the impact: {:?}",
                e
            );
            let after = &samples[e.impact_index..(e.impact_index + 5).min(n)];
            prop_assert!(
                after.iter().any(|&a| a < limit),
                "no crossing at the impact: {:?}",
                e
            );
            // Step 5: nothing integrated at the rail.
            let rail = 0.999 * c.full_scale;
            prop_assert!(
                before.iter().all(|&a| a.abs() < rail),
                "a saturated sample: {:?}",
                e
            );
            // Step 3: bias and noise are the mean and deviation of the rest window.
            let rest = &samples[e.rest_start..e.rest_end];
            let count = rest.len() as f64;
            let mean = rest.iter().map(|&a| f64::from(a)).sum::<f64>() / count;
            let spread = (rest
                .iter()
                .map(|&a| (f64::from(a) - mean).powi(2))
                .sum::<f64>()
                / count)
                .sqrt();
            let size = rest.iter().map(|&a| f64::from(a).abs()).fold(0.0, f64::max);
            prop_assert!(
                (f64::from(e.bias) - mean).abs() <= 8.0 * EPS32 * size,
                "bias {} vs mean {mean}",
                e.bias
            );
            prop_assert!(
                (f64::from(e.rest_noise) - spread).abs() <= 1e-5 * spread + 8.0 * EPS32 * size,
                "noise {} vs {spread}",
                e.rest_noise
            );
            if !with_pitch {
                let (v, bound) = step5(samples, e, w.rate);
                let err = (f64::from(e.cue_speed) - v).abs();
                prop_assert!(
                    err <= bound,
                    "speed {} vs {v} (bound {bound:e})",
                    e.cue_speed
                );
                if bound > 0.0 {
                    out.worst_step5 = out.worst_step5.max(err / bound);
                }
            }
            // The strike model takes every speed up to 20 m/s.
            let hit = e.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE);
            match hit {
                Ok(h) if e.cue_speed <= 20.0 => prop_assert!(
                    h.speed.is_finite() && h.spin.to_array().iter().all(|x| x.is_finite()),
                    "{:?}",
                    h
                ),
                Err(StrokeError::Strike(CoreError::OutOfRange {
                    field: Field::CueSpeed,
                    value,
                })) if e.cue_speed > 20.0 => prop_assert_eq!(value, e.cue_speed),
                other => return Err(fail(format!("strike of {}: {other:?}", e.cue_speed))),
            }
        }
    }
    *out.counts.entry(kind(got)).or_default() += 1;
    Ok(())
}

#[test]
fn estimator_answers_any_window_within_its_contract() {
    let name = "estimator_answers_any_window_within_its_contract";
    let mut runner = runner(name, WINDOW_CASES, 0x7769_6e64_0001);
    let outcomes = RefCell::new([Outcomes::default(), Outcomes::default()]);
    let started = std::time::Instant::now();
    let result = runner.run(&any::<Raw>().prop_map(Window::decode), |w| {
        let Err(StrokeError::TooShort { min, .. }) = estimate(&[], &w.config) else {
            return Err(fail("an empty window was not TooShort".into()));
        };
        let samples = w.samples();
        let mut out = outcomes.borrow_mut();
        let plain = estimate_raw(&w.accel, w.scale, &w.config);
        check_answer(&w, &samples, &plain, min as usize, false, &mut out[0])?;
        let aided = estimate_raw_with_pitch(&w.accel, w.scale, &w.pitch, w.pitch_scale, &w.config);
        check_answer(&w, &samples, &aided, min as usize, true, &mut out[1])?;
        // The pitch series changes the speed only: the rest and the impact are the
        // accelerometer's.
        if let (Ok(a), Ok(b)) = (&plain, &aided) {
            prop_assert_eq!(
                (a.rest_start, a.rest_end, a.impact_index),
                (b.rest_start, b.rest_end, b.impact_index)
            );
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    let [plain, aided] = outcomes.into_inner();
    println!(
        "{name}: {WINDOW_CASES} cases in {:.2} s\n  accelerometer only: {:?}, step 5 within {:.3} of its bound\n  gyro-aided: {:?}",
        started.elapsed().as_secs_f64(),
        plain.counts,
        plain.worst_step5,
        aided.counts
    );
    cuesight_figures::record!(
        "reliability-sensors-window-step5",
        "{:.2}",
        plain.worst_step5
    );
    // The domain must reach every kind of answer the windows can give.
    for k in [
        "ok",
        "TooShort",
        "NotAtRest",
        "NoImpact",
        "Saturated",
        "NotForward",
    ] {
        assert!(
            plain.counts.get(k).copied().unwrap_or(0) > 20,
            "too few {k}: {:?}",
            plain.counts
        );
    }
}

#[test]
fn raw_estimate_is_exactly_scale_covariant() {
    let name = "raw_estimate_is_exactly_scale_covariant";
    let mut runner = runner(name, COVARIANCE_CASES, 0x636f_7661_0001);
    let oks = RefCell::new(0usize);
    let started = std::time::Instant::now();
    let strategy = (any::<Raw>().prop_map(Window::decode), -10i32..=10);
    let result = runner.run(&strategy, |(w, k)| {
        let factor = 2f32.powi(k);
        let base = estimate_raw(&w.accel, w.scale, &w.config);
        let moved = estimate_raw(&w.accel, w.scale * factor, &scaled(&w.config, factor));
        match (base, moved) {
            (Ok(a), Ok(b)) => {
                *oks.borrow_mut() += 1;
                prop_assert_eq!(
                    (a.rest_start, a.rest_end, a.impact_index),
                    (b.rest_start, b.rest_end, b.impact_index)
                );
                prop_assert_eq!(
                    (a.cue_speed * factor).to_bits(),
                    b.cue_speed.to_bits(),
                    "speed"
                );
                prop_assert_eq!((a.bias * factor).to_bits(), b.bias.to_bits(), "bias");
                prop_assert_eq!(
                    (a.rest_noise * factor).to_bits(),
                    b.rest_noise.to_bits(),
                    "noise"
                );
                prop_assert_eq!(a.stroke_duration.to_bits(), b.stroke_duration.to_bits());
            }
            (
                Err(StrokeError::NotForward { speed: a }),
                Err(StrokeError::NotForward { speed: b }),
            ) => {
                prop_assert_eq!((a * factor).to_bits(), b.to_bits())
            }
            (a, b) => prop_assert_eq!(a, b, "factor 2^{}", k),
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    println!(
        "{name}: {COVARIANCE_CASES} cases in {:.2} s ({} estimated)",
        started.elapsed().as_secs_f64(),
        oks.into_inner()
    );
}

// ---------------------------------------------------------------------------------------
// 6, 8. Piecewise-constant strokes
// ---------------------------------------------------------------------------------------

/// A piecewise stroke from the domain where the estimator must be exact.
#[derive(Clone, Debug)]
struct Exact {
    rate: f32,
    stroke: Piecewise,
    level: f32,
}

impl Exact {
    /// Rate 6667 Hz or log-uniform 500 Hz–100 kHz; level uniform ±2 g; rest 0.25–0.5 s;
    /// the first move ±(1–50) m/s² for 50–200 ms (it must end the rest: a departure above
    /// the motion floor over at least two blocks), then up to three moves of ±50 m/s²,
    /// each differing from the one before by ≥ 1 m/s² (two adjacent moves are not one
    /// still stretch) for 2 ms–200 ms (shorter than the rest, so the rest stays the
    /// longest still stretch); a coast at the level of 12 samples to 30 ms, or none; the
    /// impact 6 samples 10–60 g below the level. Every sample stays above `level − 8 g`
    /// before the impact and below the rail.
    fn decode(r: Raw) -> Exact {
        let rate = if r[0] % 3 == 0 {
            6667.0
        } else {
            log_uniform(r[1], 500.0, 100_000.0) as f32
        };
        let count = |seconds: f64| ((seconds * f64::from(rate)) as usize).max(1);
        let g = f64::from(STANDARD_GRAVITY);
        let level = (uniform(r[2], -2.0, 2.0) * g) as f32;
        let rest = count(uniform(r[3], 0.25, 0.5));
        let sign = if r[4] & 1 == 0 { 1.0 } else { -1.0 };
        let mut moves = vec![(
            (sign * uniform(r[5], 1.0, 50.0)) as f32,
            count(uniform(r[6], 0.05, 0.2)).max(12),
        )];
        for i in 0..(r[7] % 4) as usize {
            let previous = moves[moves.len() - 1].0;
            let mut a = uniform(r[8 + i], -50.0, 50.0) as f32;
            if (a - previous).abs() < 1.0 {
                a = previous + if previous < 0.0 { 1.0 } else { -1.0 };
            }
            moves.push((a, count(uniform(r[11 + i], 0.002, 0.2))));
        }
        // The last move feeds the pre-impact level when there is no coast: ≥ 12 samples.
        let last = moves.len() - 1;
        moves[last].1 = moves[last].1.max(12);
        let coast = if r[14] % 3 == 0 {
            0
        } else {
            count(uniform(r[15], 0.0, 0.03)).max(12)
        };
        let mut stroke = piecewise(rate, level, rest, &moves, coast);
        let depth = (uniform(r[15].rotate_left(16), 10.0, 60.0) * g) as f32;
        for s in &mut stroke.samples[stroke.impact..stroke.impact + 6] {
            *s = level - depth;
        }
        Exact {
            rate,
            stroke,
            level,
        }
    }

    /// The rounding bound of an estimate against the exact speed: step 5's bound on the
    /// estimate's own span, plus the rest samples in it (`|level − bias|` ≤ a few ulps
    /// of the level over the span's duration).
    fn bound(&self, samples: &[f32], e: &StrokeEstimate) -> f64 {
        let (_, b) = step5(samples, e, self.rate);
        let span = (e.impact_index - e.rest_end) as f64 / f64::from(self.rate);
        b + 8.0 * EPS32 * f64::from(self.level.abs()) * span + 4.0 * EPS32 * self.stroke.speed.abs()
    }
}

#[derive(Default, Debug)]
struct ExactFigures {
    ok: usize,
    not_forward: usize,
    worst: f64,
}

/// The speed within `bound` of `exact`, `NotForward` when `exact` is below −bound,
/// the impact at its first sample and the rest before the stroke.
fn check_exact(
    x: &Exact,
    samples: &[f32],
    exact: f64,
    got: Result<StrokeEstimate, StrokeError>,
    fig: &mut ExactFigures,
) -> Result<(), TestCaseError> {
    match got {
        Ok(e) => {
            check_estimate(&e, samples.len(), x.rate, false).map_err(fail)?;
            let bound = x.bound(samples, &e);
            let err = (f64::from(e.cue_speed) - exact).abs();
            prop_assert!(
                err <= bound,
                "{} vs exact {exact} (bound {bound:e}): {:?}",
                e.cue_speed,
                e
            );
            prop_assert_eq!(e.impact_index, x.stroke.impact, "{:?}", e);
            prop_assert!(e.rest_end <= x.stroke.rest_end, "{:?}", e);
            fig.ok += 1;
            if bound > 0.0 {
                fig.worst = fig.worst.max(err / bound);
            }
        }
        Err(StrokeError::NotForward { speed }) => {
            let slack = 16.0 * EPS32 * exact.abs() + 1e-6;
            prop_assert!(
                exact <= slack,
                "a forward stroke ({exact} m/s) refused as NotForward ({speed})"
            );
            prop_assert!(
                (f64::from(speed) - exact).abs() <= 1e-4 * exact.abs() + 1e-6,
                "{speed} vs {exact}"
            );
            fig.not_forward += 1;
        }
        Err(e) => return Err(fail(format!("refused ({exact} m/s): {e:?}"))),
    }
    Ok(())
}

#[test]
fn estimator_recovers_piecewise_strokes_exactly() {
    let name = "estimator_recovers_piecewise_strokes_exactly";
    let mut runner = runner(name, PIECEWISE_CASES, 0x6578_6163_0001);
    let figures = RefCell::new([ExactFigures::default(), ExactFigures::default()]);
    let started = std::time::Instant::now();
    let result = runner.run(&any::<Raw>().prop_map(Exact::decode), |x| {
        let config = StrokeConfig::new(x.rate);
        let samples = &x.stroke.samples;
        let mut fig = figures.borrow_mut();
        let got = estimate(samples, &config);
        let zero = vec![0.0f32; samples.len()];
        prop_assert_eq!(
            got,
            estimate_with_pitch(samples, &zero, &config),
            "zero pitch"
        );
        check_exact(&x, samples, x.stroke.speed, got, &mut fig[0])?;
        // The same stroke as raw words: the exact speed of the quantised samples.
        let raw = to_raw(samples, ACCEL_MPS2_PER_LSB);
        let seen: Vec<f32> = raw
            .iter()
            .map(|&w| f32::from(w) * ACCEL_MPS2_PER_LSB)
            .collect();
        let level = seen[0];
        let exact: f64 = seen[x.stroke.rest_end..x.stroke.impact]
            .iter()
            .map(|&a| (f64::from(a) - f64::from(level)) / f64::from(x.rate))
            .sum();
        let got = estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config);
        let zero = vec![0i16; raw.len()];
        prop_assert_eq!(
            got,
            estimate_raw_with_pitch(&raw, ACCEL_MPS2_PER_LSB, &zero, GYRO_RADPS_PER_LSB, &config),
            "zero pitch, raw"
        );
        let quantised = Exact { level, ..x.clone() };
        check_exact(&quantised, &seen, exact, got, &mut fig[1])?;
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    let [f, raw] = figures.into_inner();
    println!(
        "{name}: {PIECEWISE_CASES} cases in {:.2} s\n  f32: {f:?}\n  raw: {raw:?}",
        started.elapsed().as_secs_f64()
    );
    assert!(f.ok > PIECEWISE_CASES as usize / 4 && f.not_forward > PIECEWISE_CASES as usize / 10);
    cuesight_figures::record!(
        "reliability-sensors-piecewise-worst",
        "{:.2}",
        f.worst.max(raw.worst)
    );
    let not_forward = thousands(f.not_forward);
    cuesight_figures::record!("reliability-sensors-piecewise-not-forward", "{not_forward}");
}

#[test]
fn constant_pitch_rate_is_removed_as_gyro_bias() {
    let name = "constant_pitch_rate_is_removed_as_gyro_bias";
    let mut runner = runner(name, PITCH_CASES, 0x7069_7463_0001);
    let worst = RefCell::new(0.0f64);
    let started = std::time::Instant::now();
    let strategy = (any::<Raw>().prop_map(Exact::decode), any::<u32>());
    let result = runner.run(&strategy, |(x, p)| {
        let samples = &x.stroke.samples;
        let config = StrokeConfig::new(x.rate);
        let omega = uniform(p, -2000.0, 2000.0).to_radians() as f32;
        let pitch = vec![omega; samples.len()];
        let plain = estimate(samples, &config);
        let aided = estimate_with_pitch(samples, &pitch, &config);
        match (plain, aided) {
            (Ok(a), Ok(b)) => {
                prop_assert_eq!(
                    (a.rest_start, a.rest_end, a.impact_index),
                    (b.rest_start, b.rest_end, b.impact_index)
                );
                let t = f64::from(b.stroke_duration);
                let bound = 8.0 * EPS32 * G * f64::from(omega.abs()) * t * t + x.bound(samples, &a);
                let err = f64::from(b.cue_speed - a.cue_speed).abs();
                prop_assert!(
                    err <= bound,
                    "{} vs {} (bound {bound:e})",
                    b.cue_speed,
                    a.cue_speed
                );
                prop_assert!(
                    f64::from(b.tilt_at_impact.abs())
                        <= 4.0 * EPS32 * f64::from(omega.abs()) * t + 1e-12
                );
                if bound > 0.0 {
                    let mut w = worst.borrow_mut();
                    *w = w.max(err / bound);
                }
            }
            (Err(StrokeError::NotForward { .. }), Err(StrokeError::NotForward { .. })) => {}
            (a, b) => {
                // Only a speed within rounding of zero may fall either side.
                let near_zero = x.stroke.speed.abs() <= 1e-5;
                prop_assert!(near_zero, "{:?} vs {:?}", a, b);
            }
        }
        Ok(())
    });
    if let Err(e) = result {
        panic!("{name}: {e}\n{runner}");
    }
    let worst = worst.into_inner();
    println!(
        "{name}: {PITCH_CASES} cases in {:.2} s, speed change ≤ {worst:.3} of the bound",
        started.elapsed().as_secs_f64(),
    );
    cuesight_figures::record!("reliability-sensors-pitch-worst", "{worst:.2}");
}
