//! Extremes suite of the sensors crate (issue 6, item 1): named tests at the edges of
//! every public entry point — the LSM6DSOX driver and its decoding (i16::MIN / i16::MAX
//! words on every axis, every chip id, status byte, ODR trim byte and bus address, a bus
//! error at every step of `init`, the reset poll limit), the ring buffer (capacities 0
//! and 1, lengths 0, 1, capacity and capacity + 1, wrap-around at every head position,
//! the 24,000-sample capture ring), the impact trigger (exactly at the threshold and one
//! ulp either side, from the smallest subnormal to `f32::MAX`; NaN and ±∞ samples; 0, 1
//! and `usize::MAX` post-impact samples) and the stroke estimator (windows of length 0,
//! 1, one short of and exactly the minimum, the smallest and largest accepted sample
//! rates, full scales and rest lengths, raw words at the rail, constant bias, the
//! slowest and fastest strokes, reversed strokes, NaN/±∞ and extreme finite samples).
//!
//! Every output is finite or a typed error, never a panic. Expected values come from
//! first principles: the datasheet's sensitivities (0.488 mg/LSB, 70 mdps/LSB) and the
//! trim's 0.15 %/LSB, evaluated in f64; for the estimator, piecewise-constant strokes
//! whose speed is the exact sum `Σ (a_i − level) Δt` of the stored f32 samples.
//! `-- --nocapture` prints the figures.

mod common;

use common::*;
use cuesight::strike::{Cue, TipOffset};
use cuesight::{Error as CoreError, Field, Params};
use cuesight_figures::thousands;
use cuesight_sensors::lsm6dsox::{
    trimmed_odr_hz, DataReady, Error, ACCEL_FULL_SCALE_MPS2, ADDRESS_SA0_HIGH, ADDRESS_SA0_LOW,
    NOMINAL_ODR_HZ, RESET_POLLS, STANDARD_GRAVITY, WHO_AM_I_VALUE,
};
use cuesight_sensors::{
    accel_lsb_to_mps2, estimate, estimate_raw, estimate_raw_with_pitch, estimate_with_pitch,
    gyro_lsb_to_radps, Axis, ImpactTrigger, Lsm6dsox, RawSample, RingBuffer, StrokeConfig,
    StrokeError, StrokeEstimate, ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB,
};
use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::i2c::{Mock, Transaction};

const A: u8 = ADDRESS_SA0_LOW;

/// Datasheet sensitivities in f64: 0.488 mg/LSB at ±16 g, 70 mdps/LSB at ±2000 dps.
const ACCEL_LSB_F64: f64 = 0.488e-3 * G;
const GYRO_LSB_F64: f64 = 70.0e-3 * std::f64::consts::PI / 180.0;

const WORDS: [i16; 7] = [i16::MIN, i16::MIN + 1, -1, 0, 1, i16::MAX - 1, i16::MAX];

// ---------------------------------------------------------------------------------------
// LSM6DSOX driver and decoding
// ---------------------------------------------------------------------------------------

/// The init sequence of docs/sensors.md §2, written out by hand, at `address`.
fn init_sequence(address: u8, polls: &[u8], trim: u8) -> Vec<Transaction> {
    let mut t = vec![
        Transaction::write_read(address, vec![0x0F], vec![0x6C]),
        Transaction::write(address, vec![0x12, 0x01]),
    ];
    for &p in polls {
        t.push(Transaction::write_read(address, vec![0x12], vec![p]));
    }
    t.extend([
        Transaction::write(address, vec![0x12, 0x44]),
        Transaction::write(address, vec![0x18, 0xE2]),
        Transaction::write(address, vec![0x10, 0xA4]),
        Transaction::write(address, vec![0x11, 0xAC]),
        Transaction::write_read(address, vec![0x63], vec![trim]),
    ]);
    t
}

/// Pins: the sensitivities are the datasheet's (ST's `lsm6dsox_from_fs16_to_mg`,
/// `lsm6dsox_from_fs2000_to_mdps`), the full scale is 16 g, and every conversion at the
/// i16 extremes equals word × sensitivity (f64) to 2ε (the constant and the product each
/// round once); the most negative word is within the ±16 g full scale.
#[test]
fn conversions_at_the_i16_extremes_match_the_datasheet() {
    let close = |got: f32, want: f64| (f64::from(got) - want).abs() <= 2.0 * EPS32 * want.abs();
    assert!(close(ACCEL_MPS2_PER_LSB, ACCEL_LSB_F64));
    assert!(close(GYRO_RADPS_PER_LSB, GYRO_LSB_F64));
    assert!(close(ACCEL_FULL_SCALE_MPS2, 16.0 * G));
    assert_eq!(f64::from(STANDARD_GRAVITY), f64::from(9.806_65f32));
    for w in WORDS {
        let (a, g) = (accel_lsb_to_mps2(w), gyro_lsb_to_radps(w));
        assert!(close(a, f64::from(w) * ACCEL_LSB_F64), "accel {w}: {a}");
        assert!(close(g, f64::from(w) * GYRO_LSB_F64), "gyro {w}: {g}");
        assert!(a.is_finite() && g.is_finite());
        assert!(f64::from(a.abs()) <= 16.0 * G, "{w} beyond the full scale");
    }
    // −32768 LSB × 0.488 mg = −15.990784 g.
    let min_g = f64::from(accel_lsb_to_mps2(i16::MIN)) / G;
    assert!((min_g + 15.990_784).abs() < 1e-5, "{min_g}");
    // 32767 LSB × 70 mdps = 2293.69 dps.
    let max_dps = f64::from(gyro_lsb_to_radps(i16::MAX)).to_degrees();
    assert!((max_dps - 2293.69).abs() < 1e-3, "{max_dps}");
    println!("i16::MIN = {min_g:.6} g, i16::MAX = {max_dps:.2} dps");
}

/// Pins: a twelve-byte block read decodes each little-endian word at its position (gyro
/// X, Y, Z then accelerometer X, Y, Z) for the extreme words on every axis, `read` is
/// `read_raw().to_si()`, and a two-byte axis read addresses `OUTX_L_A + 2·axis`.
#[test]
fn extreme_words_on_every_axis_decode_exactly() {
    for position in 0..6 {
        for w in WORDS {
            // The other five words carry a distinct pattern, so a shifted decode shows.
            let words: [i16; 6] =
                std::array::from_fn(|i| if i == position { w } else { 0x1234 + i as i16 });
            let bytes: Vec<u8> = words.iter().flat_map(|x| x.to_le_bytes()).collect();
            let expectations = [
                Transaction::write_read(A, vec![0x22], bytes.clone()),
                Transaction::write_read(A, vec![0x22], bytes),
            ];
            let mut i2c = Mock::new(&expectations);
            let mut imu = Lsm6dsox::new(i2c.clone(), A);
            let raw = imu.read_raw().unwrap();
            assert_eq!(raw.gyro, [words[0], words[1], words[2]]);
            assert_eq!(raw.accel, [words[3], words[4], words[5]]);
            let si = imu.read().unwrap();
            assert_eq!(si, raw.to_si());
            for axis in 0..3 {
                assert_eq!(si.gyro[axis], gyro_lsb_to_radps(words[axis]));
                assert_eq!(si.accel[axis], accel_lsb_to_mps2(words[3 + axis]));
            }
            i2c.done();
        }
    }
    for (axis, register) in [(Axis::X, 0x28u8), (Axis::Y, 0x2A), (Axis::Z, 0x2C)] {
        let expectations: Vec<Transaction> = WORDS
            .iter()
            .map(|w| Transaction::write_read(A, vec![register], w.to_le_bytes().to_vec()))
            .collect();
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), A);
        for w in WORDS {
            assert_eq!(imu.read_accel_axis_raw(axis).unwrap(), w, "{axis:?}");
        }
        i2c.done();
    }
    assert_eq!(RawSample::default().to_si().accel, [0.0; 3]);
}

