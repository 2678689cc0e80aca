//! Input validation of the sensors crate, table-driven (issue 6, item 2): every invalid
//! input to every public constructor and function — the LSM6DSOX driver (bus address,
//! chip id, reset, bus errors), `ImpactTrigger::new`, every `StrokeConfig` field through
//! each of the four estimators, raw scales, non-finite samples, window and series
//! lengths, windows the estimator cannot use, and `StrokeEstimate::strike` — returns its
//! typed error: the variant, every field it carries (values bit for bit), and a
//! `Display` message that is not empty and names the problem (the field, index, value
//! or address). The accepted edges are accepted, the ring buffer's refusals are values
//! (never a panic), and the conversion functions, which return no `Result`, are finite
//! on their whole domain. `-- --nocapture` prints every row.

mod common;

use common::*;
use cuesight::strike::{Cue, TipOffset};
use cuesight::{Error as CoreError, Field, Params};
use cuesight_sensors::lsm6dsox::{
    trimmed_odr_hz, Error as ImuError, I2cInterface, ADDRESS_SA0_HIGH, ADDRESS_SA0_LOW,
    RESET_POLLS, STANDARD_GRAVITY,
};
use cuesight_sensors::{
    accel_lsb_to_mps2, estimate, estimate_raw, estimate_raw_with_pitch, estimate_with_pitch,
    gyro_lsb_to_radps, Axis, ConfigField, ImpactTrigger, InvalidThreshold, Lsm6dsox, RingBuffer,
    StrokeConfig, StrokeError, StrokeEstimate, ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB,
};
use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::i2c::{Mock, Transaction};

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;
const POOL_RADIUS: f32 = 0.028575;

/// Any of the crate's error types.
#[derive(Clone, Copy, Debug)]
enum Refusal {
    Stroke(StrokeError),
    Imu(ImuError<ErrorKind>),
    Trigger(InvalidThreshold),
}

impl Refusal {
    fn message(&self) -> String {
        match self {
            Refusal::Stroke(e) => e.to_string(),
            Refusal::Imu(e) => e.to_string(),
            Refusal::Trigger(e) => e.to_string(),
        }
    }

    /// Equal variants and fields, f32 fields bit for bit.
    fn same(&self, other: &Refusal) -> bool {
        match (self, other) {
            (Refusal::Trigger(a), Refusal::Trigger(b)) => {
                a.threshold.to_bits() == b.threshold.to_bits()
            }
            (
                Refusal::Stroke(StrokeError::NotForward { speed: a }),
                Refusal::Stroke(StrokeError::NotForward { speed: b }),
            ) => a.to_bits() == b.to_bits(),
            (
                Refusal::Stroke(StrokeError::Strike(CoreError::OutOfRange {
                    field: fa,
                    value: a,
                })),
                Refusal::Stroke(StrokeError::Strike(CoreError::OutOfRange {
                    field: fb,
                    value: b,
                })),
            ) => fa == fb && a.to_bits() == b.to_bits(),
            (Refusal::Stroke(a), Refusal::Stroke(b)) => a == b,
            (Refusal::Imu(a), Refusal::Imu(b)) => a == b,
            _ => false,
        }
    }
}

type Call = Box<dyn Fn() -> Result<(), Refusal>>;

/// One row: what is called, the call, the expected refusal, and what its message must
/// contain (besides being non-empty).
struct Row {
    what: String,
    call: Call,
    expect: Refusal,
    needles: Vec<String>,
}

fn row(
    what: impl Into<String>,
    call: impl Fn() -> Result<(), Refusal> + 'static,
    expect: Refusal,
    needles: &[&str],
) -> Row {
    Row {
        what: what.into(),
        call: Box::new(call),
        expect,
        needles: needles.iter().map(|s| s.to_string()).collect(),
    }
}

