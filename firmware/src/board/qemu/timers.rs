//! CMSDK APB timers (QEMU's `cmsdk-apb-timer`): 32-bit down-counters at the 25 MHz
//! peripheral clock. TIMER0 runs free from `u32::MAX` (the log's timestamps, and the
//! instruction counts of the live pipeline: under `-icount shift=0` one tick is 40
//! instructions); TIMER1 is the emulated IMU's data-ready, one interrupt per sample
//! period.
//!
//! Registers (Arm DDI0479C §4.4): `CTRL` 0x000 (bit 0 enable, 3 interrupt enable),
//! `VALUE` 0x004, `RELOAD` 0x008 (a write loads `VALUE` too), `INTSTATUS`/`INTCLEAR`
//! 0x00C (write 1 to clear). The counter interrupts when it reaches 0 and reloads.

use super::{read_at, write_at, PCLK_HZ};

const TIMER0: usize = 0x4000_0000;
const TIMER1: usize = 0x4000_1000;
const CTRL: usize = 0x000;
const VALUE: usize = 0x004;
const RELOAD: usize = 0x008;
const INTCLEAR: usize = 0x00C;
const CTRL_ENABLE: u32 = 1 << 0;
const CTRL_INT_ENABLE: u32 = 1 << 3;

/// Instructions per TIMER0 tick under `-icount shift=0` (1 ns per instruction, 40 ns
/// per tick; `bench-firmware` calibrates this).
pub const INSTRUCTIONS_PER_TICK: u32 = 40;

/// Waits `phase % 40` turns of a 3-instruction loop (`phase` = the sample count), so
/// that the next [`ticks`] readings fall at every phase of TIMER0's 40-instruction tick
/// in turn (3 and 40 are coprime): a task that starts at the same phase every period
/// would otherwise read every duration with the same rounding, up to 40 instructions
/// off, and the mean with it. Dithered, the rounding averages out of the mean.
#[inline(always)]
pub fn dither(phase: u32) {
    for _ in 0..phase % INSTRUCTIONS_PER_TICK {
        cortex_m::asm::nop();
    }
}

/// Starts TIMER0 counting down from `u32::MAX`, no interrupt.
pub(super) fn start_uptime() {
    write_at(TIMER0 + RELOAD, u32::MAX);
    write_at(TIMER0 + CTRL, CTRL_ENABLE);
}

/// TIMER0's ticks since [`start_uptime`] (wrapping after 172 s).
pub fn ticks() -> u32 {
    u32::MAX - read_at(TIMER0 + VALUE)
}

/// Microseconds since [`start_uptime`] (0 before).
pub fn uptime_us() -> u64 {
    if read_at(TIMER0 + CTRL) & CTRL_ENABLE == 0 {
        return 0;
    }
    super::super::clock::micros(ticks(), PCLK_HZ / 1_000_000)
}

/// Starts TIMER1 as the IMU's data-ready clock: an interrupt every `PCLK / rate_hz`
/// ticks (rounded; 3,750 at 6,667 Hz), from now.
///
/// QEMU's model (10.0) interrupts at every second expiry of the counter: with `RELOAD`
/// at 3,749 the interrupts came 7,500 TIMER0 ticks apart (measured over the 44,305
/// sample periods of `three-strokes-6667.csv`), so `RELOAD` is half a period. Real
/// CMSDK silicon would need the whole period here (Arm DDI0479C §4.4).
pub fn start_sampling(rate_hz: u32) {
    let period = (PCLK_HZ + rate_hz / 2) / rate_hz.max(1) / 2;
    write_at(TIMER1 + CTRL, 0);
    write_at(TIMER1 + RELOAD, period.saturating_sub(1).max(1));
    write_at(TIMER1 + CTRL, CTRL_ENABLE | CTRL_INT_ENABLE);
}

/// Stops TIMER1 (an interrupt already pending stays pending).
pub fn stop_sampling() {
    write_at(TIMER1 + CTRL, 0);
}

/// Whether TIMER1 runs.
pub fn sampling() -> bool {
    read_at(TIMER1 + CTRL) & CTRL_ENABLE != 0
}

/// Clears TIMER1's interrupt (its handler calls this).
pub fn acknowledge_sample() {
    write_at(TIMER1 + INTCLEAR, 1);
}