/// Pins: `STATUS_REG` decoding for all 256 bytes — bit 0 `XLDA`, bit 1 `GDA`, bit 2
/// `TDA`, the five other bits ignored.
#[test]
fn status_register_every_byte() {
    let expectations: Vec<Transaction> = (0..=255u8)
        .map(|b| Transaction::write_read(A, vec![0x1E], vec![b]))
        .collect();
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    for b in 0..=255u8 {
        let want = DataReady {
            accel: b & 1 != 0,
            gyro: b & 2 != 0,
            temperature: b & 4 != 0,
        };
        assert_eq!(imu.data_ready().unwrap(), want, "{b:#04x}");
    }
    i2c.done();
}

/// Pins: `trimmed_odr_hz` for all 256 trim bytes is `6667 Hz × (1 + 0.0015 × (i8)b)` (f64,
/// to 4ε), strictly increasing in the signed value; the extremes 0x80 (−19.2 %) and 0x7F
/// (+19.05 %) are inside the estimator's accepted rate range; `init` applies them.
#[test]
fn odr_trim_over_every_byte() {
    let mut previous = 0.0f32;
    for signed in -128i16..=127 {
        let b = signed as i8 as u8;
        let odr = trimmed_odr_hz(b);
        let want = 6667.0 * (1.0 + 0.0015 * f64::from(signed));
        assert!(
            (f64::from(odr) - want).abs() <= 4.0 * EPS32 * want,
            "{b:#04x}: {odr} vs {want}"
        );
        assert!(odr > previous, "not increasing at {signed}");
        previous = odr;
        // Accepted by the estimator: a window of zeros is refused for its content only.
        let err = estimate(&[0.0; 4000], &StrokeConfig::new(odr)).unwrap_err();
        assert!(
            !matches!(err, StrokeError::InvalidConfig(_)),
            "{odr}: {err}"
        );
    }
    for (trim, want) in [(0x80u8, 5386.936), (0x7F, 7937.0635), (0x00, 6667.0)] {
        let expectations = init_sequence(A, &[0x00], trim);
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), A);
        assert_eq!(imu.odr_hz(), NOMINAL_ODR_HZ);
        imu.init().unwrap();
        assert!((f64::from(imu.odr_hz()) - want).abs() < 1e-3, "{trim:#04x}");
        i2c.done();
    }
}

/// Pins: the software reset may clear on the first poll or on the last allowed one
/// (`RESET_POLLS` = 100); if it has not cleared after 100 polls, `ResetTimeout` and no
/// further traffic.
#[test]
fn reset_clears_on_the_first_or_the_last_allowed_poll() {
    let mut last = vec![0x05u8; RESET_POLLS - 1];
    last.push(0x04);
    for polls in [vec![0x00u8], last] {
        let expectations = init_sequence(A, &polls, 0);
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), A);
        assert_eq!(imu.init(), Ok(()), "{} polls", polls.len());
        i2c.done();
    }
    let mut expectations = init_sequence(A, &[0x05; RESET_POLLS], 0);
    expectations.truncate(2 + RESET_POLLS);
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    assert_eq!(imu.init(), Err(Error::ResetTimeout));
    i2c.done();
}

/// Pins: a bus error at each of the eight transactions of `init` (one reset poll) is returned as
/// `Error::Bus` with the bus's own error, nothing further goes on the bus, and the ODR
/// stays nominal.
#[test]
fn bus_error_at_every_init_transaction() {
    let full = init_sequence(A, &[0x00], 0x05);
    assert_eq!(full.len(), 8);
    for k in 0..full.len() {
        let mut expectations: Vec<Transaction> = full[..k].to_vec();
        expectations.push(full[k].clone().with_error(ErrorKind::ArbitrationLoss));
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), A);
        assert_eq!(
            imu.init(),
            Err(Error::Bus(ErrorKind::ArbitrationLoss)),
            "{k}"
        );
        assert_eq!(imu.odr_hz(), NOMINAL_ODR_HZ);
        i2c.done();
    }
}

/// Pins: every one of the 255 wrong `WHO_AM_I` values is refused as `WrongChipId(id)`
/// after that single read (no write to the unknown part).
#[test]
fn every_wrong_chip_id_is_refused_before_any_write() {
    for id in (0..=255u8).filter(|&id| id != WHO_AM_I_VALUE) {
        let expectations = [Transaction::write_read(A, vec![0x0F], vec![id])];
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), A);
        assert_eq!(imu.init(), Err(Error::WrongChipId(id)));
        i2c.done();
    }
}

/// Pins: of the 256 possible address bytes, exactly 0x6A and 0x6B reach the bus (the
/// full init runs there); every other one (the 8-bit forms 0xD4/0xD6, values above 0x7F
/// that are no 7-bit address) is refused by every bus method with
/// `InvalidAddress(address)` before any traffic, and `release` hands the bus back.
#[test]
fn every_bus_address() {
    for address in 0..=255u8 {
        if address == ADDRESS_SA0_LOW || address == ADDRESS_SA0_HIGH {
            let expectations = init_sequence(address, &[0x00], 0);
            let mut i2c = Mock::new(&expectations);
            let mut imu = Lsm6dsox::new(i2c.clone(), address);
            assert_eq!(imu.init(), Ok(()));
            i2c.done();
            continue;
        }
        let mut i2c = Mock::new(&[]);
        let mut imu = Lsm6dsox::new(i2c.clone(), address);
        let bad = Error::InvalidAddress(address);
        assert_eq!(imu.init(), Err(bad));
        assert_eq!(imu.who_am_i(), Err(bad));
        assert_eq!(imu.data_ready(), Err(bad));
        assert_eq!(imu.enable_accel_data_ready_int1(), Err(bad));
        assert_eq!(imu.read_raw(), Err(bad));
        assert_eq!(imu.read(), Err(bad));
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            assert_eq!(imu.read_accel_axis_raw(axis), Err(bad));
        }
        assert_eq!(imu.odr_hz(), NOMINAL_ODR_HZ);
        let _bus = imu.release();
        i2c.done();
    }
}

