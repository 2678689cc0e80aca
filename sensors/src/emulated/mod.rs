//! An LSM6DSOX register model behind the embedded-hal 1.0 [`I2c`](embedded_hal::i2c::I2c)
//! trait, for a board with no IMU (QEMU): the unchanged [`Lsm6dsox`](crate::Lsm6dsox)
//! driver runs on it, and the board feeds it samples (from a trace, [`crate::trace`]) at
//! the configured rate with [`EmulatedLsm6dsox::latch`], as the part's data-ready event
//! would. `no_std`, no heap, 68 bytes of state.
//!
//! ```
//! use cuesight_sensors::emulated::{EmulatedLsm6dsox, Sa0, SensorLatch};
//! use cuesight_sensors::Lsm6dsox;
//!
//! let mut part = EmulatedLsm6dsox::new(Sa0::Low);
//! let mut imu = Lsm6dsox::new(&mut part, 0x6A); // `&mut` an I2c is an I2c
//! imu.init().unwrap();
//! // The data-ready event: [ax, ay, az, gx, gy, gz] in raw LSB.
//! let report = part.latch([2049, 0, 0, 0, -14, 0]);
//! assert_eq!(report.accel, SensorLatch::New);
//! let s = Lsm6dsox::new(&mut part, 0x6A).read_raw().unwrap();
//! assert_eq!((s.accel[0], s.gyro[1]), (2049, -14));
//! ```
//!
//! # What is modelled
//!
//! Sources: the LSM6DSOX datasheet (DS12814), its register address map and register
//! description, and ST's `lsm6dsox_reg.h` (github.com/STMicroelectronics/lsm6dsox-pid)
//! for the bit layouts; the driver's own table is in [`crate::lsm6dsox`].
//!
//! | register | addr | model |
//! |---|---|---|
//! | `INT1_CTRL` | `0x0D` | rw, reset `0x00`; bits 0 `INT1_DRDY_XL` and 1 `INT1_DRDY_G` drive [`EmulatedLsm6dsox::int1`] |
//! | `WHO_AM_I` | `0x0F` | r, `0x6C` |
//! | `CTRL1_XL` | `0x10` | rw, reset `0x00`; `ODR_XL` (7:4) gates the accelerometer, see [`EmulatedLsm6dsox::accel_odr_hz`] and `FS_XL` (3:2) |
//! | `CTRL2_G` | `0x11` | rw, reset `0x00`; `ODR_G` (7:4) gates the gyroscope, `FS_G` (3:2), `FS_125` (1) |
//! | `CTRL3_C` | `0x12` | rw, reset `0x04`; `SW_RESET` (0), `IF_INC` (2) and `BDU` (6) act as below; `BOOT` (7) is dropped |
//! | `CTRL9_XL` | `0x18` | rw, reset `0xE0`, stored only |
//! | `STATUS_REG` | `0x1E` | r; `XLDA` (0), `GDA` (1); `TDA` (2) always 0 |
//! | `OUTX_L_G` … `OUTZ_H_A` | `0x22`–`0x2D` | r; the latched sample, gyro X, Y, Z then accel X, Y, Z, little-endian two's complement |
//! | `INTERNAL_FREQ_FINE` | `0x63` | r; the trim byte given to [`EmulatedLsm6dsox::with_freq_fine`] (default 0) |
//!
//! * **I²C address.** The part answers on `0x6A` (`SA0` low) or `0x6B` (`SA0` high),
//!   datasheet, I²C serial interface: `SAD = 110101x`. A transaction to any other
//!   address fails with [`BusError::AddressNack`], whose
//!   [`kind`](embedded_hal::i2c::Error::kind) is `NoAcknowledge(Address)`, as no device
//!   acknowledges it; nothing in the model changes.
//! * **Register pointer.** The first byte written after a START (or a repeated START
//!   into a write) is the register address; the following written bytes go to it.
//!   Every byte read or written then moves the pointer on by one when `IF_INC` is set,
//!   and leaves it when clear (datasheet, CTRL3_C: "register address automatically
//!   incremented during a multiple byte access"), so a twelve-byte read from `0x22`
//!   returns gyro then accel. A read with no register written first continues from the
//!   pointer. (The `ROUNDING` wrap-around of `CTRL5_C` is not modelled: the pointer runs
//!   on linearly, past `0x2D` into unmodelled registers.)
//! * **`SW_RESET`.** Writing `CTRL3_C` with bit 0 set restores the reset values of every
//!   modelled control register (table above), clears `STATUS_REG`, the output registers
//!   and any BDU hold; the other bits of that write are dropped. The datasheet has the
//!   bit clear itself when the reset is done; the model has no clock, so the reset lasts
//!   a number of `CTRL3_C` reads instead ([`EmulatedLsm6dsox::with_reset_reads`], 1 by
//!   default: the first poll reads `0x05`, the next `0x04`).
//! * **Samples and `STATUS_REG`.** [`EmulatedLsm6dsox::latch`] is the end of a
//!   conversion: the accelerometer half is taken when `ODR_XL` ≠ 0 and the gyroscope half
//!   when `ODR_G` ≠ 0 (a sensor in power-down makes no data), written to the output
//!   registers, and `XLDA` / `GDA` set ("a new set of data is available"). The words are
//!   stored as given: the model does not rescale for the full scale (the trace format
//!   fixes ±16 g and ±2000 dps). `XLDA` is cleared by a read of any accelerometer high
//!   byte (`OUTx_H_A`), `GDA` by any gyroscope high byte (`OUTx_H_G`): ST's rule for the
//!   LSM6DS family's data-ready (application note AN5272 for the LSM6DSOX, "reading
//!   output data"; taken from ST's documentation as recalled, not re-checked against
//!   the note's text in this work).
//! * **`BDU`.** With `BDU` set, reading a low byte (`OUTx_L_*`) holds that sensor's
//!   output registers: a sample latched meanwhile waits, and is written (setting its
//!   flag) when the high byte of the same word is read, so a word's two bytes always
//!   come from one sample (CTRL3_C: "output registers are not updated until MSB and LSB
//!   have been read"). The hold is per sensor (the datasheet does not say how wide it
//!   is). With `BDU` clear a latch overwrites the registers at once, so a word read one
//!   byte at a time across a latch tears. Clearing `BDU` releases a hold.
//! * **Data-ready on INT1**, latched mode (`dataready_pulsed` = 0, the reset value of
//!   `COUNTER_BDR_REG1`): [`EmulatedLsm6dsox::int1`] is `INT1_DRDY_XL && XLDA ||
//!   INT1_DRDY_G && GDA`, the level the pin would show. Polarity (`H_LACTIVE`) and
//!   push-pull/open-drain (`PP_OD`) are stored in `CTRL3_C` but do not change it.
//! * **Overrun.** The part has no overrun flag outside its FIFO; the model reports one
//!   for the firmware's stalled-reader checks: a latch whose sensor still has an unread
//!   sample ([`SensorLatch::Overrun`], counted in [`EmulatedLsm6dsox::overruns`]).
//!   "Unread" means no high byte of that sensor was read since the sample was written,
//!   or a sample held by `BDU` is replaced before it reached the registers.
//! * **Faults** for the firmware's bad-input reports: [`EmulatedLsm6dsox::set_bus_failing`]
//!   makes every transaction fail with [`BusError::BusFault`] (`ErrorKind::Bus`) with no
//!   effect; [`EmulatedLsm6dsox::set_stalled`] makes [`EmulatedLsm6dsox::latch`] drop its
//!   samples (no conversion, no data-ready: a stalled sensor).
//! * **Other registers.** A read of a register not in the table returns `0x00` and a
//!   write to one, or to a read-only register, is ignored; both are counted
//!   ([`EmulatedLsm6dsox::unmodelled_reads`], [`EmulatedLsm6dsox::ignored_writes`]) so a
//!   test can assert the firmware touches nothing else. (The datasheet asks that
//!   reserved registers never be written and does not define reads of them.)
//!
//! # Not modelled
//!
//! The FIFO, the temperature sensor (`OUT_TEMP_*`, `TDA`), filters and their settling
//! (`LPF2_XL_EN`, `CTRL4_C`–`CTRL8_XL`), power modes, the boot and turn-on times, `BOOT`,
//! self-test, timestamps, the embedded functions and their register banks
//! (`FUNC_CFG_ACCESS`), INT2, pulsed data-ready, the OIS/auxiliary SPI, the I3C
//! interface, SPI, big-endian data (`BLE` does not exist on this part), clock stretching
//! and timing of any kind (a transaction takes no time; the board decides when samples
//! arrive).
//!
//! # Driver access
//!
//! The driver owns its bus. To latch samples while it runs, a board shares the model
//! (e.g. a `&RefCell<EmulatedLsm6dsox>` / critical-section mutex implementing
//! [`I2c`](embedded_hal::i2c::I2c) by delegation, as `embedded-hal-bus` does), or the
//! tests take it back with [`Lsm6dsox::release`](crate::Lsm6dsox::release). `&mut
//! EmulatedLsm6dsox` is an `I2c` too (embedded-hal's blanket impl), so the driver can
//! borrow it for a while.

