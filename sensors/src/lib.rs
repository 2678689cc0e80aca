//! IMU driver, sample ring buffer and stroke estimator for the cuesight smart cue.
//!
//! * [`lsm6dsox`]: embedded-hal 1.0 I²C driver for the ST LSM6DSOX, configured for
//!   6.66 kHz, ±16 g, ±2000 dps, with its register map documented.
//! * [`ring`]: [`RingBuffer`], a fixed-capacity, heap-free ring holding the latest
//!   samples.
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod lsm6dsox;
pub mod ring;

pub use lsm6dsox::{
    accel_lsb_to_mps2, gyro_lsb_to_radps, Axis, ImuSample, Lsm6dsox, RawSample, ACCEL_MPS2_PER_LSB,
    GYRO_RADPS_PER_LSB,
};
pub use ring::RingBuffer;
