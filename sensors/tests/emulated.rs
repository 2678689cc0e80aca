//! The unchanged LSM6DSOX driver (`sensors/src/lsm6dsox/`) on the register model
//! (`sensors/src/emulated/`). Expected values come from the datasheet's register
//! description (written out here as numbers) and from the samples each test latches.

use cuesight_sensors::emulated::{
    BusError, EmulatedLsm6dsox, LatchReport, Overruns, Sa0, SensorLatch,
};
use cuesight_sensors::lsm6dsox::{
    self, Axis, DataReady, Error, I2cInterface, RawSample, RESET_POLLS,
};
use cuesight_sensors::trace::parse_trace;
use cuesight_sensors::Lsm6dsox;
use embedded_hal::i2c::{Error as _, ErrorKind, I2c, NoAcknowledgeSource, Operation};

const A: u8 = 0x6A;

/// A sample with every byte distinct and both signs: `[ax, ay, az, gx, gy, gz]`.
const S1: [i16; 6] = [0x1234, -2, 0x7F01, -32768, 32767, 0x0A0B];
const S2: [i16; 6] = [-0x2345, 0x0102, -3, 0x4321, -0x1111, 1];
const S3: [i16; 6] = [77, -77, 2049, -1000, 1000, 0];

fn driver(part: &mut EmulatedLsm6dsox) -> Lsm6dsox<I2cInterface<&mut EmulatedLsm6dsox>> {
    Lsm6dsox::new(part, A)
}

/// A part the driver has initialised (BDU + IF_INC, 6.66 kHz, ±16 g, ±2000 dps).
fn ready() -> EmulatedLsm6dsox {
    let mut part = EmulatedLsm6dsox::new(Sa0::Low);
    driver(&mut part).init().unwrap();
    part
}

fn raw(sample: [i16; 6]) -> RawSample {
    RawSample {
        accel: [sample[0], sample[1], sample[2]],
        gyro: [sample[3], sample[4], sample[5]],
    }
}

fn read(part: &mut EmulatedLsm6dsox, register: u8, len: usize) -> Vec<u8> {
    let mut buf = vec![0; len];
    part.write_read(A, &[register], &mut buf).unwrap();
    buf
}

fn ready_flags(part: &mut EmulatedLsm6dsox) -> DataReady {
    driver(part).data_ready().unwrap()
}

const BOTH: DataReady = DataReady {
    accel: true,
    gyro: true,
    temperature: false,
};
const NONE: DataReady = DataReady {
    accel: false,
    gyro: false,
    temperature: false,
};

#[test]
fn power_on_state_is_the_datasheet_reset_values() {
    let part = EmulatedLsm6dsox::new(Sa0::Low);
    // DS12814 register address map: WHO_AM_I 6Ch, CTRL3_C 04h (IF_INC), CTRL9_XL E0h.
    for (register, value) in [
        (0x0D, 0x00),
        (0x0F, 0x6C),
        (0x10, 0x00),
        (0x11, 0x00),
        (0x12, 0x04),
        (0x18, 0xE0),
        (0x1E, 0x00),
    ] {
        assert_eq!(part.peek(register), value, "register 0x{register:02X}");
    }
    assert_eq!(part.accel_odr_hz(), None);
    assert_eq!(part.gyro_odr_hz(), None);
    assert_eq!(part.address(), 0x6A);
    assert_eq!(EmulatedLsm6dsox::new(Sa0::High).address(), 0x6B);
}

