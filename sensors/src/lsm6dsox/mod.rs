//! ST LSM6DSOX 6-axis IMU over I²C or SPI (embedded-hal 1.0), configured for stroke capture.
//!
//! # Register map used
//!
//! Addresses, bit layouts and the `WHO_AM_I` value as in ST's reference driver
//! `lsm6dsox_reg.h` (github.com/STMicroelectronics/lsm6dsox-pid), which follows the
//! register description of the LSM6DSOX datasheet.
//!
//! | register | addr | access | value written / meaning |
//! |---|---|---|---|
//! | `COUNTER_BDR_REG1` | `0x0B` | rw | `0x80` = `dataready_pulsed`: data-ready as a 75 µs pulse per sample, not latched until read (optional, [`Lsm6dsox::enable_accel_data_ready_int1_pulsed`]) |
//! | `INT1_CTRL` | `0x0D` | rw | `0x01` = `INT1_DRDY_XL`: accelerometer data-ready on INT1 (optional, [`Lsm6dsox::enable_accel_data_ready_int1`]) |
//! | `WHO_AM_I` | `0x0F` | r | must read `0x6C` |
//! | `CTRL1_XL` | `0x10` | rw | `0xA4`: `ODR_XL = 1010` (6.66 kHz, high-performance), `FS_XL = 01` (±16 g), `LPF2_XL_EN = 0` |
//! | `CTRL2_G` | `0x11` | rw | `0xAC`: `ODR_G = 1010` (6.66 kHz), `FS_G = 11` (±2000 dps), `FS_125 = 0` |
//! | `CTRL3_C` | `0x12` | rw | `0x01` = `SW_RESET` (self-clearing, polled); then `0x44` = `BDU` (bit 6) + `IF_INC` (bit 2) |
//! | `CTRL9_XL` | `0x18` | rw | `0xE2`: reset value `0xE0` (`DEN_X/Y/Z`) + `I3C_DISABLE` (bit 1), recommended on an I²C-only bus |
//! | `STATUS_REG` | `0x1E` | r | bit 0 `XLDA`, bit 1 `GDA`, bit 2 `TDA` (new data available) |
//! | `OUTX_L_G` … `OUTZ_H_G` | `0x22`–`0x27` | r | gyro X, Y, Z, little-endian two's complement |
//! | `OUTX_L_A` … `OUTZ_H_A` | `0x28`–`0x2D` | r | accelerometer X, Y, Z, little-endian two's complement |
//! | `INTERNAL_FREQ_FINE` | `0x63` | r | ODR trim: actual ODR = nominal × (1 + 0.0015 × value), value an `i8` |
//!
//! With `IF_INC` set a read starting at `0x22` auto-increments through all twelve output
//! bytes in one transaction (gyro first, then accelerometer), and `BDU` keeps the low and
//! high bytes of each axis from the same sample.
//!
//! Sensitivities, as in ST's driver conversions `lsm6dsox_from_fs16_to_mg` and
//! `lsm6dsox_from_fs2000_to_mdps`: ±16 g → 0.488 mg/LSB; ±2000 dps → 70 mdps/LSB.
//!
//! `WHO_AM_I` is `0x6C` on the LSM6DSO and LSM6DSO32 as well. On an LSM6DSO32,
//! `FS_XL = 01` selects ±32 g, so every acceleration read here would be half the true
//! value: the board must carry an LSM6DSOX (or LSM6DSO).
//!
//! # Bus budget
//!
//! At 6.66 kHz a sample arrives every 150 µs. A twelve-byte six-axis read over 400 kHz
//! I²C is ≈ 16 bytes on the wire (≈ 360 µs) and cannot keep up; reading only the cue
//! axis ([`Lsm6dsox::read_accel_axis_raw`], two data bytes, ≈ 5 bytes on the wire,
//! ≈ 125 µs) can, at about 80 % bus load. For full six-axis capture at this rate use
//! SPI ([`Lsm6dsox::on_spi`]): the same twelve-byte read is thirteen bytes on the wire,
//! 13 µs at 8 MHz (the nRF52840 board's SPIM3; the part takes up to 10 MHz).
//!
//! # SPI
//!
//! Mode 0 or 3, chip select low for one transaction. A read sends the register address
//! with bit 7 set (`0x80 | address`), then clocks the data out (auto-incrementing with
//! `IF_INC`); a write sends the address (bit 7 clear) and the value. The part selects
//! SPI by its chip select going low, so the same register sequence serves both buses.

