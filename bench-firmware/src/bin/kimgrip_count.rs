//! The instruction-count gate of `cargo xtask test` (reliability issue: a `KimGrip`
//! regression of more than 5 % fails CI; issue 4: `KimGrip` f32 ≤ 150 instructions per
//! collision): counts the f32 `KimGrip` prediction on fixed shots, one for each branch
//! of its constant-μ fast path, one for each branch of its speed-dependent μ(v) fast path
//! (issue 16 item 6: ≤ 200), plus seven the general path takes (three on a cloth of large
//! friction, whose slide it follows in pieces), with the bench's method
//! ([`cuesight_bench::count`]: function pointer, empty call subtracted, QEMU
//! `-icount shift=0`). A branch has no loop, so its count does not depend on the
//! numbers: the largest fast-path count is the fast path's worst case.
//!
//! Prints `kimgrip-shot <label> <fast|speed|general> <milli-instructions>` per shot, then
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

/// `(label, the path that takes it, μ (< 0: TP A.14's speed-dependent law), v, ω)`.
type Shot = (&'static str, Path, f32, [f32; 2], [f32; 3]);

/// Which path of `KimGrip` a shot takes.
#[derive(Clone, Copy, PartialEq)]
enum Path {
    /// The constant-μ fast path (≤ 150 instructions per branch).
    Fast,
    /// The speed-dependent μ(v) fast path (≤ 200 per branch).
    Speed,
    /// The general path.
    General,
}
use Path::{Fast, General, Speed};

/// The shots: `(label, takes the fast path, μ, v, ω)`, POOL parameters otherwise. Topspin
/// (`ω_y > 0`) presses the object ball into the cloth; "certain" grips are those where
/// the frictionless impulse `(1+e)a/2` already reaches the grip impulse `p*`, "band"
/// the one where only the table friction's extra normal impulse does.
const SHOTS: [Shot; 20] = [
    ("topspin-slides", Fast, 0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
    (
        "topspin-grips-restitution",
        Fast,
        0.05,
        [2.0, 0.3],
        [0.0, 7.0, 0.0],
    ),
    (
        "topspin-grips-compression",
        Fast,
        0.05,
        [2.0, 0.1],
        [0.0, 3.0, 0.0],
    ),
    (
        "topspin-band-grips",
        Fast,
        0.05,
        [2.0, 0.0],
        [0.0, 17.98, 0.0],
    ),
    ("stun-cut-slides", Fast, 0.05, [1.732, 1.0], [0.0, 0.0, 0.0]),
    (
        "draw-grips-restitution",
        Fast,
        0.05,
        [2.0, 0.3],
        [0.0, -7.0, 0.0],
    ),
    (
        "draw-grips-compression",
        Fast,
        0.05,
        [2.0, 0.1],
        [0.0, -3.0, 0.0],
    ),
    (
        "near-gearing",
        Fast,
        0.05,
        [0.866, 0.5],
        [0.0, 0.0, -17.497_813],
    ),
    // TP A.14's speed-dependent law: one shot per branch of its fast path, each with
    // c v₀ > 1 (the exponential's branch, longer than φ's), and one band grip with
    // c v₀ < 1 to show φ's branch.
    (
        "mu-v-topspin-slides",
        Speed,
        -1.0,
        [2.0, 0.0],
        [0.0, 70.0, 0.0],
    ),
    (
        "mu-v-topspin-grips-restitution",
        Speed,
        -1.0,
        [5.0, 0.0],
        [0.0, 40.0, 0.0],
    ),
    (
        "mu-v-topspin-grips-compression",
        Speed,
        -1.0,
        [8.0, 0.0],
        [0.0, 40.0, 0.0],
    ),
    (
        "mu-v-topspin-band-grips",
        Speed,
        -1.0,
        [3.4, 0.0],
        [0.0, 40.0, 0.0],
    ),
    (
        "mu-v-topspin-band-grips-small-slip",
        Speed,
        -1.0,
        [2.0, 0.0],
        [0.0, 28.13, 0.0],
    ),
    (
        "mu-v-stun-cut-slides",
        Speed,
        -1.0,
        [1.732, 1.0],
        [0.0, 0.0, 0.0],
    ),
    (
        "mu-v-draw-grips-restitution",
        Speed,
        -1.0,
        [4.4, 0.0],
        [0.0, -40.0, 0.0],
    ),
    (
        "mu-v-draw-grips-compression",
        Speed,
        -1.0,
        [8.0, 0.0],
        [0.0, -40.0, 0.0],
    ),
    // The general path: the speed-dependent μ past the speed path's range (a c k̄ p₁ >
    // 1), no friction, and slips below the fast path's 1 pm/s (exact gearing).
    (
        "speed-dependent-mu",
        General,
        -1.0,
        [16.0, 3.0],
        [0.0, 30.0, 0.0],
    ),
    ("frictionless", General, 0.0, [1.0, 0.5], [0.0, 10.0, 0.0]),
    ("gearing-side", General, 0.05, [1.0, 1e-13], [0.0, 0.0, 0.0]),
    (
        "gearing-topspin",
        General,
        0.05,
        [1.0, 0.0],
        [0.0, 1e-12, 0.0],
    ),
];

/// μ_s of the cloth shots: above `CURVED_MIN_MU_S` (0.4), where the general path
/// follows a pressed object ball's slide in pieces (`kim_grip::curved`).
const CLOTH_MU_S: f32 = 0.8;

/// Shots on a cloth of μ_s [`CLOTH_MU_S`] (μ 0.05 or, `< 0`, TP A.14's speed-dependent
/// law; POOL otherwise), on the general path: topspin that slides to the end and topspin
/// that grips; the speed-dependent law's slide, each piece at its own rate of slip
/// (`kim_grip::budget`).
const CLOTH_SHOTS: [(&str, f32, [f32; 2], [f32; 3]); 3] = [
    ("cloth-topspin-slides", 0.05, [2.0, 0.0], [0.0, 70.0, 0.0]),
    ("cloth-topspin-grips", 0.05, [2.0, 0.3], [0.0, 7.0, 0.0]),
    (
        "cloth-mu-v-topspin-slides",
        -1.0,
        [2.0, 0.0],
        [0.0, 70.0, 0.0],
    ),
];

/// Instructions per f32 `KimGrip` prediction, in thousandths (the bench's method).
fn milli_instructions(params: &Params, impact: &Impact) -> u64 {
    let c = count::count(cuesight::collide, params, impact, Model::KimGrip);
    let ticks = u64::from(c.ticks.saturating_sub(c.empty_ticks));
    ticks * u64::from(INSTRUCTIONS_PER_TICK) * 1000 / u64::from(c.reps)
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    let (mut fast_total_milli, mut fast_max_milli, mut fast_shots) = (0u64, 0u64, 0u64);
    for (label, path, mu, v, w) in SHOTS {
        // μ < 0 stands for TP A.14's speed-dependent law (Marlow's data).
        let params = if mu < 0.0 {
            Ok(Params::POOL.with_friction_law(FrictionLaw::MARLOW))
        } else {
            Params::POOL.with_mu(mu)
        };
        let (Ok(params), Ok(impact)) = (params, Impact::from_velocity(v, w)) else {
            exit::exit(false)
        };
        let milli = milli_instructions(&params, &impact);
        let name = match path {
            Fast => "fast",
            Speed => "speed",
            General => "general",
        };
        let _ = writeln!(out, "kimgrip-shot {label} {name} {milli}");
        if path == Fast {
            fast_total_milli += milli;
            fast_max_milli = fast_max_milli.max(milli);
            fast_shots += 1;
        }
    }
    for (label, mu, v, w) in CLOTH_SHOTS {
        let params = if mu < 0.0 {
            Ok(Params::POOL.with_friction_law(FrictionLaw::MARLOW))
        } else {
            Params::POOL.with_mu(mu)
        }
        .and_then(|p| p.with_mu_s(CLOTH_MU_S));
        let (Ok(params), Ok(impact)) = (params, Impact::from_velocity(v, w)) else {
            exit::exit(false)
        };
        let milli = milli_instructions(&params, &impact);
        let _ = writeln!(out, "kimgrip-shot {label} general {milli}");
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