#[test]
fn init_configures_the_documented_rate_and_scales() {
    let mut part = EmulatedLsm6dsox::new(Sa0::Low);
    let mut imu = driver(&mut part);
    assert_eq!(imu.who_am_i().unwrap(), 0x6C);
    imu.init().unwrap();
    assert_eq!(imu.odr_hz(), 6667.0);
    // The values the driver's register table gives, as the datasheet decodes them:
    // CTRL1_XL A4h = ODR_XL 1010 (6.66 kHz), FS_XL 01 (±16 g); CTRL2_G ACh = ODR_G 1010,
    // FS_G 11 (±2000 dps); CTRL3_C 44h = BDU + IF_INC; CTRL9_XL E2h.
    assert_eq!(part.peek(0x10), 0xA4);
    assert_eq!(part.peek(0x11), 0xAC);
    assert_eq!(part.peek(0x12), 0x44);
    assert_eq!(part.peek(0x18), 0xE2);
    assert_eq!(part.accel_odr_hz(), Some(6667.0));
    assert_eq!(part.gyro_odr_hz(), Some(6667.0));
    assert_eq!(part.accel_full_scale_g(), 16);
    assert_eq!(part.gyro_full_scale_dps(), 2000);
    // The driver touched only modelled, writable registers.
    assert_eq!((part.unmodelled_reads(), part.ignored_writes()), (0, 0));
}

#[test]
fn full_scale_and_odr_fields_decode_as_the_datasheet_tables() {
    let mut part = EmulatedLsm6dsox::new(Sa0::Low);
    // (CTRL1_XL, ODR Hz, ±g), (CTRL2_G, ODR Hz, ±dps).
    for (ctrl1, odr, g) in [
        (0x10, Some(12.5), 2),
        (0x98, Some(3333.0), 4),
        (0x8C, Some(1667.0), 8),
        (0xB4, None, 16),
        (0x04, None, 16),
    ] {
        part.write(A, &[0x10, ctrl1]).unwrap();
        assert_eq!((part.accel_odr_hz(), part.accel_full_scale_g()), (odr, g));
    }
    for (ctrl2, odr, dps) in [
        (0x40, Some(104.0), 250),
        (0x74, Some(833.0), 500),
        (0x58, Some(208.0), 1000),
        (0x1E, Some(12.5), 125),
        (0xFC, None, 2000),
    ] {
        part.write(A, &[0x11, ctrl2]).unwrap();
        assert_eq!((part.gyro_odr_hz(), part.gyro_full_scale_dps()), (odr, dps));
    }
}

#[test]
fn the_odr_trim_reaches_the_driver() {
    for (trim, per_lsb) in [(0xF6u8, -10.0f32), (0x0A, 10.0), (0x80, -128.0)] {
        let mut part = EmulatedLsm6dsox::new(Sa0::Low).with_freq_fine(trim);
        let mut imu = driver(&mut part);
        imu.init().unwrap();
        // ODR = 6667 Hz × (1 + 0.0015 × trim), trim two's complement.
        let expected = 6667.0 * (1.0 + 0.0015 * per_lsb);
        assert!((imu.odr_hz() - expected).abs() < 1e-2, "{trim:#x}");
    }
}

#[test]
fn software_reset_clears_itself_after_the_configured_polls() {
    // The driver polls CTRL3_C at most RESET_POLLS times.
    let mut part = EmulatedLsm6dsox::new(Sa0::Low).with_reset_reads(RESET_POLLS as u16 - 1);
    driver(&mut part).init().unwrap();
    let mut part = EmulatedLsm6dsox::new(Sa0::Low).with_reset_reads(RESET_POLLS as u16);
    assert_eq!(driver(&mut part).init(), Err(Error::ResetTimeout));

    // One poll by default: 05h (reset running, IF_INC), then 04h.
    let mut part = ready();
    part.write(A, &[0x0D, 0x01]).unwrap();
    part.latch(S1);
    part.write(A, &[0x12, 0x01]).unwrap();
    assert_eq!(read(&mut part, 0x12, 1), [0x05]);
    assert_eq!(read(&mut part, 0x12, 1), [0x04]);
    assert_eq!(read(&mut part, 0x12, 1), [0x04]);
    // Every modelled register back at its reset value, flags and outputs cleared.
    for (register, value) in [(0x0D, 0), (0x10, 0), (0x11, 0), (0x18, 0xE0), (0x1E, 0)] {
        assert_eq!(part.peek(register), value, "register 0x{register:02X}");
    }
    assert_eq!(read(&mut part, 0x22, 12), [0; 12]);
    // Powered down again: no data.
    assert_eq!(
        part.latch(S2),
        LatchReport {
            accel: SensorLatch::PoweredDown,
            gyro: SensorLatch::PoweredDown
        }
    );
}