use core::fmt;

use embedded_hal::i2c::I2c;
use embedded_hal::spi::SpiDevice;

mod interface;
pub use interface::{I2cInterface, Interface, SpiInterface, SPI_READ};

/// 7-bit I²C address with `SA0` tied low.
pub const ADDRESS_SA0_LOW: u8 = 0x6A;
/// 7-bit I²C address with `SA0` tied high.
pub const ADDRESS_SA0_HIGH: u8 = 0x6B;
/// Content of `WHO_AM_I` on an LSM6DSOX.
pub const WHO_AM_I_VALUE: u8 = 0x6C;

/// Register addresses used by the driver (see the module docs).
pub mod reg {
    /// Interrupt 1 routing.
    pub const INT1_CTRL: u8 = 0x0D;
    /// `COUNTER_BDR_REG1`: bit 7 `dataready_pulsed`.
    pub const COUNTER_BDR_REG1: u8 = 0x0B;
    /// Device identification, reads [`super::WHO_AM_I_VALUE`].
    pub const WHO_AM_I: u8 = 0x0F;
    /// Accelerometer control: ODR, full scale.
    pub const CTRL1_XL: u8 = 0x10;
    /// Gyroscope control: ODR, full scale.
    pub const CTRL2_G: u8 = 0x11;
    /// Common control: reset, block data update, auto-increment.
    pub const CTRL3_C: u8 = 0x12;
    /// Accelerometer control 9: DEN, I3C disable.
    pub const CTRL9_XL: u8 = 0x18;
    /// Data-ready flags.
    pub const STATUS_REG: u8 = 0x1E;
    /// First gyroscope output byte (X low).
    pub const OUTX_L_G: u8 = 0x22;
    /// First accelerometer output byte (X low).
    pub const OUTX_L_A: u8 = 0x28;
    /// ODR trim, two's complement, 0.15 % per LSB.
    pub const INTERNAL_FREQ_FINE: u8 = 0x63;
}

/// Register values written by [`Lsm6dsox::init`] (see the module docs).
pub mod value {
    /// `CTRL3_C`: software reset.
    pub const CTRL3_C_SW_RESET: u8 = 0x01;
    /// `CTRL3_C`: block data update + register auto-increment.
    pub const CTRL3_C_BDU_IF_INC: u8 = 0x44;
    /// `CTRL9_XL`: reset value with `I3C_DISABLE` set.
    pub const CTRL9_XL_I3C_DISABLE: u8 = 0xE2;
    /// `CTRL1_XL`: 6.66 kHz, ±16 g.
    pub const CTRL1_XL_6667HZ_16G: u8 = 0xA4;
    /// `CTRL2_G`: 6.66 kHz, ±2000 dps.
    pub const CTRL2_G_6667HZ_2000DPS: u8 = 0xAC;
    /// `INT1_CTRL`: accelerometer data-ready on INT1.
    pub const INT1_DRDY_XL: u8 = 0x01;
    /// `COUNTER_BDR_REG1`: `dataready_pulsed` (a 75 µs pulse per sample on the
    /// data-ready line instead of a level held until the data are read).
    pub const COUNTER_BDR_REG1_DRDY_PULSED: u8 = 0x80;
}

