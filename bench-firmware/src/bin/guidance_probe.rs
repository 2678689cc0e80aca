//! Shot guidance on the Cortex-M4F (shot-guidance issue targets: ≤ 3,000 instructions
//! and ≤ 2 KB of stack for one shot with `KimGrip`): instruction counts under QEMU
//! `-icount shift=0` with the bench's method (function pointer, empty call
//! subtracted, [`cuesight_bench::count`]), and the peak stack of each call measured by
//! painting the stack below the caller's frame.
//!
//! Measured: building the scene (pool table, cue ball, object ball, a third ball), the
//! same plus `shot::play` (stroke → travel → first contact → collision → both paths →
//! pocket), and the same plus `aim::solve_aim` (inverse aim, several forward plays).
//!
//! Run: `cd bench-firmware && cargo run --release --bin guidance-probe` (prints
//! `guidance <what> <model> <instructions> <peak stack bytes>` lines and exits 0).
#![no_std]
#![no_main]
#![deny(missing_docs)]

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight::aim::solve_aim;
use cuesight::shot::{play, ShotSetup, Stroke};
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{Scene, Table};
use cuesight::travel::Cloth;
use cuesight::{Error, Impact, Model, Outcome, Params, Result};
use cuesight_bench::count;
use cuesight_bench::exit;
use cuesight_bench::out::Out;
use cuesight_bench::timer::{self, INSTRUCTIONS_PER_TICK};

fn scene(params: &Params) -> Result<Scene> {
    let mut scene = Scene::new(Table::pool(), params.radius(), [0.6, 0.5])?;
    scene.add_ball([1.6, 0.62])?;
    scene.add_ball([2.0, 1.0])?;
    Ok(scene)
}

fn setup(params: &Params, model: Model) -> ShotSetup {
    ShotSetup {
        params: *params,
        cue: Cue::TYPICAL,
        cloth: Cloth::TYPICAL,
        model,
    }
}

/// Scene construction only (subtracted from the others).
#[inline(never)]
fn build(params: &Params, _: &Impact, _: Model) -> Result<Outcome> {
    let s = scene(params)?;
    black_box(&s);
    Err(Error::NumericalFailure)
}

/// Scene + one forward shot.
#[inline(never)]
fn forward(params: &Params, _: &Impact, model: Model) -> Result<Outcome> {
    let s = scene(params)?;
    let tip = TipOffset::from_radius_fraction(0.1, 0.3, params.radius())?;
    let stroke = Stroke::new(3.0, tip, [1.0, 0.12])?;
    let shot = play(&s, &stroke, &setup(params, model))?;
    shot.contact
        .map(|c| c.outcome)
        .ok_or(Error::NumericalFailure)
}

/// Scene + inverse aim into the top-right corner.
#[inline(never)]
fn inverse(params: &Params, _: &Impact, model: Model) -> Result<Outcome> {
    let s = scene(params)?;
    let tip = TipOffset::from_radius_fraction(0.1, 0.3, params.radius())?;
    match solve_aim(&s, 1, 3, 3.0, tip, &setup(params, model)) {
        Ok(solution) => {
            black_box(&solution);
            Err(Error::NumericalFailure)
        }
        Err(_) => Err(Error::OutOfRange {
            field: cuesight::Field::Aim,
            value: 0.0,
        }),
    }
}

const PAINT: u32 = 0xC0DE_5EED;
const PAINTED_BYTES: usize = 24 * 1024;

/// Peak stack (bytes below the caller's stack pointer) of one call of `f`.
#[inline(never)]
#[allow(unsafe_code)]
fn peak_stack(f: count::Predict, params: &Params, impact: &Impact, model: Model) -> usize {
    let sp = cortex_m::register::msp::read() as usize;
    let low = sp - PAINTED_BYTES;
    // SAFETY: the words painted lie below the current stack pointer, in the free part of
    // the stack (RAM is 256 KiB, this image uses a few KiB); nothing lives there yet.
    for addr in (low..sp - 64).step_by(4) {
        unsafe { core::ptr::write_volatile(addr as *mut u32, PAINT) };
    }
    let result = f(black_box(params), black_box(impact), black_box(model));
    black_box(&result);
    let mut lowest = sp - 64;
    for addr in (low..sp - 64).step_by(4) {
        // SAFETY: as above; reading back the painted region.
        if unsafe { core::ptr::read_volatile(addr as *const u32) } != PAINT {
            lowest = addr;
            break;
        }
    }
    sp - lowest
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    let params = Params::POOL;
    let Ok(impact) = Impact::from_velocity([1.0, 0.0], [0.0; 3]) else {
        exit::exit(false)
    };
    let mut ok = forward(&params, &impact, Model::KimGrip).is_ok();
    for model in [Model::KimGrip, Model::Auto { tolerance: 1e-3 }] {
        let base = count::count(build, &params, &impact, model);
        let base_instr =
            (base.ticks.saturating_sub(base.empty_ticks)) * INSTRUCTIONS_PER_TICK / base.reps;
        for (what, f) in [
            ("forward", forward as count::Predict),
            ("inverse-aim", inverse as count::Predict),
        ] {
            let c = count::count(f, &params, &impact, model);
            let instr = (c.ticks.saturating_sub(c.empty_ticks)) * INSTRUCTIONS_PER_TICK / c.reps;
            let stack = peak_stack(f, &params, &impact, model);
            let _ = writeln!(
                out,
                "guidance {what} {} {} {stack} (scene construction {base_instr} excluded)",
                model.name(),
                instr.saturating_sub(base_instr)
            );
        }
    }
    // `inverse` reports a solved aim as NumericalFailure (a marker: the count API wants
    // an Outcome), a failed solve as OutOfRange.
    ok &= inverse(&params, &impact, Model::KimGrip) == Err(Error::NumericalFailure);
    out.flush();
    exit::exit(ok)
}