#[test]
fn six_axis_reads_return_the_latched_samples() {
    let mut part = ready();
    for sample in [S1, S2, S3, [0; 6], [i16::MIN; 6], [i16::MAX; 6]] {
        part.latch(sample);
        let mut imu = driver(&mut part);
        assert_eq!(imu.read_raw().unwrap(), raw(sample));
    }
    // Little-endian, gyro X, Y, Z then accel X, Y, Z from 22h.
    part.latch(S1);
    assert_eq!(
        read(&mut part, 0x22, 12),
        [
            0x00, 0x80, 0xFF, 0x7F, 0x0B, 0x0A, // gx −32768, gy 32767, gz 0x0A0B
            0x34, 0x12, 0xFE, 0xFF, 0x01, 0x7F, // ax 0x1234, ay −2, az 0x7F01
        ]
    );
    // SI: 0.488 mg/LSB and 70 mdps/LSB.
    part.latch(S3);
    let si = driver(&mut part).read().unwrap();
    let g = 9.806_65f32;
    assert!((si.accel[2] - 2049.0 * 0.488e-3 * g).abs() < 1e-4);
    assert!((si.gyro[1] - 1000.0 * 0.070f32.to_radians()).abs() < 1e-5);
}

#[test]
fn single_axis_reads_return_the_latched_axis() {
    let mut part = ready();
    for sample in [S1, S2, S3] {
        part.latch(sample);
        let mut imu = driver(&mut part);
        assert_eq!(imu.read_accel_axis_raw(Axis::X).unwrap(), sample[0]);
        assert_eq!(imu.read_accel_axis_raw(Axis::Y).unwrap(), sample[1]);
        assert_eq!(imu.read_accel_axis_raw(Axis::Z).unwrap(), sample[2]);
    }
}

#[test]
fn status_flags_set_on_a_latch_and_clear_on_a_high_byte() {
    let mut part = EmulatedLsm6dsox::new(Sa0::Low);
    // Power-down: no data, no flag.
    let off = part.latch(S1);
    assert_eq!(off.accel, SensorLatch::PoweredDown);
    assert_eq!(ready_flags(&mut part), NONE);

    let mut part = ready();
    assert_eq!(ready_flags(&mut part), NONE);
    part.latch(S1);
    assert_eq!(ready_flags(&mut part), BOTH);
    // Reading STATUS_REG does not clear it; a low byte alone does not either.
    assert_eq!(ready_flags(&mut part), BOTH);
    read(&mut part, 0x28, 1);
    read(&mut part, 0x22, 1);
    assert_eq!(ready_flags(&mut part), BOTH);
    // One accelerometer axis: XLDA only.
    driver(&mut part).read_accel_axis_raw(Axis::Z).unwrap();
    assert_eq!(ready_flags(&mut part), DataReady { gyro: true, ..NONE });
    // Any gyroscope high byte clears GDA.
    read(&mut part, 0x25, 1);
    assert_eq!(ready_flags(&mut part), NONE);
    // The block read clears both.
    part.latch(S2);
    driver(&mut part).read_raw().unwrap();
    assert_eq!(ready_flags(&mut part), NONE);

    // Accelerometer alone (CTRL2_G power-down): only XLDA.
    part.write(A, &[0x11, 0x00]).unwrap();
    assert_eq!(
        part.latch(S3),
        LatchReport {
            accel: SensorLatch::New,
            gyro: SensorLatch::PoweredDown
        }
    );
    assert_eq!(
        ready_flags(&mut part),
        DataReady {
            accel: true,
            ..NONE
        }
    );
    // The gyroscope output keeps S2.
    assert_eq!(
        driver(&mut part).read_raw().unwrap(),
        RawSample {
            accel: raw(S3).accel,
            gyro: raw(S2).gyro,
        }
    );
}

