//! The streaming stroke estimator on the Cortex-M4F (issue 15: per-sample work ≤ 250
//! instructions mean, ≤ 400 max; the whole firmware within 48 KiB of flash).
//!
//! 1. The stream: `sensors/tests/streaming.rs` writes its bench stream (five strokes of
//!    the kinematic model with a trusted rest, a double hit and a knock; 181,736
//!    samples, 27 s at 6667 Hz) when `CUESIGHT_BENCH_STREAM` names a file.
//! 2. `bench-firmware`'s `stream-count` image, built in the shipped firmware's
//!    configuration: profile `release-z` (opt-level "z", fat LTO, one codegen unit)
//!    plus the inline threshold of `firmware/.cargo/config.toml`, read from there.
//! 3. One plain QEMU run (`-icount shift=0`): the timer method over the whole stream
//!    (calls minus empty calls, as the other benches), the estimator's state size, and
//!    where strokes start and events happen.
//! 4. One traced run (one instruction per translation block, `-d exec,nochain`, the
//!    log read from QEMU's stderr as it is written): the exact length of every call of
//!    `bench_stream_push`, from its first instruction to its return, callees included
//!    (the caller's `bl` is not). The traced mean minus the empty call's traced length
//!    must equal the timer's figure.
//! 5. Code size: every function reachable from the entry points through direct
//!    branches (`llvm-objdump`), with the symbol table's sizes.
//!
//! Results: `target/bench/stream.json` and a console summary.

use std::collections::{BTreeMap, BTreeSet};
use std::io::BufReader;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use super::disasm;
use super::firmware::{
    bench_firmware_dir, one_insn_per_tb, run_qemu_with, target_dir, INSTRUCTIONS_PER_TICK,
    QEMU_ARGS,
};
use crate::cmd::{self, probe, Failure, Result};
use crate::tools;

const BIN: &str = "stream-count";
/// The shipped firmware's profile, as `bench-firmware/Cargo.toml` copies it.
const PROFILE: &str = "release-z";
/// What is counted, the empty call, and the two callers the trace tells apart.
const ROOT: &str = "bench_stream_push";
const EMPTY: &str = "bench_stream_empty";
const LOOP: &str = "bench_stream_loop";
const TIMED: &str = "bench_stream_timed";
/// Entry points of the estimator's whole API in the image (constructor with a run-time
/// configuration, per-sample step, end of stream).
const API: [&str; 3] = ["bench_stream_new", ROOT, "bench_stream_finish"];
/// The sensors test that writes the stream.
const STREAM_TEST: &str = "the_bench_stream_gives_its_strokes_and_faults";

/// Issue 15's budget for the per-sample work (interrupt + estimator step).
pub const MEAN_TARGET: f64 = 250.0;
pub const MAX_TARGET: u64 = 400;

/// A timer figure may miss the trace's by at most this (instructions per call).
const AGREEMENT: f64 = 0.01;

/// What one measurement found.
pub struct StreamBench {
    pub rate_hz: f64,
    pub samples: usize,
    pub state_bytes: u64,
    /// Instructions per call from the timer, empty call subtracted.
    pub timer_mean: f64,
    /// Traced length of the empty call.
    pub empty: u64,
    /// Traced length of every call, in stream order.
    pub counts: Vec<u64>,
    /// What happened on each sample (see [`causes`]).
    pub causes: Vec<String>,
    pub code: Code,
}

/// Bytes of code reachable from the entry points.
pub struct Code {
    /// Reachable from `bench_stream_push` (the per-sample step), by function.
    pub push: Vec<(String, u64)>,
    /// Reachable from any entry point of the API, by function.
    pub api: Vec<(String, u64)>,
}

