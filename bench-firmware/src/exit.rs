//! How the bench ends: through semihosting, with a status QEMU turns into its exit
//! code. A panic or a fault prints one line on the host's stderr and exits with failure.

use core::fmt::Write as _;
use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hio};

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

/// Prints `message` on the host's stderr and exits with failure.
pub fn fail(message: core::fmt::Arguments) -> ! {
    static FAILING: AtomicBool = AtomicBool::new(false);
    if !FAILING.swap(true, Ordering::Relaxed) {
        if let Ok(mut err) = hio::hstderr() {
            let _ = writeln!(err, "bench firmware: {message}");
        }
    }
    exit(false)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    fail(format_args!("panicked: {info}"))
}

#[exception]
#[allow(unsafe_code)] // cortex-m-rt requires the HardFault handler to be `unsafe fn`
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    fail(format_args!("HardFault at pc {:#010x}", frame.pc()))
}

#[exception]
#[allow(unsafe_code)] // same signature requirement as HardFault
unsafe fn DefaultHandler(irqn: i16) {
    fail(format_args!("unexpected exception or interrupt {irqn}"))
}
