//! cuesight on a Cortex-M4F: serves the device link of `cuesight-link` on the board's
//! serial port (postcard messages in COBS frames with a CRC: `version`, `collide`,
//! `params`, `stroke`, `shot` with the `shot` feature, a default one, `shutdown`; see
//! `docs/protocol.md`), logging with defmt.
//!
//! At boot it runs every model on a few built-in shots as a self-test (exit with
//! failure if any outcome is not finite and sane), then serves until a `shutdown`
//! request, after which it exits with success. Panics and faults exit with failure
//! (`exit.rs`). Boots under QEMU's `mps2-an386`: `cargo xtask run`.
//!
//! With the `live` feature (QEMU) the firmware is an RTIC 2 application (`app.rs`):
//! besides the link it samples the emulated IMU and reports each stroke (the live cue,
//! issue 15); with `nrf52840-live` the same on the nRF52840 with a real LSM6DSOX
//! (`app_nrf52840.rs`). Without either, it serves the link alone from `main`
//! (`blocking.rs`).
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

#[cfg(feature = "live")]
mod app;
#[cfg(feature = "nrf52840-live")]
mod app_nrf52840;
#[cfg(not(feature = "live-cue"))]
mod blocking;
