//! The instruction-count regression gate of `cargo xtask test` (reliability issue: a
//! `KimGrip` regression of more than 5 % fails CI): counts the f32 `KimGrip` prediction
//! on fixed shots covering each of its branches with the bench's method
//! ([`cuesight_bench::count`]: function pointer, empty call subtracted, QEMU
//! `-icount shift=0`), and prints `kimgrip-count <milli-instructions per prediction,
//! mean over the shots>`. xtask compares it with `bench-firmware/kimgrip-baseline.txt`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::fmt::Write as _;

use cuesight::{Impact, Model, Params};
use cuesight_bench::count;
use cuesight_bench::exit;
use cuesight_bench::out::Out;
use cuesight_bench::timer::{self, INSTRUCTIONS_PER_TICK};

/// `(μ, v, ω)`: stun cut, follow, draw, side spin, near grip, exact gearing.
const SHOTS: [(f32, [f32; 2], [f32; 3]); 6] = [
    (0.05, [1.732, 1.0], [0.0, 0.0, 0.0]),
    (0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
    (0.05, [1.879, 0.684], [0.0, -70.0, 0.0]),
    (0.06, [0.9, 0.3], [0.0, 20.0, 40.0]),
    (0.1, [1.0, 0.2], [5.0, 0.5, -7.5]),
    (0.05, [0.866, 0.5], [0.0, 0.0, -17.497]),
];

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    let mut total_milli: u64 = 0;
    for (mu, v, w) in SHOTS {
        let (Ok(params), Ok(impact)) = (Params::POOL.with_mu(mu), Impact::from_velocity(v, w))
        else {
            exit::exit(false)
        };
        let c = count::count(cuesight::collide, &params, &impact, Model::KimGrip);
        let ticks = u64::from(c.ticks.saturating_sub(c.empty_ticks));
        total_milli += ticks * u64::from(INSTRUCTIONS_PER_TICK) * 1000 / u64::from(c.reps);
    }
    let _ = writeln!(out, "kimgrip-count {}", total_milli / SHOTS.len() as u64);
    out.flush();
    exit::exit(true)
}
