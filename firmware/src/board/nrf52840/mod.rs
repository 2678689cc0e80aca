//! Nordic nRF52840 (Cortex-M4F at 64 MHz; e.g. the nRF52840-DK), through
//! `nrf52840-hal`. Built by `cargo xtask test`, not run there (no hardware); flashed
//! and run with probe-rs (see the README):
//!
//! ```sh
//! cd firmware
//! cargo build --release --no-default-features --features nrf52840
//! probe-rs run --chip nRF52840_xxAA target/thumbv7em-none-eabihf/release/cuesight-firmware
//! ```
//!
//! * **Serial:** UARTE0 at 115,200 baud 8N1, TXD on P0.06 and RXD on P0.08 — the
//!   nRF52840-DK's interface-MCU virtual COM port (the USB serial port of the DK). The
//!   HFXO is started first, so the baud rate is crystal-accurate.
//! * **Log:** defmt over RTT (`defmt-rtt`), which `probe-rs run` decodes; the protocol
//!   owns the UART alone.
//! * **Exit:** a breakpoint (`bkpt`), where `probe-rs run` stops and reports; without a
//!   debugger attached the core then sleeps.
//! * **Stack:** painted at boot, so [`peak_stack`] can tell how deep it went.

use defmt_rtt as _;
use nrf52840_hal::clocks::Clocks;
use nrf52840_hal::gpio::{p0, Level};
use nrf52840_hal::pac;
use nrf52840_hal::uarte::{self, Baudrate, Parity, Uarte};

use super::stack;
pub use stack::peak as peak_stack;

/// The board, as reported by `version`.
pub const NAME: &str = "nrf52840";

/// The board's peripherals, as the firmware uses them.
/// Core clock (MHz): the DWT cycle counter's rate.
const CORE_MHZ: u32 = 64;

/// Microseconds since [`init`] started the DWT cycle counter (0 before).
pub fn uptime_us() -> u64 {
    super::clock::micros(cortex_m::peripheral::DWT::cycle_count(), CORE_MHZ)
}

pub struct Board {
    /// The protocol's serial port.
    pub serial: Serial,
}

/// Takes the peripherals, starts the HFXO and sets up UARTE0; a second call exits with
/// failure.
pub fn init() -> Board {
    stack::paint();
    let Some(p) = pac::Peripherals::take() else {
        defmt::error!("board::init called twice");
        exit(false);
    };
    // The clocks stay configured for the life of the program.
    let _clocks = Clocks::new(p.CLOCK).enable_ext_hfosc();
    // The log's timestamps: the DWT cycle counter (64 MHz core clock).
    if let Some(mut core) = cortex_m::Peripherals::take() {
        core.DCB.enable_trace();
        core.DWT.enable_cycle_counter();
    }
    let port0 = p0::Parts::new(p.P0);
    let pins = uarte::Pins {
        txd: port0.p0_06.into_push_pull_output(Level::High).degrade(),
        rxd: port0.p0_08.into_floating_input().degrade(),
        cts: None,
        rts: None,
    };
    let uarte = Uarte::new(p.UARTE0, pins, Parity::EXCLUDED, Baudrate::BAUD115200);
    Board {
        serial: Serial {
            uarte,
            tx: [0; TX_CHUNK],
        },
    }
}

/// Bytes per UARTE transmission: EasyDMA reads only RAM, so every write is copied
/// through this buffer first (the caller's bytes may be in flash).
const TX_CHUNK: usize = 64;

/// UARTE0, blocking, as `embedded_io::Read + Write`.
pub struct Serial {
    uarte: Uarte<pac::UARTE0>,
    tx: [u8; TX_CHUNK],
}

/// A UARTE error (framing, overrun, a buffer EasyDMA refused).
#[derive(Debug)]
pub struct SerialError(pub uarte::Error);

impl core::fmt::Display for SerialError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "UARTE0: {:?}", self.0)
    }
}

impl core::error::Error for SerialError {}

impl embedded_io::Error for SerialError {
    fn kind(&self) -> embedded_io::ErrorKind {
        embedded_io::ErrorKind::Other
    }
}

impl embedded_io::ErrorType for Serial {
    type Error = SerialError;
}

impl embedded_io::Read for Serial {
    /// Blocks for exactly one byte (an EasyDMA receive completes only when its buffer
    /// is full, so reading more would wait for bytes that may never come).
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, SerialError> {
        let Some(first) = buf.first_mut() else {
            return Ok(0);
        };
        let mut byte = [0u8; 1]; // on the stack: RAM, as EasyDMA needs
        self.uarte.read(&mut byte).map_err(SerialError)?;
        *first = byte[0];
        Ok(1)
    }
}

impl embedded_io::Write for Serial {
    fn write(&mut self, buf: &[u8]) -> Result<usize, SerialError> {
        let Some(chunk) = buf.get(..buf.len().min(TX_CHUNK)) else {
            return Ok(0);
        };
        if chunk.is_empty() {
            return Ok(0);
        }
        let Some(tx) = self.tx.get_mut(..chunk.len()) else {
            return Ok(0);
        };
        tx.copy_from_slice(chunk);
        self.uarte.write(tx).map_err(SerialError)?;
        Ok(chunk.len())
    }

    fn flush(&mut self) -> Result<(), SerialError> {
        // `Uarte::write` returns once the transmission has ended.
        Ok(())
    }
}

/// Ends the program: a breakpoint for the debugger (`probe-rs run` stops there; the
/// defmt log says whether it was a success), then sleep.
pub fn exit(success: bool) -> ! {
    if success {
        defmt::info!("exit: success");
    } else {
        defmt::error!("exit: failure");
    }
    cortex_m::asm::bkpt();
    loop {
        cortex_m::asm::wfi();
    }
}
