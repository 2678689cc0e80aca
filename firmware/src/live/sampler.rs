//! The IMU sampling step: a sample arrives at the LSM6DSOX (on QEMU, latched into the
//! emulated part from the trace; on the nRF52840, the real part on SPI), the unchanged
//! driver reads it over the embedded-hal bus, and the streaming estimator takes the
//! along-cue acceleration `ax` and the pitch rate `gy` (`docs/sensors.md`). O(1) per
//! sample, no buffer.

use cuesight_sensors::emulated::{BusError, EmulatedLsm6dsox, Sa0, SensorLatch};
use cuesight_sensors::lsm6dsox::{Error as ImuError, Interface, ADDRESS_SA0_LOW};
use cuesight_sensors::{
    Lsm6dsox, StreamConfig, StreamConfigError, StreamEvent, StreamingEstimator, Wobble,
};

/// Why sampling could not start (`E`: the bus's error).
#[derive(Clone, Copy, Debug, defmt::Format)]
pub enum StartError<E> {
    /// The part did not come up (chip id, reset, bus).
    Imu(ImuError<E>),
    /// The rate is not one the estimator takes.
    Rate(StreamConfigError),
}

/// The part (`P`: the emulated part, or the driver on the real part's bus) and the
/// estimator.
pub struct Sampler<P> {
    part: P,
    estimator: StreamingEstimator,
    /// The yaw rate's spread over the stroke in progress (restarted when one starts).
    wobble: Wobble,
    /// Samples the estimator never got (a failed read, a stalled part): its indices
    /// count the samples it took, the trace's count these too.
    lost: u64,
}

impl Sampler<EmulatedLsm6dsox> {
    /// Brings the part up with the driver's `init` (chip id, reset, 6.66 kHz ±16 g /
    /// ±2000 dps, block data update) and an estimator for `rate_hz`, into `slot`
    /// (`None` if either fails).
    ///
    /// Fills the slot rather than returning the sampler: a 1.6 KB `Result` moved into
    /// an `Option` is copied twice more (flash and stack in the sampling interrupt).
    #[inline(never)]
    pub fn start(slot: &mut Option<Self>, rate_hz: f32) -> Result<(), StartError<BusError>> {
        *slot = None;
        let mut part = EmulatedLsm6dsox::new(Sa0::Low);
        Lsm6dsox::new(&mut part, ADDRESS_SA0_LOW)
            .init()
            .map_err(StartError::Imu)?;
        Self::fill(slot, part, rate_hz)
    }

    /// The conversion: the part latches `words` (`[ax, ay, az, gx, gy, gz]`) and
    /// raises data-ready. Returns whether the part took them (not stalled).
    pub fn latch(&mut self, words: [i16; 6]) -> bool {
        self.part.latch(words).accel != SensorLatch::Stalled
    }

    /// The driver reads the sample over the bus: `[ax, gy, gz]`.
    pub fn read(&mut self) -> Result<[i16; 3], ImuError<BusError>> {
        let sample = Lsm6dsox::new(&mut self.part, ADDRESS_SA0_LOW).read_raw()?;
        Ok([sample.accel[0], sample.gyro[1], sample.gyro[2]])
    }

    /// Fault injection (the bad-input cases of issue 15): a failing bus, a stalled part.
    pub fn set_faults(&mut self, bus_failing: bool, stalled: bool) {
        self.part.set_bus_failing(bus_failing);
        self.part.set_stalled(stalled);
    }
}

impl<P> Sampler<P> {
    /// An estimator for `rate_hz` beside `part`, into `slot`.
    #[inline(always)]
    fn fill<E>(slot: &mut Option<Self>, part: P, rate_hz: f32) -> Result<(), StartError<E>> {
        #[allow(unused_mut)] // without the live images' features
        let mut config = StreamConfig::new(rate_hz);
        // Each reported stroke's follow-through, once the cue is still again (the
        // `live-cue` feature turns the estimator's `follow-through` feature on; this
        // module is compiled, not linked, in the other images).
        #[cfg(feature = "live-cue")]
        {
            config.follow_through = true;
        }
        let estimator = StreamingEstimator::new(&config).map_err(StartError::Rate)?;
        *slot = Some(Self {
            part,
            estimator,
            wobble: Wobble::new(),
            lost: 0,
        });
        Ok(())
    }

    /// The estimator's step (the along-cue acceleration `ax`, the pitch rate `gy`), and
    /// the yaw rate `gz` into the wobble while a stroke runs.
    #[inline(always)]
    pub fn estimate(&mut self, [ax, gy, gz]: [i16; 3]) -> Option<StreamEvent> {
        let was_moving = self.estimator.in_stroke();
        let event = self.estimator.push_raw(ax, Some(gy));
        if self.estimator.in_stroke() {
            if !was_moving {
                self.wobble.restart();
            }
            self.wobble.push(gz);
        }
        event
    }

    /// The yaw-rate statistics of the stroke in progress or just reported.
    pub fn wobble(&self) -> Wobble {
        self.wobble
    }

    /// The trace ended: a stroke being integrated is reported as ended mid-stroke, and
    /// the estimator starts over at sample 0.
    pub fn finish(&mut self) -> Option<StreamEvent> {
        self.estimator.finish()
    }

    /// Trace samples since the start, taken or lost.
    pub fn samples(&self) -> u64 {
        self.estimator.samples() + self.lost
    }

    /// Counts a sample the estimator did not get; returns its trace index.
    pub fn lose_sample(&mut self) -> u64 {
        self.lost += 1;
        self.samples() - 1
    }

    /// A trace index for an estimator index (the samples lost so far come before it:
    /// exact for reports made as they happen).
    pub fn trace_index(&self, estimator_index: u64) -> u64 {
        estimator_index + self.lost
    }
}

impl<B: Interface> Sampler<Lsm6dsox<B>> {
    /// Brings a real part up with the driver's `init` (as [`Sampler::start`]), routes
    /// its accelerometer data-ready to INT1 as a 75 µs pulse per sample (a lost read
    /// does not hold the line high: the next sample pulses again), and fills `slot` with
    /// an estimator at the part's trimmed output data rate.
    pub fn start_part(
        slot: &mut Option<Self>,
        mut part: Lsm6dsox<B>,
    ) -> Result<(), StartError<B::Error>> {
        *slot = None;
        part.init().map_err(StartError::Imu)?;
        part.enable_accel_data_ready_int1_pulsed()
            .map_err(StartError::Imu)?;
        let rate_hz = part.odr_hz();
        Self::fill(slot, part, rate_hz)
    }

    /// The driver reads the sample over the bus: `[ax, gy, gz]`.
    pub fn read(&mut self) -> Result<[i16; 3], ImuError<B::Error>> {
        let sample = self.part.read_raw()?;
        Ok([sample.accel[0], sample.gyro[1], sample.gyro[2]])
    }
}
