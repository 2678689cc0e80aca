//! The `u32` sample indices across their wrap (7.4 days of samples at 6.66 kHz, too
//! many to push in a test): an estimator started just before 2³² gives the events of
//! one started at 0, bit for bit, with every index shifted by the start.

extern crate std;

use std::vec::Vec;

use super::{StreamConfig, StreamEvent, StreamFault, StreamingEstimator};

const FS: f32 = 6667.0;

/// A plain stroke stream in raw words (0.488 mg/LSB, 70 mdps/LSB): 0.6 s still, a
/// 0.5 s backswing (one sine period of acceleration), a 0.3 s pause, a 0.3 s forward swing reaching about
/// 2 m/s, a 1.5 ms contact at −30 g (clipped at full scale), 0.3 s of follow-through, 0.6 s still; 1 g of
/// gravity along the cue, a small pitch rate in the swing, ±3 LSB of deterministic
/// noise on both words. Then the same once more, and a knock in the last rest.
fn stream() -> (Vec<i16>, Vec<i16>) {
    let (mut accel, mut pitch) = (Vec::new(), Vec::new());
    let mut seed = 0x2545_f491_u32;
    let mut noise = move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        (seed % 7) as i32 - 3
    };
    let lsb = 9.806_65 * 0.488e-3;
    let pi = core::f32::consts::PI;
    for _ in 0..2 {
        let phases: [(f32, f32); 7] = [
            (0.6, 0.0),
            (0.5, -1.5),
            (0.3, 0.0),
            (0.3, 10.5),
            (0.0015, -294.0),
            (0.3, -6.0),
            (0.6, 0.0),
        ];
        for (k, (length, peak)) in phases.into_iter().enumerate() {
            let samples = (length * FS) as usize;
            for i in 0..samples {
                let phase = pi * i as f32 / samples as f32;
                let shape = match k {
                    4 => 1.0,
                    // Back and stopped again: one period of the sine.
                    1 if i < samples / 2 => libm_free_sin(2.0 * phase),
                    1 => -libm_free_sin(2.0 * phase - pi),
                    _ => libm_free_sin(phase),
                };
                let a = (peak * shape + 9.806_65) / lsb;
                accel.push((a as i32 + noise()).clamp(-32_768, 32_767) as i16);
                let rate = if k == 1 || k == 3 { 40 } else { 0 };
                pitch.push((rate + noise()) as i16);
            }
        }
    }
    let knock = accel.len() - 2_000;
    accel[knock..knock + 4].fill(-30_000);
    (accel, pitch)
}

/// `sin x` for `0 ≤ x ≤ π` (a polynomial is plenty for a test shape).
fn libm_free_sin(x: f32) -> f32 {
    let y = if x > core::f32::consts::FRAC_PI_2 {
        core::f32::consts::PI - x
    } else {
        x
    };
    let y2 = y * y;
    y * (1.0 - y2 / 6.0 * (1.0 - y2 / 20.0 * (1.0 - y2 / 42.0)))
}

/// Every event of the stream, from an estimator whose first sample has index `start`.
fn events_from(start: u64) -> Vec<(usize, StreamEvent)> {
    let mut est = StreamingEstimator::new(&StreamConfig::new(FS)).unwrap();
    est.block_base = start;
    est.block.start = start as u32;
    assert_eq!(est.samples(), start);
    let (accel, pitch) = stream();
    let mut events = Vec::new();
    for (i, (&a, &p)) in accel.iter().zip(&pitch).enumerate() {
        if let Some(e) = est.push_raw(a, Some(p)) {
            events.push((i, e));
        }
    }
    assert_eq!(est.samples(), start + accel.len() as u64);
    events
}

/// `event` with every index less `offset`.
fn shifted(event: StreamEvent, offset: u64) -> StreamEvent {
    match event {
        StreamEvent::Stroke(mut s) => {
            s.impact_index -= offset;
            s.rest_start -= offset;
            s.rest_end -= offset;
            s.backswing_start -= offset;
            StreamEvent::Stroke(s)
        }
        #[cfg(feature = "follow-through")]
        StreamEvent::FollowThrough {
            impact,
            length,
            time,
        } => StreamEvent::FollowThrough {
            impact: impact - offset,
            length,
            time,
        },
        StreamEvent::Fault(f) => StreamEvent::Fault(match f {
            StreamFault::NotAtRest { index } => StreamFault::NotAtRest {
                index: index - offset,
            },
            StreamFault::DoubleHit { first, second } => StreamFault::DoubleHit {
                first: first - offset,
                second: second - offset,
            },
            StreamFault::Saturated { index, impact } => StreamFault::Saturated {
                index: index - offset,
                impact: impact - offset,
            },
            StreamFault::NotForward { impact, speed } => StreamFault::NotForward {
                impact: impact - offset,
                speed,
            },
            StreamFault::NotFinite { index } => StreamFault::NotFinite {
                index: index - offset,
            },
            StreamFault::EndedMidStroke { rest_end, samples } => StreamFault::EndedMidStroke {
                rest_end: rest_end - offset,
                samples: samples - offset,
            },
        }),
    }
}

