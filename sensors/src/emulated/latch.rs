//! Samples arriving: [`EmulatedLsm6dsox::latch`], the data-ready flags and INT1, the
//! `BDU` hold, overruns (module docs of [`super`]).

use super::registers as r;
use super::EmulatedLsm6dsox;

/// What [`EmulatedLsm6dsox::latch`] did with one sensor's half of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensorLatch {
    /// Written (or, under `BDU`, held for the registers); the previous sample had been read.
    New,
    /// Written (or held) as `New`, but the previous sample was never read: it is lost.
    Overrun,
    /// Dropped: the sensor is in power-down (its ODR field is `0000` or reserved).
    PoweredDown,
    /// Dropped: the model is in stalled mode.
    Stalled,
}

/// What [`EmulatedLsm6dsox::latch`] did with a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LatchReport {
    /// The accelerometer half (`ax`, `ay`, `az`).
    pub accel: SensorLatch,
    /// The gyroscope half (`gx`, `gy`, `gz`).
    pub gyro: SensorLatch,
}

/// Overruns counted since the model was made ([`SensorLatch::Overrun`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Overruns {
    /// Accelerometer samples lost unread.
    pub accel: u32,
    /// Gyroscope samples lost unread.
    pub gyro: u32,
}

/// Index of the gyroscope / accelerometer in per-sensor arrays (output byte order).
pub(super) const GYRO: usize = 0;
pub(super) const ACCEL: usize = 1;

impl EmulatedLsm6dsox {
    /// The end of a conversion: `[ax, ay, az, gx, gy, gz]` in raw LSB (the trace's
    /// column order) become the output registers of each powered sensor, and its
    /// data-ready flag is set (module docs: `STATUS_REG`, `BDU`, overrun).
    pub fn latch(&mut self, sample: [i16; 6]) -> LatchReport {
        if self.stalled {
            return LatchReport {
                accel: SensorLatch::Stalled,
                gyro: SensorLatch::Stalled,
            };
        }
        self.latched = self.latched.wrapping_add(1);
        let [ax, ay, az, gx, gy, gz] = sample;
        let accel_on = r::odr_hz(self.ctrl1_xl >> 4).is_some();
        let gyro_on = r::odr_hz(self.ctrl2_g >> 4).is_some();
        LatchReport {
            accel: if accel_on {
                self.deliver(ACCEL, [ax, ay, az])
            } else {
                SensorLatch::PoweredDown
            },
            gyro: if gyro_on {
                self.deliver(GYRO, [gx, gy, gz])
            } else {
                SensorLatch::PoweredDown
            },
        }
    }

    /// The INT1 pin (latched data-ready): `INT1_DRDY_XL && XLDA || INT1_DRDY_G && GDA`.
    pub const fn int1(&self) -> bool {
        (self.int1_ctrl & r::INT1_DRDY_XL != 0 && self.status & r::XLDA != 0)
            || (self.int1_ctrl & r::INT1_DRDY_G != 0 && self.status & r::GDA != 0)
    }

    /// One sensor's half of a latch.
    fn deliver(&mut self, sensor: usize, words: [i16; 3]) -> SensorLatch {
        let mut bytes = [0u8; 6];
        for (i, w) in words.iter().enumerate() {
            bytes[2 * i..2 * i + 2].copy_from_slice(&w.to_le_bytes());
        }
        let lost = if self.hold[sensor].is_some() {
            // Registers held mid-read: the sample waits. Only a waiting one can be lost.
            self.pending[sensor].replace(bytes).is_some()
        } else {
            let flag = Self::flag(sensor);
            let unread = self.status & flag != 0;
            self.write_out(sensor, bytes);
            unread
        };
        if lost {
            match sensor {
                ACCEL => self.overruns.accel = self.overruns.accel.wrapping_add(1),
                _ => self.overruns.gyro = self.overruns.gyro.wrapping_add(1),
            }
            SensorLatch::Overrun
        } else {
            SensorLatch::New
        }
    }

    pub(super) fn flag(sensor: usize) -> u8 {
        if sensor == ACCEL {
            r::XLDA
        } else {
            r::GDA
        }
    }

    fn write_out(&mut self, sensor: usize, bytes: [u8; 6]) {
        self.out[6 * sensor..6 * sensor + 6].copy_from_slice(&bytes);
        self.status |= Self::flag(sensor);
    }

    /// End a sensor's `BDU` hold, writing a sample that waited. Out of line: the bus
    /// releases at three places (222 B of flash when each had its own copy).
    #[inline(never)]
    pub(super) fn release(&mut self, sensor: usize) {
        self.hold[sensor] = None;
        if let Some(bytes) = self.pending[sensor].take() {
            self.write_out(sensor, bytes);
        }
    }
}