/// The whole measurement: writes the stream, builds and runs the image, parses the
/// trace, writes `stream.json` into `dir`.
pub fn run(dir: &Path, timeout: Duration) -> Result<StreamBench> {
    let stream = dir.join("stream.bin");
    write_stream(&stream)?;
    let elf = build(&stream, dir)?;
    let plain = dir.join("qemu-stream.txt");
    run_qemu_with(&[], &elf, &plain, timeout)?;
    let listing = read(&plain)?;
    let header = Header::parse(&listing)
        .ok_or_else(|| Failure::new(format!("{}: no complete output", plain.display())))?;
    let traced = dir.join("qemu-stream-trace.txt");
    let trace = trace(&elf, &traced, timeout)?;
    if read(&traced)? != listing.replace(&header.timer_line, "") {
        return Err(Failure::new(format!(
            "the traced run printed otherwise than the plain one: {} vs {}",
            traced.display(),
            plain.display()
        )));
    }
    if trace.counts.len() != header.samples {
        return Err(Failure::new(format!(
            "the trace shows {} calls from {LOOP}, the stream has {} samples",
            trace.counts.len(),
            header.samples
        )));
    }
    let empty = trace
        .empty
        .ok_or_else(|| Failure::new(format!("the trace shows no call of {EMPTY}")))?;
    let traced_mean = mean(&trace.counts) - empty as f64;
    if (traced_mean - header.timer_mean).abs() > AGREEMENT {
        return Err(Failure::new(format!(
            "the timer counts {:.3} instructions per sample, the trace {traced_mean:.3} \
             ({:.3} - {empty})",
            header.timer_mean,
            mean(&trace.counts)
        )));
    }
    let bench = StreamBench {
        rate_hz: header.rate_hz,
        samples: header.samples,
        state_bytes: header.state_bytes,
        timer_mean: header.timer_mean,
        empty,
        causes: causes(header.rate_hz, header.samples, &header.marks),
        counts: trace.counts,
        code: code_size(&elf)?,
    };
    let json_path = dir.join("stream.json");
    let text = serde_json::to_string_pretty(&bench.json()).expect("JSON values serialise");
    std::fs::write(&json_path, text)
        .map_err(|e| Failure::new(format!("writing {}: {e}", json_path.display())))?;
    println!("{}", bench.console());
    println!("xtask bench: wrote {}", json_path.display());
    bench.record()?;
    Ok(bench)
}

/// `cause` as a figure key's part: `block end, measuring follow-through` →
/// `block-end-measuring-follow-through`.
fn slug(cause: &str) -> String {
    let mut out = String::new();
    for c in cause.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('-') {
            out.push('-');
        }
    }
    out.trim_matches('-').to_string()
}

/// Runs the sensors test that writes the bench stream into `path`.
fn write_stream(path: &Path) -> Result {
    let _ = std::fs::remove_file(path);
    cmd::run(
        cmd::cargo()
            .args([
                "test",
                "-p",
                "cuesight-sensors",
                "--test",
                "streaming",
                "--",
            ])
            .args(["--exact", STREAM_TEST])
            .env("CUESIGHT_BENCH_STREAM", path),
    )?;
    if !path.is_file() {
        return Err(Failure::new(format!(
            "{STREAM_TEST} did not write {}",
            path.display()
        )));
    }
    Ok(())
}

/// The firmware's `-C llvm-args=-inline-threshold=N` flag, from its cargo config.
fn firmware_inline_flag() -> Result<String> {
    let config = cmd::firmware_dir().join(".cargo").join("config.toml");
    let text = read(&config)?;
    text.lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .find_map(|l| {
            let at = l.find("llvm-args=-inline-threshold=")?;
            let value: String = l[at..]
                .chars()
                .take_while(|c| *c != '"' && *c != '\'' && !c.is_whitespace())
                .collect();
            Some(value)
        })
        .ok_or_else(|| {
            Failure::new(format!(
                "{}: no llvm-args=-inline-threshold flag",
                config.display()
            ))
        })
}

