//! The live cue on the nRF52840 as an RTIC 2 application: the tasks of the QEMU image
//! (`app.rs`), on a real LSM6DSOX instead of a trace.
//!
//! | task | runs on | priority | does |
//! |---|---|---|---|
//! | `sample` | GPIOTE, the LSM6DSOX's INT1 data-ready (a pulse per sample) | 4 | restarts the stall watchdog, reads the sample with the driver over SPIM3, steps the streaming estimator; pends `resolve` when the sample found something |
//! | `stalled` | TIMER1, the stall watchdog: no data-ready for 10 ms | 4 | hands `report` a `stalled` fault, once per stall |
//! | `resolve` | SWI1_EGU1, pended by `sample` | 3 | computes the report the estimator deferred (a stroke, its follow-through) or takes a failed read, and hands it to `report`, before the next sample |
//! | `report` | SWI0_EGU0, pended by `sample` | 2 | plays the planned shot at the stroke's speed, sends the live report frame unprompted, logs it (`live::report`) |
//! | `idle` | thread mode | 0 | serves the link on UARTE0: frames in, answers out (`serve.rs`) |
//!
//! The part is brought up in `init` (chip id, reset, 6.66 kHz at ±16 g / ±2000 dps, its
//! ODR trim read, data-ready on INT1 as a pulse), and sampling runs from then on. A part
//! that does not come up is reported (`sensor: not_started`, queued at boot, sent when
//! the reporting task first runs), and the link goes on without a live cue. A failed read loses its
//! sample and is reported once per run of failures, as under QEMU.
//!
//! Latencies are in DWT cycles at 64 MHz (at least one per instruction on the
//! Cortex-M4, so an upper bound of the instructions QEMU reports).
//!
//! Not measured here (no hardware): the per-sample cost, the latency, and whether the
//! pins are right on a given board. What the build proves: the image links within the
//! flash and RAM budgets (`cargo xtask test`, step "firmware: nrf52840 board").

/// The firmware name and version, as `version` reports them.
pub const FIRMWARE: &str = concat!(env!("CARGO_PKG_NAME"), " ", env!("CARGO_PKG_VERSION"));

#[allow(unsafe_code)]
#[rtic::app(device = nrf52840_hal::pac, peripherals = false)]
mod app {
    use cortex_m::peripheral::DWT;
    use cuesight_firmware::board::{self, Imu, Link, STALL_US};
    use cuesight_firmware::live::report::Reporter;
    use cuesight_firmware::live::sampler::{Sampler, StartError};
    use cuesight_firmware::live::tasks::{self, LiveSession, DETECTED};
    use cuesight_firmware::live::Detected;
    use cuesight_link::frame::{FrameReader, MAX_FRAME};
    use cuesight_link::live::SensorFault;
    use cuesight_sensors::lsm6dsox::Error as ImuError;
    use heapless::spsc::{Consumer, Producer, Queue};
    use nrf52840_hal::gpiote::Gpiote;
    use nrf52840_hal::pac::{Interrupt, TIMER1};
    use nrf52840_hal::timer::{OneShot, Timer};

    use super::FIRMWARE;

    #[shared]
    struct Shared {
        link: Link,
        session: LiveSession,
        /// The sampling state, shared by `sample` and `stalled` (one priority: no lock
        /// between them) and `resolve` (which locks it).
        sampling: Sampling,
    }

    /// What the two sampling tasks share.
    pub struct Sampling {
        sampler: Option<Sampler<Imu>>,
        detected_tx: Producer<'static, Detected, DETECTED>,
        watchdog: Timer<TIMER1, OneShot>,
        /// The last read failed (one report per run of failures).
        failing: bool,
        /// The watchdog fired and no data-ready came since (one report per stall).
        stalled: bool,
    }

    #[local]
    struct Local {
        gpiote: Gpiote,
        detected_rx: Consumer<'static, Detected, DETECTED>,
        frames: &'static mut FrameReader,
        answer: &'static mut [u8; MAX_FRAME],
        report_out: &'static mut [u8; MAX_FRAME],
    }

