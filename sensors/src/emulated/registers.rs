//! The registers the model holds: addresses, reset values, the bits it interprets, and
//! the decoders of the ODR and full-scale fields.
//!
//! Addresses, reset values and bit layouts as in the register address map and register
//! description of the LSM6DSOX datasheet (DS12814) and the bitfield structs of ST's
//! `lsm6dsox_reg.h` (`lsm6dsox_int1_ctrl_t`, `lsm6dsox_ctrl1_xl_t`, `lsm6dsox_ctrl2_g_t`,
//! `lsm6dsox_ctrl3_c_t`, `lsm6dsox_ctrl9_xl_t`, `lsm6dsox_status_reg_t`, enums
//! `lsm6dsox_odr_xl_t`, `lsm6dsox_fs_xl_t`, `lsm6dsox_odr_g_t`, `lsm6dsox_fs_g_t`).

pub use crate::lsm6dsox::reg::{
    CTRL1_XL, CTRL2_G, CTRL3_C, CTRL9_XL, INT1_CTRL, INTERNAL_FREQ_FINE, OUTX_L_A, OUTX_L_G,
    STATUS_REG, WHO_AM_I,
};

/// Last output byte, `OUTZ_H_A`.
pub const OUTZ_H_A: u8 = 0x2D;

/// Reset value of `CTRL3_C`: `IF_INC` set (DS12814, CTRL3_C: "IF_INC … Default value: 1").
pub const CTRL3_C_RESET: u8 = 0x04;
/// Reset value of `CTRL9_XL`: `DEN_X`, `DEN_Y`, `DEN_Z` set (register address map).
pub const CTRL9_XL_RESET: u8 = 0xE0;

/// `CTRL3_C` bit 0, `SW_RESET` (self-clearing).
pub const SW_RESET: u8 = 0x01;
/// `CTRL3_C` bit 2, `IF_INC`: register address incremented on multi-byte access.
pub const IF_INC: u8 = 0x04;
/// `CTRL3_C` bit 6, `BDU`: output registers not updated until MSB and LSB have been read.
pub const BDU: u8 = 0x40;
/// `CTRL3_C` bit 7, `BOOT` (memory reboot, self-clearing): not modelled, never stored.
pub const BOOT: u8 = 0x80;

/// `STATUS_REG` bit 0, `XLDA`: a new accelerometer sample is at the output.
pub const XLDA: u8 = 0x01;
/// `STATUS_REG` bit 1, `GDA`: a new gyroscope sample is at the output.
pub const GDA: u8 = 0x02;

/// `INT1_CTRL` bit 0, `INT1_DRDY_XL`: accelerometer data-ready on INT1.
pub const INT1_DRDY_XL: u8 = 0x01;
/// `INT1_CTRL` bit 1, `INT1_DRDY_G`: gyroscope data-ready on INT1.
pub const INT1_DRDY_G: u8 = 0x02;

/// Output data rate (Hz) of an `ODR_XL` / `ODR_G` code (bits 7:4 of `CTRL1_XL` /
/// `CTRL2_G`), `None` for power-down (`0000`) and the reserved codes (`1100`–`1111`;
/// `1011` is 1.6 Hz for the accelerometer in low-power mode only and reserved for the
/// gyroscope: both read as `None` here, as the model does not track the power mode).
pub fn odr_hz(code: u8) -> Option<f32> {
    Some(match code {
        0b0001 => 12.5,
        0b0010 => 26.0,
        0b0011 => 52.0,
        0b0100 => 104.0,
        0b0101 => 208.0,
        0b0110 => 416.0,
        0b0111 => 833.0,
        0b1000 => 1667.0,
        0b1001 => 3333.0,
        0b1010 => 6667.0,
        _ => return None,
    })
}

/// Accelerometer full scale (g) of `CTRL1_XL`'s `FS_XL` (bits 3:2) with `XL_FS_MODE = 0`
/// (`CTRL8_XL`, reset value, not modelled): `00` ±2 g, `01` ±16 g, `10` ±4 g, `11` ±8 g.
pub fn accel_full_scale_g(ctrl1_xl: u8) -> u16 {
    match (ctrl1_xl >> 2) & 0b11 {
        0b00 => 2,
        0b01 => 16,
        0b10 => 4,
        _ => 8,
    }
}

/// Gyroscope full scale (dps) of `CTRL2_G`: `FS_125` (bit 1) gives 125, else `FS_G`
/// (bits 3:2) `00` 250, `01` 500, `10` 1000, `11` 2000.
pub fn gyro_full_scale_dps(ctrl2_g: u8) -> u16 {
    if ctrl2_g & 0x02 != 0 {
        return 125;
    }
    match (ctrl2_g >> 2) & 0b11 {
        0b00 => 250,
        0b01 => 500,
        0b10 => 1000,
        _ => 2000,
    }
}

/// What an output register address is: which sensor, which word, which byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct OutByte {
    /// 0: gyroscope (`0x22`–`0x27`), 1: accelerometer (`0x28`–`0x2D`).
    pub sensor: usize,
    /// Word 0–2 (X, Y, Z) within the sensor.
    pub word: u8,
    /// The high byte (`OUTx_H_*`).
    pub high: bool,
    /// Offset into the 12 output bytes.
    pub offset: usize,
}

/// The output byte at `register`, if it is one.
pub(crate) fn out_byte(register: u8) -> Option<OutByte> {
    if !(OUTX_L_G..=OUTZ_H_A).contains(&register) {
        return None;
    }
    let offset = usize::from(register - OUTX_L_G);
    Some(OutByte {
        sensor: offset / 6,
        word: ((offset % 6) / 2) as u8,
        high: offset % 2 == 1,
        offset,
    })
}
