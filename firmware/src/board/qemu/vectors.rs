//! The device-specific part of the vector table (`__INTERRUPTS`, after the 16 system
//! exceptions): one entry per interrupt line of QEMU's mps2-an386, whose NVIC has 48
//! (`num-irq`, QEMU's `info qtree`). The lines of [`super::pac::Interrupt`] point at
//! handlers of that name, which RTIC defines for the tasks bound to them (a `device.x`
//! that `build.rs` writes provides `DefaultHandler` for any it leaves out); every other
//! line is cortex-m-rt's `DefaultHandler`, as in cortex-m-rt's own table. That table,
//! used when no device crate provides one, has the architecture's 240 entries: 960 B of
//! flash, 768 B more than this one.

use super::pac::Interrupt;

/// Interrupt lines of the mps2-an386 in QEMU.
const LINES: usize = 48;

extern "C" {
    /// cortex-m-rt's default exception handler (its link.x provides the symbol).
    fn DefaultHandler();
    fn UART0RX();
    fn UART1RX();
    fn UART2RX();
    fn TIMER1();
    fn DUALTIMER();
}

/// The vector table's interrupt part: `DefaultHandler` but for the named lines.
const fn table() -> [unsafe extern "C" fn(); LINES] {
    let mut lines = [DefaultHandler as unsafe extern "C" fn(); LINES];
    lines[Interrupt::UART0RX as usize] = UART0RX;
    lines[Interrupt::UART1RX as usize] = UART1RX;
    lines[Interrupt::UART2RX as usize] = UART2RX;
    lines[Interrupt::TIMER1 as usize] = TIMER1;
    lines[Interrupt::DUALTIMER as usize] = DUALTIMER;
    lines
}

/// The interrupt vectors, where cortex-m-rt's link.x places `.vector_table.interrupts`.
// SAFETY (the lint's concern with `no_mangle` and `link_section`): this is the one
// `__INTERRUPTS` in the image (cortex-m-rt defines none with `device`), an array of
// handler addresses as the vector table needs.
#[allow(unsafe_code)]
#[link_section = ".vector_table.interrupts"]
#[no_mangle]
static __INTERRUPTS: [unsafe extern "C" fn(); LINES] = table();
