//! The IMU sampling step: a sample arrives at the LSM6DSOX (on QEMU, latched into the
//! emulated part from the trace; on the nRF52840, the real part on SPI), the unchanged
//! driver reads it over the embedded-hal bus, and the streaming estimator takes the
//! along-cue acceleration `ax` and the pitch rate `gy` (`docs/sensors.md`). O(1) per
//! sample, no buffer.

use cuesight_link::live::{SensorFault, TraceEnd};
use cuesight_sensors::emulated::{BusError, EmulatedLsm6dsox, Sa0, SensorLatch};
use cuesight_sensors::lsm6dsox::{Error as ImuError, Interface, ADDRESS_SA0_LOW};
use cuesight_sensors::{
    CheckedConfig, Lsm6dsox, StreamConfig, StreamConfigError, StreamEvent, StreamPlan,
    StreamingEstimator, Wobble,
};

/// Why sampling could not start (`E`: the bus's error).
#[derive(Clone, Copy, Debug, defmt::Format)]
pub enum StartError<E> {
    /// The part did not come up (chip id, reset, bus).
    Imu(ImuError<E>),
    /// The rate is not one the estimator takes.
    Rate(StreamConfigError),
}

/// What a sample found, for the resolving task (`live::tasks::resolve`) to hand over.
#[derive(Clone, Copy)]
enum Found {
    Nothing,
    /// The estimator deferred work (a report, a block end); the sample's interrupt
    /// began at `at` (the board's clock).
    Deferred {
        at: u32,
    },
    /// The part failed.
    Sensor(SensorFault),
}

/// What the sampling task hands to the reporting task.
#[derive(Clone, Copy)]
pub enum Detected {
    /// The estimator's report, and the board's clock (QEMU: TIMER0 ticks; nRF52840:
    /// DWT cycles) when the interrupt that delivered the detecting sample began.
    Event {
        /// The report.
        event: StreamEvent,
        /// When its interrupt began.
        at: u32,
        /// Samples lost before it (the estimator's indices do not count them).
        lost: u64,
        /// The stroke's yaw-rate statistics (its wobble, computed by the reporting
        /// task, not in the interrupt).
        wobble: cuesight_sensors::Wobble,
    },
    /// The IMU failed.
    Sensor(SensorFault),
    /// The trace ended.
    End(TraceEnd),
}

impl Detected {
    /// The estimator's `event`, detected on the sample whose interrupt began at `at`.
    #[inline(never)]
    pub fn event<P>(sampler: &Sampler<P>, event: StreamEvent, at: u32) -> Self {
        Detected::Event {
            event,
            at,
            lost: sampler.trace_index(0),
            wobble: sampler.wobble(),
        }
    }
}

/// The part (`P`: the emulated part, or the driver on the real part's bus) and the
/// estimator.
///
/// The estimator defers its reports ([`StreamConfig::defer_reports`]): the sample that
/// finds a stroke's impact or a follow-through's end only marks it, and the resolving
/// task, pended by the sampling task at the priority just below its own, computes the
/// report before the next sample ([`Self::take_found`]): the sampling interrupt stays
/// short (issue 15: at most 400 instructions a sample).
pub struct Sampler<P> {
    part: P,
    estimator: StreamingEstimator,
    /// What the last sample found, until the resolving task takes it.
    found: Found,
    /// The yaw rate's spread over the stroke in progress (restarted when one starts).
    wobble: Wobble,
    /// A stroke ran at the last sample (the estimator's state before its deferred work).
    moving: bool,
    /// Samples the estimator never got (a failed read, a stalled part): its indices
    /// count the samples it took, the trace's count these too.
    lost: u64,
}