fn check_rows(rows: Vec<Row>) -> usize {
    let n = rows.len();
    let mut failures = Vec::new();
    for r in rows {
        match (r.call)() {
            Err(got) if got.same(&r.expect) => {
                let message = got.message();
                let missing: Vec<&String> = r
                    .needles
                    .iter()
                    .filter(|s| !message.contains(s.as_str()))
                    .collect();
                if message.trim().is_empty() || !missing.is_empty() {
                    failures.push(format!("{}: message {message:?} lacks {missing:?}", r.what));
                } else {
                    println!("{:64} -> {message}", r.what);
                }
            }
            got => failures.push(format!("{}: expected {:?}, got {got:?}", r.what, r.expect)),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {n} rows failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    n
}

// ---------------------------------------------------------------------------------------
// LSM6DSOX
// ---------------------------------------------------------------------------------------

/// Run `f` on a driver over a mock bus expecting exactly `expectations`.
fn with_imu(
    address: u8,
    expectations: Vec<Transaction>,
    f: impl Fn(&mut Lsm6dsox<I2cInterface<Mock>>) -> Result<(), ImuError<ErrorKind>> + 'static,
) -> impl Fn() -> Result<(), Refusal> + 'static {
    move || {
        let mut i2c = Mock::new(&expectations);
        let mut imu = Lsm6dsox::new(i2c.clone(), address);
        let result = f(&mut imu);
        i2c.done();
        result.map_err(Refusal::Imu)
    }
}

fn imu_rows() -> Vec<Row> {
    let a = ADDRESS_SA0_LOW;
    let mut rows = Vec::new();
    for address in [0x00u8, 0x69, 0x6C, 0x7F, 0x80, 0xD4, 0xD6, 0xFF] {
        let hex = format!("0x{address:02X}");
        rows.push(row(
            format!("Lsm6dsox::new(_, {hex}).init()"),
            with_imu(address, vec![], |imu| imu.init()),
            Refusal::Imu(ImuError::InvalidAddress(address)),
            &[&hex, "0x6A", "0x6B", "address"],
        ));
    }
    type Method = fn(&mut Lsm6dsox<I2cInterface<Mock>>) -> Result<(), ImuError<ErrorKind>>;
    let methods: [(&str, Method); 6] = [
        ("who_am_i", |imu| imu.who_am_i().map(drop)),
        ("data_ready", |imu| imu.data_ready().map(drop)),
        ("enable_accel_data_ready_int1", |imu| {
            imu.enable_accel_data_ready_int1()
        }),
        ("read_raw", |imu| imu.read_raw().map(drop)),
        ("read", |imu| imu.read().map(drop)),
        ("read_accel_axis_raw(Y)", |imu| {
            imu.read_accel_axis_raw(Axis::Y).map(drop)
        }),
    ];
    for (name, method) in methods {
        rows.push(row(
            format!("Lsm6dsox::new(_, 0xD4).{name}() (8-bit address form)"),
            with_imu(0xD4, vec![], method),
            Refusal::Imu(ImuError::InvalidAddress(0xD4)),
            &["0xD4", "address"],
        ));
    }
    for id in [0x00u8, 0x69, 0x6A, 0x6B, 0x6D, 0xFF] {
        let hex = format!("0x{id:02X}");
        rows.push(row(
            format!("init, WHO_AM_I reads {hex}"),
            with_imu(
                a,
                vec![Transaction::write_read(a, vec![0x0F], vec![id])],
                |imu| imu.init(),
            ),
            Refusal::Imu(ImuError::WrongChipId(id)),
            &[&hex, "0x6C", "WHO_AM_I"],
        ));
    }
    let mut never = vec![
        Transaction::write_read(a, vec![0x0F], vec![0x6C]),
        Transaction::write(a, vec![0x12, 0x01]),
    ];
    never.extend((0..RESET_POLLS).map(|_| Transaction::write_read(a, vec![0x12], vec![0x45])));
    rows.push(row(
        "init, SW_RESET never clears",
        with_imu(a, never, |imu| imu.init()),
        Refusal::Imu(ImuError::ResetTimeout),
        &["reset", &RESET_POLLS.to_string()],
    ));
    let fail = |t: Transaction| {
        vec![t.with_error(ErrorKind::NoAcknowledge(
            embedded_hal::i2c::NoAcknowledgeSource::Address,
        ))]
    };
    let bus = Refusal::Imu(ImuError::Bus(ErrorKind::NoAcknowledge(
        embedded_hal::i2c::NoAcknowledgeSource::Address,
    )));
    let b = ADDRESS_SA0_HIGH;
    let cases: [(&str, Vec<Transaction>, Method); 6] = [
        (
            "init, NACK on WHO_AM_I",
            fail(Transaction::write_read(b, vec![0x0F], vec![0])),
            |imu| imu.init(),
        ),
        (
            "who_am_i, NACK",
            fail(Transaction::write_read(b, vec![0x0F], vec![0])),
            |imu| imu.who_am_i().map(drop),
        ),
        (
            "data_ready, NACK",
            fail(Transaction::write_read(b, vec![0x1E], vec![0])),
            |imu| imu.data_ready().map(drop),
        ),
        (
            "enable_accel_data_ready_int1, NACK",
            fail(Transaction::write(b, vec![0x0D, 0x01])),
            |imu| imu.enable_accel_data_ready_int1(),
        ),
        (
            "read_raw, NACK",
            fail(Transaction::write_read(b, vec![0x22], vec![0; 12])),
            |imu| imu.read_raw().map(drop),
        ),
        (
            "read_accel_axis_raw(Z), NACK",
            fail(Transaction::write_read(b, vec![0x2C], vec![0; 2])),
            |imu| imu.read_accel_axis_raw(Axis::Z).map(drop),
        ),
    ];
    for (what, expectations, method) in cases {
        rows.push(row(
            what,
            with_imu(b, expectations, method),
            bus,
            &["bus", "NoAcknowledge"],
        ));
    }
    rows
}

#[test]
fn driver_refusals_are_typed() {
    let n = check_rows(imu_rows());
    println!("{n} driver rows");
    cuesight_figures::record!("reliability-sensors-validation-driver-rows", "{n}");
}

// ---------------------------------------------------------------------------------------
// Impact trigger
// ---------------------------------------------------------------------------------------

#[test]
fn trigger_threshold_refusals_are_typed() {
    let mut rows = Vec::new();
    for t in [
        NAN,
        INF,
        -INF,
        0.0,
        -0.0,
        -f32::from_bits(1),
        -8.0 * STANDARD_GRAVITY,
        -f32::MAX,
    ] {
        let shown = format!("{t}");
        rows.push(row(
            format!("ImpactTrigger::new({t:e}, 333)"),
            move || {
                ImpactTrigger::new(t, 333)
                    .map(drop)
                    .map_err(Refusal::Trigger)
            },
            Refusal::Trigger(InvalidThreshold { threshold: t }),
            &["threshold", &shown, "finite", "> 0"],
        ));
    }
    let n = check_rows(rows);
    cuesight_figures::record!("reliability-sensors-validation-trigger-rows", "{n}");
    // Accepted edges: the smallest subnormal and the largest finite threshold, any count.
    for t in [
        f32::from_bits(1),
        f32::MIN_POSITIVE,
        8.0 * STANDARD_GRAVITY,
        f32::MAX,
    ] {
        for post in [0, 1, usize::MAX] {
            let trigger = ImpactTrigger::new(t, post).unwrap();
            assert_eq!(trigger.threshold().to_bits(), t.to_bits());
            assert!(!trigger.is_triggered());
        }
    }
    println!("{n} trigger rows");
}

// ---------------------------------------------------------------------------------------
// Stroke estimator
// ---------------------------------------------------------------------------------------

/// A valid stroke (0.3 s rest, 10 m/s² for 800 samples, impact) and its raw words.
fn stroke() -> (Vec<f32>, Vec<i16>) {
    let s = step(FS, 0.0, 10.0, 800).samples;
    let raw = to_raw(&s, ACCEL_MPS2_PER_LSB);
    (s, raw)
}

/// The four estimators on the same window, each as a row call.
fn four_estimators(samples: Vec<f32>, config: StrokeConfig) -> Vec<(&'static str, Call)> {
    let raw = to_raw(&samples, ACCEL_MPS2_PER_LSB);
    let pitch = vec![0.0f32; samples.len()];
    let raw_pitch = vec![0i16; samples.len()];
    let (s1, s2, r1, r2) = (samples.clone(), samples, raw.clone(), raw);
    let err = |r: Result<StrokeEstimate, StrokeError>| r.map(drop).map_err(Refusal::Stroke);
    vec![
        ("estimate", Box::new(move || err(estimate(&s1, &config)))),
        (
            "estimate_with_pitch",
            Box::new(move || err(estimate_with_pitch(&s2, &pitch, &config))),
        ),
        (
            "estimate_raw",
            Box::new(move || err(estimate_raw(&r1, ACCEL_MPS2_PER_LSB, &config))),
        ),
        (
            "estimate_raw_with_pitch",
            Box::new(move || {
                err(estimate_raw_with_pitch(
                    &r2,
                    ACCEL_MPS2_PER_LSB,
                    &raw_pitch,
                    GYRO_RADPS_PER_LSB,
                    &config,
                ))
            }),
        ),
    ]
}

/// Every `StrokeConfig` field's invalid values, each through the four estimators.
fn config_rows() -> Vec<Row> {
    let base = StrokeConfig::new(FS);
    let thr = base.impact_threshold;
    type Set = fn(&mut StrokeConfig, f32);
    let positive = [NAN, INF, -INF, 0.0, -0.0, -1.0, -f32::MAX];
    let fields: Vec<(ConfigField, Set, Vec<f32>)> = vec![
        (
            ConfigField::SampleRate,
            |c, v| c.sample_rate_hz = v,
            vec![
                NAN,
                INF,
                -INF,
                0.0,
                -0.0,
                -6667.0,
                1.0,
                next_down(500.0),
                next_up(100_000.0),
                1e9,
            ],
        ),
        (
            ConfigField::ImpactThreshold,
            |c, v| c.impact_threshold = v,
            positive.to_vec(),
        ),
        (
            ConfigField::OnsetDrop,
            |c, v| c.onset_drop = v,
            positive.to_vec(),
        ),
        (
            ConfigField::MinRest,
            |c, v| c.min_rest = v,
            vec![NAN, INF, -INF, 0.0, -0.0, -0.15, next_up(10.0), 60.0],
        ),
        (
            ConfigField::RestNoiseLimit,
            |c, v| c.rest_noise_limit = v,
            positive.to_vec(),
        ),
        (
            ConfigField::RestLevelTolerance,
            |c, v| c.rest_level_tolerance = v,
            positive.to_vec(),
        ),
        (
            ConfigField::MotionFloor,
            |c, v| c.motion_floor = v,
            positive.to_vec(),
        ),
        (
            ConfigField::FullScale,
            |c, v| c.full_scale = v,
            vec![NAN, -INF, 0.0, -1.0, thr, next_down(thr)],
        ),
        (
            ConfigField::CueElevation,
            |c, v| c.cue_elevation = v,
            vec![
                NAN,
                INF,
                -INF,
                next_up(1.2),
                next_down(-1.2),
                std::f32::consts::PI,
            ],
        ),
    ];
    let (samples, _) = stroke();
    let mut rows = Vec::new();
    for (field, set, values) in fields {
        for value in values {
            let mut config = base;
            set(&mut config, value);
            for (name, call) in four_estimators(samples.clone(), config) {
                rows.push(Row {
                    what: format!("{name}, {} = {value:e}", field.name()),
                    call,
                    expect: Refusal::Stroke(StrokeError::InvalidConfig(field)),
                    needles: vec![field.name().to_string(), "must be".to_string()],
                });
            }
        }
    }
    rows
}

#[test]
fn config_refusals_are_typed() {
    let n = check_rows(config_rows());
    println!("{n} configuration rows");
    cuesight_figures::record!("reliability-sensors-validation-config-rows", "{n}");
    // Names and ranges: distinct, non-empty, as in the source.
    let all = [
        ConfigField::SampleRate,
        ConfigField::ImpactThreshold,
        ConfigField::OnsetDrop,
        ConfigField::MinRest,
        ConfigField::RestNoiseLimit,
        ConfigField::RestLevelTolerance,
        ConfigField::MotionFloor,
        ConfigField::FullScale,
        ConfigField::CueElevation,
    ];
    let names: std::collections::HashSet<&str> = all.iter().map(|f| f.name()).collect();
    assert_eq!(names.len(), all.len());
    for f in all {
        assert_eq!(f.to_string(), f.name());
        assert!(!f.valid_range().is_empty());
    }
}

/// The accepted edge of every configuration field passes validation (the estimate may
/// still refuse the window for its content, never as `InvalidConfig`).
#[test]
fn config_edges_are_accepted() {
    let base = StrokeConfig::new(FS);
    let tiny = f32::from_bits(1);
    let edges = [
        StrokeConfig::new(500.0),
        StrokeConfig::new(100_000.0),
        StrokeConfig {
            impact_threshold: tiny,
            ..base
        },
        StrokeConfig {
            impact_threshold: f32::MAX,
            full_scale: INF,
            ..base
        },
        StrokeConfig {
            onset_drop: tiny,
            rest_noise_limit: tiny,
            rest_level_tolerance: tiny,
            motion_floor: tiny,
            ..base
        },
        StrokeConfig {
            onset_drop: f32::MAX,
            rest_noise_limit: f32::MAX,
            rest_level_tolerance: f32::MAX,
            motion_floor: f32::MAX,
            ..base
        },
        StrokeConfig {
            min_rest: tiny,
            ..base
        },
        StrokeConfig {
            min_rest: 10.0,
            ..base
        },
        StrokeConfig {
            full_scale: next_up(base.impact_threshold),
            ..base
        },
        StrokeConfig {
            full_scale: INF,
            ..base
        },
        StrokeConfig {
            cue_elevation: 1.2,
            ..base
        },
        StrokeConfig {
            cue_elevation: -1.2,
            ..base
        },
    ];
    let (samples, _) = stroke();
    let mut long = vec![0.0f32; 70_000];
    long.extend(&samples);
    for config in edges {
        for (name, call) in four_estimators(long.clone(), config) {
            if let Err(Refusal::Stroke(StrokeError::InvalidConfig(f))) = call() {
                panic!("{name}: {config:?} refused as {f:?}");
            }
        }
    }
    // Raw scales: any finite non-zero value, either sign (an all-zero window: no overflow).
    let zeros = vec![0i16; 5000];
    for scale in [
        tiny,
        -tiny,
        ACCEL_MPS2_PER_LSB,
        -ACCEL_MPS2_PER_LSB,
        f32::MAX,
        -f32::MAX,
    ] {
        assert_eq!(
            estimate_raw(&zeros, scale, &base),
            Err(StrokeError::NoImpact)
        );
        assert_eq!(
            estimate_raw_with_pitch(&zeros, scale, &zeros, scale, &base),
            Err(StrokeError::NoImpact)
        );
    }
}

/// Samples, scales, lengths and windows the estimator cannot use, and the strike.
fn input_rows() -> Vec<Row> {
    let config = StrokeConfig::new(FS);
    let (samples, raw) = stroke();
    let n = samples.len();
    let Err(StrokeError::TooShort { min, .. }) = estimate(&[], &config) else {
        panic!("an empty window was accepted");
    };
    let mut rows = Vec::new();
    let e = |r: Result<StrokeEstimate, StrokeError>| r.map(drop).map_err(Refusal::Stroke);
    let stroke_err = Refusal::Stroke;

    for len in [0u32, 1, min - 1] {
        let s = vec![0.0f32; len as usize];
        rows.push(row(
            format!("estimate, {len} samples"),
            move || e(estimate(&s, &config)),
            stroke_err(StrokeError::TooShort { len, min }),
            &[&format!("{len} samples"), &min.to_string(), "too short"],
        ));
        let r = vec![0i16; len as usize];
        rows.push(row(
            format!("estimate_raw, {len} samples"),
            move || e(estimate_raw(&r, ACCEL_MPS2_PER_LSB, &config)),
            stroke_err(StrokeError::TooShort { len, min }),
            &[&format!("{len} samples"), &min.to_string()],
        ));
    }
    for bad in [NAN, INF, -INF] {
        for index in [0, 1234, n - 1] {
            let mut s = samples.clone();
            s[index] = bad;
            rows.push(row(
                format!("estimate, sample {index} = {bad}"),
                move || e(estimate(&s, &config)),
                stroke_err(StrokeError::NotFinite {
                    index: index as u32,
                }),
                &[&format!("sample {index}"), "finite"],
            ));
            let mut p = vec![0.0f32; n];
            p[index] = bad;
            let s = samples.clone();
            rows.push(row(
                format!("estimate_with_pitch, pitch {index} = {bad}"),
                move || e(estimate_with_pitch(&s, &p, &config)),
                stroke_err(StrokeError::NotFinite {
                    index: index as u32,
                }),
                &[&format!("sample {index}"), "finite"],
            ));
        }
    }
    for scale in [NAN, INF, -INF, 0.0, -0.0] {
        let r = raw.clone();
        rows.push(row(
            format!("estimate_raw, scale {scale}"),
            move || e(estimate_raw(&r, scale, &config)),
            stroke_err(StrokeError::NotFinite { index: 0 }),
            &["scale", "finite", "non-zero"],
        ));
        let (r, z) = (raw.clone(), vec![0i16; n]);
        rows.push(row(
            format!("estimate_raw_with_pitch, accel scale {scale}"),
            move || {
                e(estimate_raw_with_pitch(
                    &r,
                    scale,
                    &z,
                    GYRO_RADPS_PER_LSB,
                    &config,
                ))
            },
            stroke_err(StrokeError::NotFinite { index: 0 }),
            &["scale"],
        ));
        let (r, z) = (raw.clone(), vec![0i16; n]);
        rows.push(row(
            format!("estimate_raw_with_pitch, pitch scale {scale}"),
            move || {
                e(estimate_raw_with_pitch(
                    &r,
                    ACCEL_MPS2_PER_LSB,
                    &z,
                    scale,
                    &config,
                ))
            },
            stroke_err(StrokeError::NotFinite { index: 0 }),
            &["scale"],
        ));
    }
    for (accel, pitch) in [(n, n - 1), (n, n + 1), (n, 0), (0, 1)] {
        let (a, p) = (samples[..accel.min(n)].to_vec(), vec![0.0f32; pitch]);
        let a = if accel > n { vec![0.0; accel] } else { a };
        let needles = [&accel.to_string()[..], &pitch.to_string()[..], "pitch"];
        let (a2, p2) = (to_raw(&a, ACCEL_MPS2_PER_LSB), vec![0i16; pitch]);
        rows.push(row(
            format!("estimate_with_pitch, {accel} vs {pitch} samples"),
            move || e(estimate_with_pitch(&a, &p, &config)),
            stroke_err(StrokeError::LengthMismatch {
                accel: accel as u32,
                pitch: pitch as u32,
            }),
            &needles,
        ));
        rows.push(row(
            format!("estimate_raw_with_pitch, {accel} vs {pitch} samples"),
            move || {
                e(estimate_raw_with_pitch(
                    &a2,
                    ACCEL_MPS2_PER_LSB,
                    &p2,
                    GYRO_RADPS_PER_LSB,
                    &config,
                ))
            },
            stroke_err(StrokeError::LengthMismatch {
                accel: accel as u32,
                pitch: pitch as u32,
            }),
            &needles,
        ));
    }
    // Windows the estimator cannot use.
    let moving: Vec<f32> = (0..6000)
        .map(|i| 5.0 * (2.0 * std::f32::consts::PI * 3.0 * i as f32 / FS).sin())
        .chain(std::iter::repeat_n(-40.0 * STANDARD_GRAVITY, 6))
        .collect();
    rows.push(row(
        "estimate, moving from the start (3 Hz swing)",
        move || e(estimate(&moving, &config)),
        stroke_err(StrokeError::NotAtRest),
        &["rest"],
    ));
    let still = vec![0.2f32; 5000];
    rows.push(row(
        "estimate, rest only",
        move || e(estimate(&still, &config)),
        stroke_err(StrokeError::NoImpact),
        &["impact"],
    ));
    let mut clipped = raw.clone();
    clipped[2300] = i16::MAX;
    rows.push(row(
        "estimate_raw, i16::MAX word in the stroke",
        move || e(estimate_raw(&clipped, ACCEL_MPS2_PER_LSB, &config)),
        stroke_err(StrokeError::Saturated { index: 2300 }),
        &["sample 2300", "full scale"],
    ));
    let back = step(FS, 0.0, -10.0, 800);
    let back_speed = {
        // The exact −10 m/s² × 800 / 6667 Hz = −1.19994 m/s; the f32 answer within 1e-5.
        let Err(StrokeError::NotForward { speed }) = estimate(&back.samples, &config) else {
            panic!("a backward stroke was accepted");
        };
        assert!((f64::from(speed) - back.speed).abs() <= 1e-5 * back.speed.abs());
        speed
    };
    rows.push(row(
        "estimate, backward push only",
        move || e(estimate(&back.samples, &config)),
        stroke_err(StrokeError::NotForward { speed: back_speed }),
        &[&back_speed.to_string(), "not forward"],
    ));
    // The strike model through StrokeEstimate::strike (its public fields can hold
    // anything).
    let est = estimate(&samples, &config).unwrap();
    for speed in [NAN, INF, -INF] {
        rows.push(row(
            format!("StrokeEstimate::strike, cue_speed {speed}"),
            move || {
                let s = StrokeEstimate {
                    cue_speed: speed,
                    ..est
                };
                s.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE)
                    .map(drop)
                    .map_err(Refusal::Stroke)
            },
            stroke_err(StrokeError::Strike(CoreError::NotFinite {
                field: Field::CueSpeed,
            })),
            &["strike model", "cue_speed", "finite"],
        ));
    }
    for speed in [0.0f32, -0.0, -1.0, next_up(20.0), 1e6] {
        rows.push(row(
            format!("StrokeEstimate::strike, cue_speed {speed}"),
            move || {
                let s = StrokeEstimate {
                    cue_speed: speed,
                    ..est
                };
                s.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE)
                    .map(drop)
                    .map_err(Refusal::Stroke)
            },
            stroke_err(StrokeError::Strike(CoreError::OutOfRange {
                field: Field::CueSpeed,
                value: speed,
            })),
            &["strike model", "cue_speed", "(0, 20]"],
        ));
    }
    let far = 0.6 * POOL_RADIUS;
    rows.push(row(
        "StrokeEstimate::strike, tip 0.6 R from centre",
        move || {
            est.strike(
                &Params::POOL,
                &Cue::TYPICAL,
                TipOffset::new(far, 0.0).unwrap(),
            )
            .map(drop)
            .map_err(Refusal::Stroke)
        },
        stroke_err(StrokeError::Strike(CoreError::OutOfRange {
            field: Field::TipOffset,
            value: far,
        })),
        &["strike model", "tip_offset"],
    ));
    rows
}

