//! IMU driver, sample ring buffer and stroke estimator for the cuesight smart cue.
//!
//! * [`lsm6dsox`]: embedded-hal 1.0 driver for the ST LSM6DSOX on I²C or SPI,
//!   configured for 6.66 kHz, ±16 g, ±2000 dps, with its register map documented.
//! * [`ring`]: [`RingBuffer`], a fixed-capacity, heap-free ring holding the latest
//!   samples.
//! * [`stroke`]: [`estimate`] / [`estimate_raw`] turn the cue-axis samples of a stroke —
//!   from a still address position through the tip impact — into the cue speed at
//!   impact; [`estimate_with_pitch`] / [`estimate_raw_with_pitch`] also take the gyro's
//!   pitch rate and remove the gravity error of a cue that tilts during the stroke;
//!   [`StrokeEstimate::strike`] feeds the speed to the cue-strike model
//!   ([`cuesight::strike`], TP A.30) for ball speed and spin.
//! * [`trigger`]: [`ImpactTrigger`] tells the capture loop when the ring holds the stroke.
//! * [`streaming`]: [`StreamingEstimator`], the same estimate one sample at a time in
//!   1,464 bytes, with no window: a stroke (or a typed fault) on the impact sample.
//! * [`emulated`]: an LSM6DSOX register model behind the embedded-hal `I2c` trait, on
//!   which the unchanged driver runs (QEMU, host tests); [`trace`]: the CSV trace format
//!   that feeds it, and a byte-at-a-time parser.
//!
//! Measured accuracy and the models behind it: `docs/sensors.md`.
//!
//! Capture loop, in outline (the firmware owns the timing). The window must hold the
//! whole stroke from at least 150 ms of stillness before the backswing: 24,000 samples
//! (3.6 s at 6.66 kHz, 48 kB of `i16`) is what the tests use.
//!
//! ```
//! use cuesight::strike::{Cue, TipOffset};
//! use cuesight_sensors::{estimate_raw, ImpactTrigger, RingBuffer, StrokeConfig};
//! use cuesight_sensors::lsm6dsox::{accel_lsb_to_mps2, ACCEL_MPS2_PER_LSB};
//!
//! # fn capture(next_sample: impl FnMut() -> i16, odr_hz: f32) -> Option<f32> {
//! # let mut next_sample = next_sample;
//! // A firmware keeps the ring in a static.
//! let mut ring = RingBuffer::<i16, 24_000>::new(0);
//! let mut trigger = ImpactTrigger::new(8.0 * 9.806_65, 333).ok()?; // keep 50 ms after impact
//! loop {
//!     let raw = next_sample(); // e.g. Lsm6dsox::read_accel_axis_raw(Axis::X) on DRDY
//!     ring.push(raw);
//!     if trigger.push(accel_lsb_to_mps2(raw)) {
//!         break;
//!     }
//! }
//! let config = StrokeConfig::new(odr_hz); // the part's trimmed ODR
//! let est = estimate_raw(ring.make_contiguous(), ACCEL_MPS2_PER_LSB, &config).ok()?;
//! let hit = est.strike(&cuesight::Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE).ok()?;
//! Some(hit.speed)
//! # }
//! ```
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod emulated;
pub mod glitch;
pub mod lsm6dsox;
pub mod ring;
pub mod streaming;
pub mod stroke;
pub mod trace;
pub mod trigger;

pub use glitch::{find_glitch, Glitch, GlitchKind};
pub use lsm6dsox::{
    accel_lsb_to_mps2, gyro_lsb_to_radps, Axis, ImuSample, Lsm6dsox, RawSample, ACCEL_MPS2_PER_LSB,
    GYRO_RADPS_PER_LSB,
};
pub use ring::RingBuffer;
pub use streaming::{
    CheckedConfig, StreamConfig, StreamConfigError, StreamEvent, StreamFault, StreamPlan,
    StreamStroke, StreamingEstimator, Wobble,
};
pub use stroke::{
    estimate, estimate_raw, estimate_raw_with_pitch, estimate_with_pitch, ConfigField,
    StrokeConfig, StrokeError, StrokeEstimate,
};
pub use trigger::{ImpactTrigger, InvalidThreshold};
