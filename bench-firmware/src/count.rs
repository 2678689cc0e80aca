//! Instruction counting: a prediction called `reps` times through a function pointer,
//! minus the same loop calling a function that returns at once (the empty call), and
//! calibration blocks of known length that check the method.
//!
//! Everything QEMU executes is deterministic under `-icount`, so the only error is the
//! timer's resolution, one tick (40 instructions) per reading. Each measurement runs
//! about 500,000 instructions, so a count is within ±0.02 % (two readings each of the
//! prediction and the empty loop), and within ±0.02 instruction for the cheapest.

use core::hint::black_box;

use cuesight::{Error, Impact, Model, Outcome, Params, Result};

use crate::timer::{self, INSTRUCTIONS_PER_TICK};

/// The signature of [`cuesight::collide`] and its siblings in other precisions.
pub type Predict = fn(&Params, &Impact, Model) -> Result<Outcome>;

/// Instructions each measurement aims at (≈ 12,500 timer ticks).
const TARGET_INSTRUCTIONS: u32 = 500_000;
const MIN_REPS: u32 = 8;
const MAX_REPS: u32 = 4096;

/// The empty call: same signature, returns at once (storing only the `Err` discriminant).
#[inline(never)]
pub fn empty(_: &Params, _: &Impact, _: Model) -> Result<Outcome> {
    Err(Error::NumericalFailure)
}

/// Ticks for `reps` calls of `predict`. Every argument goes through `black_box`, so
/// the loop is the same machine code whatever function is measured.
#[inline(never)]
pub fn ticks(predict: Predict, params: &Params, impact: &Impact, model: Model, reps: u32) -> u32 {
    let predict = black_box(predict);
    let reps = black_box(reps);
    let start = timer::now();
    for _ in 0..reps {
        // By reference: the result must be stored, but is not copied again.
        let result = predict(black_box(params), black_box(impact), black_box(model));
        black_box(&result);
    }
    timer::elapsed(start, timer::now())
}

/// One counted prediction: `reps` calls took `ticks`, `reps` empty calls `empty_ticks`.
#[derive(Clone, Copy, Debug)]
pub struct Count {
    /// Calls per measurement.
    pub reps: u32,
    /// Ticks for the predictions.
    pub ticks: u32,
    /// Ticks for as many empty calls.
    pub empty_ticks: u32,
}

/// Warms up, estimates the cost from one call, then measures with enough repetitions.
pub fn count(predict: Predict, params: &Params, impact: &Impact, model: Model) -> Count {
    let warm_up = predict(black_box(params), black_box(impact), black_box(model));
    black_box(&warm_up);
    let once = ticks(predict, params, impact, model, 1)
        .saturating_sub(ticks(empty, params, impact, model, 1))
        .max(1)
        .saturating_mul(INSTRUCTIONS_PER_TICK);
    let reps = (TARGET_INSTRUCTIONS / once).clamp(MIN_REPS, MAX_REPS);
    Count {
        reps,
        ticks: ticks(predict, params, impact, model, reps),
        empty_ticks: ticks(empty, params, impact, model, reps),
    }
}

/// A calibration block: a function of known length (besides its `bx lr`), timed
/// against the same loop calling an empty function.
pub struct Calibration {
    /// Name shown in the results.
    pub name: &'static str,
    /// Instructions in one call, not counting the return shared with the empty call.
    pub instructions: u32,
    block: unsafe extern "C" fn(),
}

impl Calibration {
    /// Ticks for `reps` calls of the block and for `reps` calls of the empty function.
    pub fn measure(&self, reps: u32) -> (u32, u32) {
        (time_calls(self.block, reps), time_calls(calib_empty, reps))
    }
}

/// Repetitions of each calibration block.
pub const CALIBRATION_REPS: u32 = 1000;

/// The calibration blocks (assembly below).
pub const CALIBRATIONS: [Calibration; 3] = [
    Calibration {
        name: "1000 integer adds",
        instructions: 1000,
        block: calib_adds,
    },
    Calibration {
        // 14 cycles each on a Cortex-M4F, one instruction each here.
        name: "100 x (vsqrt.f32 + vdiv.f32)",
        instructions: 200,
        block: calib_fp,
    },
    Calibration {
        name: "loop of 100: movs + 100 x (subs + bne)",
        instructions: 201,
        block: calib_loop,
    },
];

#[inline(never)]
#[allow(unsafe_code)]
fn time_calls(f: unsafe extern "C" fn(), reps: u32) -> u32 {
    let f = black_box(f);
    let reps = black_box(reps);
    let start = timer::now();
    for _ in 0..reps {
        // SAFETY: the calibration functions touch only caller-saved registers
        // (r0, s0, s1, flags), which the C ABI lets them clobber.
        unsafe { f() };
    }
    timer::elapsed(start, timer::now())
}

#[allow(unsafe_code)]
extern "C" {
    fn calib_empty();
    fn calib_adds();
    fn calib_fp();
    fn calib_loop();
}

// The blocks are whole functions (reached by `bl`), so the compiler's loop branch
// never has to span them.
#[allow(unsafe_code)]
mod blocks {
    core::arch::global_asm!(
        ".syntax unified",
        ".thumb",
        ".fpu fpv4-sp-d16",
        ".section .text.cuesight_calibration, \"ax\", %progbits",
        ".balign 4",
        ".global calib_empty",
        ".type calib_empty, %function",
        ".thumb_func",
        "calib_empty:",
        "bx lr",
        ".global calib_adds",
        ".type calib_adds, %function",
        ".thumb_func",
        "calib_adds:",
        ".rept 1000",
        "adds r0, r0, #1",
        ".endr",
        "bx lr",
        ".global calib_fp",
        ".type calib_fp, %function",
        ".thumb_func",
        "calib_fp:",
        ".rept 100",
        "vsqrt.f32 s0, s1",
        "vdiv.f32 s1, s0, s1",
        ".endr",
        "bx lr",
        ".global calib_loop",
        ".type calib_loop, %function",
        ".thumb_func",
        "calib_loop:",
        "movs r0, #100",
        "1:",
        "subs r0, r0, #1",
        "bne 1b",
        "bx lr",
    );
}
