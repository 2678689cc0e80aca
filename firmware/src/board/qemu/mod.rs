//! QEMU `mps2-an386`: Arm's MPS2 FPGA image AN386 (Cortex-M4F at 25 MHz), as QEMU
//! models it.
//!
//! * **Serial:** CMSDK APB UART0 at `0x4000_4000`, which QEMU connects to its first
//!   `-serial` chardev (`-serial stdio` in `cargo xtask`). Register map (Arm DDI0479C
//!   §4.3, the CMSDK TRM; QEMU `hw/char/cmsdk-apb-uart.c`):
//!
//!   | offset | register  | bits used here                                          |
//!   |--------|-----------|---------------------------------------------------------|
//!   | 0x000  | DATA      | `[7:0]` byte received (read) / to send (write)          |
//!   | 0x004  | STATE     | 0 TX buffer full, 1 RX buffer full                      |
//!   | 0x008  | CTRL      | 0 TX enable, 1 RX enable, 3 RX interrupt enable         |
//!   | 0x00C  | INTSTATUS | 1 RX interrupt (write 1 to clear)                       |
//!   | 0x010  | BAUDDIV   | PCLK / baud, at least 16                                |
//!
//!   One byte of buffering each way, no FIFO. Waiting for a byte sleeps in `wfi`: the
//!   RX interrupt (NVIC line 0 on AN385/AN386, QEMU `hw/arm/mps2.c`) is enabled in the
//!   NVIC but interrupts stay masked by PRIMASK, so it wakes the core without running
//!   a handler (Armv7-M ARM B1.5.19). QEMU then idles instead of spinning.
//! * **Log:** defmt frames over semihosting to QEMU's stderr ([`log`]), so the binary
//!   log never mixes with the protocol on stdout.
//! * **Exit:** semihosting `SYS_EXIT`, which QEMU turns into its own exit code.
//! * **Stack:** painted at boot, so [`peak_stack`] can tell how deep it went.
//! * **Vectors:** one per interrupt line of the device, 48 ([`vectors`]).

use core::convert::Infallible;
use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m::interrupt::InterruptNumber;
use cortex_m::peripheral::NVIC;
use cortex_m_semihosting::debug;

mod log;
mod vectors;

use super::stack;
pub use stack::peak as peak_stack;

/// The board, as reported by `version`.
pub const NAME: &str = "qemu-mps2-an386";

/// APB clock of AN386 (QEMU's `SYSCLK_FRQ`).
const PCLK_HZ: u32 = 25_000_000;
/// Nominal baud rate (QEMU moves bytes as fast as the chardev takes them).
const BAUD: u32 = 115_200;

const UART0: usize = 0x4000_4000;
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

/// Reads UART0's register at `offset`.
fn read(offset: usize) -> u32 {
    read_at(UART0 + offset)
}

/// Writes UART0's register at `offset`.
fn write(offset: usize, value: u32) {
    write_at(UART0 + offset, value)
}

#[allow(unsafe_code)]
fn read_at(address: usize) -> u32 {
    // SAFETY: an aligned 32-bit register of UART0 or TIMER0, which only this module
    // touches (guarded by `TAKEN`); reads have the side effects the driver expects.
    unsafe { core::ptr::read_volatile(address as *const u32) }
}

#[allow(unsafe_code)]
fn write_at(address: usize, value: u32) {
    // SAFETY: as in `read_at`.
    unsafe { core::ptr::write_volatile(address as *mut u32, value) }
}

#[allow(unsafe_code)]
fn unmask_rx_interrupt() {
    // SAFETY: unmasking cannot break a critical section: PRIMASK is set (see `init`)
    // and stays set, so the interrupt only pends and wakes `wfi`.
    unsafe { NVIC::unmask(Uart0Rx) }
}

/// NVIC line of UART0's RX interrupt.
#[derive(Clone, Copy)]
struct Uart0Rx;

// SAFETY: 0 is a valid interrupt number of this device (UART0 RX, hw/arm/mps2.c).
#[allow(unsafe_code)]
unsafe impl InterruptNumber for Uart0Rx {
    fn number(self) -> u16 {
        0
    }
}

