//! The device-specific part of the vector table (`__INTERRUPTS`, after the 16 system
//! exceptions): one entry per interrupt line of QEMU's mps2-an386, whose NVIC has 48
//! (`num-irq`, QEMU's `info qtree`). No handler runs on this board (PRIMASK stays set:
//! UART0's RX interrupt only wakes `wfi`, see the board module), so every entry is
//! cortex-m-rt's `DefaultHandler`, as in cortex-m-rt's own table. That table, used when
//! no device crate provides one, has the architecture's 240 entries: 960 B of flash, 768
//! B more than this one.
//!
//! cortex-m-rt's `device` feature (turned on by the `qemu` feature) makes its link.x
//! take `__INTERRUPTS` from here and include a `device.x`, which `build.rs` writes for
//! this board (empty: no handler names to provide).

/// Interrupt lines of the mps2-an386 in QEMU.
const LINES: usize = 48;

extern "C" {
    /// cortex-m-rt's default exception handler (its link.x provides the symbol).
    fn DefaultHandler();
}

/// The interrupt vectors, where cortex-m-rt's link.x places `.vector_table.interrupts`.
// SAFETY (the lint's concern with `no_mangle` and `link_section`): this is the one
// `__INTERRUPTS` in the image (cortex-m-rt defines none with `device`), an array of
// handler addresses as the vector table needs.
#[allow(unsafe_code)]
#[link_section = ".vector_table.interrupts"]
#[no_mangle]
static __INTERRUPTS: [unsafe extern "C" fn(); LINES] = [DefaultHandler; LINES];