// ---------------------------------------------------------------------------------------
// Ring buffer
// ---------------------------------------------------------------------------------------

/// Check a ring against the values pushed since it was last cleared: it holds the last
/// `min(pushed, N)` of them, oldest first, through every accessor.
fn check_ring<const N: usize>(ring: &RingBuffer<i32, N>, pushed: &[i32], what: &str) {
    let keep = pushed.len().min(N);
    let want = &pushed[pushed.len() - keep..];
    assert_eq!(ring.len(), keep, "{what}");
    assert_eq!(ring.is_empty(), keep == 0, "{what}");
    assert_eq!(ring.is_full(), keep == N, "{what}");
    assert_eq!(ring.capacity(), N);
    assert_eq!(ring.iter().collect::<Vec<_>>(), want, "{what}");
    let (a, b) = ring.as_slices();
    assert_eq!([a, b].concat(), want, "{what}");
    assert!(keep == 0 || !a.is_empty(), "{what}: empty first slice");
    for (i, &v) in want.iter().enumerate() {
        assert_eq!(ring.get(i), Some(v), "{what}");
    }
    assert_eq!(ring.get(keep), None, "{what}");
    assert_eq!(ring.get(usize::MAX), None, "{what}");
    assert_eq!(ring.latest(), want.last().copied(), "{what}");
    for out_len in [0, keep.saturating_sub(1), keep, keep + 1] {
        let mut out = vec![i32::MIN; out_len];
        let n = ring.copy_to(&mut out);
        assert_eq!(n, keep.min(out_len), "{what}");
        assert_eq!(&out[..n], &want[..n], "{what}");
        assert!(
            out[n..].iter().all(|&x| x == i32::MIN),
            "{what}: wrote past the count"
        );
    }
}

/// Pushes `count` values into a fresh ring, checking each eviction, then the contents.
fn fill<const N: usize>(count: usize) -> (RingBuffer<i32, N>, Vec<i32>) {
    let mut ring = RingBuffer::<i32, N>::new(-1);
    let mut pushed = Vec::new();
    for k in 0..count {
        let v = k as i32 * 7 - 3;
        let evicted = ring.push(v);
        let want = if N == 0 {
            Some(v)
        } else if pushed.len() >= N {
            Some(pushed[pushed.len() - N])
        } else {
            None
        };
        assert_eq!(evicted, want, "N = {N}, push {k}");
        pushed.push(v);
    }
    (ring, pushed)
}

/// Pins: capacity 0 stores nothing (every push hands its value back, `try_push` refuses,
/// the ring is both empty and full, every accessor is empty) and capacity 1 keeps the
/// newest value only.
#[test]
fn ring_capacity_zero_and_one() {
    let (mut zero, _) = fill::<0>(3);
    for v in [i32::MIN, 0, i32::MAX] {
        assert_eq!(zero.push(v), Some(v));
        assert_eq!(zero.try_push(v), Err(v));
    }
    assert!(zero.is_empty() && zero.is_full());
    check_ring(&zero, &[], "N = 0");
    assert_eq!(zero.make_contiguous(), &[] as &[i32]);
    zero.clear();
    check_ring(&zero, &[], "N = 0 cleared");

    let (mut one, pushed) = fill::<1>(5);
    check_ring(&one, &pushed, "N = 1");
    assert_eq!(one.make_contiguous(), &pushed[4..]);
    assert_eq!(one.try_push(9), Err(9));
    one.clear();
    assert_eq!(one.try_push(i32::MIN), Ok(()));
    check_ring(&one, &[i32::MIN], "N = 1 after clear");
}

fn lengths_for<const N: usize>() {
    for count in [0, 1, N.saturating_sub(1), N, N + 1, 2 * N, 2 * N + 1] {
        let what = format!("N = {N}, {count} pushed");
        let (mut ring, pushed) = fill::<N>(count);
        check_ring(&ring, &pushed, &what);
        let keep = count.min(N);
        assert_eq!(ring.make_contiguous(), &pushed[count - keep..], "{what}");
        check_ring(&ring, &pushed, &what);
        // try_push succeeds exactly while there is room.
        let room = ring.len() < N;
        assert_eq!(ring.try_push(i32::MAX).is_ok(), room, "{what}");
    }
}

/// Pins: lengths 0, 1, capacity − 1, capacity, capacity + 1, 2·capacity and
/// 2·capacity + 1 for capacities 1, 2, 7 and 64: the ring holds the last `min(n, N)`
/// values in push order, each push past capacity returns the value it overwrote, and
/// `make_contiguous` returns the same values.
#[test]
fn ring_lengths_zero_one_capacity_and_capacity_plus_one() {
    lengths_for::<1>();
    lengths_for::<2>();
    lengths_for::<7>();
    lengths_for::<64>();
}

/// Pins: wrap-around at every head position of a capacity-7 ring (0 to 3·7 + 1 values
/// pushed): `make_contiguous` there gives the last values in order, the ring keeps
/// working afterwards (8 more pushes), and `clear` restarts it.
#[test]
fn ring_wrap_around_at_every_head_position() {
    const N: usize = 7;
    for count in 0..=3 * N + 1 {
        let (mut ring, mut pushed) = fill::<N>(count);
        let what = format!("{count} pushed");
        let keep = count.min(N);
        let (_, second) = ring.as_slices();
        if count > N && count % N != 0 {
            assert!(
                !second.is_empty(),
                "{what}: a wrapped ring is in two pieces"
            );
        }
        assert_eq!(ring.make_contiguous(), &pushed[count - keep..], "{what}");
        assert!(ring.as_slices().1.is_empty(), "{what}");
        for k in 0..=N {
            let v = 1000 + k as i32;
            ring.push(v);
            pushed.push(v);
            check_ring(&ring, &pushed, &format!("{what}, then {} more", k + 1));
        }
        ring.clear();
        check_ring(&ring, &[], &what);
        ring.push(5);
        check_ring(&ring, &[5], &what);
    }
}

/// Pins: the 24,000-sample capture ring (48 kB of i16, the size docs/sensors.md uses) at
/// its boundaries — 24,000, 24,001, 48,000 and 48,001 words, i16::MIN and i16::MAX
/// among them — keeps the last 24,000 in order, also through `make_contiguous`.
#[test]
fn capture_ring_at_its_boundaries() {
    const N: usize = 24_000;
    let word = |k: usize| (k as i64 * 2731 % 65536 - 32768) as i16;
    for count in [N - 1, N, N + 1, 2 * N, 2 * N + 1] {
        let mut ring = Box::new(RingBuffer::<i16, N>::new(0));
        let mut seen = (false, false);
        for k in 0..count {
            let w = if k == count - 2 {
                i16::MIN
            } else if k == count - 1 {
                i16::MAX
            } else {
                word(k)
            };
            seen = (seen.0 || w == i16::MIN, seen.1 || w == i16::MAX);
            ring.push(w);
        }
        assert!(seen.0 && seen.1);
        let keep = count.min(N);
        assert_eq!(ring.len(), keep);
        assert_eq!(ring.latest(), Some(i16::MAX));
        assert_eq!(ring.get(keep - 2), Some(i16::MIN));
        let first = count - keep;
        assert_eq!(ring.get(0), Some(word(first)), "{count}");
        let slice = ring.make_contiguous();
        assert_eq!(slice.len(), keep);
        assert!(slice[..keep - 2]
            .iter()
            .enumerate()
            .all(|(i, &w)| w == word(first + i)));
    }
}