/// Builds the image with `stream` baked in, in the firmware's configuration; returns a
/// copy of the ELF in `dir`.
fn build(stream: &Path, dir: &Path) -> Result<PathBuf> {
    let flag = firmware_inline_flag()?;
    cmd::run(
        cmd::cargo()
            .args(["build", "--bin", BIN, "--profile", PROFILE, "--config"])
            .arg(format!(
                "target.{}.rustflags=[\"-C\", \"{flag}\"]",
                tools::TARGET
            ))
            .env("CUESIGHT_BENCH_STREAM", stream)
            .current_dir(bench_firmware_dir()),
    )?;
    let built = target_dir().join(tools::TARGET).join(PROFILE).join(BIN);
    let elf = dir.join(format!("{BIN}.elf"));
    std::fs::copy(&built, &elf)
        .map_err(|e| Failure::new(format!("copying {}: {e}", built.display())))?;
    Ok(elf)
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("reading {}: {e}", path.display())))
}

fn mean(values: &[u64]) -> f64 {
    values.iter().sum::<u64>() as f64 / values.len().max(1) as f64
}

/// The plain run's output.
struct Header {
    rate_hz: f64,
    samples: usize,
    state_bytes: u64,
    timer_mean: f64,
    /// The `stream-timer` line and its newline (the traced run does not print it).
    timer_line: String,
    /// `(sample, what)` of the `stream-mark` lines.
    marks: Vec<(usize, String)>,
}

impl Header {
    fn parse(listing: &str) -> Option<Self> {
        let mut fields = listing
            .lines()
            .find_map(|l| l.strip_prefix("stream "))?
            .split(' ');
        let rate_hz = f64::from(f32::from_bits(
            u32::from_str_radix(fields.next()?, 16).ok()?,
        ));
        let samples = fields.next()?.parse().ok()?;
        let state_bytes = fields.next()?.parse().ok()?;
        let timer = listing.lines().find(|l| l.starts_with("stream-timer "))?;
        let numbers: Vec<f64> = timer
            .split(' ')
            .skip(1)
            .filter_map(|n| n.parse().ok())
            .collect();
        let [timed, ticks, empty] = numbers[..] else {
            return None;
        };
        let marks = listing
            .lines()
            .filter_map(|l| {
                let mut f = l.strip_prefix("stream-mark ")?.split(' ');
                Some((f.next()?.parse().ok()?, f.next()?.to_string()))
            })
            .collect();
        listing.lines().any(|l| l == "end").then(|| Self {
            rate_hz,
            samples,
            state_bytes,
            timer_mean: (ticks - empty) * INSTRUCTIONS_PER_TICK / timed,
            timer_line: format!("{timer}\n"),
            marks,
        })
    }
}

/// What the trace showed.
struct Trace {
    /// Length of every call of [`ROOT`] from [`LOOP`], in order.
    counts: Vec<u64>,
    /// Length of a call of [`EMPTY`].
    empty: Option<u64>,
}

/// Runs the image in trace mode with every executed instruction logged on QEMU's stderr
/// and measures each call of the root as it streams past (gigabytes: never stored).
fn trace(elf: &Path, listing: &Path, timeout: Duration) -> Result<Trace> {
    let out = std::fs::File::create(listing)
        .map_err(|e| Failure::new(format!("creating {}: {e}", listing.display())))?;
    let mut qemu = Command::new("qemu-system-arm");
    let (options, kernel) = QEMU_ARGS.split_at(QEMU_ARGS.len() - 1);
    qemu.args(options)
        .args(["-semihosting-config", "arg=stream-count,arg=trace"])
        .args(one_insn_per_tb())
        .args(["-d", "exec,nochain", "-D", "/dev/stderr"])
        .args(kernel)
        .arg(elf);
    println!(
        "$ {} > {} (trace parsed from stderr)",
        cmd::display(&qemu),
        listing.display()
    );
    let started = Instant::now();
    let mut child = qemu
        .stdin(Stdio::null())
        .stdout(out)
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start qemu-system-arm: {e}")))?;
    let stderr = child.stderr.take().expect("stderr is piped");
    let parser = std::thread::spawn(move || parse_trace(BufReader::with_capacity(1 << 20, stderr)));
    let deadline = started + timeout;
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Ok(status),
            Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(100)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                break Err(Failure {
                    message: format!(
                        "the traced QEMU run did not exit within {} s and was killed",
                        timeout.as_secs()
                    ),
                    code: 124,
                });
            }
        }
    };
    let parsed = parser
        .join()
        .map_err(|_| Failure::new("the trace parser panicked"))?;
    let (trace, other) = parsed?;
    let status = status?;
    if !status.success() {
        return Err(Failure::new(format!(
            "the traced QEMU run failed ({status}): {}",
            other.join("\n")
        )));
    }
    println!(
        "xtask bench: traced {} calls in {:.0} s",
        trace.counts.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(trace)
}

