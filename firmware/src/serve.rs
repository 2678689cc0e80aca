//! The serial loop: bytes in, lines through the protocol's [`Session`], answers out.
//! Generic over `embedded_io`, so any board's serial port serves; all protocol logic is
//! in `cuesight-protocol`, tested on the host.

use cuesight_protocol::{AnswerLine, Control, LineReader, Session, MAX_LINE};
use embedded_io::{Read, Write};

/// Serves requests until a `shutdown` request has been answered (`Ok`) or the serial
/// port fails (`Err`). Each line gets exactly one answer line, in order; a line longer
/// than [`MAX_LINE`] gets a `line_too_long` error and the next line is read normally.
///
/// The buffers come from the caller (statics in `main.rs`): the line buffer alone is
/// [`MAX_LINE`] bytes, too much for the stack budget.
pub fn serve<S: Read + Write>(
    serial: &mut S,
    session: &mut Session,
    lines: &mut LineReader<MAX_LINE>,
    answer: &mut AnswerLine,
) -> Result<(), S::Error> {
    let mut chunk = [0u8; 64];
    loop {
        let received = serial.read(&mut chunk)?;
        for &byte in chunk.get(..received).unwrap_or_default() {
            let Some(event) = lines.push(byte) else {
                continue;
            };
            let Some(served) = session.serve(event, answer) else {
                continue; // blank line
            };
            match (served.request, served.error) {
                (Some(request), _) => defmt::debug!("{=str}: answered", request),
                (None, Some(kind)) => defmt::debug!("error answer: {}", kind),
                (None, None) => {}
            }
            serial.write_all(answer)?;
            if served.control == Control::Shutdown {
                serial.flush()?;
                return Ok(());
            }
        }
    }
}