// ---------------------------------------------------------------------------------------
// Impact trigger
// ---------------------------------------------------------------------------------------

/// Pins: the impact is a sample strictly below `−threshold` — exactly `−threshold` and
/// one ulp towards zero do not trigger, one ulp beyond does (for `f32::MAX` that is
/// −∞) — for thresholds from the smallest subnormal through 8 g to `f32::MAX`.
#[test]
fn trigger_exactly_at_the_threshold_and_one_ulp_either_side() {
    let thresholds = [
        f32::from_bits(1),
        f32::MIN_POSITIVE,
        1.0,
        8.0 * STANDARD_GRAVITY,
        16.0 * STANDARD_GRAVITY,
        f32::MAX,
    ];
    for t in thresholds {
        for (sample, fires) in [(next_up(-t), false), (-t, false), (next_down(-t), true)] {
            let mut trigger = ImpactTrigger::new(t, 0).unwrap();
            assert_eq!(trigger.threshold(), t);
            assert_eq!(
                trigger.push(sample),
                fires,
                "threshold {t:e}, sample {sample:e}"
            );
            assert_eq!(trigger.is_triggered(), fires);
        }
    }
}

/// Pins: with `post_samples` = 0 the impact sample completes the capture; with 1 the
/// next one; with 333 (50 ms at 6.66 kHz) exactly the 333rd after it; with `usize::MAX`
/// it never completes (10,000 samples later) but is triggered; once complete it stays
/// complete whatever follows (NaN included) until `reset` re-arms it.
#[test]
fn trigger_post_samples_zero_one_and_huge() {
    let impact = -100.0;
    for post in [0usize, 1, 333] {
        let mut t = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, post).unwrap();
        assert!(!t.push(0.0));
        for k in 0..=post {
            let sample = if k == 0 { impact } else { 0.0 };
            assert_eq!(t.push(sample), k == post, "post {post}, sample {k}");
        }
        for s in [f32::NAN, 0.0, impact, f32::INFINITY] {
            assert!(t.push(s));
        }
        t.reset();
        assert!(!t.is_triggered());
        assert!(!t.push(0.0));
        assert_eq!(t.push(impact), post == 0);
    }
    let mut forever = ImpactTrigger::new(1.0, usize::MAX).unwrap();
    assert!(!forever.push(-2.0));
    assert!((0..10_000).all(|_| !forever.push(0.0)));
    assert!(forever.is_triggered());
}

/// Pins: NaN and +∞ samples never trigger (for every threshold up to `f32::MAX`), −∞
/// always does; an i16::MIN word (−15.99 g) triggers an 8 g trigger and i16::MAX does
/// not; the first word beyond −8 g is −16,394 (−8 g / 0.488 mg = −16,393.4, f64).
#[test]
fn trigger_on_non_finite_samples_and_rail_words() {
    for t in [f32::from_bits(1), 1.0, 8.0 * STANDARD_GRAVITY, f32::MAX] {
        let mut trigger = ImpactTrigger::new(t, 0).unwrap();
        assert!(!trigger.push(f32::NAN));
        assert!(!trigger.push(f32::INFINITY));
        assert!(!trigger.is_triggered());
        assert!(trigger.push(f32::NEG_INFINITY), "{t:e}");
    }
    let eight_g = 8.0 * STANDARD_GRAVITY;
    let boundary = -(8.0 / 0.488e-3f64).floor() as i16 - 1; // −16,394
    assert_eq!(boundary, -16_394);
    for (word, fires) in [
        (i16::MIN, true),
        (boundary, true),
        (boundary + 1, false),
        (0, false),
        (i16::MAX, false),
    ] {
        let mut trigger = ImpactTrigger::new(eight_g, 0).unwrap();
        assert_eq!(trigger.push(accel_lsb_to_mps2(word)), fires, "{word}");
    }
}

// ---------------------------------------------------------------------------------------
// Stroke estimator
// ---------------------------------------------------------------------------------------

/// An `Ok` estimate of a piecewise stroke must pass the contract checks, find the
/// stroke's exact impact sample and a rest that ends before the stroke, and give the
/// exact speed to the f32 rounding bound of step 5.
fn assert_exact(
    stroke: &Piecewise,
    got: Result<StrokeEstimate, StrokeError>,
    rate: f32,
    what: &str,
) {
    let e = got.unwrap_or_else(|err| panic!("{what}: refused: {err}"));
    check_estimate(&e, stroke.samples.len(), rate, false).unwrap_or_else(|m| panic!("{what}: {m}"));
    assert_eq!(e.impact_index, stroke.impact, "{what}: {e:?}");
    assert!(e.rest_end <= stroke.rest_end, "{what}: {e:?}");
    let (_, bound) = step5(&stroke.samples, &e, rate);
    let err = (f64::from(e.cue_speed) - stroke.speed).abs();
    assert!(
        err <= bound + 2.0 * EPS32 * stroke.speed.abs(),
        "{what}: {} vs exact {} (bound {bound:e})",
        e.cue_speed,
        stroke.speed
    );
}

/// Pins: the minimum window length at the smallest (500 Hz), nominal (6667 Hz) and
/// largest (100 kHz) rates and with `min_rest` at 0.15 s and at its 10 s limit: lengths
/// 0, 1 and one short of it are `TooShort { len, min }` with the same `min`; exactly
/// `min` samples pass the length check (an all-zero window is then `NoImpact`); `min`
/// holds the rest (≥ max(min_rest, 3 blocks of 25 ms) × rate) and not much more (the
/// 25 ms blocks rounded to samples, the 2.4 ms window and 8 samples of margin).
#[test]
fn window_lengths_zero_one_and_around_the_minimum() {
    let (mut fewest, mut most) = (u32::MAX, 0);
    for rate in [500.0f32, FS, 100_000.0] {
        for min_rest in [0.15f32, 10.0] {
            let config = StrokeConfig {
                min_rest,
                ..StrokeConfig::new(rate)
            };
            let Err(StrokeError::TooShort { len: 0, min }) = estimate(&[], &config) else {
                panic!("{rate} Hz: an empty window was not TooShort");
            };
            for len in [1, min - 1] {
                assert_eq!(
                    estimate(&vec![0.0; len as usize], &config),
                    Err(StrokeError::TooShort { len, min })
                );
                assert_eq!(
                    estimate_raw(&vec![0; len as usize], ACCEL_MPS2_PER_LSB, &config),
                    Err(StrokeError::TooShort { len, min })
                );
            }
            assert_eq!(
                estimate(&vec![0.0; min as usize], &config),
                Err(StrokeError::NoImpact)
            );
            let rest = f64::from(min_rest).max(3.0 * 0.025);
            let (lo, hi) = (
                rest * f64::from(rate),
                (rest + 0.03) * f64::from(rate) * 1.02 + 16.0,
            );
            assert!(
                (lo..=hi).contains(&(min as f64)),
                "{rate} Hz, min_rest {min_rest}: min {min} not in [{lo}, {hi}]"
            );
            println!("{rate} Hz, min_rest {min_rest} s: at least {min} samples");
            (fewest, most) = (fewest.min(min), most.max(min));
        }
    }
    cuesight_figures::record!("reliability-sensors-window-min-fewest", "{fewest}");
    cuesight_figures::record!("reliability-sensors-window-min-most", "{}", thousands(most));
}