#[test]
fn int1_follows_the_accelerometer_data_ready_once_routed() {
    let mut part = ready();
    part.latch(S1);
    assert!(!part.int1(), "not routed yet");
    driver(&mut part).read_raw().unwrap();
    driver(&mut part).enable_accel_data_ready_int1().unwrap();
    assert_eq!(part.peek(0x0D), 0x01);
    assert!(!part.int1());
    part.latch(S2);
    assert!(part.int1());
    driver(&mut part).read_accel_axis_raw(Axis::X).unwrap();
    assert!(!part.int1(), "GDA alone is not routed");
    // INT1_DRDY_G (bit 1) routes the gyroscope too.
    part.write(A, &[0x0D, 0x02]).unwrap();
    assert!(part.int1());
}

#[test]
fn block_data_update_keeps_a_words_bytes_from_one_sample() {
    // BDU on (the driver's init): low byte of ax from S1, a new sample, high byte still S1.
    let mut part = ready();
    part.latch(S1);
    let low = read(&mut part, 0x28, 1)[0];
    assert_eq!(part.latch(S2).accel, SensorLatch::New);
    let high = read(&mut part, 0x29, 1)[0];
    assert_eq!(i16::from_le_bytes([low, high]), S1[0]);
    // The held sample reached the registers with the high byte, flagged as new.
    assert!(ready_flags(&mut part).accel);
    assert_eq!(
        driver(&mut part).read_accel_axis_raw(Axis::X).unwrap(),
        S2[0]
    );
    // The hold is per sensor: the gyroscope took S2 at once.
    assert_eq!(driver(&mut part).read_raw().unwrap(), raw(S2));

    // BDU off: the same reads tear the word.
    let mut part = ready();
    part.write(A, &[0x12, 0x04]).unwrap();
    part.latch(S1);
    let low = read(&mut part, 0x28, 1)[0];
    part.latch(S2);
    let high = read(&mut part, 0x29, 1)[0];
    let torn = i16::from_le_bytes([S1[0].to_le_bytes()[0], S2[0].to_le_bytes()[1]]);
    assert_eq!(i16::from_le_bytes([low, high]), torn);

    // Clearing BDU during a hold writes the held sample.
    let mut part = ready();
    part.latch(S1);
    read(&mut part, 0x2A, 1);
    part.latch(S2);
    assert_eq!(read(&mut part, 0x2A, 2), S1[1].to_le_bytes());
    read(&mut part, 0x2C, 1);
    part.latch(S3);
    part.write(A, &[0x12, 0x04]).unwrap();
    assert_eq!(read(&mut part, 0x2C, 2), S3[2].to_le_bytes());
}

#[test]
fn auto_increment_follows_if_inc() {
    let mut part = ready();
    part.latch(S1);
    // IF_INC off (BDU kept): a 12-byte read from 22h repeats OUTX_L_G.
    part.write(A, &[0x12, 0x40]).unwrap();
    let gx_low = S1[3].to_le_bytes()[0];
    assert_eq!(read(&mut part, 0x22, 12), [gx_low; 12]);
    // A multi-byte write goes to one register too: the last byte stays.
    part.write(A, &[0x10, 0x00, 0x98]).unwrap();
    assert_eq!((part.peek(0x10), part.peek(0x11)), (0x98, 0xAC));

    // IF_INC on: consecutive registers, for writes as for reads.
    part.write(A, &[0x12, 0x44]).unwrap();
    part.write(A, &[0x10, 0xA4, 0xAC]).unwrap();
    assert_eq!((part.peek(0x10), part.peek(0x11)), (0xA4, 0xAC));
    // A read with no register address continues where the last access ended (12h+1).
    let mut next = [0u8; 1];
    part.write(A, &[0x12]).unwrap();
    part.read(A, &mut next).unwrap();
    assert_eq!(next, [0x44]);
    part.read(A, &mut next).unwrap();
    assert_eq!(next, [0x00], "CTRL4_C (13h) is not modelled");
    // Split operations: adjacent writes are one transfer; a read after a write is a
    // repeated START.
    part.latch(S2);
    let mut buf = [0u8; 4];
    let (first, rest) = buf.split_at_mut(1);
    part.transaction(
        A,
        &mut [
            Operation::Write(&[]),
            Operation::Write(&[0x2A]),
            Operation::Read(first),
            Operation::Read(rest),
        ],
    )
    .unwrap();
    let [ay0, ay1] = S2[1].to_le_bytes();
    let [az0, az1] = S2[2].to_le_bytes();
    assert_eq!(buf, [ay0, ay1, az0, az1]);
}

