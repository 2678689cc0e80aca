//! How the firmware ends: through semihosting, with a status QEMU turns into its own
//! exit code. Panics and faults end with failure, so a broken image cannot pass.
//!
//! Everything is logged with defmt only: the defmt frames share semihosting's stdout
//! with nothing else, so plain text must never be written there.

use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::debug;

/// Ends the program: QEMU exits with 0 for `success`, with 1 otherwise.
pub fn exit(success: bool) -> ! {
    debug::exit(if success {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    // Only reached without a semihosting host (a real board with no debugger).
    loop {
        cortex_m::asm::wfi();
    }
}

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

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(|| defmt::error!("panicked: {}", defmt::Display2Format(info)))
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
