//! `cargo xtask live --trace FILE [--odr HZ] [--plan FILE]`: plays an IMU trace (the
//! CSV of `firmware/traces/README.md`) through the firmware's emulated LSM6DSOX in QEMU
//! (`cuesight_host::live`) and prints, for each stroke the device detects, one JSON line
//! on stdout:
//!
//! ```text
//! {"stroke":0,"impact_sample":8030,"cue_speed_mps":0.8229,"latency_instructions":1680,"metrics":{...},"guidance":null}
//! ```
//!
//! (`impact_sample`: 0-based index of the first contact sample in the trace;
//! `cue_speed_mps`: the cue's speed just before tip contact; `latency_instructions`:
//! from the start of the interrupt that delivered the sample the impact was detected on
//! to the guidance computed; `guidance`: the planned shot (`--plan`, a `shot` request's
//! JSON) played at the stroke's speed, the `shot` answer's keys, or `null` without a
//! plan). `--stall FROM:COUNT` and `--bus-fail FROM:COUNT` make the emulated part stall
//! or its bus fail for those samples. A fault is a line `{"fault":{...}}`, a sensor
//! failure `{"sensor":{...}}`, a stroke's follow-through, once the cue has stopped,
//! `{"follow_through":{"stroke":0,"length_m":0.21,"time_s":0.24}}`; the last line is
//! the summary `{"summary":{...}}`. Everything else (the QEMU command,
//! the firmware's log) goes to stderr.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::time::Duration;

use cuesight_host::live::{self, RATES_HZ};
use cuesight_link::live::{LiveReport, LiveStroke, TraceEnd};
use cuesight_link::{Response, ShotRequest};
use serde_json::{json, Value};

use crate::cmd::{Failure, Result};
use crate::tools;

/// Largest trace file taken (bytes): 64 MiB, 40 minutes at 6.66 kHz.
const MAX_TRACE_BYTES: u64 = 64 << 20;

/// Options of `cargo xtask live`.
#[derive(clap::Args)]
pub struct Args {
    /// The trace: CSV with the header `ax,ay,az,gx,gy,gz`, raw LSM6DSOX words.
    #[arg(long, value_name = "FILE")]
    pub trace: PathBuf,
    /// The trace's output data rate (Hz): 6667 or 3333.
    #[arg(long, default_value_t = 6667)]
    pub odr: u16,
    /// The planned shot, a `shot` request's JSON (`cuesight shot` scene keys; `speed`
    /// is replaced by each stroke's).
    #[arg(long, value_name = "FILE")]
    pub plan: Option<PathBuf>,
    /// Stall the emulated part (no conversion, no data-ready) for COUNT samples from
    /// sample FROM (0-based): `FROM:COUNT`; may be repeated.
    #[arg(long, value_name = "FROM:COUNT", value_parser = window)]
    pub stall: Vec<(usize, usize)>,
    /// Fail every bus transaction for COUNT samples from sample FROM: `FROM:COUNT`; may
    /// be repeated.
    #[arg(long, value_name = "FROM:COUNT", value_parser = window)]
    pub bus_fail: Vec<(usize, usize)>,
    /// Kill QEMU after this many seconds and fail.
    #[arg(long, default_value_t = 600)]
    pub timeout: u64,
    /// Boot this firmware ELF (built with the `live` feature) instead of building the
    /// release one into firmware/target/live.
    #[arg(long, value_name = "ELF")]
    pub elf: Option<PathBuf>,
}

/// What `cargo xtask run` plays after the demo session.
pub const DEMO_COMMAND: &str = "cargo xtask live --trace firmware/traces/three-strokes-6667.csv --plan firmware/traces/plan-cut-to-corner.json";

impl Args {
    /// [`DEMO_COMMAND`]'s arguments.
    pub fn demo() -> Self {
        let traces = crate::cmd::firmware_dir().join("traces");
        Self {
            trace: traces.join("three-strokes-6667.csv"),
            odr: 6667,
            plan: Some(traces.join("plan-cut-to-corner.json")),
            stall: Vec::new(),
            bus_fail: Vec::new(),
            timeout: 120,
            elf: None,
        }
    }
}

/// `FROM:COUNT`.
fn window(text: &str) -> std::result::Result<(usize, usize), String> {
    let (from, count) = text
        .split_once(':')
        .ok_or_else(|| format!("`{text}` is not FROM:COUNT"))?;
    let number = |s: &str| {
        s.parse::<usize>()
            .map_err(|_| format!("`{s}` in `{text}` is not a sample count"))
    };
    Ok((number(from)?, number(count)?))
}

/// Reads `path`, at most [`MAX_TRACE_BYTES`].
fn read_bounded(path: &Path, what: &str) -> Result<Vec<u8>> {
    let size = std::fs::metadata(path)
        .map_err(|e| Failure::new(format!("cannot read the {what} {}: {e}", path.display())))?
        .len();
    if size > MAX_TRACE_BYTES {
        return Err(Failure::new(format!(
            "the {what} {} is {size} bytes, more than {MAX_TRACE_BYTES}",
            path.display()
        )));
    }
    std::fs::read(path)
        .map_err(|e| Failure::new(format!("cannot read the {what} {}: {e}", path.display())))
}