/// Call lengths from a `-d exec,nochain` log with one instruction per block: a call
/// starts at a line in [`ROOT`] (or [`EMPTY`]) and ends at the next line in a caller.
/// Returns the calls and the log's other lines (QEMU's messages).
fn parse_trace(log: impl std::io::BufRead) -> Result<(Trace, Vec<String>)> {
    let mut trace = Trace {
        counts: Vec::new(),
        empty: None,
    };
    let mut other = Vec::new();
    // Inside a call: of the root (true) or the empty function, and its length so far.
    let mut inside: Option<(bool, u64)> = None;
    let mut log = log;
    let mut buffer = Vec::with_capacity(256);
    loop {
        buffer.clear();
        let read = log
            .read_until(b'\n', &mut buffer)
            .map_err(|e| Failure::new(format!("reading the trace: {e}")))?;
        if read == 0 {
            break;
        }
        let line = buffer.strip_suffix(b"\n").unwrap_or(&buffer);
        // `Trace 0: 0x… [……/pc/……/……] symbol`: the symbol follows the last "] ".
        let mut at = line.len();
        while at >= 2 && !(line[at - 2] == b']' && line[at - 1] == b' ') {
            at -= 1;
        }
        if at < 2 {
            if !line.is_empty() && other.len() < 20 {
                other.push(String::from_utf8_lossy(line).into_owned());
            }
            continue;
        }
        let symbol = &line[at..];
        match &mut inside {
            Some((root, length)) => {
                if symbol == LOOP.as_bytes() || symbol == TIMED.as_bytes() {
                    if *root && symbol == LOOP.as_bytes() {
                        trace.counts.push(*length);
                    } else if !*root {
                        trace.empty = Some(*length);
                    }
                    inside = None;
                } else {
                    *length += 1;
                }
            }
            None if symbol == ROOT.as_bytes() => inside = Some((true, 1)),
            None if symbol == EMPTY.as_bytes() => inside = Some((false, 1)),
            None => {}
        }
    }
    Ok((trace, other))
}

/// What each sample did, from the image's `stream-mark` lines and the block length:
/// the event on it (`impact: stroke`, `impact: not-forward`, …), `rest end` (a stroke
/// starts integrating), `rest end (re-anchor)` (a later rest replaces its origin),
/// `block end` (every 25 ms), joined with ` + `; otherwise `integrating` (a stroke is
/// running) or `idle`. A `follow-through` report (`follow-through decided`) relabels
/// the `idle` samples and block ends since the stroke before it: `idle, measuring
/// follow-through`, `block end, measuring follow-through`.
pub fn causes(rate_hz: f64, samples: usize, marks: &[(usize, String)]) -> Vec<String> {
    // `sensors/src/streaming/config.rs`: `samples(0.025, rate, 8)`, in f32.
    let block = (((0.025f32 * rate_hz as f32) + 0.5) as usize).max(8);
    let marks: BTreeMap<usize, &str> = marks.iter().map(|(i, w)| (*i, w.as_str())).collect();
    let mut integrating = false;
    let mut causes: Vec<String> = (0..samples)
        .map(|i| {
            let mut parts = Vec::new();
            match marks.get(&i) {
                Some(&"follow-through") => parts.push("follow-through decided".to_string()),
                Some(&"rest-end") => parts.push("rest end".to_string()),
                Some(&"re-anchor") => parts.push("rest end (re-anchor)".to_string()),
                Some(&"stroke-end") => parts.push("stroke dropped".to_string()),
                Some(event) => parts.push(format!("impact: {event}")),
                None => {}
            }
            if (i + 1) % block == 0 {
                parts.push("block end".into());
            }
            let cause = if parts.is_empty() {
                if integrating { "integrating" } else { "idle" }.to_string()
            } else {
                parts.join(" + ")
            };
            match marks.get(&i) {
                Some(&"rest-end" | &"re-anchor") => integrating = true,
                Some(_) => integrating = false,
                None => {}
            }
            cause
        })
        .collect();
    let mut stroke = None;
    for (&i, &what) in &marks {
        match what {
            "stroke" => stroke = Some(i),
            "follow-through" => {
                for cause in causes.iter_mut().take(i).skip(stroke.map_or(i, |s| s + 1)) {
                    if cause == "idle" || cause == "block end" {
                        cause.push_str(", measuring follow-through");
                    }
                }
            }
            _ => {}
        }
    }
    causes
}