/// The board's peripherals, as the firmware uses them.
/// CMSDK APB TIMER0 (QEMU's `cmsdk-apb-timer`): a 32-bit down-counter at the
/// peripheral clock, here free-running from `u32::MAX` (the log's timestamps).
const TIMER0: usize = 0x4000_0000;
const TIMER_CTRL: usize = 0x000;
const TIMER_VALUE: usize = 0x004;
const TIMER_RELOAD: usize = 0x008;
const TIMER_CTRL_ENABLE: u32 = 1 << 0;

/// Starts TIMER0 counting down from `u32::MAX` (a write to RELOAD loads VALUE too),
/// no interrupt.
fn start_uptime() {
    write_at(TIMER0 + TIMER_RELOAD, u32::MAX);
    write_at(TIMER0 + TIMER_CTRL, TIMER_CTRL_ENABLE);
}

/// Microseconds since [`init`] started TIMER0 (0 before).
pub fn uptime_us() -> u64 {
    if read_at(TIMER0 + TIMER_CTRL) & TIMER_CTRL_ENABLE == 0 {
        return 0;
    }
    let elapsed = u32::MAX - read_at(TIMER0 + TIMER_VALUE);
    super::clock::micros(elapsed, PCLK_HZ / 1_000_000)
}

pub struct Board {
    /// The protocol's serial port.
    pub serial: Uart0,
}

static TAKEN: AtomicBool = AtomicBool::new(false);

/// Sets up UART0 (8N1, RX wake-up) and returns the board; a second call exits with
/// failure.
pub fn init() -> Board {
    if TAKEN.swap(true, Ordering::Relaxed) {
        defmt::error!("board::init called twice");
        exit(false);
    }
    // Interrupts only wake `wfi`; no handler ever runs.
    cortex_m::interrupt::disable();
    stack::paint();
    start_uptime();
    write(BAUDDIV, PCLK_HZ / BAUD);
    write(CTRL, CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_INT_EN);
    write(INTSTATUS, INT_RX);
    NVIC::unpend(Uart0Rx);
    unmask_rx_interrupt();
    Board {
        serial: Uart0 { _owned: () },
    }
}

/// CMSDK APB UART0, blocking, as `embedded_io::Read + Write`.
pub struct Uart0 {
    _owned: (),
}

impl Uart0 {
    fn try_read_byte(&mut self) -> Option<u8> {
        if read(STATE) & STATE_RX_FULL == 0 {
            return None;
        }
        let byte = read(DATA) as u8; // clears RX full
        write(INTSTATUS, INT_RX);
        NVIC::unpend(Uart0Rx);
        Some(byte)
    }

    fn read_byte(&mut self) -> u8 {
        loop {
            if let Some(byte) = self.try_read_byte() {
                return byte;
            }
            // A byte arriving after the check pends the RX interrupt, so this returns.
            cortex_m::asm::wfi();
        }
    }

    fn wait_tx_empty(&self) {
        while read(STATE) & STATE_TX_FULL != 0 {}
    }
}

impl embedded_io::ErrorType for Uart0 {
    type Error = Infallible;
}

impl embedded_io::Read for Uart0 {
    /// Blocks for the first byte, then takes whatever else has already arrived.
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        let Some((first, rest)) = buf.split_first_mut() else {
            return Ok(0);
        };
        *first = self.read_byte();
        let mut count = 1;
        for slot in rest {
            match self.try_read_byte() {
                Some(byte) => {
                    *slot = byte;
                    count += 1;
                }
                None => break,
            }
        }
        Ok(count)
    }
}

impl embedded_io::Write for Uart0 {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        for &byte in buf {
            self.wait_tx_empty();
            write(DATA, u32::from(byte));
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), Infallible> {
        self.wait_tx_empty();
        Ok(())
    }
}

/// Ends the program: QEMU exits with 0 for `success`, with 1 otherwise.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    // Only reached without a semihosting host.
    loop {
        cortex_m::asm::wfi();
    }
}
