//! The whole-table simulation on the Cortex-M4F (issue 17's cost targets: a
//! three-cushion carom shot ≤ 50,000 instructions, a 16-ball shot with at least three
//! cushion hits ≤ 100,000, a 9-ball break ≤ 1,500 instructions per event on average):
//! instruction counts under QEMU `-icount shift=0` with the bench's method (function
//! pointer, empty call subtracted, [`cuesight_bench::count`]), the scene's construction
//! subtracted, f32 and `KimGrip`, and each shot's event counts.
//!
//! Run: `cd bench-firmware && cargo run --release --bin table-probe` (prints `table
//! <shot> <instructions> <events> <collisions> <cushions> <pockets>` lines and exits 0).
#![no_std]
#![no_main]
#![deny(missing_docs)]

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight::shot::Stroke;
use cuesight::sim::{play, EventKind, Event, Setup};
use cuesight::strike::TipOffset;
use cuesight::table::{BallSet, Scene, Table};
use cuesight::{Error, Impact, Model, Outcome, Params, Result};
use cuesight_bench::count;
use cuesight_bench::exit;
use cuesight_bench::out::Out;
use cuesight_bench::timer::INSTRUCTIONS_PER_TICK;

/// One shot: its scene, stroke and setup.
struct Shot {
    scene: Scene,
    stroke: Stroke,
    setup: Setup,
}

/// The three-cushion point of `cli/tests/shot_cli.rs` (two cushions, ball 1, a third
/// cushion, ball 2).
fn carom() -> Result<Shot> {
    let r = BallSet::CAROM.radius;
    let mut scene = Scene::new(Table::carom(), r, [0.7, 0.4])?;
    scene.add_ball([1.4, 0.9])?;
    scene.add_ball([2.2, 1.1])?;
    let aim = 84.0f32.to_radians();
    Ok(Shot {
        scene,
        stroke: Stroke::at_angle(5.0, TipOffset::from_radius_fraction(0.3, 0.2, r)?, aim)?,
        setup: Setup::carom()?,
    })
}

/// Sixteen balls: the cue ball and fifteen spread over a pool table, a firm stroke.
fn sixteen() -> Result<Shot> {
    let r = BallSet::POOL.radius;
    let mut scene = Scene::new(Table::pool(), r, [0.5, 0.4])?;
    for i in 0..15 {
        let (row, column) = ((i / 5) as f32, (i % 5) as f32);
        scene.add_ball([0.9 + 0.3 * column, 0.3 + 0.3 * row + 0.05 * column])?;
    }
    Ok(Shot {
        scene,
        stroke: Stroke::at_angle(6.0, TipOffset::from_radius_fraction(0.0, 0.2, r)?, 0.35)?,
        setup: Setup::POOL,
    })
}

/// A 9-ball break: the diamond rack (rows of 1, 2, 3, 2, 1, 0.1 mm apart) on the foot
/// spot, the cue ball on the head string, 8 m/s into the head ball.
fn break_shot() -> Result<Shot> {
    let r = BallSet::POOL.radius;
    let (foot, middle) = (1.905, 0.635);
    let mut scene = Scene::new(Table::pool(), r, [0.635, 0.6])?;
    let pitch = 2.0 * r + 1e-4;
    let row_step = pitch * 0.866_025_4;
    for (row, count) in [1, 2, 3, 2, 1].into_iter().enumerate() {
        for k in 0..count {
            let y = middle + pitch * (k as f32 - (count - 1) as f32 / 2.0);
            scene.add_ball([foot + row_step * row as f32, y])?;
        }
    }
    let aim = [foot - 0.635, middle - 0.6];
    Ok(Shot {
        scene,
        stroke: Stroke::new(8.0, TipOffset::CENTRE, aim)?,
        setup: Setup::POOL,
    })
}

const SHOTS: [(&str, fn() -> Result<Shot>); 3] =
    [("three-cushion", carom), ("sixteen-balls", sixteen), ("nine-ball-break", break_shot)];

/// The shot of index `model`'s tolerance field… no: of the `Impact`'s speed (the count
/// API passes a `Params`, an `Impact` and a `Model`; the impact's `v_x` selects it).
fn which(impact: &Impact) -> usize {
    impact.velocity().x as usize
}

/// Construction of the selected shot only (subtracted from the others).
#[inline(never)]
fn build(_: &Params, impact: &Impact, _: Model) -> Result<Outcome> {
    let shot = (SHOTS[which(impact) % SHOTS.len()].1)()?;
    black_box(&shot.scene);
    Err(Error::NumericalFailure)
}

/// Construction and the whole-table simulation of the selected shot.
#[inline(never)]
fn simulate(_: &Params, impact: &Impact, _: Model) -> Result<Outcome> {
    let shot = (SHOTS[which(impact) % SHOTS.len()].1)()?;
    let finish = play(&shot.scene, &shot.stroke, &shot.setup, |event: &Event, _| {
        black_box(event);
    })?;
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
    for (index, (name, make)) in SHOTS.iter().enumerate() {
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
    }
    out.flush();
    exit::exit(ok)
}