#[test]
fn another_address_is_not_acknowledged() {
    let mut part = EmulatedLsm6dsox::new(Sa0::Low);
    let mut imu = Lsm6dsox::new(&mut part, lsm6dsox::ADDRESS_SA0_HIGH);
    let err = imu.init().unwrap_err();
    assert_eq!(err, Error::Bus(BusError::AddressNack(0x6B)));
    let Error::Bus(bus) = err else { unreachable!() };
    assert_eq!(
        bus.kind(),
        ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address)
    );
    // Nothing happened: still at reset.
    assert_eq!((part.peek(0x12), part.peek(0x10)), (0x04, 0x00));
    // The other strap answers on 0x6B.
    let mut high = EmulatedLsm6dsox::new(Sa0::High);
    Lsm6dsox::new(&mut high, 0x6B).init().unwrap();
    assert_eq!(high.peek(0x10), 0xA4);
}

#[test]
fn a_failing_bus_gives_the_drivers_bus_error_and_changes_nothing() {
    let mut part = ready();
    part.latch(S1);
    part.set_bus_failing(true);
    let fault = Error::Bus(BusError::BusFault);
    {
        let mut imu = driver(&mut part);
        assert_eq!(imu.init(), Err(fault));
        assert_eq!(imu.who_am_i(), Err(fault));
        assert_eq!(imu.read_raw(), Err(fault));
        assert_eq!(imu.read_accel_axis_raw(Axis::X), Err(fault));
        assert_eq!(imu.data_ready(), Err(fault));
        assert_eq!(imu.enable_accel_data_ready_int1(), Err(fault));
    }
    assert_eq!(BusError::BusFault.kind(), ErrorKind::Bus);
    // Samples still arrive; the failed reads cleared nothing.
    assert_eq!(part.latch(S2).accel, SensorLatch::Overrun);
    part.set_bus_failing(false);
    assert_eq!(ready_flags(&mut part), BOTH);
    assert_eq!(driver(&mut part).read_raw().unwrap(), raw(S2));
    assert_eq!(part.peek(0x0D), 0x00);
}

#[test]
fn overruns_are_samples_replaced_unread() {
    let mut part = ready();
    assert_eq!(
        part.latch(S1),
        LatchReport {
            accel: SensorLatch::New,
            gyro: SensorLatch::New
        }
    );
    assert_eq!(
        part.latch(S2),
        LatchReport {
            accel: SensorLatch::Overrun,
            gyro: SensorLatch::Overrun
        }
    );
    assert_eq!(part.overruns(), Overruns { accel: 1, gyro: 1 });
    // Reading the cue axis only: the gyroscope overruns, the accelerometer does not.
    for sample in [S3, S1, S2] {
        driver(&mut part).read_accel_axis_raw(Axis::X).unwrap();
        let report = part.latch(sample);
        assert_eq!(report.accel, SensorLatch::New);
        assert_eq!(report.gyro, SensorLatch::Overrun);
    }
    assert_eq!(part.overruns(), Overruns { accel: 1, gyro: 4 });
    // The whole block read each time: none.
    for sample in [S1, S2, S3] {
        driver(&mut part).read_raw().unwrap();
        assert_eq!(part.latch(sample).gyro, SensorLatch::New);
    }
    // Under a BDU hold, a sample that waits and is replaced is lost.
    driver(&mut part).read_raw().unwrap();
    read(&mut part, 0x28, 1);
    assert_eq!(part.latch(S1).accel, SensorLatch::New);
    assert_eq!(part.latch(S2).accel, SensorLatch::Overrun);
    read(&mut part, 0x29, 1);
    assert_eq!(
        driver(&mut part).read_accel_axis_raw(Axis::X).unwrap(),
        S2[0]
    );
    assert_eq!(part.overruns(), Overruns { accel: 2, gyro: 5 });
    assert_eq!(part.latched(), 2 + 3 + 3 + 2);
}

