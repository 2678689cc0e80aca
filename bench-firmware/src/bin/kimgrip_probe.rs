//! The smallest image that runs `cuesight::collide(.., Model::KimGrip)` in f32, for the
//! disassembly check of `cargo xtask test`: starting from [`cuesight_kimgrip_f32`],
//! the code it can reach must call no software double-precision routine and must
//! contain the FPU's `vsqrt.f32`.
//!
//! It also runs under QEMU: the shots below cover every branch of `KimGrip` (sliding
//! with the object ball pressed or not, gripping, exact gearing, frictionless) and the
//! image exits with failure if an outcome is not finite.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::hint::black_box;

use cuesight::{Impact, Model, Outcome, Params, Result};
use cuesight_bench::exit;

/// The f32 `KimGrip` hot path, as a firmware calls it. The root of the check.
// An unmangled name the check can find; nothing else defines it.
#[allow(unsafe_code)]
#[no_mangle]
#[inline(never)]
pub fn cuesight_kimgrip_f32(params: &Params, impact: &Impact) -> Result<Outcome> {
    cuesight::collide(params, impact, Model::KimGrip)
}

/// `(μ, v, ω)`: stun cut, follow, draw, side spin, near grip, exact gearing, no friction.
const SHOTS: [(f32, [f32; 2], [f32; 3]); 7] = [
    (0.05, [1.732, 1.0], [0.0, 0.0, 0.0]),
    (0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
    (0.05, [1.879, 0.684], [0.0, -70.0, 0.0]),
    (0.06, [0.9, 0.3], [0.0, 20.0, 40.0]),
    (0.1, [1.0, 0.2], [5.0, 0.5, -7.5]),
    (0.05, [0.866, 0.5], [0.0, 0.0, -17.497]),
    (0.0, [1.0, 0.5], [0.0, 10.0, 0.0]),
];

#[cortex_m_rt::entry]
fn main() -> ! {
    let mut ok = true;
    for (mu, v, w) in SHOTS {
        let (Ok(params), Ok(impact)) = (Params::POOL.with_mu(mu), Impact::from_velocity(v, w))
        else {
            exit::exit(false)
        };
        let predict: fn(&Params, &Impact) -> Result<Outcome> = black_box(cuesight_kimgrip_f32);
        ok &= predict(&params, &impact).is_ok();
    }
    exit::exit(ok)
}
