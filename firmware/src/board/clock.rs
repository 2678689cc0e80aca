//! Uptime for the defmt log's timestamps: a free-running 32-bit hardware counter
//! (the board's: `qemu` CMSDK TIMER0 at the 25 MHz peripheral clock, `nrf52840` the
//! DWT cycle counter at 64 MHz) turned into microseconds since it started.
//!
//! Each reading adds the ticks since the previous one (a 32-bit wrapping difference),
//! converted with 32-bit divisions (the Cortex-M4's `udiv`; a 64-bit division would
//! pull in a software routine) and the remainder carried, so the count is exact. That
//! holds while readings come less than one counter period apart (171 s at 25 MHz, 67 s
//! at 64 MHz): a log that stays silent longer loses whole periods. Readings happen
//! inside defmt's critical section (the logger's `acquire`), so the words are updated
//! together.

use core::sync::atomic::{AtomicU32, Ordering::Relaxed};

/// The counter at the last reading (ticks since it started).
static LAST: AtomicU32 = AtomicU32::new(0);
/// Ticks read but not yet counted as a whole microsecond.
static CARRY: AtomicU32 = AtomicU32::new(0);
/// Microseconds counted so far, low and high words.
static MICROS_LOW: AtomicU32 = AtomicU32::new(0);
static MICROS_HIGH: AtomicU32 = AtomicU32::new(0);

/// Microseconds since the counter started, `elapsed` ticks at `ticks_per_us` (MHz,
/// at least 1) read now.
pub fn micros(elapsed: u32, ticks_per_us: u32) -> u64 {
    let ticks_per_us = ticks_per_us.max(1);
    let delta = elapsed.wrapping_sub(LAST.swap(elapsed, Relaxed));
    let carry = CARRY.load(Relaxed) + delta % ticks_per_us; // < 2 ticks_per_us
    CARRY.store(carry % ticks_per_us, Relaxed);
    let added = u64::from(delta / ticks_per_us + carry / ticks_per_us);
    let total = (u64::from(MICROS_HIGH.load(Relaxed)) << 32 | u64::from(MICROS_LOW.load(Relaxed)))
        .wrapping_add(added);
    MICROS_LOW.store(total as u32, Relaxed);
    MICROS_HIGH.store((total >> 32) as u32, Relaxed);
    total
}
