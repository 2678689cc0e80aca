//! The whole-table simulation on the Cortex-M4F (issue 17's cost targets: a
//! three-cushion carom shot ≤ 50,000 instructions, a 16-ball shot with at least three
//! cushion hits ≤ 100,000, a 9-ball break ≤ 1,500 instructions per event on average):
//! instruction counts under QEMU `-icount shift=0` with the bench's method (function
//! pointer, empty call subtracted, [`cuesight_bench::count`]), the scene's construction
//! subtracted, f32 and `KimGrip`, and each shot's event counts.
//!
//! The shots are `cuesight::sim::shots`; each one's result digest
//! (`cuesight::sim::shots::digest`, to the bit) is printed for the host to compare.
//!
//! Run: `cd bench-firmware && cargo run --release --bin table-probe` (prints `table
//! <shot> <instructions> <events> <collisions> <cushions> <pockets>` and `table-digest
//! <shot> <hex>` lines and exits 0).
#![no_std]
#![no_main]
#![deny(missing_docs)]

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight::sim::shots::{digest, ALL};
use cuesight::sim::{play, Event, EventKind};
use cuesight::{Error, Impact, Model, Outcome, Params, Result};
use cuesight_bench::count;
use cuesight_bench::exit;
use cuesight_bench::out::Out;
use cuesight_bench::timer::INSTRUCTIONS_PER_TICK;

/// The shot of the count API's `Impact` (its `v_x` selects it: the API passes a
/// `Params`, an `Impact` and a `Model`).
fn which(impact: &Impact) -> usize {
    impact.velocity().x as usize
}

/// Construction of the selected shot only (subtracted from the others).
#[inline(never)]
fn build(_: &Params, impact: &Impact, _: Model) -> Result<Outcome> {
    let shot = (ALL[which(impact) % ALL.len()].1)()?;
    black_box(&shot.scene);
    Err(Error::NumericalFailure)
}

/// Construction and the whole-table simulation of the selected shot.
#[inline(never)]
fn simulate(_: &Params, impact: &Impact, _: Model) -> Result<Outcome> {
    let shot = (ALL[which(impact) % ALL.len()].1)()?;
    let finish = play(
        &shot.scene,
        &shot.stroke,
        &shot.setup,
        |event: &Event, _| {
            black_box(event);
        },
    )?;
    black_box(&finish);
    Err(Error::NumericalFailure)
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    cuesight_bench::timer::start();
    let mut out = Out::stdout();
    let params = Params::POOL;
    let mut ok = true;
    for (index, (name, make)) in ALL.iter().enumerate() {
        let Ok(impact) = Impact::from_velocity([index as f32 + 0.5, 0.0], [0.0; 3]) else {
            exit::exit(false)
        };
        // The events, counted once.
        let (mut events, mut balls, mut cushions, mut pockets) = (0u32, 0u32, 0u32, 0u32);
        let played = make().and_then(|shot| {
            play(&shot.scene, &shot.stroke, &shot.setup, |event, _| {
                events += 1;
                match event.kind {
                    EventKind::Ball => balls += 1,
                    EventKind::Cushion => cushions += 1,
                    EventKind::Pocket(_) => pockets += 1,
                    EventKind::Rest => {}
                }
            })
        });
        ok &= played.is_ok();
        let base = count::count(build, &params, &impact, Model::KimGrip);
        let c = count::count(simulate, &params, &impact, Model::KimGrip);
        let per = |c: count::Count| {
            (c.ticks.saturating_sub(c.empty_ticks)) * INSTRUCTIONS_PER_TICK / c.reps
        };
        let instructions = per(c).saturating_sub(per(base));
        let _ = writeln!(
            out,
            "table {name} {instructions} {events} {balls} {cushions} {pockets} (scene construction {} excluded)",
            per(base)
        );
        match make().and_then(|shot| digest(&shot)) {
            Ok(hash) => {
                let _ = writeln!(out, "table-digest {name} {hash:08x}");
            }
            Err(_) => ok = false,
        }
    }
    out.flush();
    exit::exit(ok)
}