/// Pins: windows of constant raw words — all zero, i16::MAX (clipped at +16 g), i16::MIN
/// (clipped at −16 g: every block looks like a knock), alternating i16::MIN/i16::MAX —
/// and all-zero f32 data are typed errors (`NoImpact`, `NotAtRest`), never a speed.
#[test]
fn constant_and_clipped_windows() {
    let config = StrokeConfig::new(FS);
    let n = 5000;
    let alternating: Vec<i16> = (0..n)
        .map(|i| if i % 2 == 0 { i16::MIN } else { i16::MAX })
        .collect();
    let cases: [(&str, Vec<i16>, StrokeError); 4] = [
        ("all zero", vec![0; n], StrokeError::NoImpact),
        ("all i16::MAX", vec![i16::MAX; n], StrokeError::NoImpact),
        ("all i16::MIN", vec![i16::MIN; n], StrokeError::NotAtRest),
        ("alternating rails", alternating, StrokeError::NotAtRest),
    ];
    for (what, raw, want) in cases {
        assert_eq!(
            estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config),
            Err(want),
            "{what}"
        );
        let pitch = vec![i16::MAX; raw.len()];
        assert_eq!(
            estimate_raw_with_pitch(
                &raw,
                ACCEL_MPS2_PER_LSB,
                &pitch,
                GYRO_RADPS_PER_LSB,
                &config
            ),
            Err(want),
            "{what}, gyro-aided"
        );
    }
    assert_eq!(estimate(&vec![0.0; n], &config), Err(StrokeError::NoImpact));
    assert_eq!(
        estimate_with_pitch(&vec![0.0; n], &vec![0.0; n], &config),
        Err(StrokeError::NoImpact)
    );
}

/// Pins: a raw word at the rail before the impact is refused, and where the rail is:
/// the estimator refuses |a| ≥ 99.9 % of the 16 g full scale, i.e. words from
/// ⌈0.999 × 16 / 0.488e-3⌉ = 32,755 up (f64, datasheet sensitivity); 32,754 is
/// integrated. A word at i16::MIN before the true impact is itself the impact (the
/// first deceleration beyond 8 g), not a saturation.
#[test]
fn clipped_accelerometer_words_at_the_rail() {
    let first_refused = (0.999 * 16.0 / 0.488e-3f64).ceil() as i16;
    assert_eq!(first_refused, 32_755);
    let config = StrokeConfig::new(FS);
    let base = step(FS, 0.0, 20.0, 800);
    let mut raw = to_raw(&base.samples, ACCEL_MPS2_PER_LSB);
    let at = base.rest_end + 400;
    for (word, saturated) in [
        (first_refused - 1, false),
        (first_refused, true),
        (i16::MAX, true),
    ] {
        raw[at] = word;
        let got = estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config);
        if saturated {
            assert_eq!(
                got,
                Err(StrokeError::Saturated { index: at as u32 }),
                "{word}"
            );
        } else {
            let e = got.unwrap();
            check_estimate(&e, raw.len(), FS, false).unwrap();
        }
    }
    raw[at] = i16::MIN;
    let e = estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config).unwrap();
    assert_eq!(e.impact_index, at);
}

/// Pins: a constant bias (sensor offset + gravity along the cue) from −7 g to +7 g is
/// removed exactly — the speed of the same push is the exact `Σ a Δt` at every level;
/// a level below −8 g (where every still block reads as a knock) is `NotAtRest`.
#[test]
fn constant_bias_from_minus_seven_to_plus_seven_g() {
    let config = StrokeConfig::new(FS);
    for level_g in [-7.0f32, -1.0, -0.05, 0.0, 0.05, 1.0, 7.0] {
        let s = step(FS, level_g * STANDARD_GRAVITY, 10.0, 800);
        let e = estimate(&s.samples, &config);
        assert_exact(&s, e, FS, &format!("level {level_g} g"));
        println!(
            "level {level_g:+} g: {:.7} m/s (exact {:.7})",
            e.unwrap().cue_speed,
            s.speed
        );
        let raw = to_raw(&s.samples, ACCEL_MPS2_PER_LSB);
        let scaled: Vec<f32> = raw
            .iter()
            .map(|&w| f32::from(w) * ACCEL_MPS2_PER_LSB)
            .collect();
        let e = estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config).unwrap();
        check_estimate(&e, raw.len(), FS, false).unwrap();
        let (v, bound) = step5(&scaled, &e, FS);
        assert!(
            (f64::from(e.cue_speed) - v).abs() <= bound,
            "raw, level {level_g} g"
        );
    }
    let s = step(FS, -8.5 * STANDARD_GRAVITY, 10.0, 800);
    assert_eq!(estimate(&s.samples, &config), Err(StrokeError::NotAtRest));
}

/// Pins: the smallest and largest accepted sample rates (500 Hz and 100 kHz) and the
/// LSM6DSOX's trim extremes give the exact speed; the next f32 outside either end is
/// `InvalidConfig(SampleRate)`.
#[test]
fn smallest_and_largest_sample_rates() {
    for rate in [
        500.0f32,
        trimmed_odr_hz(0x80),
        FS,
        trimmed_odr_hz(0x7F),
        100_000.0,
    ] {
        let push = (0.15 * rate) as usize;
        let s = step(rate, 0.3, 12.0, push);
        assert_exact(
            &s,
            estimate(&s.samples, &StrokeConfig::new(rate)),
            rate,
            &format!("{rate} Hz"),
        );
    }
    for rate in [next_down(500.0), next_up(100_000.0)] {
        let s = step(FS, 0.0, 12.0, 1000);
        assert_eq!(
            estimate(&s.samples, &StrokeConfig::new(rate)),
            Err(StrokeError::InvalidConfig(
                cuesight_sensors::ConfigField::SampleRate
            ))
        );
    }
}

