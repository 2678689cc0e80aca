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

/// The link's serial port on the QEMU board, for [`serve`]: UART0, shared with the
/// tasks that send unprompted frames (an RTIC resource, locked per access). `read`
/// sleeps in `wfi` until a byte arrives; the UART0 receive task only acknowledges the
/// interrupt, so the byte waits in the UART (QEMU holds the next one back meanwhile).
#[cfg(feature = "live")]
pub struct LinkPort<M> {
    link: M,
}

#[cfg(feature = "live")]
impl<M: rtic::Mutex<T = crate::board::uart::Uart>> LinkPort<M> {
    /// The port over the shared UART.
    pub fn new(link: M) -> Self {
        Self { link }
    }
}

#[cfg(feature = "live")]
impl<M> embedded_io::ErrorType for LinkPort<M> {
    type Error = core::convert::Infallible;
}

#[cfg(feature = "live")]
impl<M: rtic::Mutex<T = crate::board::uart::Uart>> Read for LinkPort<M> {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        if buf.is_empty() {
            return Ok(0);
        }
        loop {
            let count = self.link.lock(|uart| {
                let mut count = 0;
                for slot in buf.iter_mut() {
                    let Some(byte) = uart.try_read() else { break };
                    *slot = byte;
                    count += 1;
                }
                count
            });
            if count > 0 {
                return Ok(count);
            }
            // Checked with interrupts masked: a byte arriving after the check pends the
            // receive interrupt, which ends the `wfi` (and runs once unmasked).
            let link = &mut self.link;
            cortex_m::interrupt::free(|_| {
                if !link.lock(|uart| uart.rx_full()) {
                    cortex_m::asm::wfi();
                }
            });
        }
    }
}

#[cfg(feature = "live")]
impl<M: rtic::Mutex<T = crate::board::uart::Uart>> Write for LinkPort<M> {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        self.link.lock(|uart| uart.write_all(buf));
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}