/// Functions reachable from each entry point, with their sizes (symbol table).
fn code_size(elf: &Path) -> Result<Code> {
    let objdump = disasm::llvm_objdump()?;
    let run = |args: &[&str]| {
        probe(Command::new(&objdump).args(args).arg(elf)).ok_or_else(|| {
            Failure::new(format!(
                "{} {} failed on {}",
                objdump.display(),
                args.join(" "),
                elf.display()
            ))
        })
    };
    let listing = run(&["--disassemble", "--demangle", "--no-show-raw-insn"])?;
    let symbols = run(&["--syms", "--demangle"])?;
    let functions = disasm::parse(&listing);
    // `00000a00 g     F .text	00000050 name`: function symbols' sizes by address.
    let mut sizes: BTreeMap<u64, u64> = BTreeMap::new();
    for line in symbols.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        let Some(f) = fields.iter().position(|f| *f == "F") else {
            continue;
        };
        let (Some(address), Some(size)) = (
            fields.first().and_then(|a| u64::from_str_radix(a, 16).ok()),
            fields
                .get(f + 2)
                .and_then(|s| u64::from_str_radix(s, 16).ok()),
        ) else {
            continue;
        };
        sizes.insert(address & !1, size);
    }
    let owner = |address: u64| functions.range(..=address).next_back().map(|(a, _)| *a);
    let reach = |roots: &[&str]| -> Result<Vec<(String, u64)>> {
        let mut queue = Vec::new();
        for root in roots {
            let found = functions
                .iter()
                .find(|(_, f)| f.name == *root)
                .map(|(a, _)| *a)
                .ok_or_else(|| {
                    Failure::new(format!("no function `{root}` in {}", elf.display()))
                })?;
            queue.push(found);
        }
        let mut reached: BTreeSet<u64> = queue.iter().copied().collect();
        while let Some(at) = queue.pop() {
            for (_, mnemonic, operands) in &functions[&at].instructions {
                if !disasm::is_branch(mnemonic) {
                    continue;
                }
                if let Some(callee) = disasm::target(operands).and_then(owner) {
                    if reached.insert(callee) {
                        queue.push(callee);
                    }
                }
            }
        }
        let mut list: Vec<(String, u64)> = reached
            .iter()
            .map(|a| {
                (
                    functions[a].name.clone(),
                    sizes.get(a).copied().unwrap_or(0),
                )
            })
            .collect();
        list.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        Ok(list)
    };
    Ok(Code {
        push: reach(&[ROOT])?,
        api: reach(&API)?,
    })
}

/// Per-cause statistics: `(cause, samples, mean, max, first sample at the max)`, by
/// descending max.
fn by_cause(counts: &[u64], causes: &[String]) -> Vec<(String, usize, f64, u64, usize)> {
    let mut groups: BTreeMap<&str, (usize, u64, u64, usize)> = BTreeMap::new();
    for (i, (&n, cause)) in counts.iter().zip(causes).enumerate() {
        let g = groups.entry(cause).or_insert((0, 0, 0, i));
        g.0 += 1;
        g.1 += n;
        if n > g.2 {
            g.2 = n;
            g.3 = i;
        }
    }
    let mut rows: Vec<_> = groups
        .into_iter()
        .map(|(c, (k, sum, max, at))| (c.to_string(), k, sum as f64 / k as f64, max, at))
        .collect();
    rows.sort_by(|a, b| b.3.cmp(&a.3).then_with(|| a.0.cmp(&b.0)));
    rows
}

