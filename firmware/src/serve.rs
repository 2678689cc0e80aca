//! The serial loop: bytes in, frames through the link's [`Session`], answer frames out.
//! Generic over `embedded_io`, so any board's serial port serves; all link logic is in
//! `cuesight-link`, tested on the host.

use cuesight_device::{Control, Session, Upload};
use cuesight_link::frame::FrameReader;
use embedded_io::{Read, Write};

/// Sends the unprompted `version` frame (the schema hash, for a host that is listening
/// from boot), then serves frames until a `shutdown` request has been answered (`Ok`)
/// or the serial port fails (`Err`). Every frame (a `0x00` ends it) gets exactly one
/// answer frame, in order; a frame that cannot be read gets a typed error answer.
///
/// The buffers come from the caller (statics in `main.rs`): a frame reader and an
/// answer buffer are a kilobyte each, too much for the stack budget.
pub fn serve<S: Read + Write>(
    serial: &mut S,
    session: &mut Session<&'static mut Upload>,
    frames: &mut FrameReader,
    answer: &mut [u8],
) -> Result<(), S::Error> {
    let hello = session.hello(answer);
    serial.write_all(answer.get(..hello).unwrap_or_default())?;
    let mut chunk = [0u8; 64];
    loop {
        let received = serial.read(&mut chunk)?;
        for &byte in chunk.get(..received).unwrap_or_default() {
            let Some(frame) = frames.push(byte) else {
                continue;
            };
            let served = session.serve(frame, answer);
            match served.outcome {
                Ok(request) => defmt::debug!("{=str}: answered", request),
                Err(error) => defmt::debug!("error answer: {}", error),
            }
            serial.write_all(answer.get(..served.len).unwrap_or_default())?;
            if served.control == Control::Shutdown {
                serial.flush()?;
                return Ok(());
            }
        }
    }
}
