//! Cross-check of the instruction counting on real code, for `cargo xtask bench`: one
//! `KimGrip` prediction counted with the timer method (as `cuesight-bench` does), while
//! QEMU logs every executed instruction (`-accel tcg,one-insn-per-tb=on -d exec,nochain`).
//! The timer's figure must equal the traced length of a call of [`bench_trace_root`]
//! minus that of a call of the empty function.
//!
//! Prints `trace-check <reps> <ticks> <empty ticks>` on semihosting stdout.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight::{Impact, Model, Outcome, Params, Result};
use cuesight_bench::count::{self, Predict};
use cuesight_bench::{exit, out::Out, timer};

/// What is counted: `collide` as the bench calls it. An unmangled name the trace
/// analysis can find; nothing else defines it.
#[allow(unsafe_code)]
#[no_mangle]
#[inline(never)]
pub fn bench_trace_root(params: &Params, impact: &Impact, model: Model) -> Result<Outcome> {
    cuesight::collide(params, impact, model)
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    // Natural roll head-on at 2 m/s: sliding, object ball pressed into the cloth.
    let (Ok(params), Ok(impact)) = (
        Params::POOL.with_mu(0.05),
        Impact::from_velocity([2.0, 0.0], [0.0, 70.0, 0.0]),
    ) else {
        exit::exit(false)
    };
    let predict: Predict = black_box(bench_trace_root);
    let c = count::count(predict, &params, &impact, Model::KimGrip);
    let _ = writeln!(out, "trace-check {} {} {}", c.reps, c.ticks, c.empty_ticks);
    out.flush();
    exit::exit(true)
}
