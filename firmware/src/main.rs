//! cuesight on a Cortex-M4F: serves the device link of `cuesight-link` on the board's
//! serial port (postcard messages in COBS frames with a CRC: `version`, `collide`,
//! `params`, `stroke`, `shot` with the `shot` feature, a default one, `shutdown`; see
//! `docs/protocol.md`), logging with defmt.
//!
//! At boot it runs every model on a few built-in shots as a self-test (exit with
//! failure if any outcome is not finite and sane), then serves until a `shutdown`
//! request, after which it exits with success. Panics and faults exit with failure
//! (`exit.rs`). Boots under QEMU's `mps2-an386`: `cargo xtask run`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

mod board;
mod exit;
mod serve;
mod shots;

use cuesight_link::frame::{FrameReader, MAX_FRAME};
use cuesight_link::{Identity, Session, SCHEMA_HASH};
use static_cell::{ConstStaticCell, StaticCell};

/// Firmware name and version, as `version` reports them.
const FIRMWARE: &str = concat!(env!("CARGO_PKG_NAME"), " ", env!("CARGO_PKG_VERSION"));

/// The session (10 KB of stroke samples), in `.bss`: built in place by `init_with`, so
/// it never passes through the stack. (A `ConstStaticCell` would put it in `.data`, and
/// its 10 KB initial image in flash.)
static SESSION: StaticCell<Session> = StaticCell::new();
/// The frame reader (a raw frame's [`cuesight_link::frame::MAX_RAW`] bytes), built in
/// place like the session: its initial value is not all zero, so a `ConstStaticCell`
/// would put it in `.data`, and a kilobyte of its image in flash.
static FRAMES: StaticCell<FrameReader> = StaticCell::new();
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
    let session = SESSION.try_init_with(|| {
        Session::new(Identity {
            firmware: FIRMWARE,
            board: board::NAME,
        })
    });
    let (Some(session), Some(frames), Some(answer)) = (
        session,
        FRAMES.try_init_with(FrameReader::new),
        ANSWER.try_take(),
    ) else {
        defmt::error!("the session buffers were already taken");
        board::exit(false)
    };
    defmt::info!(
        "serving link schema {=u32:#010x} on the serial port (frames up to {=usize} bytes)",
        SCHEMA_HASH,
        MAX_FRAME
    );
    match serve::serve(&mut board.serial, session, frames, answer) {
        Ok(()) => {
            defmt::info!(
                "shutdown: {=u32} requests answered, {=u32} with an error",
                session.requests(),
                session.errors()
            );
            let (peak, size) = board::peak_stack();
            defmt::info!(
                "peak stack {=u32} of {=u32} bytes (statics: session {=usize}, frame reader {=usize}, answer {=usize})",
                peak,
                size,
                core::mem::size_of::<Session>(),
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