#[test]
fn input_refusals_are_typed() {
    let n = check_rows(input_rows());
    println!("{n} input rows");
    cuesight_figures::record!("reliability-sensors-validation-input-rows", "{n}");
}

// ---------------------------------------------------------------------------------------
// What returns no error
// ---------------------------------------------------------------------------------------

/// The ring buffer has no invalid input: its refusals are values. `try_push` on a full
/// ring (and any push on capacity 0) hands the value back, `get` past the length and
/// `latest` on an empty ring are `None`, `copy_to` into a short slice copies what fits.
#[test]
fn ring_refusals_are_values() {
    let mut full = RingBuffer::<i16, 3>::new(0);
    for v in [i16::MIN, 0, i16::MAX] {
        assert_eq!(full.try_push(v), Ok(()));
    }
    assert_eq!(full.try_push(7), Err(7));
    assert_eq!(full.iter().collect::<Vec<_>>(), [i16::MIN, 0, i16::MAX]);
    assert_eq!(full.get(3), None);
    assert_eq!(full.get(usize::MAX), None);
    assert_eq!(full.copy_to(&mut []), 0);
    let mut none = RingBuffer::<i16, 0>::new(0);
    assert_eq!(none.push(i16::MIN), Some(i16::MIN));
    assert_eq!(none.try_push(i16::MAX), Err(i16::MAX));
    assert_eq!(none.latest(), None);
    let empty = RingBuffer::<f32, 4>::new(f32::NAN);
    assert_eq!(empty.latest(), None);
    assert_eq!(empty.get(0), None);
    assert_eq!(empty.iter().count(), 0);
}

/// The functions without a `Result` are total: every i16 word converts to a finite
/// value (|a| ≤ 16 g, |ω| ≤ 2294 dps), every trim byte to a finite ODR the estimator
/// accepts.
#[test]
fn conversions_are_finite_on_their_whole_domain() {
    for w in i16::MIN..=i16::MAX {
        let (a, g) = (accel_lsb_to_mps2(w), gyro_lsb_to_radps(w));
        assert!(a.is_finite() && f64::from(a.abs()) <= 16.0 * G, "{w}");
        assert!(
            g.is_finite() && f64::from(g.abs()).to_degrees() <= 2294.0,
            "{w}"
        );
    }
    for b in 0..=255u8 {
        let odr = trimmed_odr_hz(b);
        assert!(odr.is_finite() && (500.0..=100_000.0).contains(&odr), "{b}");
    }
}