#[test]
fn the_stream_has_its_strokes_and_the_knock() {
    let events = events_from(0);
    let strokes = events
        .iter()
        .filter(|(_, e)| matches!(e, StreamEvent::Stroke(_)))
        .count();
    assert_eq!(strokes, 2, "{events:?}");
    assert!(
        matches!(
            events.last(),
            Some((
                _,
                StreamEvent::Fault(StreamFault::NotAtRest { .. } | StreamFault::NotForward { .. })
            ))
        ),
        "{events:?}"
    );
}

#[test]
fn indices_wrap_without_changing_any_event() {
    let reference = events_from(0);
    let first_impact = reference[0].0 as u64;
    // The wrap in the first rest, just before the first impact, at it, in the second
    // stroke, and a whole stream after it (the block starts then lie beyond 2³²).
    for before in [
        100,
        first_impact - 10,
        first_impact,
        first_impact + 20_000,
        0,
    ] {
        let start = (1u64 << 32) - before;
        let start = if before == 0 { 1u64 << 33 } else { start };
        let events = events_from(start);
        assert_eq!(events.len(), reference.len(), "start {start}: {events:?}");
        for ((i, e), (j, r)) in events.into_iter().zip(&reference) {
            assert_eq!(i, *j, "start {start}");
            assert_eq!(shifted(e, start), *r, "start {start}");
        }
    }
}

#[test]
fn rest_end_follows_the_stroke() {
    let mut est = StreamingEstimator::new(&StreamConfig::new(FS)).unwrap();
    let (accel, pitch) = stream();
    let mut seen = None;
    for (&a, &p) in accel.iter().zip(&pitch) {
        let before = est.rest_end();
        match est.push_raw(a, Some(p)) {
            Some(StreamEvent::Stroke(s)) => {
                // Reported with the origin it had before the impact ended it.
                assert_eq!(before, Some(s.rest_end));
                assert_eq!(est.rest_end(), None);
                seen = Some(s.rest_end);
            }
            _ => assert_eq!(est.rest_end().is_some(), est.in_stroke()),
        }
    }
    assert!(seen.is_some());
}

/// The validation as fifteen separate tests (how it was written before the table),
/// for the table's equivalence on edge values.
fn validation_as_tests(config: &StreamConfig) -> Result<(), super::StreamConfigError> {
    use super::StreamConfigError as E;
    use crate::stroke::ConfigField as F;
    let positive = |x: f32| x > 0.0 && x < f32::INFINITY;
    let nonzero = |x: f32| positive(x) || (x < 0.0 && x > f32::NEG_INFINITY);
    let s = &config.stroke;
    let rate = s.sample_rate_hz;
    let checks = [
        ((500.0..=10_000.0).contains(&rate), E::SampleRate),
        (positive(s.impact_threshold), E::Stroke(F::ImpactThreshold)),
        (positive(s.onset_drop), E::Stroke(F::OnsetDrop)),
        (positive(s.rest_noise_limit), E::Stroke(F::RestNoiseLimit)),
        (
            positive(s.rest_level_tolerance),
            E::Stroke(F::RestLevelTolerance),
        ),
        (positive(s.motion_floor), E::Stroke(F::MotionFloor)),
        (
            positive(s.min_rest) && s.min_rest <= 10.0,
            E::Stroke(F::MinRest),
        ),
        (s.full_scale > s.impact_threshold, E::Stroke(F::FullScale)),
        (
            s.cue_elevation >= -1.2 && s.cue_elevation <= 1.2,
            E::Stroke(F::CueElevation),
        ),
        (nonzero(config.accel_scale), E::AccelScale),
        (nonzero(config.pitch_scale), E::PitchScale),
        (
            config.trusted_rest >= s.min_rest && config.trusted_rest <= 60.0,
            E::TrustedRest,
        ),
        (
            positive(config.max_stroke) && config.max_stroke <= 60.0,
            E::MaxStroke,
        ),
        (
            positive(config.double_hit_window) && config.double_hit_window <= 1.0,
            E::DoubleHitWindow,
        ),
        (
            config.min_speed >= 0.0 && config.min_speed < f32::INFINITY,
            E::MinSpeed,
        ),
    ];
    match checks.iter().find(|(ok, _)| !ok) {
        Some(&(_, error)) => Err(error),
        None => Ok(()),
    }
}

