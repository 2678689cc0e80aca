//! The task bodies both live images run (`app.rs` on QEMU, `app_nrf52840.rs` on the
//! nRF52840): the boot (self-test, the session's buffers), the link in `idle`, the
//! hand-over from the sampling task and the reporting task. The RTIC apps bind them to
//! their boards' interrupts; what differs (the IMU, the clock) stays there.

use cuesight_device::{live_frame, Identity, Session, Upload};
use cuesight_link::frame::{FrameReader, MAX_FRAME};
use heapless::spsc::{Consumer, Producer};
use static_cell::ConstStaticCell;

use super::report::Reporter;
use super::sampler::Sampler;
use super::Detected;
use crate::serve::{self, SharedSerial};
use crate::{board, shots};

/// Reports waiting for the reporting task (a power of two, one slot unused: 3).
pub const DETECTED: usize = 4;

/// The link's session, as both apps share it.
pub type LiveSession = Session<&'static mut Upload>;

/// The session's upload and the [`Buffers`], in one cell: one take at boot (a take is
/// an atomic swap; four cells cost about 140 B more flash). All zeros: `.bss`.
struct Statics {
    upload: Upload,
    frames: FrameReader,
    answer: [u8; MAX_FRAME],
    report: [u8; MAX_FRAME],
}

static STATICS: ConstStaticCell<Statics> = ConstStaticCell::new(Statics {
    upload: Upload::new(),
    frames: FrameReader::new(),
    answer: [0; MAX_FRAME],
    report: [0; MAX_FRAME],
});

/// The statics the tasks work in (a kilobyte each: too much for the stack budget).
pub struct Buffers {
    /// The link's frame reader (`idle`).
    pub frames: &'static mut FrameReader,
    /// `idle`'s answer frame.
    pub answer: &'static mut [u8; MAX_FRAME],
    /// The reporting task's frame.
    pub report_out: &'static mut [u8; MAX_FRAME],
}

/// The boot of either live image, after `board::init`: the log line, the self-test
/// (exit with failure if a model fails it), the session and the buffers.
/// (Inlined: out of line, the QEMU live image is 56 B larger, over its flash budget.)
#[inline(always)]
pub fn boot(firmware: &'static str) -> (LiveSession, Buffers) {
    defmt::info!("{=str} on {=str}", firmware, board::NAME);
    if shots::run_all() != 0 {
        board::exit(false);
    }
    let identity = Identity {
        firmware,
        board: board::NAME,
    };
    let Some(Statics {
        upload,
        frames,
        answer,
        report: report_out,
    }) = STATICS.try_take()
    else {
        defmt::error!("the session buffers were already taken");
        board::exit(false)
    };
    (
        Session::with_upload(identity, upload),
        Buffers {
            frames,
            answer,
            report_out,
        },
    )
}

/// `idle`: every frame gets its answer, until `shutdown` (then the counts and the peak
/// stack are logged and the program exits). `on_first` runs once, after the first
/// request is answered (QEMU: the host is there, the emulated IMU starts).
/// (Inlined, as [`boot`]: 8 B less.)
#[inline(always)]
pub fn serve_link<L, S>(
    link: L,
    mut session: S,
    frames: &mut FrameReader,
    answer: &mut [u8],
    mut on_first: impl FnMut(),
) -> !
where
    L: rtic::Mutex,
    L::T: SharedSerial,
    S: rtic::Mutex<T = LiveSession>,
{
    let hello = session.lock(|session| session.hello(answer));
    let mut port = serve::LinkPort::new(link);
    let mut first = true;
    let served = serve::serve(&mut port, hello, frames, answer, |frame, out| {
        let served = session.lock(|session| session.serve(frame, out));
        if core::mem::take(&mut first) {
            on_first();
        }
        served
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

/// Queues `detected` for the reporting task and pends its interrupt `report` (a full
/// queue drops it: the reporting task runs at every return from the sampling task, so
/// three waiting means it is stuck).
///
/// Out of line: the sampling tasks hand over at several places, each a 104-byte copy
/// into the queue (none on a sample that reports nothing).
#[inline(never)]
pub fn hand_over<I: cortex_m::interrupt::InterruptNumber>(
    detected_tx: &mut Producer<'static, Detected, DETECTED>,
    detected: Detected,
    report: I,
) {
    let _ = detected_tx.enqueue(detected);
    rtic::pend(report);
}

/// The resolving task's body: what the sampling task found on its last sample (a
/// deferred report, computed now, or a fault of the part) goes to the reporting task.
/// It runs one priority below the sampling task, above everything else, so before the
/// next sample (`live::sampler`).
#[inline(always)]
pub fn resolve<P, I: cortex_m::interrupt::InterruptNumber>(
    sampler: &mut Sampler<P>,
    detected_tx: &mut Producer<'static, Detected, DETECTED>,
    report: I,
) {
    if let Some(detected) = sampler.take_found() {
        hand_over(detected_tx, detected, report);
    }
}

/// The reporting task: each waiting detection becomes a live report frame, sent
/// unprompted (`live::report`). `latency` turns the detecting interrupt's start (the
/// board's clock) into instructions, read after the guidance is computed.
pub fn report_all<L, S>(
    detected_rx: &mut Consumer<'static, Detected, DETECTED>,
    reporter: &mut Reporter,
    report_out: &mut [u8; MAX_FRAME],
    mut link: L,
    mut session: S,
    latency: impl Fn(u32) -> u32,
) where
    L: rtic::Mutex,
    L::T: SharedSerial,
    S: rtic::Mutex<T = LiveSession>,
{
    while let Some(detected) = detected_rx.dequeue() {
        let Some(report) = reporter.report(
            detected,
            |speed| session.lock(|s| s.plan_guidance(speed)),
            &latency,
        ) else {
            continue;
        };
        let len = live_frame(report, &mut report_out[..]);
        let frame = report_out.get(..len).unwrap_or_default();
        link.lock(|link| link.write_all(frame));
    }
}
