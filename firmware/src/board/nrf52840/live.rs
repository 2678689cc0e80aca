//! The nRF52840's live-cue peripherals (the `nrf52840-live` image): the LSM6DSOX on
//! SPIM3 with its data-ready on GPIOTE, and UARTE0 as a link the RTIC tasks share.
//!
//! | signal | nRF52840 | DK's Arduino header | LSM6DSOX |
//! |---|---|---|---|
//! | SPI clock | P1.15 | D13 | SCL/SPC |
//! | MOSI | P1.13 | D11 | SDA/SDI |
//! | MISO | P1.14 | D12 | SDO/SA0 |
//! | chip select | P1.12 | D10 | CS |
//! | data-ready | P1.03 | D2 | INT1 |
//!
//! (The header's pins as the DK's board description maps them: Zephyr's
//! `nrf52840dk_nrf52840.dts`, `arduino_header`.) SPIM3, the nRF52840's high-speed SPI
//! master, at 8 MHz in mode 3 (the part takes up to 10 MHz, modes 0 and 3): a
//! twelve-byte sample read is thirteen bytes on the wire, 13 µs, where 400 kHz I²C
//! would need ≈ 360 µs of a 150 µs sample period (`cuesight_sensors::lsm6dsox`, "Bus
//! budget"). The driver reads it blocking, in the sampling interrupt, through
//! [`ImuSpi`]: its register access as the HAL's one EasyDMA transaction per read
//! (`Spim::transfer_split_uneven`, chip select included), not an embedded-hal
//! `SpiDevice` (embedded-hal-bus's `ExclusiveDevice` walks a list of operations: 764 B
//! of flash for this image, where the flash budget has none to spare).

use cuesight_link::frame::MAX_FRAME;
use cuesight_sensors::lsm6dsox::{Error as ImuError, Interface, SPI_READ};
use cuesight_sensors::Lsm6dsox;
use nrf52840_hal::gpio::{p1, Floating, Input, Level, Output, Pin, PushPull};
use nrf52840_hal::gpiote::Gpiote;
use nrf52840_hal::pac;
use nrf52840_hal::spim::{self, Frequency, Spim, MODE_3};
use nrf52840_hal::uarte::{UarteRx, UarteTx};
use static_cell::ConstStaticCell;

use super::{common, exit, start_cycle_counter};

/// The driver on the part's SPI bus.
pub type Imu = Lsm6dsox<ImuSpi>;

/// The LSM6DSOX's registers over SPIM3 and its chip-select pin (the datasheet's SPI
/// framing, as `cuesight_sensors::lsm6dsox::SpiInterface` has it for an embedded-hal
/// `SpiDevice`).
pub struct ImuSpi {
    spim: Spim<pac::SPIM3>,
    chip_select: Pin<Output<PushPull>>,
}

/// The longest read the driver makes: the twelve output bytes.
const LONGEST_READ: usize = 12;

impl Interface for ImuSpi {
    type Error = spim::Error;

    fn write_register(&mut self, register: u8, value: u8) -> Result<(), ImuError<spim::Error>> {
        // On the stack: RAM, as EasyDMA needs.
        let command = [register & !SPI_READ, value];
        self.spim.write(&mut self.chip_select, &command)?;
        Ok(())
    }

    fn read_registers(&mut self, first: u8, buf: &mut [u8]) -> Result<(), ImuError<spim::Error>> {
        // The SPIM receives from the first clock on: the byte clocked during the
        // address is the first received, and dropped.
        let mut received = [0u8; 1 + LONGEST_READ];
        let Some(received) = received.get_mut(..=buf.len()) else {
            // Longer than any read the driver makes: not received.
            return Err(ImuError::Bus(spim::Error::Receive));
        };
        self.spim
            .transfer_split_uneven(&mut self.chip_select, &[first | SPI_READ], received)?;
        for (slot, byte) in buf.iter_mut().zip(received.iter().skip(1)) {
            *slot = *byte;
        }
        Ok(())
    }
}

