//! The firmware without the live cue: the link alone, served from `main` with blocking
//! reads (no interrupt handler runs; the serial port's receive interrupt only wakes
//! `wfi`).

use cuesight_device::{Identity, Session, Upload};
use cuesight_firmware::{board, serve, shots};
use cuesight_link::frame::{FrameReader, MAX_FRAME};
use cuesight_link::SCHEMA_HASH;
use static_cell::{ConstStaticCell, StaticCell};

/// Firmware name and version, as `version` reports them.
const FIRMWARE: &str = concat!(env!("CARGO_PKG_NAME"), " ", env!("CARGO_PKG_VERSION"));

/// The stroke upload (10 KB of samples): all zero when new, so `.bss`. Kept apart from
/// the session, which borrows it: built whole, the session passed through a 10 KB
/// temporary on the stack (peak stack 16,212 B over a `version` and a `shutdown`).
static UPLOAD: ConstStaticCell<Upload> = ConstStaticCell::new(Upload::new());
/// The session (defaults, frame count; its initial value is not zero, so it is built
/// at boot rather than kept as a `.data` image in flash).
static SESSION: StaticCell<Session<&'static mut Upload>> = StaticCell::new();
/// The frame reader (a raw frame's [`cuesight_link::frame::MAX_RAW`] bytes; `.bss`).
static FRAMES: ConstStaticCell<FrameReader> = ConstStaticCell::new(FrameReader::new());
/// The answer frame buffer (`.bss`).
static ANSWER: ConstStaticCell<[u8; MAX_FRAME]> = ConstStaticCell::new([0; MAX_FRAME]);

#[cortex_m_rt::entry]
fn main() -> ! {
    let mut board = board::init();
    defmt::info!("{=str} on {=str}", FIRMWARE, board::NAME);

    let failures = shots::run_all();
    if failures != 0 {
        board::exit(false);
    }

    // Each cell is taken once, here (`entry` runs once); the `try_` forms keep the
    // image free of static_cell's panics.
    let identity = Identity {
        firmware: FIRMWARE,
        board: board::NAME,
    };
    let session = UPLOAD
        .try_take()
        .and_then(|upload| SESSION.try_init_with(|| Session::with_upload(identity, upload)));
    let (Some(session), Some(frames), Some(answer)) =
        (session, FRAMES.try_take(), ANSWER.try_take())
    else {
        defmt::error!("the session buffers were already taken");
        board::exit(false)
    };
    defmt::info!(
        "serving link schema {=u32:#010x} on the serial port (frames up to {=usize} bytes)",
        SCHEMA_HASH,
        MAX_FRAME
    );
    let hello = session.hello(answer);
    match serve::serve(&mut board.serial, hello, frames, answer, |frame, out| {
        session.serve(frame, out)
    }) {
        Ok(()) => {
            defmt::info!(
                "shutdown: {=u32} requests answered, {=u32} with an error",
                session.requests(),
                session.errors()
            );
            let (peak, size) = board::peak_stack();
            defmt::info!(
                "peak stack {=u32} of {=u32} bytes (statics: stroke upload {=usize}, frame reader {=usize}, answer {=usize})",
                peak,
                size,
                core::mem::size_of::<Upload>(),
                core::mem::size_of::<FrameReader>(),
                MAX_FRAME
            );
            board::exit(true)
        }
        Err(error) => {
            defmt::error!("serial port failed: {}", defmt::Debug2Format(&error));
            board::exit(false)
        }
    }
}
