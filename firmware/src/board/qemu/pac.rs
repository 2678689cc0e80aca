//! The few device-crate items RTIC 2 needs of QEMU's `mps2-an386`, which has no
//! svd2rust crate: the interrupt lines the firmware binds or dispatches on, their
//! numbers, and the NVIC's priority bits.
//!
//! Line numbers: QEMU `hw/arm/mps2.c` (AN385/AN386: each CMSDK UART's RX line, its TX
//! line one above: UART0 0/1, UART1 2/3, UART2 4/5; TIMER0 8, TIMER1 9, the dual timer
//! 10), the same as AN386's own table (Arm AN386, "Interrupt map"). Only the lines named
//! here have handlers of their own; the vector table (`vectors.rs`) points every other
//! line at cortex-m-rt's `DefaultHandler`, which exits with failure (`exit.rs`).

use cortex_m::interrupt::InterruptNumber;

/// Priority bits of the NVIC: 3, the Armv7-M minimum (QEMU's M-profile NVIC implements
/// at least that many). RTIC maps its priorities 1..=8 onto them.
pub const NVIC_PRIO_BITS: u8 = 3;

/// The interrupt lines the firmware uses (RTIC's `binds` and `dispatchers` name them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(non_camel_case_types, clippy::upper_case_acronyms)]
#[repr(u16)]
pub enum Interrupt {
    /// CMSDK UART0 receive: the device link's bytes.
    UART0RX = 0,
    /// CMSDK UART1 receive. UART1 is unused: its line is pended by software for the
    /// task that reads the IMU trace (`app.rs`).
    UART1RX = 2,
    /// CMSDK UART2 receive. UART2 is unused: its line is pended by software for the
    /// task that resolves what a sample found (`app.rs`).
    UART2RX = 4,
    /// CMSDK TIMER1: the emulated IMU's data-ready, at its output data rate.
    TIMER1 = 9,
    /// The dual timer, unused as a timer: the software tasks' dispatcher.
    DUALTIMER = 10,
}

// SAFETY: every variant is a line of the device's NVIC (48 lines, `vectors.rs`).
#[allow(unsafe_code)]
unsafe impl InterruptNumber for Interrupt {
    fn number(self) -> u16 {
        self as u16
    }
}

/// svd2rust's name for the same enum, which RTIC's generated code also refers to.
pub use Interrupt as interrupt;
