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
//! * **IMU** (the `nrf52840-live` image, [`live`]): an LSM6DSOX on SPIM3 at 8 MHz, mode
//!   3 (SCK P1.15, MOSI P1.13, MISO P1.14, CS P1.12: the DK's Arduino header D13, D11,
//!   D12, D10), its INT1 data-ready on P1.03 (D2) through GPIOTE channel 0.

use defmt_rtt as _;
use nrf52840_hal::clocks::Clocks;
use nrf52840_hal::gpio::{p0, Level};
use nrf52840_hal::pac;
use nrf52840_hal::uarte::{self, Baudrate, Parity, Uarte};

use super::stack;
pub use stack::peak as peak_stack;

#[cfg(feature = "live-cue")]
mod live;
mod serial;
#[cfg(feature = "live-cue")]
pub use live::{init, Board, Imu, Link, STALL_US};
pub use serial::Serial;

/// The board, as reported by `version`.
pub const NAME: &str = "nrf52840";

/// Core clock (MHz): the DWT cycle counter's rate.
pub const CORE_MHZ: u32 = 64;

/// Microseconds since [`init`] started the DWT cycle counter (0 before).
pub fn uptime_us() -> u64 {
    super::clock::micros(cortex_m::peripheral::DWT::cycle_count(), CORE_MHZ)
}

/// The board's peripherals, as the firmware uses them: the link's serial port.
#[cfg(not(feature = "live-cue"))]
pub struct Board {
    /// The protocol's serial port.
    pub serial: Serial,
}

/// Takes the peripherals, starts the HFXO and sets up UARTE0; a second call exits with
/// failure.
#[cfg(not(feature = "live-cue"))]
pub fn init() -> Board {
    // The live cue's peripherals stay unused in this image.
    let (_, uarte) = common();
    if let Some(mut core) = cortex_m::Peripherals::take() {
        start_cycle_counter(&mut core.DCB, &mut core.DWT);
    }
    Board {
        serial: Serial::new(uarte),
    }
}

/// The log's timestamps and the live cue's latency: the DWT cycle counter (64 MHz core
/// clock).
pub fn start_cycle_counter(
    dcb: &mut cortex_m::peripheral::DCB,
    dwt: &mut cortex_m::peripheral::DWT,
) {
    dcb.enable_trace();
    dwt.enable_cycle_counter();
}

/// Paints the stack, takes the peripherals, starts the HFXO and sets up UARTE0
/// (115,200 baud, TXD P0.06, RXD P0.08); a second call exits with failure. Returns
/// the peripherals not used here.
fn common() -> (Peripherals, Uarte<pac::UARTE0>) {
    stack::paint();
    let Some(p) = pac::Peripherals::take() else {
        defmt::error!("board::init called twice");
        exit(false);
    };
    // The clocks stay configured for the life of the program.
    let _clocks = Clocks::new(p.CLOCK).enable_ext_hfosc();
    let port0 = p0::Parts::new(p.P0);
    let pins = uarte::Pins {
        txd: port0.p0_06.into_push_pull_output(Level::High).degrade(),
        rxd: port0.p0_08.into_floating_input().degrade(),
        cts: None,
        rts: None,
    };
    let uarte = Uarte::new(p.UARTE0, pins, Parity::EXCLUDED, Baudrate::BAUD115200);
    (
        Peripherals {
            p1: p.P1,
            spim3: p.SPIM3,
            gpiote: p.GPIOTE,
            timer1: p.TIMER1,
        },
        uarte,
    )
}

/// The peripherals `init` leaves to the live cue.
#[allow(dead_code)] // without the live cue
struct Peripherals {
    p1: pac::P1,
    spim3: pac::SPIM3,
    gpiote: pac::GPIOTE,
    timer1: pac::TIMER1,
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