/// Nominal output data rate configured by [`Lsm6dsox::init`] (Hz).
pub const NOMINAL_ODR_HZ: f32 = 6667.0;
/// Standard gravity (m/s²), for g ↔ SI conversion.
pub const STANDARD_GRAVITY: f32 = 9.806_65;
/// Accelerometer sensitivity at ±16 g (m/s² per LSB): 0.488 mg/LSB.
pub const ACCEL_MPS2_PER_LSB: f32 = 0.488e-3 * STANDARD_GRAVITY;
/// Gyroscope sensitivity at ±2000 dps (rad/s per LSB): 70 mdps/LSB.
pub const GYRO_RADPS_PER_LSB: f32 = 70.0e-3 * core::f32::consts::PI / 180.0;
/// Accelerometer full scale as configured (m/s²): 16 g.
pub const ACCEL_FULL_SCALE_MPS2: f32 = 16.0 * STANDARD_GRAVITY;
/// How many times [`Lsm6dsox::init`] polls `CTRL3_C` for the end of the software reset
/// before giving up. Each poll is a full I²C read (≥ 50 µs at 400 kHz); the reset takes
/// tens of microseconds.
pub const RESET_POLLS: usize = 100;

/// Driver errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Error<E> {
    /// The bus transaction (I²C or SPI) failed.
    Bus(E),
    /// `WHO_AM_I` did not read `0x6C`: no LSM6DSOX at this address.
    WrongChipId(u8),
    /// `SW_RESET` did not clear within [`RESET_POLLS`] reads.
    ResetTimeout,
    /// The address given to [`Lsm6dsox::new`] is not one the part answers on
    /// ([`ADDRESS_SA0_LOW`] or [`ADDRESS_SA0_HIGH`]; e.g. the 8-bit form `0xD4`, or a
    /// value above `0x7F`, which is no 7-bit address). Reported before any bus traffic.
    InvalidAddress(u8),
}

impl<E: fmt::Debug> fmt::Display for Error<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Bus(e) => write!(f, "bus error: {e:?}"),
            Error::WrongChipId(id) => write!(
                f,
                "WHO_AM_I reads 0x{id:02X}, not 0x{WHO_AM_I_VALUE:02X}: no LSM6DSOX at this address"
            ),
            Error::ResetTimeout => write!(
                f,
                "software reset (CTRL3_C SW_RESET) did not clear within {RESET_POLLS} polls"
            ),
            Error::InvalidAddress(address) => write!(
                f,
                "I2C address 0x{address:02X} is not an LSM6DSOX address (0x{ADDRESS_SA0_LOW:02X} \
                 with SA0 low, 0x{ADDRESS_SA0_HIGH:02X} with SA0 high)"
            ),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for Error<E> {}

impl<E> From<E> for Error<E> {
    fn from(e: E) -> Self {
        Error::Bus(e)
    }
}

/// Accelerometer axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Axis {
    /// X axis (`OUTX_L_A`, `0x28`).
    X,
    /// Y axis (`OUTY_L_A`, `0x2A`).
    Y,
    /// Z axis (`OUTZ_L_A`, `0x2C`).
    Z,
}

/// Raw output words as read from the part (LSB).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RawSample {
    /// Gyroscope X, Y, Z (70 mdps/LSB).
    pub gyro: [i16; 3],
    /// Accelerometer X, Y, Z (0.488 mg/LSB).
    pub accel: [i16; 3],
}

/// One sample in SI units.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ImuSample {
    /// Angular rate X, Y, Z (rad/s).
    pub gyro: [f32; 3],
    /// Specific force X, Y, Z (m/s²); gravity included, as any accelerometer reads it.
    pub accel: [f32; 3],
}

impl RawSample {
    /// Convert to SI units with the ±16 g / ±2000 dps sensitivities.
    pub fn to_si(&self) -> ImuSample {
        ImuSample {
            gyro: self.gyro.map(gyro_lsb_to_radps),
            accel: self.accel.map(accel_lsb_to_mps2),
        }
    }
}

