//! The I²C side of the model: transactions, the register pointer, and the side effects
//! of each register access (module docs of [`super`]).

use core::fmt;

use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, NoAcknowledgeSource, Operation};

use super::registers as r;
use super::EmulatedLsm6dsox;

/// Why a transaction on the model failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BusError {
    /// Nothing acknowledged this 7-bit address: it is not the one `SA0` selects.
    AddressNack(u8),
    /// Failing-bus mode ([`EmulatedLsm6dsox::set_bus_failing`]): the transaction failed.
    BusFault,
}

impl embedded_hal::i2c::Error for BusError {
    fn kind(&self) -> ErrorKind {
        match self {
            BusError::AddressNack(_) => ErrorKind::NoAcknowledge(NoAcknowledgeSource::Address),
            BusError::BusFault => ErrorKind::Bus,
        }
    }
}

impl fmt::Display for BusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BusError::AddressNack(a) => write!(f, "no acknowledge for I2C address 0x{a:02X}"),
            BusError::BusFault => f.write_str("I2C bus error (emulated failing bus)"),
        }
    }
}

impl core::error::Error for BusError {}

impl ErrorType for EmulatedLsm6dsox {
    type Error = BusError;
}

impl I2c for EmulatedLsm6dsox {
    fn transaction(
        &mut self,
        address: u8,
        operations: &mut [Operation<'_>],
    ) -> Result<(), Self::Error> {
        if self.bus_failing {
            return Err(BusError::BusFault);
        }
        if address != self.address {
            return Err(BusError::AddressNack(address));
        }
        // Adjacent operations of one kind are one transfer (embedded-hal's contract); a
        // write after a START or a repeated START begins with the register address.
        let mut writing = false;
        let mut register_next = false;
        for operation in operations.iter_mut() {
            match operation {
                Operation::Write(bytes) => {
                    if !writing {
                        register_next = true;
                        writing = true;
                    }
                    for &byte in bytes.iter() {
                        if register_next {
                            self.pointer = byte;
                            register_next = false;
                        } else {
                            self.write_register(self.pointer, byte);
                            self.advance();
                        }
                    }
                }
                Operation::Read(buffer) => {
                    writing = false;
                    for byte in buffer.iter_mut() {
                        *byte = self.read_register(self.pointer);
                        self.advance();
                    }
                }
            }
        }
        Ok(())
    }
}

impl EmulatedLsm6dsox {
    /// The pointer after a byte: on by one with `IF_INC`, else where it was.
    fn advance(&mut self) {
        if self.ctrl3_c & r::IF_INC != 0 {
            self.pointer = self.pointer.wrapping_add(1);
        }
    }

    fn read_register(&mut self, register: u8) -> u8 {
        match register {
            r::CTRL3_C => {
                let value = self.peek(register);
                self.reset_left = self.reset_left.saturating_sub(1);
                value
            }
            r::INT1_CTRL
            | r::WHO_AM_I
            | r::CTRL1_XL
            | r::CTRL2_G
            | r::CTRL9_XL
            | r::STATUS_REG
            | r::INTERNAL_FREQ_FINE => self.peek(register),
            _ => match r::out_byte(register) {
                Some(o) => {
                    let value = self.out[o.offset];
                    if o.high {
                        // Data-ready cleared by a high byte of the sensor; a BDU hold
                        // ends with the high byte of the word that began it.
                        self.status &= !Self::flag(o.sensor);
                        if self.hold[o.sensor] == Some(o.word) {
                            self.release(o.sensor);
                        }
                    } else if self.ctrl3_c & r::BDU != 0 {
                        self.hold[o.sensor] = Some(o.word);
                    }
                    value
                }
                None => {
                    self.unmodelled_reads = self.unmodelled_reads.wrapping_add(1);
                    0
                }
            },
        }
    }

    fn write_register(&mut self, register: u8, value: u8) {
        match register {
            r::INT1_CTRL => self.int1_ctrl = value,
            r::CTRL1_XL => self.ctrl1_xl = value,
            r::CTRL2_G => self.ctrl2_g = value,
            r::CTRL9_XL => self.ctrl9_xl = value,
            r::CTRL3_C if value & r::SW_RESET != 0 => self.software_reset(),
            r::CTRL3_C => {
                self.ctrl3_c = value & !(r::SW_RESET | r::BOOT);
                if value & r::BDU == 0 {
                    self.release(0);
                    self.release(1);
                }
            }
            _ => self.ignored_writes = self.ignored_writes.wrapping_add(1),
        }
    }
}
