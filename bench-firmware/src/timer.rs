//! Virtual time from the CMSDK APB timer 0 of QEMU's `mps2-an386`.
//!
//! The timer is a 32-bit down-counter clocked by the 25 MHz system clock, which QEMU
//! derives from its virtual clock; with `-icount shift=0` that clock advances one
//! nanosecond per guest instruction, so one tick is [`INSTRUCTIONS_PER_TICK`]
//! instructions. The counter wraps after 2³² ticks (172 s of virtual time), far more
//! than one measurement.

use core::ptr;

/// Base address of CMSDK APB timer 0 on `mps2-an386` (AN386 memory map).
const TIMER0: usize = 0x4000_0000;
const CTRL: usize = TIMER0;
const VALUE: usize = TIMER0 + 0x04;
const RELOAD: usize = TIMER0 + 0x08;

/// Instructions per timer tick under `-icount shift=0`: 1 ns per instruction, 40 ns
/// per tick of the 25 MHz clock. The calibration blocks check this.
pub const INSTRUCTIONS_PER_TICK: u32 = 40;

/// Starts the timer counting down from `u32::MAX`, without interrupts.
#[allow(unsafe_code)]
pub fn start() {
    // SAFETY: TIMER0 is a device register block on mps2-an386 that nothing else in
    // this program touches; volatile word accesses are its documented interface.
    unsafe {
        ptr::write_volatile(CTRL as *mut u32, 0);
        ptr::write_volatile(RELOAD as *mut u32, u32::MAX);
        ptr::write_volatile(VALUE as *mut u32, u32::MAX);
        ptr::write_volatile(CTRL as *mut u32, 1); // enable; no interrupt, internal clock
    }
}

/// Current counter value (counts down).
#[inline(always)]
#[allow(unsafe_code)]
pub fn now() -> u32 {
    // SAFETY: as in `start`; a read has no side effect on this register.
    unsafe { ptr::read_volatile(VALUE as *const u32) }
}

/// Ticks elapsed from `earlier` to `later` (two [`now`] readings).
#[inline(always)]
pub fn elapsed(earlier: u32, later: u32) -> u32 {
    earlier.wrapping_sub(later)
}