/// Accelerometer word (±16 g) to m/s².
pub fn accel_lsb_to_mps2(raw: i16) -> f32 {
    f32::from(raw) * ACCEL_MPS2_PER_LSB
}

/// Gyroscope word (±2000 dps) to rad/s.
pub fn gyro_lsb_to_radps(raw: i16) -> f32 {
    f32::from(raw) * GYRO_RADPS_PER_LSB
}

/// Data-ready flags from `STATUS_REG`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DataReady {
    /// `XLDA`: a new accelerometer sample is available.
    pub accel: bool,
    /// `GDA`: a new gyroscope sample is available.
    pub gyro: bool,
    /// `TDA`: a new temperature sample is available.
    pub temperature: bool,
}

/// LSM6DSOX on an I²C or SPI bus (`B`: [`I2cInterface`] or [`SpiInterface`]).
#[derive(Debug)]
pub struct Lsm6dsox<B> {
    bus: B,
    odr_hz: f32,
}

impl<I: I2c> Lsm6dsox<I2cInterface<I>> {
    /// Wrap the I²C bus; no traffic until [`Lsm6dsox::init`]. `address` is
    /// [`ADDRESS_SA0_LOW`] or [`ADDRESS_SA0_HIGH`]; with any other value every method
    /// that would use the bus returns [`Error::InvalidAddress`] without touching it (the
    /// bus stays owned here, [`Lsm6dsox::release`] gives it back).
    pub fn new(i2c: I, address: u8) -> Self {
        Self::with_interface(I2cInterface::new(i2c, address))
    }

    /// Give the bus back.
    pub fn release(self) -> I {
        self.bus.release()
    }
}

impl<S: SpiDevice> Lsm6dsox<SpiInterface<S>> {
    /// Wrap the SPI device (the part's chip select included; SPI mode 0 or 3, at most
    /// 10 MHz); no traffic until [`Lsm6dsox::init`].
    pub fn on_spi(spi: S) -> Self {
        Self::with_interface(SpiInterface::new(spi))
    }

    /// Give the SPI device back.
    pub fn release_spi(self) -> S {
        self.bus.release()
    }
}

impl<B: Interface> Lsm6dsox<B> {
    /// The driver on any bus to the part's registers (a board's own [`Interface`]); no
    /// traffic until [`Lsm6dsox::init`].
    pub fn with_interface(bus: B) -> Self {
        Self {
            bus,
            odr_hz: NOMINAL_ODR_HZ,
        }
    }

    /// Check the chip id, reset the part, and configure it for stroke capture: block data
    /// update and auto-increment, I3C off, accelerometer 6.66 kHz ±16 g, gyroscope
    /// 6.66 kHz ±2000 dps; then read the ODR trim (see [`Lsm6dsox::odr_hz`]).
    pub fn init(&mut self) -> Result<(), Error<B::Error>> {
        let id = self.who_am_i()?;
        if id != WHO_AM_I_VALUE {
            return Err(Error::WrongChipId(id));
        }
        self.write(reg::CTRL3_C, value::CTRL3_C_SW_RESET)?;
        let mut reset_done = false;
        for _ in 0..RESET_POLLS {
            if self.read_register(reg::CTRL3_C)? & value::CTRL3_C_SW_RESET == 0 {
                reset_done = true;
                break;
            }
        }
        if !reset_done {
            return Err(Error::ResetTimeout);
        }
        self.write(reg::CTRL3_C, value::CTRL3_C_BDU_IF_INC)?;
        self.write(reg::CTRL9_XL, value::CTRL9_XL_I3C_DISABLE)?;
        self.write(reg::CTRL1_XL, value::CTRL1_XL_6667HZ_16G)?;
        self.write(reg::CTRL2_G, value::CTRL2_G_6667HZ_2000DPS)?;
        let trim = self.read_register(reg::INTERNAL_FREQ_FINE)?;
        self.odr_hz = trimmed_odr_hz(trim);
        Ok(())
    }