#[test]
fn a_stalled_sensor_makes_no_data() {
    let mut part = ready();
    driver(&mut part).enable_accel_data_ready_int1().unwrap();
    part.latch(S1);
    driver(&mut part).read_raw().unwrap();
    part.set_stalled(true);
    let stalled = LatchReport {
        accel: SensorLatch::Stalled,
        gyro: SensorLatch::Stalled,
    };
    for _ in 0..3 {
        assert_eq!(part.latch(S2), stalled);
    }
    assert!(!part.int1());
    assert_eq!(ready_flags(&mut part), NONE);
    assert_eq!(driver(&mut part).read_raw().unwrap(), raw(S1));
    assert_eq!((part.latched(), part.overruns()), (1, Overruns::default()));
    part.set_stalled(false);
    part.latch(S3);
    assert!(part.int1());
    assert_eq!(driver(&mut part).read_raw().unwrap(), raw(S3));
}

#[test]
fn unmodelled_and_read_only_registers() {
    let mut part = ready();
    part.latch(S1);
    // OUT_TEMP_L/H (20h, 21h) and FIFO_STATUS1 (3Ah) read 0 and are counted.
    assert_eq!(read(&mut part, 0x20, 2), [0, 0]);
    assert_eq!(read(&mut part, 0x3A, 1), [0]);
    assert_eq!(part.unmodelled_reads(), 3);
    // Writes to WHO_AM_I, STATUS_REG, an output and INTERNAL_FREQ_FINE (read-only) and
    // to CTRL4_C (not modelled) are dropped and counted.
    for register in [0x0F, 0x1E, 0x28, 0x63, 0x13] {
        part.write(A, &[register, 0x5A]).unwrap();
    }
    assert_eq!(part.ignored_writes(), 5);
    assert_eq!(driver(&mut part).who_am_i().unwrap(), 0x6C);
    assert_eq!(ready_flags(&mut part), BOTH);
    assert_eq!(driver(&mut part).read_raw().unwrap(), raw(S1));
    assert_eq!(read(&mut part, 0x13, 1), [0]);
    // BOOT (bit 7 of CTRL3_C) is not stored.
    part.write(A, &[0x12, 0xC4]).unwrap();
    assert_eq!(part.peek(0x12), 0x44);
}

/// The shipped example trace, sample by sample through the model and the driver's
/// block read, as the firmware will take it.
#[test]
fn a_shipped_trace_round_trips_through_the_driver() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../firmware/traces/three-strokes-6667.csv"
    );
    let bytes = std::fs::read(path).expect(path);
    let mut part = ready();
    let mut count = 0;
    parse_trace(&bytes, |index, sample| {
        assert_eq!(index, count);
        assert_eq!(part.latch(sample).accel, SensorLatch::New, "sample {index}");
        assert_eq!(driver(&mut part).read_raw().unwrap(), raw(sample));
        count += 1;
    })
    .unwrap();
    assert!(count > 10_000, "{count} samples");
    assert_eq!(part.overruns(), Overruns::default());
}

/// No heap, fixed size: the module docs' 68 bytes.
#[test]
fn the_model_is_68_bytes() {
    assert_eq!(std::mem::size_of::<EmulatedLsm6dsox>(), 68);
}
