//! Support for the cuesight bench firmware (`cargo xtask bench`): a virtual-time
//! timer, instruction counting with the loop overhead subtracted, the baked scene
//! set and sample stream, buffered plain-text output over semihosting, and the exits.
//!
//! Under QEMU with `-icount shift=0` the guest executes exactly one instruction per
//! nanosecond of virtual time, and the CMSDK timers of `mps2-an386` count that
//! virtual time at 25 MHz: one timer tick is 40 instructions. Counts are therefore
//! *instructions*, whatever the cycle cost of each instruction on silicon.
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod count;
pub mod exit;
pub mod out;
pub mod scenes;
#[cfg(feature = "stream")]
pub mod stream;
pub mod timer;
