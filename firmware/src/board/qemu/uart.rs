//! CMSDK APB UART (QEMU's `cmsdk-apb-uart`), as mps2-an386 has five of. Register map
//! (Arm DDI0479C §4.3, the CMSDK TRM; QEMU `hw/char/cmsdk-apb-uart.c`):
//!
//! | offset | register  | bits used here                                          |
//! |--------|-----------|---------------------------------------------------------|
//! | 0x000  | DATA      | `[7:0]` byte received (read) / to send (write)          |
//! | 0x004  | STATE     | 0 TX buffer full, 1 RX buffer full                      |
//! | 0x008  | CTRL      | 0 TX enable, 1 RX enable, 3 RX interrupt enable         |
//! | 0x00C  | INTSTATUS | 1 RX interrupt (write 1 to clear)                       |
//! | 0x010  | BAUDDIV   | PCLK / baud, at least 16                                |
//!
//! One byte of buffering each way, no FIFO: until the byte in `DATA` is read, QEMU
//! holds the next one in its chardev, so a reader that stops reading pushes back on the
//! host. The RX interrupt is a level: it stays raised until `INTSTATUS` is cleared, so
//! a handler acknowledges it ([`Uart::acknowledge`]) whether or not it takes the byte.

use core::convert::Infallible;

use super::{read_at, write_at, PCLK_HZ};

const DATA: usize = 0x000;
const STATE: usize = 0x004;
const CTRL: usize = 0x008;
const INTSTATUS: usize = 0x00C;
const BAUDDIV: usize = 0x010;

const STATE_TX_FULL: u32 = 1 << 0;
const STATE_RX_FULL: u32 = 1 << 1;
const CTRL_TX_EN: u32 = 1 << 0;
const CTRL_RX_EN: u32 = 1 << 1;
const CTRL_RX_INT_EN: u32 = 1 << 3;
const INT_RX: u32 = 1 << 1;

/// Nominal baud rate (QEMU moves bytes as fast as the chardev takes them).
const BAUD: u32 = 115_200;

/// One CMSDK UART, by its base address; 8N1, transmitter and receiver on, the RX
/// interrupt raised for every byte received.
pub struct Uart {
    base: usize,
}

impl Uart {
    /// Sets the UART at `base` up. Only the board module makes these, once per UART.
    pub(super) fn init(base: usize) -> Self {
        let uart = Self { base };
        uart.write(BAUDDIV, PCLK_HZ / BAUD);
        uart.write(CTRL, CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_INT_EN);
        uart.acknowledge();
        uart
    }

    fn read(&self, offset: usize) -> u32 {
        read_at(self.base + offset)
    }

    fn write(&self, offset: usize, value: u32) {
        write_at(self.base + offset, value)
    }

    /// Whether a received byte waits in `DATA`.
    pub fn rx_full(&self) -> bool {
        self.read(STATE) & STATE_RX_FULL != 0
    }

    /// The received byte, if one waits (reading it lets QEMU deliver the next). Clears
    /// the receive interrupt and its pending state, for the next byte to raise them.
    pub fn try_read(&mut self) -> Option<u8> {
        if !self.rx_full() {
            return None;
        }
        let byte = self.read(DATA) as u8;
        self.acknowledge();
        cortex_m::peripheral::NVIC::unpend(super::pac::Interrupt::UART0RX);
        Some(byte)
    }

    /// Clears the RX interrupt (the line drops until the next byte arrives).
    pub fn acknowledge(&self) {
        self.write(INTSTATUS, INT_RX);
    }

    /// Sends `bytes`, waiting for the transmitter before each.
    pub fn write_all(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            while self.read(STATE) & STATE_TX_FULL != 0 {}
            self.write(DATA, u32::from(byte));
        }
    }
}

impl embedded_io::ErrorType for Uart {
    type Error = Infallible;
}

/// Blocking reads, for the firmware without the live cue: interrupts are masked and the
/// receive interrupt wakes `wfi` (see the board module).
#[cfg(not(feature = "live"))]
impl embedded_io::Read for Uart {
    /// Sleeps for the first byte, then takes whatever else has already arrived.
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        let Some((first, rest)) = buf.split_first_mut() else {
            return Ok(0);
        };
        *first = loop {
            if let Some(byte) = self.try_read() {
                break byte;
            }
            // A byte arriving after the check pends the interrupt, so this returns.
            cortex_m::asm::wfi();
        };
        let mut count = 1;
        for slot in rest {
            let Some(byte) = self.try_read() else { break };
            *slot = byte;
            count += 1;
        }
        Ok(count)
    }
}

impl embedded_io::Write for Uart {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        self.write_all(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), Infallible> {
        while self.read(STATE) & STATE_TX_FULL != 0 {}
        Ok(())
    }
}

/// The live image's link: `LinkPort` sleeps until UART0's receive interrupt.
#[cfg(feature = "live")]
impl crate::serve::SharedSerial for Uart {
    const WAKES_ON_RECEIVE: bool = true;

    fn try_read(&mut self) -> Option<u8> {
        Uart::try_read(self)
    }

    fn rx_waiting(&mut self) -> bool {
        self.rx_full()
    }

    fn write_all(&mut self, bytes: &[u8]) {
        Uart::write_all(self, bytes)
    }
}