mod bus;
mod latch;
pub mod registers;

pub use bus::BusError;
pub use latch::{LatchReport, Overruns, SensorLatch};

use registers as r;

/// The level of the `SA0` pin, which sets the I²C address.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Sa0 {
    /// `SA0` tied low: address `0x6A`.
    Low,
    /// `SA0` tied high: address `0x6B`.
    High,
}

/// The LSM6DSOX register model (see the module docs for what it models).
#[derive(Clone, Debug)]
pub struct EmulatedLsm6dsox {
    address: u8,
    int1_ctrl: u8,
    ctrl1_xl: u8,
    ctrl2_g: u8,
    /// Without `SW_RESET` and `BOOT`.
    ctrl3_c: u8,
    ctrl9_xl: u8,
    freq_fine: u8,
    /// `CTRL3_C` reads a reset lasts, and how many are left of the current one.
    reset_reads: u16,
    reset_left: u16,
    status: u8,
    /// `OUTX_L_G` … `OUTZ_H_A`.
    out: [u8; 12],
    /// Per sensor: the word whose low byte was read under `BDU` (holding the registers).
    hold: [Option<u8>; 2],
    /// Per sensor: a sample latched during a hold.
    pending: [Option<[u8; 6]>; 2],
    pointer: u8,
    bus_failing: bool,
    stalled: bool,
    latched: u32,
    overruns: Overruns,
    unmodelled_reads: u32,
    ignored_writes: u32,
}

