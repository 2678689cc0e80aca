//! cuesight's firmware as a library: the board support, the serial loop, the boot
//! self-test and the fault handlers, shared by the firmware binary (`main.rs`) and the
//! on-target tests (`tests/on_target.rs`, defmt-test under QEMU).
//!
//! Linking this crate brings the panic and fault handlers (`exit`), the defmt global
//! logger (the board's) and the log's timestamp (microseconds since boot).
#![no_std]
#![deny(unsafe_code)]
#![deny(missing_docs)]

pub mod board;
mod exit;
pub mod live;
pub mod mem;
pub mod serve;
pub mod shots;

defmt::timestamp!("{=u64:us}", board::uptime_us());