/// Pins: the full-scale setting at its smallest accepted value (one ulp above the impact
/// threshold) and its largest (+∞, which disables the check); the refused samples are
/// exactly those at or beyond `0.999 × full_scale` (one ulp below is integrated); a
/// sample at `−0.999 × full_scale` is the impact when that is beyond the threshold
/// (16 g), else saturated (the smallest full scale).
#[test]
fn full_scale_at_its_smallest_and_largest() {
    let base = StrokeConfig::new(FS);
    let smallest = StrokeConfig {
        full_scale: next_up(base.impact_threshold),
        ..base
    };
    let s = step(FS, 0.0, 10.0, 800);
    assert_exact(
        &s,
        estimate(&s.samples, &smallest),
        FS,
        "smallest full scale",
    );
    for config in [smallest, base] {
        let rail = 0.999 * config.full_scale;
        let at = s.rest_end + 100;
        for (value, saturated) in [(rail, true), (next_down(rail), false)] {
            let mut samples = s.samples.clone();
            samples[at] = value;
            let got = estimate(&samples, &config);
            if saturated {
                assert_eq!(
                    got,
                    Err(StrokeError::Saturated { index: at as u32 }),
                    "{value}"
                );
            } else {
                check_estimate(&got.unwrap(), samples.len(), FS, false).unwrap();
            }
        }
        // −rail: saturated if it is above −impact_threshold, else it is the impact.
        let mut samples = s.samples.clone();
        samples[at] = -rail;
        let got = estimate(&samples, &config);
        if -rail < -config.impact_threshold {
            assert_eq!(got.unwrap().impact_index, at);
        } else {
            assert_eq!(got, Err(StrokeError::Saturated { index: at as u32 }));
        }
    }
    let infinite = StrokeConfig {
        full_scale: f32::INFINITY,
        ..base
    };
    let s = piecewise(FS, 0.0, 2000, &[(1e30, 1), (0.0, 100)], 300);
    assert_exact(&s, estimate(&s.samples, &infinite), FS, "full scale +inf");
}

/// Pins: `min_rest` at its limits — 10 s needs 10 s of stillness (10.2 s is measured
/// exactly, 9.5 s is `NotAtRest`); the smallest positive value (1e-45 s) is accepted
/// and still needs three 25 ms blocks.
#[test]
fn min_rest_at_its_limits() {
    let rate = 500.0;
    let longest = StrokeConfig {
        min_rest: 10.0,
        ..StrokeConfig::new(rate)
    };
    let s = piecewise(rate, 0.2, 5100, &[(12.0, 100)], 50);
    assert_exact(&s, estimate(&s.samples, &longest), rate, "10.2 s rest");
    let s = piecewise(rate, 0.2, 4750, &[(12.0, 100)], 250);
    assert_eq!(estimate(&s.samples, &longest), Err(StrokeError::NotAtRest));
    let shortest = StrokeConfig {
        min_rest: f32::from_bits(1),
        ..StrokeConfig::new(FS)
    };
    let s = step(FS, 0.2, 12.0, 700);
    assert_exact(&s, estimate(&s.samples, &shortest), FS, "min_rest 1e-45 s");
    // 60 ms of rest (under 3 blocks); the push alternates 12 and 13 m/s² every 100
    // samples so that no block of it is still either.
    let push: Vec<(f32, usize)> = (0..7).map(|k| (12.0 + (k % 2) as f32, 100)).collect();
    let s = piecewise(FS, 0.2, 400, &push, 300);
    assert_eq!(estimate(&s.samples, &shortest), Err(StrokeError::NotAtRest));
}

/// Pins: the slowest strokes — one sample of 1 m/s² (1.5e-4 m/s at 6667 Hz) and ten of
/// 0.05 m/s² (7.5e-5 m/s) are measured exactly; pushes the rest detector cannot tell
/// from stillness (a single sample whose share of the 2.4 ms moving average, a/16,
/// stays under the 0.03 m/s² motion floor, or a push level within the 0.05 m/s²
/// rest-level tolerance for whole blocks) are refused as `NotForward` with a finite
/// speed ≤ 0, never reported as a forward speed.
#[test]
fn slowest_strokes() {
    let config = StrokeConfig::new(FS);
    for (a, push) in [(1.0f32, 1usize), (0.05, 10), (0.05, 100)] {
        let s = piecewise(FS, 0.0, 2000, &[(a, push)], 300);
        assert_exact(
            &s,
            estimate(&s.samples, &config),
            FS,
            &format!("{a} m/s² × {push}"),
        );
    }
    for (a, push) in [
        (0.001f32, 1usize),
        (0.03, 1),
        (0.05, 1),
        (0.01, 1000),
        (0.05, 1000),
    ] {
        let s = piecewise(FS, 0.0, 2000, &[(a, push)], 300);
        match estimate(&s.samples, &config) {
            Err(StrokeError::NotForward { speed }) => {
                assert!(speed.is_finite() && speed <= 0.0, "{a} × {push}: {speed}")
            }
            other => panic!("{a} m/s² × {push}: {other:?}"),
        }
    }
}

/// Pins: the fastest strokes — 15.9 g (just under the 99.9 % rail) held for 1 s after a
/// 1.5 s rest is 155.9 m/s, measured exactly; the strike model then refuses it (cue
/// speed above 20 m/s) as `Strike(OutOfRange { CueSpeed })`; the chain accepts 19.8 m/s
/// and refuses 20.2 m/s. A constant push held longer than the rest is taken for the
/// rest (the documented longest-still-run rule: an accelerometer cannot tell a constant
/// acceleration from gravity) and refused as `NotForward`, not measured wrongly.
#[test]
fn fastest_strokes() {
    let config = StrokeConfig::new(FS);
    let s = piecewise(FS, 0.0, 10_000, &[(15.9 * STANDARD_GRAVITY, 6667)], 100);
    let e = estimate(&s.samples, &config);
    assert_exact(&s, e, FS, "15.9 g for 1 s");
    let e = e.unwrap();
    println!("15.9 g for 1 s: {} m/s", e.cue_speed);
    cuesight_figures::record!("reliability-sensors-fastest-speed", "{:.1}", e.cue_speed);
    match e.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE) {
        Err(StrokeError::Strike(CoreError::OutOfRange {
            field: Field::CueSpeed,
            value,
        })) => assert_eq!(value, e.cue_speed),
        other => panic!("{other:?}"),
    }
    let plateau = piecewise(FS, 0.0, 2000, &[(15.9 * STANDARD_GRAVITY, 6667)], 100);
    assert!(matches!(
        estimate(&plateau.samples, &config),
        Err(StrokeError::NotForward { speed }) if speed <= 0.0
    ));
    for (push, ok) in [(99usize, true), (101, false)] {
        let s = piecewise(500.0, 0.0, 200, &[(100.0, push)], 20);
        let e = estimate(&s.samples, &StrokeConfig::new(500.0)).unwrap();
        let hit = e.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE);
        assert_eq!(hit.is_ok(), ok, "{} m/s: {hit:?}", e.cue_speed);
        if let Ok(hit) = hit {
            assert!(hit.speed.is_finite() && hit.spin.to_array().iter().all(|x| x.is_finite()));
        }
    }
}