    /// Read `WHO_AM_I`.
    pub fn who_am_i(&mut self) -> Result<u8, Error<B::Error>> {
        self.read_register(reg::WHO_AM_I)
    }

    /// The output data rate corrected by `INTERNAL_FREQ_FINE` (Hz): the sample spacing to
    /// give the stroke estimator. Nominal 6667 Hz until [`Lsm6dsox::init`] has run.
    pub fn odr_hz(&self) -> f32 {
        self.odr_hz
    }

    /// Route the accelerometer data-ready signal to the INT1 pin.
    pub fn enable_accel_data_ready_int1(&mut self) -> Result<(), Error<B::Error>> {
        self.write(reg::INT1_CTRL, value::INT1_DRDY_XL)
    }

    /// Route the accelerometer data-ready signal to the INT1 pin as a 75 µs pulse per
    /// sample (`dataready_pulsed`): an edge-triggered input sees every sample, and a
    /// read that fails does not leave the line high (which latched mode would, stopping
    /// every later edge).
    pub fn enable_accel_data_ready_int1_pulsed(&mut self) -> Result<(), Error<B::Error>> {
        self.write(reg::COUNTER_BDR_REG1, value::COUNTER_BDR_REG1_DRDY_PULSED)?;
        self.enable_accel_data_ready_int1()
    }

    /// Read the data-ready flags.
    pub fn data_ready(&mut self) -> Result<DataReady, Error<B::Error>> {
        let s = self.read_register(reg::STATUS_REG)?;
        Ok(DataReady {
            accel: s & 0x01 != 0,
            gyro: s & 0x02 != 0,
            temperature: s & 0x04 != 0,
        })
    }

    /// Read gyroscope and accelerometer in one twelve-byte block read from `OUTX_L_G`.
    pub fn read_raw(&mut self) -> Result<RawSample, Error<B::Error>> {
        let mut buf = [0u8; 12];
        self.bus.read_registers(reg::OUTX_L_G, &mut buf)?;
        let word = |i: usize| i16::from_le_bytes([buf[2 * i], buf[2 * i + 1]]);
        Ok(RawSample {
            gyro: [word(0), word(1), word(2)],
            accel: [word(3), word(4), word(5)],
        })
    }

    /// Read one six-axis sample in SI units (rad/s, m/s²).
    pub fn read(&mut self) -> Result<ImuSample, Error<B::Error>> {
        Ok(self.read_raw()?.to_si())
    }

    /// Read one accelerometer axis (two-byte block read): the fast path for capturing the
    /// cue axis at 6.66 kHz over I²C.
    pub fn read_accel_axis_raw(&mut self, axis: Axis) -> Result<i16, Error<B::Error>> {
        let register = reg::OUTX_L_A
            + match axis {
                Axis::X => 0,
                Axis::Y => 2,
                Axis::Z => 4,
            };
        let mut buf = [0u8; 2];
        self.bus.read_registers(register, &mut buf)?;
        Ok(i16::from_le_bytes(buf))
    }

    fn read_register(&mut self, register: u8) -> Result<u8, Error<B::Error>> {
        let mut buf = [0u8; 1];
        self.bus.read_registers(register, &mut buf)?;
        Ok(buf[0])
    }

    fn write(&mut self, register: u8, value: u8) -> Result<(), Error<B::Error>> {
        self.bus.write_register(register, value)
    }
}

/// ODR from the `INTERNAL_FREQ_FINE` trim byte: `6667 Hz × (1 + 0.0015 × trim)` with the
/// byte read as two's complement, 0.15 % per LSB (ST's reference driver,
/// `lsm6dsox_odr_cal_reg_get`).
pub fn trimmed_odr_hz(trim: u8) -> f32 {
    let trim = f32::from(trim as i8);
    NOMINAL_ODR_HZ * (1.0 + 0.0015 * trim)
}

#[cfg(test)]
mod tests;
