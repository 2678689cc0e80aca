//! Calls everything a capture firmware would (driver, ring buffers, trigger, both
//! estimators, the strike model) on values the optimiser cannot see, so nothing is
//! constant-folded away. Built, never run.
#![no_std]
#![no_main]

use core::ptr::{read_volatile, write_volatile};

use cuesight::strike::{Cue, TipOffset};
use cuesight::Params;
use cuesight_sensors::lsm6dsox::{ADDRESS_SA0_LOW, STANDARD_GRAVITY};
use cuesight_sensors::{
    accel_lsb_to_mps2, estimate_raw, estimate_raw_with_pitch, Axis, ImpactTrigger, Lsm6dsox,
    RingBuffer, StrokeConfig, ACCEL_MPS2_PER_LSB, GYRO_RADPS_PER_LSB,
};
use embedded_hal::i2c::{ErrorKind, ErrorType, I2c, Operation};

extern "C" {
    /// Deliberately undefined: referencing it fails the link.
    fn a_panic_path_is_reachable() -> !;
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never executed; the symbol does not exist, so a reachable call fails the link.
    unsafe { a_panic_path_is_reachable() }
}

/// A bus whose reads come from memory the optimiser cannot predict.
struct OpaqueBus;

impl ErrorType for OpaqueBus {
    type Error = ErrorKind;
}

impl I2c for OpaqueBus {
    fn transaction(&mut self, _address: u8, ops: &mut [Operation<'_>]) -> Result<(), ErrorKind> {
        for op in ops {
            if let Operation::Read(buf) = op {
                for byte in buf.iter_mut() {
                    // SAFETY: a link-only probe; the address is never dereferenced at run time.
                    *byte = unsafe { read_volatile(0x2000_0000 as *const u8) };
                }
            }
        }
        Ok(())
    }
}

#[no_mangle]
pub extern "C" fn _start() -> ! {
    let mut imu = Lsm6dsox::new(OpaqueBus, ADDRESS_SA0_LOW);
    let _ = imu.init();
    let mut accel = RingBuffer::<i16, 24_000>::new(0);
    let mut pitch = RingBuffer::<i16, 24_000>::new(0);
    let Ok(mut trigger) = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, 333) else {
        loop {}
    };
    loop {
        let a = imu.read_accel_axis_raw(Axis::X).unwrap_or(0);
        let g = imu.read_raw().map(|raw| raw.gyro[1]).unwrap_or(0);
        accel.push(a);
        pitch.push(g);
        if trigger.push(accel_lsb_to_mps2(a)) {
            break;
        }
    }
    let config = StrokeConfig::new(imu.odr_hz());
    let plain = estimate_raw(accel.make_contiguous(), ACCEL_MPS2_PER_LSB, &config);
    let pitch = pitch.make_contiguous();
    let accel = accel.make_contiguous();
    let aided = estimate_raw_with_pitch(
        accel,
        ACCEL_MPS2_PER_LSB,
        pitch,
        GYRO_RADPS_PER_LSB,
        &config,
    );
    let mut out = 0.0f32;
    for estimate in [plain, aided].into_iter().flatten() {
        if let Ok(hit) = estimate.strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE) {
            out += hit.speed + hit.spin.y;
        }
    }
    // SAFETY: as above.
    unsafe { write_volatile(0x2000_0004 as *mut f32, out) };
    loop {}
}
