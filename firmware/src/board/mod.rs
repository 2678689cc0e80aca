//! Board support: everything hardware-specific lives in one module per board, chosen
//! by a cargo feature (`qemu`, the default, or `nrf52840`). The rest of the firmware sees only this
//! interface:
//!
//! * `NAME: &str` — the board, as the `version` answer reports it;
//! * `init() -> Board` — takes the peripherals, sets up the clocks, the defmt logger
//!   and the serial port;
//! * `Board` — the peripherals: on `nrf52840`, `serial`, the protocol's byte stream
//!   (`embedded_io::Read + Write`, blocking); on `qemu`, `link` and `trace`, the
//!   UARTs the RTIC app (`app.rs`) serves the link on and takes the IMU trace from;
//! * `exit(success: bool) -> !` — ends the program (under QEMU: QEMU's exit code);
//! * `peak_stack() -> (u32, u32)` — the most stack used so far and the stack's size, in
//!   bytes (stack painting);
//! * `uptime_us() -> u64` — microseconds since `init` started the board's counter (the
//!   defmt log's timestamps; [`clock`]).
//!
//! Adding a board is a new module here, a feature in `Cargo.toml` and an arm below;
//! `serve.rs` and `main.rs` do not change. The boards:
//!
//! * `qemu` ([`qemu`]): QEMU's `mps2-an386`, CMSDK UART0, defmt over semihosting;
//! * `nrf52840` (`nrf52840/`): UARTE0 through `nrf52840-hal`, `defmt-rtt`, exit as a
//!   breakpoint for probe-rs (`--no-default-features --features nrf52840`).
//!
//! Stack painting (`stack.rs`) is plain Cortex-M, shared by both.

mod clock;
mod stack;

#[cfg(feature = "qemu")]
mod qemu;
#[cfg(feature = "qemu")]
pub use qemu::{exit, init, pac, peak_stack, timers, trace_file, uart, uptime_us, Board, NAME};

#[cfg(feature = "nrf52840-board")]
mod nrf52840;
#[cfg(feature = "nrf52840-board")]
pub use nrf52840::{exit, init, peak_stack, uptime_us, Board, CORE_MHZ, NAME};
#[cfg(feature = "nrf52840-live")]
pub use nrf52840::{Imu, Link, STALL_US};

#[cfg(not(any(feature = "qemu", feature = "nrf52840-board")))]
compile_error!("select a board with a cargo feature: `qemu` (the default) or `nrf52840`");

#[cfg(all(feature = "qemu", feature = "nrf52840-board"))]
compile_error!("select one board: `qemu` is the default, so build `nrf52840` with `--no-default-features --features nrf52840`");
