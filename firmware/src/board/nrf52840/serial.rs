//! UARTE0 as a blocking `embedded_io` port: the link of the firmware without the live
//! cue (`blocking.rs` serves it from `main`), and the transmit side of the live cue's
//! link ([`super::live::Link`]).

use nrf52840_hal::pac;
use nrf52840_hal::uarte::{self, Uarte};

/// Bytes per UARTE transmission: EasyDMA reads only RAM, so every write is copied
/// through this buffer first (the caller's bytes may be in flash).
const TX_CHUNK: usize = 64;

/// UARTE0, blocking, as `embedded_io::Read + Write`.
pub struct Serial {
    uarte: Uarte<pac::UARTE0>,
    tx: [u8; TX_CHUNK],
}

/// A UARTE error (framing, overrun, a buffer EasyDMA refused).
#[derive(Debug)]
pub struct SerialError(pub uarte::Error);

impl core::fmt::Display for SerialError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "UARTE0: {:?}", self.0)
    }
}

impl core::error::Error for SerialError {}

impl embedded_io::Error for SerialError {
    fn kind(&self) -> embedded_io::ErrorKind {
        embedded_io::ErrorKind::Other
    }
}

impl embedded_io::ErrorType for Serial {
    type Error = SerialError;
}

impl embedded_io::Read for Serial {
    /// Blocks for exactly one byte (an EasyDMA receive completes only when its buffer
    /// is full, so reading more would wait for bytes that may never come).
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, SerialError> {
        let Some(first) = buf.first_mut() else {
            return Ok(0);
        };
        let mut byte = [0u8; 1]; // on the stack: RAM, as EasyDMA needs
        self.uarte.read(&mut byte).map_err(SerialError)?;
        *first = byte[0];
        Ok(1)
    }
}

impl embedded_io::Write for Serial {
    fn write(&mut self, buf: &[u8]) -> Result<usize, SerialError> {
        let Some(chunk) = buf.get(..buf.len().min(TX_CHUNK)) else {
            return Ok(0);
        };
        if chunk.is_empty() {
            return Ok(0);
        }
        let Some(tx) = self.tx.get_mut(..chunk.len()) else {
            return Ok(0);
        };
        tx.copy_from_slice(chunk);
        self.uarte.write(tx).map_err(SerialError)?;
        Ok(chunk.len())
    }

    fn flush(&mut self) -> Result<(), SerialError> {
        // `Uarte::write` returns once the transmission has ended.
        Ok(())
    }
}

impl Serial {
    /// The port over the configured UARTE0.
    pub(super) fn new(uarte: Uarte<pac::UARTE0>) -> Self {
        Self {
            uarte,
            tx: [0; TX_CHUNK],
        }
    }
}