/// Pins: reversed strokes — a push backwards only is `NotForward` with the exact
/// negative speed; a backswing then a stronger forward stroke gives the exact net speed;
/// a sensor mounted backwards (words negated) with a negative scale gives the same
/// speed as the forward mounting.
#[test]
fn reversed_strokes() {
    let config = StrokeConfig::new(FS);
    let back = piecewise(FS, 0.4, 2000, &[(-10.0, 800)], 300);
    match estimate(&back.samples, &config) {
        Err(StrokeError::NotForward { speed }) => {
            let err = (f64::from(speed) - back.speed).abs();
            assert!(err <= 1e-5 * back.speed.abs(), "{speed} vs {}", back.speed);
        }
        other => panic!("{other:?}"),
    }
    let swing = piecewise(FS, 0.4, 2000, &[(-5.0, 1000), (0.0, 300), (12.0, 800)], 300);
    assert_exact(
        &swing,
        estimate(&swing.samples, &config),
        FS,
        "backswing + stroke",
    );
    let raw = to_raw(&swing.samples, ACCEL_MPS2_PER_LSB);
    let flipped: Vec<i16> = raw.iter().map(|&w| w.saturating_neg()).collect();
    let forward = estimate_raw(&raw, ACCEL_MPS2_PER_LSB, &config).unwrap();
    let backward = estimate_raw(&flipped, -ACCEL_MPS2_PER_LSB, &config).unwrap();
    assert!((forward.cue_speed - backward.cue_speed).abs() <= 1e-5 * forward.cue_speed);
    assert!((f64::from(forward.cue_speed) - swing.speed).abs() <= 1e-3 * swing.speed);
}

/// Pins: NaN, +∞ and −∞ at the first, a middle and the last sample of the acceleration
/// or the pitch series are `NotFinite { index }` naming that sample, in all four
/// estimators; a non-finite or zero raw scale is `NotFinite { index: 0 }`.
#[test]
fn non_finite_samples_at_the_ends() {
    let config = StrokeConfig::new(FS);
    let s = step(FS, 0.0, 10.0, 800);
    let n = s.samples.len();
    let pitch = vec![0.0f32; n];
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for index in [0, n / 2, n - 1] {
            let mut a = s.samples.clone();
            a[index] = bad;
            let want = Err(StrokeError::NotFinite {
                index: index as u32,
            });
            assert_eq!(estimate(&a, &config), want);
            assert_eq!(estimate_with_pitch(&a, &pitch, &config), want);
            let mut p = pitch.clone();
            p[index] = bad;
            assert_eq!(estimate_with_pitch(&s.samples, &p, &config), want);
        }
    }
    let raw = to_raw(&s.samples, ACCEL_MPS2_PER_LSB);
    let zeros = vec![0i16; n];
    for scale in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, -0.0] {
        let want = Err(StrokeError::NotFinite { index: 0 });
        assert_eq!(estimate_raw(&raw, scale, &config), want, "{scale}");
        assert_eq!(
            estimate_raw_with_pitch(&raw, scale, &zeros, 1.0, &config),
            want
        );
        assert_eq!(
            estimate_raw_with_pitch(&raw, ACCEL_MPS2_PER_LSB, &zeros, scale, &config),
            want
        );
    }
}

/// Pins: extreme finite inputs — windows of ±`f32::MAX`, `f32::MIN_POSITIVE`, the
/// smallest subnormal, alternating ±`f32::MAX`, 1e30 spikes; raw scales of 1e-45 and
/// `f32::MAX`; i16::MIN/MAX pitch words — under the default configuration and with the
/// saturation check off: every answer is a typed error or an estimate passing the
/// contract checks.
#[test]
fn extreme_finite_samples_and_scales() {
    let n = 3000;
    let base = StrokeConfig::new(FS);
    let open = StrokeConfig {
        full_scale: f32::INFINITY,
        ..base
    };
    let mut windows: Vec<(&str, Vec<f32>)> = vec![
        ("f32::MAX", vec![f32::MAX; n]),
        ("-f32::MAX", vec![-f32::MAX; n]),
        ("MIN_POSITIVE", vec![f32::MIN_POSITIVE; n]),
        ("subnormal", vec![f32::from_bits(1); n]),
        (
            "alternating ±MAX",
            (0..n)
                .map(|i| if i % 2 == 0 { f32::MAX } else { -f32::MAX })
                .collect(),
        ),
    ];
    let mut spikes = step(FS, 0.0, 10.0, 800).samples;
    for i in (2100..2500).step_by(7) {
        spikes[i] = if i % 2 == 0 { 1e30 } else { -1e30 };
    }
    windows.push(("1e30 spikes in the stroke", spikes));
    let mut tail = step(FS, 0.0, 10.0, 800).samples;
    let last = tail.len() - 1;
    tail[last] = f32::MAX;
    windows.push(("f32::MAX after the impact", tail));
    let mut outcomes = Vec::new();
    for (what, w) in &windows {
        for (name, config) in [("default", base), ("no rail", open)] {
            match estimate(w, &config) {
                Ok(e) => {
                    check_estimate(&e, w.len(), FS, false)
                        .unwrap_or_else(|m| panic!("{what}: {m}"));
                    outcomes.push(format!("{what} ({name}): {} m/s", e.cue_speed));
                }
                Err(err) => outcomes.push(format!("{what} ({name}): {err:?}")),
            }
            let pitch = vec![f32::MAX; w.len()];
            if let Ok(e) = estimate_with_pitch(w, &pitch, &config) {
                check_estimate(&e, w.len(), FS, true).unwrap_or_else(|m| panic!("{what}: {m}"));
            }
        }
    }
    let raw = to_raw(&step(FS, 0.0, 10.0, 800).samples, ACCEL_MPS2_PER_LSB);
    let rails = vec![i16::MAX; raw.len()];
    let mut stroke_rail = vec![0i16; raw.len()];
    stroke_rail[2000..2800].fill(i16::MIN);
    for scale in [
        f32::from_bits(1),
        -f32::from_bits(1),
        1e-30,
        f32::MAX,
        -f32::MAX,
    ] {
        for config in [base, open] {
            if let Ok(e) = estimate_raw(&raw, scale, &config) {
                check_estimate(&e, raw.len(), FS, false).unwrap();
            }
            for pitch in [&rails, &stroke_rail] {
                for pitch_scale in [GYRO_RADPS_PER_LSB, f32::MAX] {
                    if let Ok(e) = estimate_raw_with_pitch(&raw, scale, pitch, pitch_scale, &config)
                    {
                        check_estimate(&e, raw.len(), FS, true).unwrap();
                    }
                }
            }
        }
    }
    for o in outcomes {
        println!("{o}");
    }
}