impl EmulatedLsm6dsox {
    /// A part at power-on (every register at its reset value), answering on the address
    /// `sa0` selects, with `INTERNAL_FREQ_FINE` = 0 and a one-poll software reset.
    pub const fn new(sa0: Sa0) -> Self {
        Self {
            address: match sa0 {
                Sa0::Low => crate::lsm6dsox::ADDRESS_SA0_LOW,
                Sa0::High => crate::lsm6dsox::ADDRESS_SA0_HIGH,
            },
            int1_ctrl: 0,
            ctrl1_xl: 0,
            ctrl2_g: 0,
            ctrl3_c: r::CTRL3_C_RESET,
            ctrl9_xl: r::CTRL9_XL_RESET,
            freq_fine: 0,
            reset_reads: 1,
            reset_left: 0,
            status: 0,
            out: [0; 12],
            hold: [None; 2],
            pending: [None; 2],
            pointer: 0,
            bus_failing: false,
            stalled: false,
            latched: 0,
            overruns: Overruns { accel: 0, gyro: 0 },
            unmodelled_reads: 0,
            ignored_writes: 0,
        }
    }

    /// The same part with this factory ODR trim in `INTERNAL_FREQ_FINE` (two's
    /// complement, 0.15 % per LSB).
    pub const fn with_freq_fine(mut self, trim: u8) -> Self {
        self.freq_fine = trim;
        self
    }

