//! The firmware on QEMU's mps2-an386 as an RTIC 2 application: concurrent tasks on the
//! Cortex-M4F's interrupt priorities, with no executor of our own and no heap.
//!
//! | task | runs on | priority | does |
//! |---|---|---|---|
//! | `sample` | TIMER1, the IMU's data-ready at the output data rate | 4 | latches the next trace sample into the emulated LSM6DSOX, reads it with the driver, steps the streaming estimator; pends `resolve` when the sample found something; hands the trace's end to `report` |
//! | `resolve` | UART2's receive line (UART2 unused), pended by `sample` | 3 | computes the report the estimator deferred (a stroke, its follow-through) or takes a fault of the part, and hands it to `report`: the sampling interrupt stays short, and this runs before the next sample |
//! | `report` | the dual timer's line, pended by `sample` | 2 | plays the planned shot at the stroke's speed, sends the live report frame unprompted, logs it |
//! | `feed` | UART1's receive line (UART1 unused), pended by `sample` | 1 | reads the next chunk of the IMU trace (`board::trace_file`), decodes it (`live::feed`) into a 127-item queue; starts the data-ready clock |
//! | `link_rx` | UART0 receive | 1 | acknowledges the byte, waking `idle` |
//! | `idle` | thread mode | 0 | serves the link: frames in, answers out (`serve.rs`) |
//!
//! The session (defaults, plan) is shared by `idle` and `report`: RTIC locks it by
//! priority ceiling, so a stroke reported while a request is being answered waits for
//! that answer (its latency says so), and two shot computations never stack. The
//! emulated IMU starts on the host's first request (a plan set first holds from the
//! first stroke).
//!
//! RTIC rather than embassy: the tasks are interrupt handlers at fixed priorities, and
//! RTIC's shared resources are locks by priority ceiling (BASEPRI), checked at compile
//! time, at a few instructions each: no executor, no time driver, no waker, which the
//! 48 KiB flash budget and the ≤ 400-instruction sampling path both want. No async task
//! either: RTIC's async executor keeps a panic for a future resumed after completion,
//! which the image's no-panic proof refuses.

/// The firmware name and version, as `version` reports them.
pub const FIRMWARE: &str = concat!(env!("CARGO_PKG_NAME"), " ", env!("CARGO_PKG_VERSION"));

#[allow(unsafe_code)]
#[rtic::app(device = cuesight_firmware::board::pac, peripherals = false)]
mod app {
    use cuesight_firmware::board::trace_file::TraceFile;
    use cuesight_firmware::board::{self, pac::Interrupt, timers, uart::Uart};
    use cuesight_firmware::live::feed::{Fed, Feed, SAMPLE_LEN};
    use cuesight_firmware::live::report::Reporter;
    use cuesight_firmware::live::sampler::Sampler;
    use cuesight_firmware::live::tasks::{self, LiveSession, DETECTED};
    use cuesight_firmware::live::Detected;
    use cuesight_link::frame::{FrameReader, MAX_FRAME};
    use cuesight_link::live::{SensorFault, TraceEnd};
    use cuesight_sensors::emulated::EmulatedLsm6dsox;
    use heapless::spsc::{Consumer, Producer, Queue};

    use super::FIRMWARE;

    /// Items (trace starts, samples, ends) between `feed` and `sample`: 128 slots, 127
    /// usable (1.8 KB).
    const QUEUE: usize = 128;
    /// `sample` wakes `feed` when fewer items than this wait (4.8 ms of samples at
    /// 6.66 kHz: `feed` runs long before they are gone).
    const RESUME_AT: usize = 32;
    /// Bytes `feed` reads at most at once: 64 samples.
    const CHUNK: usize = 64 * SAMPLE_LEN;

    /// What `feed` hands to `sample`, in trace order.
    #[derive(Clone, Copy)]
    pub enum Item {
        /// A trace starts at this rate (Hz).
        Start(u16),
        /// The emulated part's faults from here on.
        Faults { bus_failing: bool, stalled: bool },
        /// A sample, `[ax, ay, az, gx, gy, gz]` raw.
        Sample([i16; 6]),
        /// The trace ended (`truncated`: the file ended before the samples its header
        /// announced).
        End { truncated: bool },
    }

    /// Per-sample cost, in TIMER0 ticks (40 instructions each under `-icount shift=0`),
    /// the emulated bus excluded.
    #[derive(Clone, Copy, Default)]
    pub struct Cost {
        pub samples: u32,
        /// Every sample's and every resolution's.
        pub ticks: u64,
        /// The most of one sample's interrupt...
        pub max_ticks: u32,
        /// ...and of one resolution (`resolve`).
        pub max_resolve_ticks: u32,
    }

    /// What `sample` and `resolve` share (`resolve` locks it: it is the only task that
    /// may wait on `sample`).
    pub struct Sampling {
        sampler: Option<Sampler<EmulatedLsm6dsox>>,
        detected_tx: Producer<'static, Detected, DETECTED>,
        cost: Cost,
    }

    #[shared]
    struct Shared {
        link: Uart,
        session: LiveSession,
        sampling: Sampling,
    }

