//! The driver over a mocked I²C bus: the transactions written out by hand from the
//! datasheet, not produced by the driver.

extern crate std;
use std::vec;

use super::*;
use embedded_hal::i2c::ErrorKind;
use embedded_hal_mock::eh1::i2c::{Mock, Transaction};

const A: u8 = ADDRESS_SA0_LOW;

/// The init sequence as the datasheet asks for it, written out by hand.
fn init_transactions(reset_polls: &[u8], trim: u8) -> std::vec::Vec<Transaction> {
    let mut t = vec![
        Transaction::write_read(A, vec![0x0F], vec![0x6C]),
        Transaction::write(A, vec![0x12, 0x01]),
    ];
    for &p in reset_polls {
        t.push(Transaction::write_read(A, vec![0x12], vec![p]));
    }
    t.extend([
        Transaction::write(A, vec![0x12, 0x44]),
        Transaction::write(A, vec![0x18, 0xE2]),
        Transaction::write(A, vec![0x10, 0xA4]),
        Transaction::write(A, vec![0x11, 0xAC]),
        Transaction::write_read(A, vec![0x63], vec![trim]),
    ]);
    t
}

#[test]
fn init_writes_the_documented_sequence() {
    // Reset still pending on the first poll, done on the second.
    let expectations = init_transactions(&[0x05, 0x04], 0x00);
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    imu.init().unwrap();
    assert_eq!(imu.odr_hz(), 6667.0);
    i2c.done();
}

#[test]
fn init_applies_the_odr_trim() {
    // 0xF6 = −10 → −1.5 %.
    let expectations = init_transactions(&[0x04], 0xF6);
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    imu.init().unwrap();
    assert!((imu.odr_hz() - 6566.995).abs() < 0.01, "{}", imu.odr_hz());
    i2c.done();
    assert!((trimmed_odr_hz(0x0A) - 6767.005).abs() < 0.01);
}

#[test]
fn wrong_who_am_i_stops_before_any_write() {
    // An LSM6DSO32 (0x6C too) would pass; an LSM6DS3 answers 0x69.
    let expectations = [Transaction::write_read(A, vec![0x0F], vec![0x69])];
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    assert_eq!(imu.init(), Err(Error::WrongChipId(0x69)));
    i2c.done();
}

#[test]
fn bus_error_is_reported() {
    let expectations =
        [Transaction::write_read(A, vec![0x0F], vec![0x6C]).with_error(ErrorKind::Other)];
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    assert_eq!(imu.init(), Err(Error::Bus(ErrorKind::Other)));
    i2c.done();
}

#[test]
fn reset_that_never_clears_times_out() {
    let polls = [0x05u8; RESET_POLLS];
    let mut expectations = vec![
        Transaction::write_read(A, vec![0x0F], vec![0x6C]),
        Transaction::write(A, vec![0x12, 0x01]),
    ];
    for &p in &polls {
        expectations.push(Transaction::write_read(A, vec![0x12], vec![p]));
    }
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    assert_eq!(imu.init(), Err(Error::ResetTimeout));
    i2c.done();
}

#[test]
fn block_read_decodes_little_endian_words_in_si() {
    // gyro: +1000 LSB, −1 LSB, 0; accel: +2049 LSB (≈ 1 g), −32768, +32767.
    let bytes = vec![
        0xE8, 0x03, 0xFF, 0xFF, 0x00, 0x00, // gyro X, Y, Z
        0x01, 0x08, 0x00, 0x80, 0xFF, 0x7F, // accel X, Y, Z
    ];
    let expectations = [Transaction::write_read(A, vec![0x22], bytes)];
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    let s = imu.read_raw().unwrap();
    assert_eq!(s.gyro, [1000, -1, 0]);
    assert_eq!(s.accel, [2049, -32768, 32767]);
    let si = s.to_si();
    // 1000 LSB × 70 mdps = 70 dps = 1.22173 rad/s.
    assert!((si.gyro[0] - 1.221_730_5).abs() < 1e-5);
    // 2049 × 0.488 mg = 0.999912 g = 9.80579 m/s².
    assert!((si.accel[0] - 9.805_79).abs() < 1e-3);
    // −32768 LSB is the −16 g rail (−15.99 g with this sensitivity).
    assert!((si.accel[1] / STANDARD_GRAVITY + 15.990_78).abs() < 1e-3);
    i2c.done();
}