    /// The same part with a software reset that lasts `reads` reads of `CTRL3_C` (0: done
    /// before the first poll; `u16::MAX`: as good as never).
    pub const fn with_reset_reads(mut self, reads: u16) -> Self {
        self.reset_reads = reads;
        self
    }

    /// The 7-bit I²C address the part answers on.
    pub const fn address(&self) -> u8 {
        self.address
    }

    /// Every transaction fails with [`BusError::BusFault`] while `failing` (a failed bus).
    pub fn set_bus_failing(&mut self, failing: bool) {
        self.bus_failing = failing;
    }

    /// [`Self::latch`] drops every sample while `stalled` (a sensor that stopped converting).
    pub fn set_stalled(&mut self, stalled: bool) {
        self.stalled = stalled;
    }

    /// A register's content as a read would return it, without the read's side effects
    /// (no flag cleared, no hold, no reset poll counted, no unmodelled read counted).
    pub fn peek(&self, register: u8) -> u8 {
        match register {
            r::INT1_CTRL => self.int1_ctrl,
            r::WHO_AM_I => crate::lsm6dsox::WHO_AM_I_VALUE,
            r::CTRL1_XL => self.ctrl1_xl,
            r::CTRL2_G => self.ctrl2_g,
            r::CTRL3_C => self.ctrl3_c | if self.reset_left > 0 { r::SW_RESET } else { 0 },
            r::CTRL9_XL => self.ctrl9_xl,
            r::STATUS_REG => self.status,
            r::INTERNAL_FREQ_FINE => self.freq_fine,
            _ => match r::out_byte(register) {
                Some(o) => self.out[o.offset],
                None => 0,
            },
        }
    }

    /// The accelerometer's ODR (Hz) as `CTRL1_XL` sets it; `None` in power-down. A board
    /// paces [`Self::latch`] by it.
    pub fn accel_odr_hz(&self) -> Option<f32> {
        r::odr_hz(self.ctrl1_xl >> 4)
    }

    /// The gyroscope's ODR (Hz) as `CTRL2_G` sets it; `None` in power-down.
    pub fn gyro_odr_hz(&self) -> Option<f32> {
        r::odr_hz(self.ctrl2_g >> 4)
    }

    /// The accelerometer full scale (±g) `CTRL1_XL` selects.
    pub fn accel_full_scale_g(&self) -> u16 {
        r::accel_full_scale_g(self.ctrl1_xl)
    }

    /// The gyroscope full scale (±dps) `CTRL2_G` selects.
    pub fn gyro_full_scale_dps(&self) -> u16 {
        r::gyro_full_scale_dps(self.ctrl2_g)
    }

    /// Samples given to [`Self::latch`] outside stalled mode (wrapping).
    pub const fn latched(&self) -> u32 {
        self.latched
    }

    /// Overruns counted so far.
    pub const fn overruns(&self) -> Overruns {
        self.overruns
    }

    /// Reads of registers the model does not hold (each returned `0x00`).
    pub const fn unmodelled_reads(&self) -> u32 {
        self.unmodelled_reads
    }

    /// Writes dropped: to read-only or unmodelled registers.
    pub const fn ignored_writes(&self) -> u32 {
        self.ignored_writes
    }

    fn software_reset(&mut self) {
        self.int1_ctrl = 0;
        self.ctrl1_xl = 0;
        self.ctrl2_g = 0;
        self.ctrl3_c = r::CTRL3_C_RESET;
        self.ctrl9_xl = r::CTRL9_XL_RESET;
        self.status = 0;
        self.out = [0; 12];
        self.hold = [None; 2];
        self.pending = [None; 2];
        self.reset_left = self.reset_reads;
    }
}