/// Bytes UARTE0 sends per EasyDMA transfer (it reads RAM only, so frames are copied
/// through this buffer).
const TX_BUFFER: usize = 64;
static TX: ConstStaticCell<[u8; TX_BUFFER]> = ConstStaticCell::new([0; TX_BUFFER]);
static RX: ConstStaticCell<[u8; 1]> = ConstStaticCell::new([0; 1]);

// A frame fits the EasyDMA transfer counter many times over; nothing to check but that
// the link's largest frame is not empty.
const _: () = assert!(MAX_FRAME > TX_BUFFER);

/// The live cue's peripherals.
pub struct Board {
    /// The link: UARTE0, shared by the link task and the reporting task.
    pub link: Link,
    /// The IMU's driver (not yet initialised).
    pub imu: Imu,
    /// GPIOTE, channel 0 raising its interrupt on INT1's rising edge.
    pub gpiote: Gpiote,
}

/// Takes the peripherals, starts the HFXO and the cycle counter, sets up UARTE0, SPIM3
/// and GPIOTE channel 0 (its interrupt enabled in GPIOTE, not yet in the NVIC: RTIC
/// unmasks it after `init`); a second call exits with failure.
pub fn init(core: &mut cortex_m::Peripherals) -> Board {
    let (p, uarte) = common();
    start_cycle_counter(&mut core.DCB, &mut core.DWT);
    let (Some(tx), Some(rx)) = (TX.try_take(), RX.try_take()) else {
        defmt::error!("board::init called twice");
        exit(false);
    };
    let Ok((tx, rx)) = uarte.split(tx, rx) else {
        defmt::error!("UARTE0: the EasyDMA buffers were refused");
        exit(false);
    };
    let port1 = p1::Parts::new(p.p1);
    let pins = spim::Pins {
        sck: Some(port1.p1_15.into_push_pull_output(Level::High).degrade()),
        mosi: Some(port1.p1_13.into_push_pull_output(Level::Low).degrade()),
        miso: Some(port1.p1_14.into_floating_input().degrade()),
    };
    let spim = Spim::new(p.spim3, pins, Frequency::M8, MODE_3, 0);
    let chip_select = port1.p1_12.into_push_pull_output(Level::High).degrade();
    let int1: Pin<Input<Floating>> = port1.p1_03.into_floating_input().degrade();
    let gpiote = Gpiote::new(p.gpiote);
    gpiote
        .channel0()
        .input_pin(&int1)
        .lo_to_hi()
        .enable_interrupt();
    Board {
        link: Link { tx, rx },
        imu: Lsm6dsox::with_interface(ImuSpi { spim, chip_select }),
        gpiote,
    }
}

/// UARTE0 for the shared link: reads never block (EasyDMA receives one byte at a time
/// in the background), writes do.
pub struct Link {
    tx: UarteTx<pac::UARTE0>,
    rx: UarteRx<pac::UARTE0>,
}

impl crate::serve::SharedSerial for Link {
    /// The link task polls: UARTE0's interrupt is not taken (its receive event stays
    /// for `try_read`), so `wfi` would not wake on a byte.
    const WAKES_ON_RECEIVE: bool = false;

    fn try_read(&mut self) -> Option<u8> {
        if !self.rx_waiting() {
            return None;
        }
        let mut byte = [0u8; 1];
        match embedded_io_06::Read::read(&mut self.rx, &mut byte) {
            Ok(1) => Some(byte[0]),
            _ => None,
        }
    }

    fn rx_waiting(&mut self) -> bool {
        // Starts the next one-byte reception when none is under way.
        matches!(
            embedded_io_06::ReadReady::read_ready(&mut self.rx),
            Ok(true)
        )
    }

    fn write_all(&mut self, bytes: &[u8]) {
        // A transmit error loses the frame; the host's request times out and says so.
        let _ = embedded_io_06::Write::write_all(&mut self.tx, bytes);
        let _ = embedded_io_06::Write::flush(&mut self.tx);
    }
}
