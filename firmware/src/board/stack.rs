//! Peak stack use, by painting (any Cortex-M board; linked through flip-link, the stack
//! is `_stack_end.._stack_start` at the bottom of RAM): at boot every free stack word
//! below the current stack pointer is filled with a pattern; the deepest word no longer holding it marks the
//! deepest the stack has grown. The boards run no interrupt handlers, so nothing else
//! touches the region.

/// The paint: unlikely as data, and not a valid address or return address.
const PAINT: u32 = 0xA5A5_A5A5;
/// Words left unpainted just below the stack pointer, for the painting code itself.
const MARGIN: usize = 256;

extern "C" {
    /// Top of the stack (cortex-m-rt's `link.x`: the initial stack pointer).
    static _stack_start: u32;
    /// Bottom of the stack (cortex-m-rt's `link.x`: the end of `.uninit`).
    static _stack_end: u32;
}

/// `(bottom, top)` of the stack. Only the symbols' addresses are taken, which is safe.
fn bounds() -> (usize, usize) {
    (
        core::ptr::addr_of!(_stack_end) as usize,
        core::ptr::addr_of!(_stack_start) as usize,
    )
}

/// Paints the free stack (call once, early).
#[allow(unsafe_code)]
pub fn paint() {
    let (bottom, _) = bounds();
    let below_sp = (cortex_m::register::msp::read() as usize).saturating_sub(MARGIN) & !3;
    let mut addr = bottom;
    while addr < below_sp {
        // SAFETY: a word of RAM between the end of the static data and the stack
        // pointer: free stack, used by nothing yet.
        unsafe { core::ptr::write_volatile(addr as *mut u32, PAINT) };
        addr += 4;
    }
}

/// `(peak, size)`: the most stack used since [`paint`] and the stack's size, in bytes.
#[allow(unsafe_code)]
pub fn peak() -> (u32, u32) {
    let (bottom, top) = bounds();
    let mut addr = bottom;
    // SAFETY: reads of aligned RAM words inside the stack region.
    while addr < top && unsafe { core::ptr::read_volatile(addr as *const u32) } == PAINT {
        addr += 4;
    }
    ((top - addr) as u32, (top - bottom) as u32)
}