#[test]
fn the_validation_table_is_the_fifteen_tests() {
    let values = [
        f32::NAN,
        -f32::NAN,
        f32::NEG_INFINITY,
        -1.0,
        -0.0,
        0.0,
        f32::from_bits(1),
        1e-40,
        0.05,
        0.15,
        1.0,
        1.2,
        f32::from_bits(1.2f32.to_bits() + 1),
        10.0,
        10.5,
        60.0,
        60.1,
        78.45,
        78.450005,
        500.0,
        6667.0,
        10_000.0,
        10_001.0,
        f32::MAX,
        f32::INFINITY,
    ];
    let base = StreamConfig::new(FS);
    let mut checked = 0;
    for field in 0..15 {
        for &x in &values {
            for sign in [1.0f32, -1.0] {
                let x = sign * x;
                let mut c = base;
                match field {
                    0 => c.stroke.sample_rate_hz = x,
                    1 => c.stroke.impact_threshold = x,
                    2 => c.stroke.onset_drop = x,
                    3 => c.stroke.rest_noise_limit = x,
                    4 => c.stroke.rest_level_tolerance = x,
                    5 => c.stroke.motion_floor = x,
                    6 => c.stroke.min_rest = x,
                    7 => c.stroke.full_scale = x,
                    8 => c.stroke.cue_elevation = x,
                    9 => c.accel_scale = x,
                    10 => c.pitch_scale = x,
                    11 => c.trusted_rest = x,
                    12 => c.max_stroke = x,
                    13 => c.double_hit_window = x,
                    _ => c.min_speed = x,
                }
                // The impact threshold next to the full scale's edge, too.
                for threshold in [c.stroke.impact_threshold, c.stroke.full_scale] {
                    let c = StreamConfig {
                        stroke: crate::StrokeConfig {
                            impact_threshold: threshold,
                            ..c.stroke
                        },
                        ..c
                    };
                    assert_eq!(
                        StreamingEstimator::new(&c).err(),
                        validation_as_tests(&c).err(),
                        "field {field}, value {x:e}, threshold {threshold:e}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 15 * 25 * 2 * 2);
}

/// `CheckedConfig::plan_at` is `StreamPlan::new` at the rate: the same plan for every
/// rate the nRF52840's trim gives and around the accepted range's edges, the same error
/// outside it (NaN too), and `CheckedConfig::new` refuses what `StreamPlan::new` does.
#[test]
fn a_checked_config_plans_at_any_rate_as_the_plan_does() {
    use super::{CheckedConfig, StreamPlan};
    let mut base = StreamConfig::new(FS);
    base.defer_reports = true;
    #[cfg(feature = "follow-through")]
    {
        base.follow_through = true;
    }
    let checked = CheckedConfig::new(&base).unwrap();
    let trims = (-128i32..=127).map(|t| crate::lsm6dsox::trimmed_odr_hz(t as i8 as u8));
    let edges = [
        f32::NAN,
        f32::NEG_INFINITY,
        -1.0,
        0.0,
        499.99997,
        500.0,
        3333.0,
        6667.0,
        10_000.0,
        10_000.001,
        f32::MAX,
        f32::INFINITY,
    ];
    for rate in trims.chain(edges) {
        let mut config = base;
        config.stroke.sample_rate_hz = rate;
        let expected = StreamPlan::new(&config);
        let planned = checked.plan_at(rate);
        match (planned, expected) {
            (Ok(a), Ok(b)) => assert_eq!(a.0, b.0, "rate {rate:e}"),
            (a, b) => assert_eq!(a.err(), b.err(), "rate {rate:e}"),
        }
    }
    let mut bad = base;
    bad.max_stroke = 61.0;
    assert_eq!(CheckedConfig::new(&bad).err(), StreamPlan::new(&bad).err());
    assert!(CheckedConfig::new(&bad).is_err());
}