fn total(functions: &[(String, u64)]) -> u64 {
    functions.iter().map(|(_, s)| s).sum()
}

/// A memory routine every firmware links anyway (`memcpy`, `memset` and their AEABI
/// entry points): not counted as the estimator's own code.
fn shared(name: &str) -> bool {
    name.starts_with("__aeabi_mem") || name.starts_with("compiler_builtins::mem::")
}

/// [`total`] without the [`shared`] routines.
fn own(functions: &[(String, u64)]) -> u64 {
    functions
        .iter()
        .filter(|(name, _)| !shared(name))
        .map(|(_, s)| s)
        .sum()
}

impl StreamBench {
    /// Mean, max, the first sample at the max and its cause.
    pub fn summary(&self) -> (f64, u64, usize, &str) {
        let (at, max) =
            self.counts.iter().enumerate().fold(
                (0, 0),
                |(ai, am), (i, &n)| if n > am { (i, n) } else { (ai, am) },
            );
        (mean(&self.counts), max, at, &self.causes[at])
    }

    fn json(&self) -> Value {
        let (mean, max, at, cause) = self.summary();
        let functions = |list: &[(String, u64)]| -> Vec<Value> {
            list.iter()
                .map(|(name, bytes)| json!({"function": name, "bytes": bytes}))
                .collect()
        };
        json!({
            "rate_hz": self.rate_hz,
            "samples": self.samples,
            "state_bytes": self.state_bytes,
            "method": "QEMU mps2-an386 -icount shift=0, instruction trace (-d exec,nochain, one \
                       instruction per block): each call of bench_stream_push from its first \
                       instruction to its return, callees included, the caller's bl not",
            "instructions": {
                "mean": mean,
                "max": max,
                "max_sample": at,
                "max_cause": cause,
                "timer_mean_minus_empty": self.timer_mean,
                "empty_call": self.empty,
                "by_cause": by_cause(&self.counts, &self.causes).iter().map(|(c, k, m, x, i)| json!({
                    "cause": c, "samples": k, "mean": m, "max": x, "max_sample": i,
                })).collect::<Vec<_>>(),
            },
            "targets": {"mean": MEAN_TARGET, "max": MAX_TARGET},
            "code_bytes": {
                "push_raw": total(&self.code.push),
                "api": total(&self.code.api),
                "push_raw_own": own(&self.code.push),
                "api_own": own(&self.code.api),
                "push_raw_functions": functions(&self.code.push),
                "api_functions": functions(&self.code.api),
            },
        })
    }

    /// The console summary.
    /// Records the per-sample table of docs/sensors.md §11 (`bench-stream-CAUSE-count`,
    /// `-mean`, `-max`; `CAUSE` `all` for every sample): its `docs:figure` blocks,
    /// checked by `cargo xtask docs --check` after this command (a step of `cargo xtask
    /// test`, so CI runs both).
    fn record(&self) -> Result {
        const COMMAND: &str = "cargo xtask bench --stream-only";
        let (mean, max, _, _) = self.summary();
        let mut rows = vec![("all".to_string(), self.counts.len(), mean, max)];
        for (cause, samples, mean, max, _) in by_cause(&self.counts, &self.causes) {
            rows.push((slug(&cause), samples, mean, max));
        }
        let record = |key: &str, value: &str| {
            cuesight_figures::record_with(key, &value, COMMAND)
                .map_err(|e| Failure::new(format!("recording figure {key}: {e}")))
        };
        for (cause, samples, mean, max) in rows {
            for (what, value) in [
                ("count", cuesight_figures::thousands(samples)),
                ("mean", format!("{mean:.1}")),
                ("max", max.to_string()),
            ] {
                record(&format!("bench-stream-{cause}-{what}"), &value)?;
            }
        }
        // The code sizes of §11 (bytes reachable from the entry points; `own`: without
        // the memcpy/memset routines every firmware links anyway).
        for (key, bytes) in [
            ("bench-stream-code-push-raw", total(&self.code.push)),
            ("bench-stream-code-api", total(&self.code.api)),
            ("bench-stream-code-api-own", own(&self.code.api)),
        ] {
            record(key, &cuesight_figures::thousands(bytes))?;
        }
        Ok(())
    }

