//! The two buses the LSM6DSOX speaks (datasheet §6, "Digital interfaces"): I²C with a
//! 7-bit address, and 4-wire SPI. The driver ([`super::Lsm6dsox`]) needs two register
//! operations of either: write one register, read a run of registers (auto-increment,
//! `CTRL3_C.IF_INC`).

use embedded_hal::i2c::I2c;
use embedded_hal::spi::{Operation, SpiDevice};

use super::{Error, ADDRESS_SA0_HIGH, ADDRESS_SA0_LOW};

/// SPI: the read/write bit of the address byte (1 = read; datasheet §6.2): a read
/// sends `SPI_READ | address`, a write `address` with it clear.
pub const SPI_READ: u8 = 0x80;

/// A bus to the part's registers.
pub trait Interface {
    /// The bus's own error.
    type Error;
    /// Writes `value` into `register`.
    fn write_register(&mut self, register: u8, value: u8) -> Result<(), Error<Self::Error>>;
    /// Reads `buf.len()` registers from `first` on, in one transaction.
    fn read_registers(&mut self, first: u8, buf: &mut [u8]) -> Result<(), Error<Self::Error>>;
}

/// The part on an I²C bus at `address`.
#[derive(Debug)]
pub struct I2cInterface<I> {
    i2c: I,
    address: u8,
}

impl<I> I2cInterface<I> {
    /// The bus and the part's 7-bit address (checked at each use, before any traffic).
    pub fn new(i2c: I, address: u8) -> Self {
        Self { i2c, address }
    }

    /// Gives the bus back.
    pub fn release(self) -> I {
        self.i2c
    }

    /// The address, if the part can answer on it.
    fn checked_address<E>(&self) -> Result<u8, Error<E>> {
        match self.address {
            ADDRESS_SA0_LOW | ADDRESS_SA0_HIGH => Ok(self.address),
            other => Err(Error::InvalidAddress(other)),
        }
    }
}

impl<I: I2c> Interface for I2cInterface<I> {
    type Error = I::Error;

    #[inline(always)]
    fn write_register(&mut self, register: u8, value: u8) -> Result<(), Error<I::Error>> {
        let address = self.checked_address()?;
        self.i2c.write(address, &[register, value])?;
        Ok(())
    }

    #[inline(always)]
    fn read_registers(&mut self, first: u8, buf: &mut [u8]) -> Result<(), Error<I::Error>> {
        let address = self.checked_address()?;
        self.i2c.write_read(address, &[first], buf)?;
        Ok(())
    }
}

/// The part on an SPI bus (its chip select in the [`SpiDevice`]).
#[derive(Debug)]
pub struct SpiInterface<S> {
    spi: S,
}

impl<S> SpiInterface<S> {
    /// The device.
    pub fn new(spi: S) -> Self {
        Self { spi }
    }

    /// Gives the device back.
    pub fn release(self) -> S {
        self.spi
    }
}

impl<S: SpiDevice> Interface for SpiInterface<S> {
    type Error = S::Error;

    fn write_register(&mut self, register: u8, value: u8) -> Result<(), Error<S::Error>> {
        self.spi.write(&[register & !SPI_READ, value])?;
        Ok(())
    }

    fn read_registers(&mut self, first: u8, buf: &mut [u8]) -> Result<(), Error<S::Error>> {
        self.spi
            .transaction(&mut [Operation::Write(&[first | SPI_READ]), Operation::Read(buf)])?;
        Ok(())
    }
}