#[test]
fn single_axis_and_status_reads() {
    let expectations = [
        Transaction::write_read(A, vec![0x28], vec![0x34, 0x12]),
        Transaction::write_read(A, vec![0x2C], vec![0x00, 0xF0]),
        Transaction::write_read(A, vec![0x1E], vec![0x05]),
        Transaction::write(A, vec![0x0D, 0x01]),
    ];
    let mut i2c = Mock::new(&expectations);
    let mut imu = Lsm6dsox::new(i2c.clone(), A);
    assert_eq!(imu.read_accel_axis_raw(Axis::X).unwrap(), 0x1234);
    assert_eq!(imu.read_accel_axis_raw(Axis::Z).unwrap(), -4096);
    assert_eq!(
        imu.data_ready().unwrap(),
        DataReady {
            accel: true,
            gyro: false,
            temperature: true
        }
    );
    imu.enable_accel_data_ready_int1().unwrap();
    // `release` hands back the same (shared) mock.
    let _bus = imu.release();
    i2c.done();
}

/// SPI: the same init and block read, framed as the datasheet's SPI protocol (§6.2):
/// a read's address byte has bit 7 set, a write's clear, one chip-select transaction
/// each.
mod spi {
    use super::*;
    use embedded_hal_mock::eh1::spi::{Mock, Transaction};

    fn read(first: u8, data: std::vec::Vec<u8>) -> [Transaction<u8>; 4] {
        [
            Transaction::transaction_start(),
            Transaction::write_vec(vec![first]),
            Transaction::read_vec(data),
            Transaction::transaction_end(),
        ]
    }

    fn write(register: u8, value: u8) -> [Transaction<u8>; 3] {
        [
            Transaction::transaction_start(),
            Transaction::write_vec(vec![register, value]),
            Transaction::transaction_end(),
        ]
    }

    #[test]
    fn init_and_block_read_over_spi() {
        let mut expected = std::vec::Vec::new();
        expected.extend(read(0x8F, vec![0x6C]));
        expected.extend(write(0x12, 0x01));
        expected.extend(read(0x92, vec![0x00]));
        expected.extend(write(0x12, 0x44));
        expected.extend(write(0x18, 0xE2));
        expected.extend(write(0x10, 0xA4));
        expected.extend(write(0x11, 0xAC));
        expected.extend(read(0xE3, vec![0x0A]));
        expected.extend(write(0x0B, 0x80));
        expected.extend(write(0x0D, 0x01));
        expected.extend(read(
            0xA2,
            vec![
                0xE8, 0x03, 0xFF, 0xFF, 0x00, 0x00, // gyro X, Y, Z
                0x01, 0x08, 0x00, 0x80, 0xFF, 0x7F, // accel X, Y, Z
            ],
        ));
        let mut spi = Mock::new(&expected);
        let mut imu = Lsm6dsox::on_spi(spi.clone());
        imu.init().unwrap();
        // +10 trim → +1.5 %.
        assert!((imu.odr_hz() - 6767.005).abs() < 0.01, "{}", imu.odr_hz());
        imu.enable_accel_data_ready_int1_pulsed().unwrap();
        let sample = imu.read_raw().unwrap();
        assert_eq!(sample.gyro, [1000, -1, 0]);
        assert_eq!(sample.accel, [2049, -32768, 32767]);
        let _device = imu.release_spi();
        spi.done();
    }

    #[test]
    fn wrong_chip_over_spi_stops_before_any_write() {
        // A floating MISO reads 0xFF.
        let expected = read(0x8F, vec![0xFF]);
        let mut spi = Mock::new(&expected);
        let mut imu = Lsm6dsox::on_spi(spi.clone());
        assert_eq!(imu.init(), Err(Error::WrongChipId(0xFF)));
        spi.done();
    }
}
