//! The streaming stroke estimator on the Cortex-M4F (issue 15: per-sample work ≤ 250
//! instructions mean, ≤ 400 max): the baked stream ([`cuesight_bench::stream`]) one
//! sample at a time through `StreamingEstimator::push_raw`, as a sampling interrupt
//! would feed it. Built by `cargo xtask bench` in the shipped firmware's configuration
//! (profile `release-z`: opt-level "z", fat LTO, one codegen unit, and
//! `-C llvm-args=-inline-threshold=50`), run under QEMU `-icount shift=0` with an
//! instruction trace that gives every call's exact length.
//!
//! Output lines (fields separated by one space):
//!
//! * `stream <rate: f32 bits in hex> <samples> <state bytes>` — the stream and
//!   `size_of` the estimator;
//! * `stream-timer <samples> <ticks> <empty ticks>` — the timer method (as the other
//!   benches: calls minus empty calls) over the whole stream, which the trace's figure
//!   must match; not in trace mode (semihosting argument `trace`), which instead makes
//!   one empty call for its traced length;
//! * `stream-mark <index> <what>` — see [`cuesight_bench::stream::bench_stream_loop`];
//! * `stream-finish <event or none>`, then `end`.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::fmt::Write as _;
use core::hint::black_box;

use cuesight_bench::out::Out;
use cuesight_bench::stream::{
    bench_stream_empty, bench_stream_loop, bench_stream_push, bench_stream_timed, command_line_has,
    Push, Stream,
};
use cuesight_bench::{exit, timer};
use cuesight_sensors::{StreamConfig, StreamConfigError, StreamEvent, StreamingEstimator};

/// A validated estimator for a run-time configuration (the constructor's code is part
/// of the estimator's size).
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_new(config: &StreamConfig) -> Result<StreamingEstimator, StreamConfigError> {
    StreamingEstimator::new(config)
}

/// The end of a stream (its code is part of the estimator's size).
#[allow(unsafe_code)] // `no_mangle`
#[no_mangle]
#[inline(never)]
pub fn bench_stream_finish(estimator: &mut StreamingEstimator) -> Option<StreamEvent> {
    estimator.finish()
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    timer::start();
    let mut out = Out::stdout();
    let Some(stream) = Stream::baked() else {
        exit::fail(format_args!(
            "no sample stream baked into this image: build it through `cargo xtask bench`"
        ));
    };
    // With the follow-through (off by default): its cost is counted too.
    let config = black_box(StreamConfig {
        follow_through: true,
        ..StreamConfig::new(stream.rate_hz)
    });
    let Ok(fresh) = bench_stream_new(&config) else {
        exit::fail(format_args!("the stream's rate is not accepted"));
    };
    let _ = write!(out, "stream ");
    out.hex(stream.rate_hz.to_bits());
    let state = core::mem::size_of::<StreamingEstimator>();
    let _ = writeln!(out, " {} {state}", stream.len);

    let (push, empty): (Push, Push) = (bench_stream_push, bench_stream_empty);
    if command_line_has("trace") {
        // One empty call, for its traced length.
        bench_stream_timed(empty, &mut fresh.clone(), &stream, 1);
    } else {
        let calls = bench_stream_timed(push, &mut fresh.clone(), &stream, stream.len);
        let empties = bench_stream_timed(empty, &mut fresh.clone(), &stream, stream.len);
        let _ = writeln!(out, "stream-timer {} {calls} {empties}", stream.len);
    }
    out.flush();

    let mut estimator = fresh;
    bench_stream_loop(push, &mut estimator, &stream, &mut out);
    let finish = bench_stream_finish(&mut estimator);
    let _ = writeln!(
        out,
        "stream-finish {}",
        if finish.is_some() { "event" } else { "none" }
    );
    let _ = writeln!(out, "end");
    out.flush();
    exit::exit(true)
}
