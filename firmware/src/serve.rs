//! The serial loop: bytes in, frames through the device's [`cuesight_device::Session`], answer frames
//! out. Generic over `embedded_io`, so any board's serial port serves; all link logic
//! is in `cuesight-device` and `cuesight-link`, tested on the host.

use cuesight_device::{Control, Served};
use cuesight_link::frame::{FrameReader, Received};
use embedded_io::{Read, Write};

/// Sends the unprompted `version` frame (the schema hash, for a host that is listening
/// from boot), then serves frames until a `shutdown` request has been answered (`Ok`)
/// or the serial port fails (`Err`). Every frame (a `0x00` ends it) gets exactly one
/// answer frame, in order; a frame that cannot be read gets a typed error answer.
///
/// `answer_frame` answers one frame into the buffer (a [`cuesight_device::Session::serve`], through
/// whatever lock the board's tasks need). The buffers come from the caller (statics):
/// a frame reader and an answer buffer are a kilobyte each, too much for the stack
/// budget.
pub fn serve<S: Read + Write>(
    serial: &mut S,
    hello: usize,
    frames: &mut FrameReader,
    answer: &mut [u8],
    mut answer_frame: impl FnMut(Received<'_>, &mut [u8]) -> Served,
) -> Result<(), S::Error> {
    serial.write_all(answer.get(..hello).unwrap_or_default())?;
    let mut chunk = [0u8; 64];
    loop {
        let received = serial.read(&mut chunk)?;
        for &byte in chunk.get(..received).unwrap_or_default() {
            let Some(frame) = frames.push(byte) else {
                continue;
            };
            let served = answer_frame(frame, answer);
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

/// A serial port that the link's tasks share (an RTIC resource): the byte at a time
/// access [`LinkPort`] needs, none of it blocking on the receive side.
#[cfg(feature = "live-cue")]
pub trait SharedSerial {
    /// Whether `wfi` wakes when a byte arrives (the board takes its receive interrupt).
    /// Without it [`LinkPort`] polls.
    const WAKES_ON_RECEIVE: bool;
    /// The next received byte, if one is waiting.
    fn try_read(&mut self) -> Option<u8>;
    /// Whether a received byte is waiting (checked with interrupts masked before `wfi`).
    fn rx_waiting(&mut self) -> bool;
    /// Sends every byte (blocking).
    fn write_all(&mut self, bytes: &[u8]);
}

/// The link's serial port in the live images, for [`serve`]: shared with the tasks that
/// send unprompted frames (an RTIC resource, locked per access). `read` sleeps in `wfi`
/// until a byte arrives where the board wakes on one (QEMU: the UART0 receive task only
/// acknowledges the interrupt, so the byte waits in the UART, and QEMU holds the next
/// one back meanwhile), and polls otherwise (nRF52840).
#[cfg(feature = "live-cue")]
pub struct LinkPort<M> {
    link: M,
}

#[cfg(feature = "live-cue")]
impl<M: rtic::Mutex> LinkPort<M> {
    /// The port over the shared serial port.
    pub fn new(link: M) -> Self {
        Self { link }
    }
}

#[cfg(feature = "live-cue")]
impl<M> embedded_io::ErrorType for LinkPort<M> {
    type Error = core::convert::Infallible;
}

#[cfg(feature = "live-cue")]
impl<M: rtic::Mutex> Read for LinkPort<M>
where
    M::T: SharedSerial,
{
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        if buf.is_empty() {
            return Ok(0);
        }
        loop {
            let count = self.link.lock(|serial| {
                let mut count = 0;
                for slot in buf.iter_mut() {
                    let Some(byte) = serial.try_read() else { break };
                    *slot = byte;
                    count += 1;
                }
                count
            });
            if count > 0 {
                return Ok(count);
            }
            if M::T::WAKES_ON_RECEIVE {
                // Checked with interrupts masked: a byte arriving after the check pends
                // the receive interrupt, which ends the `wfi` (and runs once unmasked).
                let link = &mut self.link;
                cortex_m::interrupt::free(|_| {
                    if !link.lock(|serial| serial.rx_waiting()) {
                        cortex_m::asm::wfi();
                    }
                });
            }
        }
    }
}

#[cfg(feature = "live-cue")]
impl<M: rtic::Mutex> Write for LinkPort<M>
where
    M::T: SharedSerial,
{
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        self.link.lock(|serial| serial.write_all(buf));
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}
