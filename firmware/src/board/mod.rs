//! Board support: everything hardware-specific lives in one module per board, chosen
//! by a cargo feature (`qemu`, the default). The rest of the firmware sees only this
//! interface:
//!
//! * `NAME: &str` — the board, as the `version` answer reports it;
//! * `init() -> Board` — takes the peripherals, sets up the clocks, the defmt logger
//!   and the serial port;
//! * `Board::serial` — the protocol's byte stream: a type implementing
//!   `embedded_io::Read + Write` (blocking; `read` returns at least one byte);
//! * `exit(success: bool) -> !` — ends the program (under QEMU: QEMU's exit code);
//! * `peak_stack() -> (u32, u32)` — the most stack used so far and the stack's size, in
//!   bytes (stack painting).
//!
//! Adding a board (e.g. `nrf52840`: UARTE0 through its HAL's `embedded_io` impl,
//! `defmt-rtt` for the log, `exit` as a breakpoint or reset) is a new file here, a
//! feature in `Cargo.toml` and an arm below; `serve.rs` and `main.rs` do not change.

#[cfg(feature = "qemu")]
mod qemu;
#[cfg(feature = "qemu")]
pub use qemu::{exit, init, peak_stack, NAME};

#[cfg(not(any(feature = "qemu")))]
compile_error!("select a board with a cargo feature: `qemu` (the default)");
