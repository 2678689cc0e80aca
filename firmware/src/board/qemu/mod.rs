//! QEMU `mps2-an386`: Arm's MPS2 FPGA image AN386 (Cortex-M4F at 25 MHz), as QEMU
//! models it.
//!
//! * **Link:** CMSDK APB UART0 at `0x4000_4000` ([`uart`]), which QEMU connects to its
//!   first `-serial` chardev (`-serial stdio` in `cargo xtask`).
//! * **IMU trace** (the `live` feature): a named pipe the host streams the trace into
//!   ([`trace_file`], read through semihosting in chunks; `crate::live::feed`), whose samples the emulated LSM6DSOX gives out one
//!   per TIMER1 period ([`timers`]), as the part's data-ready would.
//! * **Interrupts:** with the `live` feature RTIC 2 drives them ([`pac`] names the lines
//!   it binds); without it no handler runs and UART0's receive interrupt only wakes
//!   `wfi`.
//! * **Log:** defmt frames over semihosting to QEMU's stderr ([`log`]), so the binary
//!   log never mixes with the protocol on stdout.
//! * **Exit:** semihosting `SYS_EXIT`, which QEMU turns into its own exit code.
//! * **Stack:** painted at boot, so [`peak_stack`] can tell how deep it went (interrupt
//!   handlers run on the same stack, so it counts them).
//! * **Vectors:** one per interrupt line of the device, 48 ([`vectors`]).

use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_semihosting::debug;

mod log;
pub mod pac;
pub mod timers;
pub mod trace_file;
pub mod uart;
mod vectors;

use super::stack;
pub use stack::peak as peak_stack;
pub use timers::uptime_us;
use uart::Uart;

/// The board, as reported by `version`.
pub const NAME: &str = "qemu-mps2-an386";

/// APB clock of AN386 (QEMU's `SYSCLK_FRQ`).
const PCLK_HZ: u32 = 25_000_000;

const UART0: usize = 0x4000_4000;

#[allow(unsafe_code)]
fn read_at(address: usize) -> u32 {
    // SAFETY: an aligned 32-bit register of a UART or timer, which only this module
    // touches (guarded by `TAKEN`); reads have the side effects the driver expects.
    unsafe { core::ptr::read_volatile(address as *const u32) }
}

#[allow(unsafe_code)]
fn write_at(address: usize, value: u32) {
    // SAFETY: as in `read_at`.
    unsafe { core::ptr::write_volatile(address as *mut u32, value) }
}

#[cfg(not(feature = "live"))]
#[allow(unsafe_code)]
fn unmask_link_interrupt() {
    // SAFETY: unmasking cannot break a critical section: PRIMASK is set and stays set,
    // so the interrupt only pends and wakes `wfi`.
    unsafe { cortex_m::peripheral::NVIC::unmask(pac::Interrupt::UART0RX) }
}

/// The board's peripherals, as the firmware uses them.
pub struct Board {
    /// The link's serial port (UART0).
    pub serial: Uart,
    /// The IMU trace, if QEMU's working directory has one.
    pub trace: Option<trace_file::TraceFile>,
}

static TAKEN: AtomicBool = AtomicBool::new(false);

/// Paints the stack, starts the uptime counter, sets up UART0 (8N1, RX interrupt
/// raised; RTIC unmasks the lines it binds), opens the IMU trace if there is one, and
/// returns the board; a second call exits with failure.
pub fn init() -> Board {
    if TAKEN.swap(true, Ordering::Relaxed) {
        defmt::error!("board::init called twice");
        exit(false);
    }
    stack::paint();
    timers::start_uptime();
    // Without the live cue no handler runs: interrupts stay masked and UART0's only
    // wakes `wfi` (Armv7-M ARM B1.5.19); `Uart`'s blocking `read` sleeps on it.
    #[cfg(not(feature = "live"))]
    {
        cortex_m::interrupt::disable();
        unmask_link_interrupt();
    }
    Board {
        serial: Uart::init(UART0),
        trace: trace_file::TraceFile::open(),
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
