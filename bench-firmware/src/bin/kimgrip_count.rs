//! The instruction-count gate of `cargo xtask test` (reliability issue: a `KimGrip`
//! regression of more than 5 % fails CI; issue 4: `KimGrip` f32 ≤ 150 instructions per
//! collision): counts the f32 `KimGrip` prediction on fixed shots, one for each branch
//! of its fast path plus three the general path takes, with the bench's method
//! ([`cuesight_bench::count`]: function pointer, empty call subtracted, QEMU
//! `-icount shift=0`). A branch has no loop, so its count does not depend on the
//! numbers: the largest fast-path count is the fast path's worst case.
//!
//! Prints `kimgrip-shot <label> <fast|general> <milli-instructions>` per shot, then
//! `kimgrip-fast-max <milli-instructions>` and `kimgrip-count <mean over the fast-path
//! shots>` (the general path's speed-dependent μ, ~3,000, would drown a fast-path
//! regression in the mean). xtask compares the mean with
//! `bench-firmware/kimgrip-baseline.txt` and the maximum with the 150. Which branch each shot takes is checked on the
//! host by `kim_grip::tests::gate_shots_take_their_branches` in the core.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::fmt::Write as _;

use cuesight::{FrictionLaw, Impact, Model, Params};
use cuesight_bench::count;
use cuesight_bench::exit;
use cuesight_bench::out::Out;
use cuesight_bench::timer::{self, INSTRUCTIONS_PER_TICK};

/// `(label, takes the fast path, μ (< 0: TP A.14's speed-dependent law), v, ω)`.
type Shot = (&'static str, bool, f32, [f32; 2], [f32; 3]);

/// The shots: `(label, takes the fast path, μ, v, ω)`, POOL parameters otherwise. Topspin
/// (`ω_y > 0`) presses the object ball into the cloth; "certain" grips are those where
/// the frictionless impulse `(1+e)a/2` already reaches the grip impulse `p*`, "band"
/// the one where only the table friction's extra normal impulse does.
const SHOTS: [Shot; 12] = [
    ("topspin-slides", true, 0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
    (
        "topspin-grips-restitution",
        true,
        0.05,
        [2.0, 0.3],
        [0.0, 7.0, 0.0],
    ),
    (
        "topspin-grips-compression",
        true,
        0.05,
        [2.0, 0.1],
        [0.0, 3.0, 0.0],
    ),
    (
        "topspin-band-grips",
        true,
        0.05,
        [2.0, 0.0],
        [0.0, 17.98, 0.0],
    ),
    ("stun-cut-slides", true, 0.05, [1.732, 1.0], [0.0, 0.0, 0.0]),
    (
        "draw-grips-restitution",
        true,
        0.05,
        [2.0, 0.3],
        [0.0, -7.0, 0.0],
    ),
    (
        "draw-grips-compression",
        true,
        0.05,
        [2.0, 0.1],
        [0.0, -3.0, 0.0],
    ),
    (
        "near-gearing",
        true,
        0.05,
        [0.866, 0.5],
        [0.0, 0.0, -17.497_813],
    ),
    // The general path: a speed-dependent μ, no friction, and slips below the fast
    // path's 1 pm/s (exact gearing).
    (
        "speed-dependent-mu",
        false,
        -1.0,
        [2.0, 0.3],
        [0.0, 30.0, 0.0],
    ),
    ("frictionless", false, 0.0, [1.0, 0.5], [0.0, 10.0, 0.0]),
    ("gearing-side", false, 0.05, [1.0, 1e-13], [0.0, 0.0, 0.0]),
    (
        "gearing-topspin",
        false,
        0.05,
        [1.0, 0.0],
        [0.0, 1e-12, 0.0],
    ),
];

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    let (mut fast_total_milli, mut fast_max_milli, mut fast_shots) = (0u64, 0u64, 0u64);
    for (label, fast, mu, v, w) in SHOTS {
        // μ < 0 stands for TP A.14's speed-dependent law (Marlow's data).
        let params = if mu < 0.0 {
            Ok(Params::POOL.with_friction_law(FrictionLaw::MARLOW))
        } else {
            Params::POOL.with_mu(mu)
        };
        let (Ok(params), Ok(impact)) = (params, Impact::from_velocity(v, w)) else {
            exit::exit(false)
        };
        let c = count::count(cuesight::collide, &params, &impact, Model::KimGrip);
        let ticks = u64::from(c.ticks.saturating_sub(c.empty_ticks));
        let milli = ticks * u64::from(INSTRUCTIONS_PER_TICK) * 1000 / u64::from(c.reps);
        let path = if fast { "fast" } else { "general" };
        let _ = writeln!(out, "kimgrip-shot {label} {path} {milli}");
        if fast {
            fast_total_milli += milli;
            fast_max_milli = fast_max_milli.max(milli);
            fast_shots += 1;
        }
    }
    let _ = writeln!(out, "kimgrip-fast-max {fast_max_milli}");
    let _ = writeln!(
        out,
        "kimgrip-count {}",
        fast_total_milli / fast_shots.max(1)
    );
    out.flush();
    exit::exit(true)
}
