//! The live cue on the nRF52840 as an RTIC 2 application: the tasks of the QEMU image
//! (`app.rs`), on a real LSM6DSOX instead of a trace.
//!
//! | task | runs on | priority | does |
//! |---|---|---|---|
//! | `sample` | GPIOTE, the LSM6DSOX's INT1 data-ready (a pulse per sample) | 3 | restarts the stall watchdog, reads the sample with the driver over SPIM3, steps the streaming estimator; hands a stroke or a fault to `report` |
//! | `stalled` | TIMER1, the stall watchdog: no data-ready for 10 ms | 3 | hands `report` a `stalled` fault, once per stall |
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
    use cuesight_device::{live_frame, Identity, Session, Upload};
    use cuesight_firmware::board::{self, Imu, Link, STALL_US};
    use cuesight_firmware::live::report::Reporter;
    use cuesight_firmware::live::sampler::{Sampler, StartError};
    use cuesight_firmware::live::Detected;
    use cuesight_firmware::{serve, shots};
    use cuesight_link::frame::{FrameReader, MAX_FRAME};
    use cuesight_link::live::SensorFault;
    use cuesight_link::SCHEMA_HASH;
    use cuesight_sensors::lsm6dsox::Error as ImuError;
    use heapless::spsc::{Consumer, Producer, Queue};
    use nrf52840_hal::gpiote::Gpiote;
    use nrf52840_hal::pac::{Interrupt, TIMER1};
    use nrf52840_hal::timer::{OneShot, Timer};
    use static_cell::ConstStaticCell;

    use super::FIRMWARE;

    /// Reports waiting for `report` (a power of two, one slot unused: 3).
    const DETECTED: usize = 4;

    static UPLOAD: ConstStaticCell<Upload> = ConstStaticCell::new(Upload::new());
    static FRAMES: ConstStaticCell<FrameReader> = ConstStaticCell::new(FrameReader::new());
    static ANSWER: ConstStaticCell<[u8; MAX_FRAME]> = ConstStaticCell::new([0; MAX_FRAME]);
    static REPORT: ConstStaticCell<[u8; MAX_FRAME]> = ConstStaticCell::new([0; MAX_FRAME]);

    #[shared]
    struct Shared {
        link: Link,
        session: Session<&'static mut Upload>,
        /// The sampling state, shared by `sample` and `stalled` (one priority: no lock).
        #[lock_free]
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
        defmt::info!("{=str} on {=str}", FIRMWARE, board::NAME);
        if shots::run_all() != 0 {
            board::exit(false);
        }
        let identity = Identity {
            firmware: FIRMWARE,
            board: board::NAME,
        };
        let (Some(upload), Some(frames), Some(answer), Some(report_out)) = (
            UPLOAD.try_take(),
            FRAMES.try_take(),
            ANSWER.try_take(),
            REPORT.try_take(),
        ) else {
            defmt::error!("the session buffers were already taken");
            board::exit(false)
        };
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
        defmt::info!("serving link schema {=u32:#010x} on UARTE0", SCHEMA_HASH);
        (
            Shared {
                link: board.link,
                session: Session::with_upload(identity, upload),
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
                frames,
                answer,
                report_out,
            },
        )
    }

    /// The link: every frame gets its answer, until `shutdown`.
    #[idle(shared = [link, session], local = [frames, answer])]
    fn idle(cx: idle::Context) -> ! {
        let idle::SharedResources {
            link, mut session, ..
        } = cx.shared;
        let answer = &mut cx.local.answer[..];
        let hello = session.lock(|session| session.hello(answer));
        let mut port = serve::LinkPort::new(link);
        let served = serve::serve(&mut port, hello, cx.local.frames, answer, |frame, out| {
            session.lock(|session| session.serve(frame, out))
        });
        let Ok(()) = served;
        let (requests, errors) = session.lock(|s| (s.requests(), s.errors()));
        defmt::info!(
            "shutdown: {=u32} requests answered, {=u32} with an error",
            requests,
            errors
        );
        let (peak, size) = board::peak_stack();
        defmt::info!("peak stack {=u32} of {=u32} bytes", peak, size);
        board::exit(true)
    }

    /// The data-ready: one sample through the driver and the estimator.
    #[task(binds = GPIOTE, priority = 3, shared = [sampling], local = [gpiote])]
    fn sample(cx: sample::Context) {
        let at = DWT::cycle_count();
        cx.local.gpiote.channel0().reset_events();
        let Sampling {
            sampler,
            detected_tx,
            watchdog,
            failing,
            stalled,
        } = cx.shared.sampling;
        let Some(live) = sampler.as_mut() else {
            return;
        };
        watchdog.start(STALL_US);
        *stalled = false;
        let event = match live.read() {
            Ok(words) => {
                *failing = false;
                live.estimate(words)
            }
            Err(_) => {
                // The sample is lost; one report per run of losses.
                let sample = live.lose_sample();
                if !core::mem::replace(failing, true) {
                    hand_over(
                        detected_tx,
                        Detected::Sensor(SensorFault::ReadFailed { sample }),
                    );
                }
                None
            }
        };
        if let Some(event) = event {
            hand_over(detected_tx, Detected::event(live, event, at));
        }
    }

    /// The stall watchdog fired: no data-ready for [`STALL_US`]. Reported once; the
    /// next data-ready restarts the watchdog (the part's pulses need no re-arming).
    #[task(binds = TIMER1, priority = 3, shared = [sampling])]
    fn stalled(cx: stalled::Context) {
        let Sampling {
            sampler,
            detected_tx,
            watchdog,
            stalled,
            ..
        } = cx.shared.sampling;
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

    /// Queues `detected` for `report` and pends it (a full queue drops it).
    #[inline(never)]
    fn hand_over(detected_tx: &mut Producer<'static, Detected, DETECTED>, detected: Detected) {
        let _ = detected_tx.enqueue(detected);
        rtic::pend(Interrupt::SWI0_EGU0);
    }

    /// Strokes and faults from `sample`: the guidance, the unprompted report frame, the
    /// log (`live::report`).
    #[task(binds = SWI0_EGU0, priority = 2, shared = [link, session], local = [detected_rx, report_out, reporter: Reporter = Reporter::new()])]
    fn report(cx: report::Context) {
        let report::LocalResources {
            detected_rx,
            report_out,
            reporter,
            ..
        } = cx.local;
        let report::SharedResources {
            mut link,
            mut session,
            ..
        } = cx.shared;
        while let Some(detected) = detected_rx.dequeue() {
            let Some(report) = reporter.report(
                detected,
                |speed| session.lock(|s| s.plan_guidance(speed)),
                |at| DWT::cycle_count().wrapping_sub(at),
            ) else {
                continue;
            };
            let len = live_frame(report, &mut report_out[..]);
            let frame = report_out.get(..len).unwrap_or_default();
            link.lock(|link| serve::SharedSerial::write_all(link, frame));
        }
    }
}
