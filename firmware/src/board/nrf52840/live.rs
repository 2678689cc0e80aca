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

use core::sync::atomic::{compiler_fence, Ordering};
use cuesight_sensors::lsm6dsox::{Error as ImuError, Interface, SPI_READ};
use cuesight_sensors::Lsm6dsox;
use nrf52840_hal::gpio::{p1, Floating, Input, Level, Output, Pin, PushPull};
use nrf52840_hal::gpiote::Gpiote;
use nrf52840_hal::pac;

use nrf52840_hal::spim::{self, Frequency, Spim, MODE_3};
use nrf52840_hal::timer::{OneShot, Timer};
use static_cell::ConstStaticCell;

use super::{common, exit, start_cycle_counter, Serial};

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

/// The byte UARTE0's EasyDMA receives into (RAM, at a fixed place).
static RX: ConstStaticCell<[u8; 1]> = ConstStaticCell::new([0; 1]);

/// The live cue's peripherals.
pub struct Board {
    /// The link: UARTE0, shared by the link task and the reporting task.
    pub link: Link,
    /// The IMU's driver (not yet initialised).
    pub imu: Imu,
    /// GPIOTE, channel 0 raising its interrupt on INT1's rising edge.
    pub gpiote: Gpiote,
    /// TIMER1 at 1 MHz, one-shot, its compare interrupt enabled: the stall watchdog
    /// (every sample restarts it; it fires when no data-ready came for
    /// [`STALL_US`]).
    pub watchdog: Timer<pac::TIMER1, OneShot>,
}

/// How long without a data-ready before the part counts as stalled (µs): 10 ms, 66
/// sample periods at 6.66 kHz.
pub const STALL_US: u32 = 10_000;

/// Takes the peripherals, starts the HFXO and the cycle counter, sets up UARTE0, SPIM3,
/// GPIOTE channel 0 and TIMER1 (their interrupts enabled in the peripherals, not yet in
/// the NVIC: RTIC unmasks them after `init`; the watchdog not started); a second call
/// exits with failure.
pub fn init(core: &mut cortex_m::Peripherals) -> Board {
    let (p, uarte) = common();
    start_cycle_counter(&mut core.DCB, &mut core.DWT);
    let Some(rx) = RX.try_take() else {
        defmt::error!("board::init called twice");
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
    let mut watchdog = Timer::one_shot(p.timer1);
    watchdog.enable_interrupt();
    Board {
        watchdog,
        link: Link {
            serial: Serial::new(uarte),
            rx,
            receiving: false,
        },
        imu: Lsm6dsox::with_interface(ImuSpi { spim, chip_select }),
        gpiote,
    }
}

/// UARTE0 for the shared link: reads never block (EasyDMA receives one byte at a time
/// in the background, as nrf52840-hal's `UarteRx` does), writes do ([`Serial`]'s).
///
/// Not nrf52840-hal's `Uarte::split`: its halves index their buffers (slices of a
/// length unknown at compile time), and those bounds checks' panics bring `core::fmt`'s
/// integer formatting (about 0.9 KB) into an image that has no flash to spare.
pub struct Link {
    serial: Serial,
    rx: &'static mut [u8; 1],
    /// A one-byte reception has been started and not yet taken.
    receiving: bool,
}

impl Link {
    /// UARTE0's registers, for the receive side.
    fn registers() -> &'static pac::uarte0::RegisterBlock {
        // SAFETY: the link owns UARTE0 (inside `serial`), so nothing else uses these
        // registers; `Serial` touches only the transmit ones.
        #[allow(unsafe_code)]
        unsafe {
            &*pac::UARTE0::ptr()
        }
    }
}

impl crate::serve::SharedSerial for Link {
    /// The link task polls: UARTE0's interrupt is not taken, so `wfi` would not wake on
    /// a byte.
    const WAKES_ON_RECEIVE: bool = false;

    fn try_read(&mut self) -> Option<u8> {
        if !self.rx_waiting() {
            return None;
        }
        let uarte = Self::registers();
        uarte.events_endrx.reset();
        uarte.events_rxstarted.reset();
        // EasyDMA has written the byte: read it only after the event.
        compiler_fence(Ordering::SeqCst);
        self.receiving = false;
        (uarte.rxd.amount.read().bits() == 1).then_some(self.rx[0])
    }

    fn rx_waiting(&mut self) -> bool {
        let uarte = Self::registers();
        if !self.receiving {
            // The next one-byte reception: EasyDMA writes it into `rx`.
            compiler_fence(Ordering::SeqCst);
            let address = self.rx.as_mut_ptr() as u32;
            #[allow(unsafe_code)]
            // SAFETY: `rx` is a static byte in RAM, one long, as MAXCNT says.
            uarte.rxd.ptr.write(|w| unsafe { w.ptr().bits(address) });
            #[allow(unsafe_code)]
            // SAFETY: 1 fits the MAXCNT field.
            uarte.rxd.maxcnt.write(|w| unsafe { w.maxcnt().bits(1) });
            uarte.tasks_startrx.write(|w| w.tasks_startrx().set_bit());
            self.receiving = true;
            return false;
        }
        uarte.events_endrx.read().bits() != 0
    }

    fn write_all(&mut self, bytes: &[u8]) {
        // A transmit error loses the frame; the host's request times out and says so.
        let _ = embedded_io::Write::write_all(&mut self.serial, bytes);
    }
}