    pub fn console(&self) -> String {
        let (mean, max, at, cause) = self.summary();
        let mut text = format!(
            "streaming estimator on the Cortex-M4F ({} samples at {} Hz, state {} B):\n  \
             per sample: mean {mean:.1} instructions (timer: {:.1} + empty call {}), max {max} \
             at sample {at} ({cause}); issue 15: <= {MEAN_TARGET} mean, <= {MAX_TARGET} max\n",
            self.samples, self.rate_hz, self.state_bytes, self.timer_mean, self.empty
        );
        for (c, k, m, x, i) in by_cause(&self.counts, &self.causes) {
            text.push_str(&format!(
                "    {c:<40} {k:>7} samples  mean {m:>6.1}  max {x:>4} (sample {i})\n"
            ));
        }
        text.push_str(&format!(
            "  code: push_raw {} B reachable ({} functions; {} B without memcpy/memset), \
             whole API (new, push_raw, finish) {} B ({} B without)\n",
            total(&self.code.push),
            self.code.push.len(),
            own(&self.code.push),
            total(&self.code.api),
            own(&self.code.api)
        ));
        for (name, bytes) in &self.code.api {
            text.push_str(&format!("    {bytes:>6} B  {name}\n"));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calls_are_told_apart_by_caller() {
        let log = "\
Trace 0: 0x1 [0/1/0/0] bench_stream_loop
Trace 0: 0x1 [0/2/0/0] bench_stream_push
Trace 0: 0x1 [0/3/0/0] helper
Trace 0: 0x1 [0/4/0/0] bench_stream_push
Trace 0: 0x1 [0/5/0/0] bench_stream_loop
Trace 0: 0x1 [0/6/0/0] bench_stream_push
Trace 0: 0x1 [0/7/0/0] bench_stream_timed
Trace 0: 0x1 [0/8/0/0] bench_stream_empty
Trace 0: 0x1 [0/9/0/0] bench_stream_empty
Trace 0: 0x1 [0/a/0/0] bench_stream_timed
qemu: a message
Trace 0: 0x1 [0/b/0/0] bench_stream_push
Trace 0: 0x1 [0/c/0/0] bench_stream_loop
";
        let (trace, other) = parse_trace(log.as_bytes()).unwrap();
        assert_eq!(trace.counts, [3, 1]);
        assert_eq!(trace.empty, Some(2));
        assert_eq!(other, ["qemu: a message"]);
    }

    #[test]
    fn memory_routines_are_shared() {
        let list = [
            ("__aeabi_memcpy4".to_string(), 156),
            ("compiler_builtins::mem::memcpy".to_string(), 730),
            ("__aeabi_l2f".to_string(), 120),
            ("bench_stream_push".to_string(), 500),
        ];
        assert_eq!((total(&list), own(&list)), (1506, 620));
    }

    #[test]
    fn causes_follow_the_marks_and_blocks() {
        // 500 Hz: 13-sample blocks (0.025 * 500 + 0.5 = 13).
        let marks = [(3, "rest-end".to_string()), (12, "stroke".to_string())];
        let causes = causes(500.0, 26, &marks);
        assert_eq!(causes[0], "idle");
        assert_eq!(causes[3], "rest end");
        assert_eq!(causes[4], "integrating");
        assert_eq!(causes[12], "impact: stroke + block end");
        assert_eq!(causes[13], "idle");
        assert_eq!(causes[25], "block end");
        let marks = [
            (12, "stroke".to_string()),
            (26, "follow-through".to_string()),
        ];
        let follow = super::causes(500.0, 40, &marks);
        assert_eq!(follow[13], "idle, measuring follow-through");
        assert_eq!(follow[25], "block end, measuring follow-through");
        assert_eq!(follow[26], "follow-through decided");
        assert_eq!(follow[27], "idle");
        assert_eq!(follow[38], "block end");
    }
}