impl Sampler<EmulatedLsm6dsox> {
    /// Brings the part up with the driver's `init` (chip id, reset, 6.66 kHz ±16 g /
    /// ±2000 dps, block data update) and an estimator for `rate_hz`, into `slot`
    /// (`None` if either fails; a rate other than 3333 or 6667 Hz is
    /// [`StreamConfigError::SampleRate`]).
    ///
    /// Fills the slot rather than returning the sampler: a 1.6 KB `Result` moved into
    /// an `Option` is copied twice more (flash and stack in the sampling interrupt).
    #[inline(never)]
    pub fn start(slot: &mut Option<Self>, rate_hz: u16) -> Result<(), StartError<BusError>> {
        *slot = None;
        let mut part = EmulatedLsm6dsox::new(Sa0::Low);
        Lsm6dsox::new(&mut part, ADDRESS_SA0_LOW)
            .init()
            .map_err(StartError::Imu)?;
        let plan = TRACE_PLANS
            .iter()
            .find(|(rate, _)| *rate == rate_hz)
            .map_or(Err(StreamConfigError::SampleRate), |(_, plan)| *plan);
        Self::fill(slot, part, plan)
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

/// The estimator's settings at `rate_hz` (Hz): the defaults, its reports deferred
/// ([`Sampler`]) and, with the `live-cue` feature (which turns the estimator's
/// `follow-through` feature on; this module is compiled, not linked, in the other
/// images), each reported stroke's follow-through.
const fn live_config(rate_hz: f32) -> StreamConfig {
    let mut config = StreamConfig::new(rate_hz);
    config.defer_reports = true;
    #[cfg(feature = "live-cue")]
    {
        config.follow_through = true;
    }
    config
}

/// The plans for the rates an emulated trace may have (`cuesight_host::live::RATES_HZ`,
/// the LSM6DSOX's 3.33 and 6.66 kHz), validated at compile time: the QEMU image carries
/// no validation code (870 B of flash).
const TRACE_PLANS: [(u16, Result<StreamPlan, StreamConfigError>); 2] = [
    (3333, StreamPlan::new(&live_config(3333.0))),
    (6667, StreamPlan::new(&live_config(6667.0))),
];

/// The estimator's settings for a real part ([`live_config`]), validated at compile
/// time but for the rate, which is the part's trimmed output data rate (known after its
/// `init`): [`CheckedConfig::plan_at`] checks that alone, so the nRF52840 image carries
/// no code for the other checks.
const PART_CONFIG: CheckedConfig =
    match CheckedConfig::new(&live_config(cuesight_sensors::lsm6dsox::NOMINAL_ODR_HZ)) {
        Ok(config) => config,
        Err(_) => panic!("the live estimator's settings are invalid"),
    };

impl<P> Sampler<P> {
    /// An estimator on `plan` beside `part`, into `slot`.
    #[inline(always)]
    fn fill<E>(
        slot: &mut Option<Self>,
        part: P,
        plan: Result<StreamPlan, StreamConfigError>,
    ) -> Result<(), StartError<E>> {
        let plan = plan.map_err(StartError::Rate)?;
        *slot = Some(Self {
            part,
            estimator: StreamingEstimator::with_plan(&plan),
            found: Found::Nothing,
            wobble: Wobble::new(),
            moving: false,
            lost: 0,
        });
        Ok(())
    }

    /// The estimator's step (the along-cue acceleration `ax`, the pitch rate `gy`), and
    /// the yaw rate `gz` into the wobble while a stroke runs. `true` when the sample
    /// found a report (a stroke's impact, a follow-through): pend the resolving task.
    /// `at`: when the sample's interrupt began.
    #[inline(always)]
    pub fn estimate(&mut self, [ax, gy, gz]: [i16; 3], at: u32) -> bool {
        // Deferred: `push_raw` reports nothing itself (`StreamConfig::defer_reports`).
        let _ = self.estimator.push_raw(ax, Some(gy));
        // An impact ends the stroke (its crossing sample is not in the wobble); a
        // deferred block end's change shows from the next sample on.
        let moving = self.estimator.in_stroke();
        if moving {
            if !self.moving {
                self.wobble.restart();
            }
            self.wobble.push(gz);
        }
        self.moving = moving;
        let deferred = self.estimator.deferred();
        if deferred {
            self.found = Found::Deferred { at };
        }
        deferred
    }

    /// A failed read or a stalled part, for the resolving task to report.
    pub fn found_fault(&mut self, fault: SensorFault) {
        self.found = Found::Sensor(fault);
    }

    /// What the last sample found, for the reporting task: the estimator's deferred
    /// report, computed now, or a fault of the part. Call it before the next sample.
    pub fn take_found(&mut self) -> Option<Detected> {
        match core::mem::replace(&mut self.found, Found::Nothing) {
            Found::Nothing => None,
            Found::Deferred { at } => {
                let event = self.estimator.resolve()?;
                Some(Detected::event(self, event, at))
            }
            Found::Sensor(fault) => Some(Detected::Sensor(fault)),
        }
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
        // `StreamPlan::new(&live_config(part.odr_hz()))`, its rate-independent checks
        // made at compile time.
        let plan = PART_CONFIG.plan_at(part.odr_hz());
        Self::fill(slot, part, plan)
    }

    /// The driver reads the sample over the bus: `[ax, gy, gz]`.
    pub fn read(&mut self) -> Result<[i16; 3], ImuError<B::Error>> {
        let sample = self.part.read_raw()?;
        Ok([sample.accel[0], sample.gyro[1], sample.gyro[2]])
    }
}