/// The JSON line of a stroke.
pub fn stroke_line(stroke: &LiveStroke) -> Value {
    let guidance = match &stroke.guidance {
        None => Value::Null,
        Some(Ok(answer)) => serde_json::to_value(answer).unwrap_or(Value::Null),
        Some(Err(error)) => json!({ "error": error }),
    };
    json!({
        "stroke": stroke.stroke.saturating_sub(1),
        "impact_sample": stroke.impact_sample,
        "cue_speed_mps": stroke.cue_speed,
        "latency_instructions": stroke.latency_instructions,
        "metrics": stroke.metrics,
        "guidance": guidance,
    })
}

/// The summary line.
fn summary_line(end: Option<&TraceEnd>, strokes: usize, faults: usize) -> Value {
    json!({ "summary": {
        "strokes": strokes,
        "faults": faults,
        "samples": end.map(|e| e.samples),
        "truncated": end.map(|e| e.truncated),
        "work_mean_instructions": end.map(TraceEnd::work_mean_instructions),
        "work_max_instructions": end.map(|e| e.work_max_instructions),
        "resolve_max_instructions": end.map(|e| e.resolve_max_instructions),
    }})
}

/// Runs `cargo xtask live`.
pub fn run(args: &Args) -> Result {
    if !RATES_HZ.contains(&args.odr) {
        return Err(Failure::new(format!(
            "--odr {} is not an output data rate of the LSM6DSOX the firmware samples at ({} or {} Hz)",
            args.odr, RATES_HZ[0], RATES_HZ[1]
        )));
    }
    let csv = read_bounded(&args.trace, "trace")?;
    let samples = live::csv_samples(&csv)
        .map_err(|e| Failure::new(format!("{}: {e}", args.trace.display())))?;
    let plan: Option<ShotRequest> = match &args.plan {
        None => None,
        Some(path) => Some(
            serde_json::from_slice(&read_bounded(path, "plan")?).map_err(|e| {
                Failure::new(format!("{}: not a shot request: {e}", path.display()))
            })?,
        ),
    };
    tools::ensure_for_qemu()?;
    let elf = match &args.elf {
        Some(elf) => elf.clone(),
        None => crate::images::LIVE.build()?,
    };
    let defmt_print = tools::defmt_print()?;
    eprintln!(
        "xtask live: {} samples at {} Hz from {} (QEMU -icount shift=0,sleep=off; the trace streamed through a named pipe, read with semihosting)",
        samples.len(),
        args.odr,
        args.trace.display()
    );
    let mut windows: Vec<live::FaultWindow> = Vec::new();
    for (list, stalled) in [(&args.stall, true), (&args.bus_fail, false)] {
        windows.extend(list.iter().map(|&(from, count)| live::FaultWindow {
            from,
            count,
            bus_failing: !stalled,
            stalled,
        }));
    }
    windows.sort_by_key(|w| w.from);
    for pair in windows.windows(2) {
        if pair[0].from + pair[0].count > pair[1].from {
            return Err(Failure::new(format!(
                "the fault windows from sample {} and {} overlap",
                pair[0].from, pair[1].from
            )));
        }
    }
    if let Some(w) = windows.iter().find(|w| w.from + w.count > samples.len()) {
        return Err(Failure::new(format!(
            "the fault window {}:{} runs past the trace's {} samples",
            w.from,
            w.count,
            samples.len()
        )));
    }
    let played = live::play(
        &elf,
        Some(&defmt_print),
        &live::trace_binary_with_faults(&samples, args.odr, &windows),
        plan.as_ref(),
        Duration::from_secs(args.timeout),
    )
    .map_err(|e| Failure::new(format!("the live run failed: {e}")))?;
    for line in &played.ended.log {
        eprintln!("{line}");
    }
    if let Some(Response::Error(error)) = &played.plan {
        return Err(Failure::new(format!(
            "the device refused the plan: {error:?}"
        )));
    }
    let mut out = io::stdout().lock();
    let mut write = |value: Value| {
        writeln!(out, "{value}").map_err(|e| Failure::new(format!("cannot write stdout: {e}")))
    };
    let (mut strokes, mut faults, mut end) = (0, 0, None);
    for report in &played.reports {
        match report {
            LiveReport::Stroke(stroke) => {
                strokes += 1;
                write(stroke_line(stroke))?;
            }
            LiveReport::Fault(fault) => {
                faults += 1;
                write(json!({ "fault": fault }))?;
            }
            LiveReport::Sensor(fault) => {
                faults += 1;
                write(json!({ "sensor": fault }))?;
            }
            LiveReport::TraceEnd(trace_end) => end = Some(trace_end),
            LiveReport::FollowThrough(follow) => write(json!({ "follow_through": {
                // 0-based, as the stroke lines count.
                "stroke": follow.stroke.saturating_sub(1),
                "length_m": follow.length,
                "time_s": follow.time,
            }}))?,
        }
    }
    write(summary_line(end, strokes, faults))?;
    match played.ended.status {
        Some(status) if status.success() => Ok(()),
        status => Err(Failure::new(format!(
            "the firmware did not exit cleanly: {status:?}"
        ))),
    }
}
