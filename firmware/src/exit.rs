//! Panics and faults end the program with failure ([`crate::board::exit`]), so a broken image
//! cannot pass: under QEMU the exit code is non-zero.
//!
//! Everything is logged with defmt only: under QEMU the defmt frames share the
//! semihosting console with nothing else, so plain text must never be written there.

use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_rt::{exception, ExceptionFrame};

use crate::board::exit;

/// Set once a panic (or fault) is being reported; a second one exits at once, so a
/// failure inside the logger cannot recurse.
static FAILING: AtomicBool = AtomicBool::new(false);

/// Logs once, then exits with failure.
fn fail(report: impl FnOnce()) -> ! {
    if !FAILING.swap(true, Ordering::Relaxed) {
        report();
    }
    exit(false)
}

/// Logs the panic's place and, when it is a literal, its message: a formatted message
/// is not rendered, which keeps `core::fmt` (about 2 KB of flash) out of the images
/// that can panic (the nRF52840's: its HAL keeps panic paths; the QEMU images have none,
/// `panic-never`).
#[cfg(not(feature = "panic-never"))]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(|| {
        let message = info
            .message()
            .as_str()
            .unwrap_or("(formatted; see the source line)");
        match info.location() {
            Some(at) => defmt::error!(
                "panicked at {=str}:{=u32}: {=str}",
                at.file(),
                at.line(),
                message
            ),
            None => defmt::error!("panicked: {=str}", message),
        }
    })
}

#[exception]
#[allow(unsafe_code)] // cortex-m-rt requires the HardFault handler to be `unsafe fn`
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    let pc = frame.pc();
    fail(|| defmt::error!("HardFault at pc {=u32:#010x}", pc))
}

#[exception]
#[allow(unsafe_code)] // same signature requirement as HardFault
unsafe fn DefaultHandler(irqn: i16) {
    fail(|| defmt::error!("unexpected exception or interrupt {=i16}", irqn))
}

#[cfg(feature = "panic-never")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "Rust" {
        /// Defined nowhere: referencing it makes the link fail while any panic path
        /// is still reachable (`--features panic-never`).
        #[link_name = "\n\nerror: the firmware image still has a reachable panic path (see the callers of this symbol above)\n\n"]
        fn panic_path_reachable() -> !;
    }
    #[allow(unsafe_code)]
    // SAFETY: never runs: the link fails unless every call of this handler has been
    // optimised away.
    unsafe {
        panic_path_reachable()
    }
}