    #[local]
    struct Local {
        trace: Option<TraceFile>,
        feed: Feed,
        rate_hz: u16,
        producer: Producer<'static, Item, QUEUE>,
        consumer: Consumer<'static, Item, QUEUE>,
        detected_rx: Consumer<'static, Detected, DETECTED>,
        frames: &'static mut FrameReader,
        answer: &'static mut [u8; MAX_FRAME],
        report_out: &'static mut [u8; MAX_FRAME],
    }

    #[init(local = [
        queue: Queue<Item, QUEUE> = Queue::new(),
        detected: Queue<Detected, DETECTED> = Queue::new(),
    ])]
    fn init(cx: init::Context) -> (Shared, Local) {
        let board = board::init();
        let (session, buffers) = tasks::boot(FIRMWARE);
        let (producer, consumer) = cx.local.queue.split();
        let (detected_tx, detected_rx) = cx.local.detected.split();
        (
            Shared {
                link: board.serial,
                session,
                sampling: Sampling {
                    sampler: None,
                    detected_tx,
                    cost: Cost::default(),
                },
            },
            Local {
                trace: board.trace,
                feed: Feed::new(),
                rate_hz: 0,
                producer,
                consumer,
                detected_rx,
                frames: buffers.frames,
                answer: buffers.answer,
                report_out: buffers.report_out,
            },
        )
    }

    /// The link: every frame gets its answer, until `shutdown`; the host's first request
    /// starts the emulated IMU.
    #[idle(shared = [link, session], local = [frames, answer])]
    fn idle(cx: idle::Context) -> ! {
        let idle::SharedResources { link, session, .. } = cx.shared;
        tasks::serve_link(
            link,
            session,
            cx.local.frames,
            &mut cx.local.answer[..],
            || rtic::pend(Interrupt::UART1RX),
        )
    }

    /// A link byte arrived: acknowledge, so `idle` (woken) reads it.
    #[task(binds = UART0RX, priority = 1, shared = [link])]
    fn link_rx(mut cx: link_rx::Context) {
        cx.shared.link.lock(|link| link.acknowledge());
    }

    /// Trace chunks in, queue items out: runs when `sample` finds the queue below
    /// [`RESUME_AT`] (and on the host's first request), reads as many whole samples as
    /// there is room for, and starts the data-ready clock.
    #[task(binds = UART1RX, priority = 1, local = [trace, feed, producer, rate_hz, chunk: [u8; CHUNK] = [0; CHUNK]])]
    fn feed(cx: feed::Context) {
        let feed::LocalResources {
            trace,
            feed,
            producer,
            rate_hz,
            chunk,
            ..
        } = cx.local;
        let Some(file) = trace.as_mut() else {
            return;
        };
        // One header or sample per free slot, and room for the end marker.
        let room = (producer.capacity() - producer.len()).saturating_sub(1);
        let want = (room * SAMPLE_LEN).min(CHUNK);
        let read = file.read(chunk.get_mut(..want).unwrap_or_default());
        for &byte in chunk.get(..read).unwrap_or_default() {
            let item = match feed.push(byte) {
                None => continue,
                Some(Fed::BadMagic) => {
                    defmt::error!("IMU trace: no `CUE1` header where one belongs; dropped");
                    *trace = None;
                    return;
                }
                Some(Fed::Header { rate_hz: rate, .. }) => {
                    *rate_hz = rate;
                    Item::Start(rate)
                }
                Some(Fed::Faults {
                    bus_failing,
                    stalled,
                    ..
                }) => Item::Faults {
                    bus_failing,
                    stalled,
                },
                Some(Fed::Sample(words)) => Item::Sample(words),
            };
            put_item(producer, item);
        }
        if read < want {
            // The file ended, and the trace with it (cut short if its last segment
            // announced more samples).
            put_item(
                producer,
                Item::End {
                    truncated: feed.left() > 0,
                },
            );
            *trace = None;
        }
        if !timers::sampling() && *rate_hz > 0 {
            timers::start_sampling(u32::from(*rate_hz));
        }
    }

    /// Queues a trace item for the sampling task (room was left for it). Out of line:
    /// the queue's enqueue inlined at both of [`feed`]'s puts cost 52 B of flash.
    #[inline(never)]
    fn put_item(producer: &mut Producer<'static, Item, QUEUE>, item: Item) {
        let _ = producer.enqueue(item);
    }

    /// The data-ready: one sample through the part, the driver and the estimator.
    #[task(binds = TIMER1, priority = 4, shared = [sampling], local = [consumer, failing: bool = false])]
    fn sample(mut cx: sample::Context) {
        let sample::LocalResources {
            consumer, failing, ..
        } = cx.local;
        // At the resource's ceiling: no lock is taken.
        cx.shared
            .sampling
            .lock(|sampling| sample_one(sampling, consumer, failing));
    }

    /// The trace's next item (emulation, not a sample's cost). Out of line: the queue's
    /// dequeue inlined at both of [`sample_one`]'s takes cost 76 B of flash.
    #[inline(never)]
    fn next_item(consumer: &mut Consumer<'static, Item, QUEUE>) -> Option<Item> {
        consumer.dequeue()
    }

    /// [`sample`]'s body.
    #[inline(always)]
    fn sample_one(
        Sampling {
            sampler,
            detected_tx,
            cost,
        }: &mut Sampling,
        consumer: &mut Consumer<'static, Item, QUEUE>,
        failing: &mut bool,
    ) {
        // Emulation only: spread the readings over the timer's tick (the instructions
        // before `at` are not counted).
        timers::dither(cost.samples);
        let at = timers::ticks();
        timers::acknowledge_sample();
        // From here to the driver's read, the emulation: the trace's next item, a
        // trace's start (the part's `init`), the part's latch and the bus. None of it
        // is a sample's cost (on the device the part converts, and the SPI peripheral
        // moves the bytes).
        let emulation = timers::ticks();
        let mut item = next_item(consumer);
        if consumer.len() < RESUME_AT {
            rtic::pend(Interrupt::UART1RX);
        }
        if let Some(Item::Start(rate)) = item {
            if Sampler::start(sampler, rate).is_err() {
                hand_over(detected_tx, Detected::Sensor(SensorFault::NotStarted));
            }
            *cost = Cost::default();
            item = next_item(consumer);
        }
        let Some(live) = sampler.as_mut() else {
            return;
        };
        match item {
            Some(Item::Faults {
                bus_failing,
                stalled,
            }) => {
                live.set_faults(bus_failing, stalled);
                // This period's sample is the next item.
                rtic::pend(Interrupt::TIMER1);
            }
            Some(Item::Sample(words)) => {
                let read = live.latch(words).then(|| live.read());
                let emulation_ticks = timers::ticks().wrapping_sub(emulation);
                let found = match read {
                    Some(Ok(words)) => {
                        *failing = false;
                        live.estimate(words, at)
                    }
                    failed => {
                        // The sample is lost; one report per run of losses.
                        let sample = live.lose_sample();
                        let first = !core::mem::replace(failing, true);
                        if first {
                            live.found_fault(match failed {
                                Some(_) => SensorFault::ReadFailed { sample },
                                None => SensorFault::Stalled { sample },
                            });
                        }
                        first
                    }
                };
                if found {
                    rtic::pend(Interrupt::UART2RX);
                }
                // From the interrupt's start, without the emulation.
                let work = timers::ticks()
                    .wrapping_sub(at)
                    .wrapping_sub(emulation_ticks);
                cost.samples += 1;
                cost.ticks += u64::from(work);
                cost.max_ticks = cost.max_ticks.max(work);
            }
            Some(Item::End { truncated }) => {
                timers::stop_sampling();
                if let Some(event) = live.finish() {
                    hand_over(detected_tx, Detected::event(live, event, at));
                }
                let per_tick = timers::INSTRUCTIONS_PER_TICK;
                hand_over(
                    detected_tx,
                    Detected::End(TraceEnd {
                        samples: u64::from(cost.samples),
                        truncated,
                        work_instructions: cost.ticks * u64::from(per_tick),
                        work_max_instructions: cost.max_ticks * per_tick,
                        resolve_max_instructions: cost.max_resolve_ticks * per_tick,
                    }),
                );
            }
            // Only while `feed` has not caught up (emulation): wait for it.
            Some(Item::Start(_)) | None => timers::stop_sampling(),
        }
    }

    /// What `sample` found, resolved one priority below it (`live::tasks::resolve`):
    /// its instructions count in the mean per-sample work, and their most in
    /// `resolve_max_instructions`.
    #[task(binds = UART2RX, priority = 3, shared = [sampling])]
    fn resolve(mut cx: resolve::Context) {
        cx.shared.sampling.lock(|sampling| {
            let begun = timers::ticks();
            if let Some(live) = sampling.sampler.as_mut() {
                tasks::resolve(live, &mut sampling.detected_tx, Interrupt::DUALTIMER);
            }
            let work = timers::ticks().wrapping_sub(begun);
            let cost = &mut sampling.cost;
            cost.ticks += u64::from(work);
            cost.max_resolve_ticks = cost.max_resolve_ticks.max(work);
        });
    }

    /// Queues `detected` for `report` and pends it (`live::tasks::hand_over`).
    fn hand_over(detected_tx: &mut Producer<'static, Detected, DETECTED>, detected: Detected) {
        tasks::hand_over(detected_tx, detected, Interrupt::DUALTIMER);
    }

    /// Strokes, faults and trace ends from `sample`: the guidance, the unprompted
    /// report frame, the log (`live::tasks::report_all`).
    #[task(binds = DUALTIMER, priority = 2, shared = [link, session], local = [detected_rx, report_out, reporter: Reporter = Reporter::new()])]
    fn report(cx: report::Context) {
        let report::LocalResources {
            detected_rx,
            report_out,
            reporter,
            ..
        } = cx.local;
        let report::SharedResources { link, session, .. } = cx.shared;
        tasks::report_all(detected_rx, reporter, report_out, link, session, |at| {
            timers::ticks().wrapping_sub(at) * timers::INSTRUCTIONS_PER_TICK
        });
    }
}