    #[init(local = [detected: Queue<Detected, DETECTED> = Queue::new()])]
    fn init(mut cx: init::Context) -> (Shared, Local) {
        let board = board::init(&mut cx.core);
        let (session, buffers) = tasks::boot(FIRMWARE);
        let (mut detected_tx, detected_rx) = cx.local.detected.split();
        let mut sampler = None;
        let mut watchdog = board.watchdog;
        match Sampler::start_part(&mut sampler, board.imu) {
            Ok(()) => {
                defmt::info!("LSM6DSOX up: sampling on INT1");
                watchdog.start(STALL_US);
            }
            Err(error) => {
                match error {
                    StartError::Imu(ImuError::WrongChipId(id)) => {
                        defmt::error!("LSM6DSOX not started: WHO_AM_I reads {=u8:#04x}", id)
                    }
                    StartError::Imu(ImuError::ResetTimeout) => {
                        defmt::error!("LSM6DSOX not started: its reset did not clear")
                    }
                    StartError::Imu(_) => defmt::error!("LSM6DSOX not started: SPI failed"),
                    StartError::Rate(_) => {
                        defmt::error!("LSM6DSOX not started: its trimmed rate is refused")
                    }
                }
                let _ = detected_tx.enqueue(Detected::Sensor(SensorFault::NotStarted));
                rtic::pend(Interrupt::SWI0_EGU0);
            }
        }
        (
            Shared {
                link: board.link,
                session,
                sampling: Sampling {
                    sampler,
                    detected_tx,
                    watchdog,
                    failing: false,
                    stalled: false,
                },
            },
            Local {
                gpiote: board.gpiote,
                detected_rx,
                frames: buffers.frames,
                answer: buffers.answer,
                report_out: buffers.report_out,
            },
        )
    }

    /// The link: every frame gets its answer, until `shutdown`.
    #[idle(shared = [link, session], local = [frames, answer])]
    fn idle(cx: idle::Context) -> ! {
        let idle::SharedResources { link, session, .. } = cx.shared;
        tasks::serve_link(
            link,
            session,
            cx.local.frames,
            &mut cx.local.answer[..],
            || {},
        )
    }

    /// The data-ready: one sample through the driver and the estimator.
    #[task(binds = GPIOTE, priority = 4, shared = [sampling], local = [gpiote])]
    fn sample(mut cx: sample::Context) {
        let at = DWT::cycle_count();
        cx.local.gpiote.channel0().reset_events();
        // At the resource's ceiling: no lock is taken.
        cx.shared.sampling.lock(|sampling| sample_one(sampling, at));
    }

    /// [`sample`]'s body.
    #[inline(always)]
    fn sample_one(
        Sampling {
            sampler,
            watchdog,
            failing,
            stalled,
            ..
        }: &mut Sampling,
        at: u32,
    ) {
        let Some(live) = sampler.as_mut() else {
            return;
        };
        watchdog.start(STALL_US);
        *stalled = false;
        let found = match live.read() {
            Ok(words) => {
                *failing = false;
                live.estimate(words, at)
            }
            Err(_) => {
                // The sample is lost; one report per run of losses.
                let sample = live.lose_sample();
                let first = !core::mem::replace(failing, true);
                if first {
                    live.found_fault(SensorFault::ReadFailed { sample });
                }
                first
            }
        };
        if found {
            rtic::pend(Interrupt::SWI1_EGU1);
        }
    }

    /// What `sample` found, resolved one priority below it (`live::tasks::resolve`).
    #[task(binds = SWI1_EGU1, priority = 3, shared = [sampling])]
    fn resolve(mut cx: resolve::Context) {
        cx.shared.sampling.lock(|sampling| {
            if let Some(live) = sampling.sampler.as_mut() {
                tasks::resolve(live, &mut sampling.detected_tx, Interrupt::SWI0_EGU0);
            }
        });
    }

    /// The stall watchdog fired: no data-ready for [`STALL_US`]. Reported once; the
    /// next data-ready restarts the watchdog (the part's pulses need no re-arming).
    #[task(binds = TIMER1, priority = 4, shared = [sampling])]
    fn stalled(mut cx: stalled::Context) {
        cx.shared.sampling.lock(stall);
    }

    /// [`stalled`]'s body.
    #[inline(always)]
    fn stall(
        Sampling {
            sampler,
            detected_tx,
            watchdog,
            stalled,
            ..
        }: &mut Sampling,
    ) {
        watchdog.reset_event();
        let Some(live) = sampler.as_ref() else {
            return;
        };
        if !core::mem::replace(stalled, true) {
            let sample = live.samples();
            hand_over(
                detected_tx,
                Detected::Sensor(SensorFault::Stalled { sample }),
            );
        }
    }

    /// Queues `detected` for `report` and pends it (`live::tasks::hand_over`).
    fn hand_over(detected_tx: &mut Producer<'static, Detected, DETECTED>, detected: Detected) {
        tasks::hand_over(detected_tx, detected, Interrupt::SWI0_EGU0);
    }

    /// Strokes and faults from `sample` and `stalled`: the guidance, the unprompted
    /// report frame, the log (`live::tasks::report_all`; latency in DWT cycles).
    #[task(binds = SWI0_EGU0, priority = 2, shared = [link, session], local = [detected_rx, report_out, reporter: Reporter = Reporter::new()])]
    fn report(cx: report::Context) {
        let report::LocalResources {
            detected_rx,
            report_out,
            reporter,
            ..
        } = cx.local;
        let report::SharedResources { link, session, .. } = cx.shared;
        tasks::report_all(detected_rx, reporter, report_out, link, session, |at| {
            DWT::cycle_count().wrapping_sub(at)
        });
    }
}