/// Regression (found writing this suite): with rest limits far beyond any sensor's
/// range (accepted: they are finite and positive), blocks that each pass the stillness
/// tests could form a rest whose spread overflows f32, and the estimate came back `Ok`
/// with `rest_noise` = NaN. Pins: such a window is `NotAtRest`.
#[test]
fn rest_spread_beyond_f32_is_not_a_rest() {
    let config = StrokeConfig {
        rest_noise_limit: 2e18,
        rest_level_tolerance: 1e17,
        impact_threshold: 1e19,
        full_scale: f32::INFINITY,
        ..StrokeConfig::new(FS)
    };
    for extra in 0..2 {
        let mut s: Vec<f32> = (0..2004 + extra)
            .map(|i| if i % 2 == 0 { 1e18 } else { -1e18 })
            .collect();
        s.extend(std::iter::repeat_n(3e17f32, 500));
        s.extend(std::iter::repeat_n(0.0f32, 300));
        s.extend(std::iter::repeat_n(-2e19f32, 6));
        assert_eq!(
            estimate(&s, &config),
            Err(StrokeError::NotAtRest),
            "{extra}"
        );
    }
}

/// Pins: the gyro-aided estimators at the cue-elevation limits (±1.2 rad) with a zero
/// pitch rate give exactly the accelerometer-only answer, and with a constant pitch
/// rate (pure gyro bias, removed at rest) the same to 1e-5.
#[test]
fn gyro_aided_at_the_elevation_limits() {
    let s = step(FS, 0.3, 10.0, 800);
    let n = s.samples.len();
    for elevation in [-1.2f32, 0.0, 1.2] {
        let config = StrokeConfig {
            cue_elevation: elevation,
            ..StrokeConfig::new(FS)
        };
        let plain = estimate(&s.samples, &config).unwrap();
        let zero = estimate_with_pitch(&s.samples, &vec![0.0; n], &config).unwrap();
        assert_eq!(plain, zero, "{elevation}");
        let biased = estimate_with_pitch(&s.samples, &vec![0.02; n], &config).unwrap();
        check_estimate(&biased, n, FS, true).unwrap();
        assert!((biased.cue_speed - plain.cue_speed).abs() <= 1e-5 * plain.cue_speed);
    }
}

/// Pins: the capture path at the ring's capacity — exactly 24,000 and 24,001 words
/// pushed (the ring drops the oldest rest sample), and 25,000, through
/// `RingBuffer<i16, 24_000>` and an 8 g `ImpactTrigger` (20 post-impact samples) give the
/// same speed, the exact `800 × 2507 LSB × 0.488 mg / 6667 Hz`; when the ring has
/// overwritten all but 0.1 s of the rest (under the 0.15 s `min_rest`), `NotAtRest`,
/// while 0.3 s kept is measured.
#[test]
fn capture_at_the_ring_capacity() {
    const N: usize = 24_000;
    const POST: usize = 20;
    let capture = |raw: &[i16]| {
        let mut ring = Box::new(RingBuffer::<i16, N>::new(0));
        let mut trigger = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, POST).unwrap();
        let mut pushed = 0;
        let done = raw.iter().any(|&w| {
            ring.push(w);
            pushed += 1;
            trigger.push(accel_lsb_to_mps2(w))
        });
        assert!(done, "the trigger never completed");
        (
            pushed,
            estimate_raw(
                ring.make_contiguous(),
                ACCEL_MPS2_PER_LSB,
                &StrokeConfig::new(FS),
            ),
        )
    };
    let word = (12.0 / ACCEL_LSB_F64).round() as i16;
    assert_eq!(word, 2507);
    let a = f32::from(word) * ACCEL_MPS2_PER_LSB;
    // Pushed: the rest, 800 + 300 stroke samples, the impact sample and POST more.
    let stroke = 800 + 300 + 1 + POST;
    let mut speeds = Vec::new();
    for pushes in [N, N + 1, N + 1000] {
        let s = piecewise(FS, 0.0, pushes - stroke, &[(a, 800)], 300);
        let (pushed, e) = capture(&to_raw(&s.samples, ACCEL_MPS2_PER_LSB));
        assert_eq!(pushed, pushes);
        speeds.push(e.unwrap().cue_speed);
    }
    assert!(speeds.iter().all(|&v| v == speeds[0]), "{speeds:?}");
    let exact = 800.0 * f64::from(word) * ACCEL_LSB_F64 / f64::from(FS);
    assert!(
        (f64::from(speeds[0]) - exact).abs() <= 1e-5 * exact,
        "{} vs {exact}",
        speeds[0]
    );
    for (kept, ok) in [(667usize, false), (2000, true)] {
        // A long rest, then 100-sample chunks of ±3 m/s² (moving: not still), the
        // stroke; the ring keeps `kept` samples of the rest.
        let mut s = vec![0.0f32; 20_000];
        let wobble = N - kept - stroke;
        s.extend((0..wobble).map(|i| if (i / 100) % 2 == 0 { 3.0 } else { -3.0 }));
        s.extend(piecewise(FS, 0.0, 0, &[(a, 800)], 300).samples);
        let (_, got) = capture(&to_raw(&s, ACCEL_MPS2_PER_LSB));
        match got {
            Ok(e) if ok => check_estimate(&e, N, FS, false).unwrap(),
            Err(StrokeError::NotAtRest) if !ok => {}
            other => panic!("{kept} rest samples kept: {other:?}"),
        }
    }
}

/// Pins: `StrokeEstimate::strike` at the strike model's cue-speed limits: the smallest
/// positive speed (1e-45 m/s) and exactly 20 m/s are accepted with finite outputs; one
/// ulp above 20 m/s is `Strike(OutOfRange { CueSpeed, value })`.
#[test]
fn strike_at_the_cue_speed_limits() {
    let s = step(FS, 0.0, 10.0, 800);
    let e = estimate(&s.samples, &StrokeConfig::new(FS)).unwrap();
    for (speed, ok) in [
        (f32::from_bits(1), true),
        (20.0, true),
        (next_up(20.0), false),
    ] {
        let est = StrokeEstimate {
            cue_speed: speed,
            ..e
        };
        for tip in [
            TipOffset::CENTRE,
            TipOffset::new(0.0, 0.4 * 0.028575).unwrap(),
        ] {
            match est.strike(&Params::POOL, &Cue::TYPICAL, tip) {
                Ok(hit) if ok => {
                    assert!(hit.speed.is_finite() && hit.speed >= 0.0);
                    assert!(hit.spin.to_array().iter().all(|x| x.is_finite()));
                }
                Err(StrokeError::Strike(CoreError::OutOfRange {
                    field: Field::CueSpeed,
                    value,
                })) if !ok => assert_eq!(value, speed),
                other => panic!("{speed}: {other:?}"),
            }
        }
    }
}
