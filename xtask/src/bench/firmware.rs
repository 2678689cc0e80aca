//! Builds `bench-firmware/` per backend and profile, runs each image under QEMU with
//! `-icount shift=0`, and turns its timer readings into instruction counts.

use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::thread;
use std::time::{Duration, Instant};

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// Instructions per tick of the 25 MHz CMSDK timer when QEMU runs one instruction per
/// nanosecond of virtual time (`-icount shift=0`). The calibration blocks check it.
pub const INSTRUCTIONS_PER_TICK: f64 = 40.0;

/// A calibration block may miss its known length by at most this (instructions).
const CALIBRATION_TOLERANCE: f64 = 0.5;

const BIN: &str = "cuesight-bench";

/// The QEMU command line (machine and CPU as in `firmware/`, plus instruction counting).
pub const QEMU_ARGS: [&str; 10] = [
    "-machine",
    "mps2-an386",
    "-cpu",
    "cortex-m4",
    "-nographic",
    "-icount",
    "shift=0",
    "-semihosting-config",
    "enable=on,target=native",
    "-kernel",
];

/// One image of the bench firmware.
pub struct Build {
    /// Math backend (cargo feature of the core).
    pub backend: &'static str,
    /// Cargo profile (`release`: opt-level 3; `release-s`: opt-level "s", as shipped).
    pub profile: &'static str,
    /// Whether the image also prints every outcome on the whole grid.
    pub outcomes: bool,
}

/// Every image measured: both backends at opt-level 3 with outcomes, and at
/// opt-level "s" for the instruction counts only.
pub const BUILDS: [Build; 4] = [
    Build {
        backend: "libm",
        profile: "release",
        outcomes: true,
    },
    Build {
        backend: "micromath",
        profile: "release",
        outcomes: true,
    },
    Build {
        backend: "libm",
        profile: "release-s",
        outcomes: false,
    },
    Build {
        backend: "micromath",
        profile: "release-s",
        outcomes: false,
    },
];

/// A calibration block as measured.
pub struct Calibration {
    pub name: String,
    pub expected: f64,
    pub measured: f64,
}

/// What one QEMU run measured.
pub struct Run {
    pub build: &'static Build,
    /// The QEMU output (kept: the error scoring reads its `outcome` lines).
    pub listing: PathBuf,
    pub calibration: Vec<Calibration>,
    /// Instructions per prediction on each counted scene, by (model label, precision),
    /// in the order the firmware printed them.
    pub counts: Vec<((String, String), Vec<f64>)>,
}

/// The bench firmware's directory (its own workspace, like `firmware/`).
pub fn bench_firmware_dir() -> PathBuf {
    cmd::root().join("bench-firmware")
}

/// The bench firmware's target directory (honours `CARGO_TARGET_DIR`).
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => bench_firmware_dir().join(dir),
        None => bench_firmware_dir().join("target"),
    }
}

/// Builds every image with `scenes` baked in, runs them (in parallel: the counts are
/// virtual time, so host load cannot change them) and parses the results.
pub fn measure(scenes: &Path, dir: &Path, timeout: Duration) -> Result<Vec<Run>> {
    let mut images = Vec::new();
    for build in &BUILDS {
        let mut features = build.backend.to_string();
        if !build.outcomes {
            features.push_str(",counts-only");
        }
        cmd::run(
            cmd::cargo()
                .args(["build", "--bin", BIN, "--profile", build.profile])
                .args(["--no-default-features", "--features", &features])
                .env("CUESIGHT_BENCH_SCENES", scenes)
                .current_dir(bench_firmware_dir()),
        )?;
        let built = target_dir()
            .join(tools::TARGET)
            .join(build.profile)
            .join(BIN);
        let stem = format!("{BIN}-{}-{}", build.backend, build.profile);
        let elf = dir.join(format!("{stem}.elf"));
        std::fs::copy(&built, &elf)
            .map_err(|e| Failure::new(format!("copying {}: {e}", built.display())))?;
        images.push((
            build,
            elf,
            dir.join(format!("qemu-{}-{}.txt", build.backend, build.profile)),
        ));
    }
    let qemu_version = cmd::probe(Command::new("qemu-system-arm").arg("--version"))
        .and_then(|v| v.lines().next().map(str::to_string))
        .unwrap_or_default();
    println!(
        "xtask bench: {qemu_version}; running {} images",
        images.len()
    );
    let started = Instant::now();
    let results: Vec<Result> = thread::scope(|s| {
        let handles: Vec<_> = images
            .iter()
            .map(|(_, elf, listing)| s.spawn(move || run_qemu(elf, listing, timeout)))
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(Failure::new("a QEMU thread panicked")))
            })
            .collect()
    });
    println!(
        "xtask bench: QEMU runs done in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let mut runs = Vec::new();
    for ((build, _, listing), result) in images.into_iter().zip(results) {
        result?;
        runs.push(parse(build, listing)?);
    }
    Ok(runs)
}

/// Records a figure the bench-firmware step of `cargo xtask test` measures, for
/// `cargo xtask docs --check`, which runs after it.
pub(super) fn record_figure(key: &str, value: &dyn std::fmt::Display) -> Result {
    cuesight_figures::record_with(key, value, "cargo xtask test --only bench-firmware")
        .map_err(|e| Failure::new(format!("recording figure {key}: {e}")))
}

/// Builds the release image of `bench-firmware`'s binary `bin`, runs it in QEMU and
/// returns what it printed (kept in `target/<bin>.txt` of the bench firmware).
pub(super) fn run_probe(bin: &str, timeout: Duration) -> Result<String> {
    tools::ensure_qemu()?;
    cmd::run(
        cmd::cargo()
            .args(["build", "--release", "--bin", bin])
            .current_dir(bench_firmware_dir()),
    )?;
    let elf = target_dir().join(tools::TARGET).join("release").join(bin);
    let listing = target_dir().join(format!("{bin}.txt"));
    run_qemu_with(&[], &elf, &listing, timeout)?;
    std::fs::read_to_string(&listing)
        .map_err(|e| Failure::new(format!("reading {}: {e}", listing.display())))
}

/// Runs `elf` in QEMU with its stdout written to `listing`; fails on a non-zero exit
/// or after `timeout`.
fn run_qemu(elf: &Path, listing: &Path, timeout: Duration) -> Result {
    run_qemu_with(&[], elf, listing, timeout)
}

/// As [`run_qemu`], with `extra` QEMU options.
pub(super) fn run_qemu_with(
    extra: &[&str],
    elf: &Path,
    listing: &Path,
    timeout: Duration,
) -> Result {
    let out = File::create(listing)
        .map_err(|e| Failure::new(format!("creating {}: {e}", listing.display())))?;
    let mut qemu = Command::new("qemu-system-arm");
    let (options, kernel) = QEMU_ARGS.split_at(QEMU_ARGS.len() - 1);
    qemu.args(options).args(extra).args(kernel).arg(elf);
    println!("$ {} > {}", cmd::display(&qemu), listing.display());
    let mut child = qemu
        .stdin(Stdio::null())
        .stdout(out)
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start qemu-system-arm: {e}")))?;
    let deadline = Instant::now() + timeout;
    loop {
        match child.try_wait() {
            Ok(Some(status)) => {
                return cmd::check(&format!("qemu-system-arm {}", elf.display()), status)
            }
            Ok(None) if Instant::now() < deadline => thread::sleep(Duration::from_millis(50)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(Failure {
                    message: format!(
                        "QEMU ({}) did not exit within {} s and was killed",
                        elf.display(),
                        timeout.as_secs()
                    ),
                    code: 124,
                });
            }
        }
    }
}

/// QEMU's option for one guest instruction per translation block: `-singlestep` before
/// 8.1, `-accel tcg,one-insn-per-tb=on` since (the old one is gone in 9.0).
pub fn one_insn_per_tb() -> Vec<&'static str> {
    insn_option(&cmd::probe(Command::new("qemu-system-arm").arg("--version")).unwrap_or_default())
}

/// [`one_insn_per_tb`] for the output of `qemu-system-arm --version`.
fn insn_option(version: &str) -> Vec<&'static str> {
    let number = version
        .split_whitespace()
        .skip_while(|w| *w != "version")
        .nth(1)
        .unwrap_or_default();
    let mut parts = number.split('.').map(|p| p.parse::<u32>().unwrap_or(0));
    let (major, minor) = (parts.next().unwrap_or(0), parts.next().unwrap_or(0));
    if (major, minor) >= (8, 1) {
        vec!["-accel", "tcg,one-insn-per-tb=on"]
    } else {
        vec!["-singlestep"]
    }
}

/// The timer method against an instruction trace, on one `KimGrip` prediction.
pub struct TraceCheck {
    /// Instructions per prediction from the timer (prediction minus empty call).
    pub timer: f64,
    /// Traced instructions of one call of the measured function (most frequent length).
    pub call: u64,
    /// Traced instructions of one call of the empty function.
    pub empty: u64,
}

/// Runs `bench-firmware`'s `trace-check` image with QEMU logging every instruction
/// (one per translation block, [`one_insn_per_tb`], and `-d exec,nochain`) and checks that the timer's count
/// equals the traced call length minus the traced empty call.
pub fn trace_check(scenes: &Path, dir: &Path, timeout: Duration) -> Result<TraceCheck> {
    const TRACE_BIN: &str = "trace-check";
    cmd::run(
        cmd::cargo()
            .args(["build", "--release", "--bin", TRACE_BIN])
            // Same value as the bench builds, so build.rs does not run again.
            .env("CUESIGHT_BENCH_SCENES", scenes)
            .current_dir(bench_firmware_dir()),
    )?;
    let elf = target_dir()
        .join(tools::TARGET)
        .join("release")
        .join(TRACE_BIN);
    let listing = dir.join("qemu-trace-check.txt");
    let trace = dir.join("trace-check.log");
    let trace_arg = trace.display().to_string();
    let mut options = one_insn_per_tb();
    options.extend(["-d", "exec,nochain", "-D", &trace_arg]);
    run_qemu_with(&options, &elf, &listing, timeout)?;
    let text = std::fs::read_to_string(&listing)
        .map_err(|e| Failure::new(format!("reading {}: {e}", listing.display())))?;
    let numbers: Vec<f64> = text
        .lines()
        .find_map(|l| l.strip_prefix("trace-check "))
        .map(|l| l.split(' ').filter_map(|n| n.parse().ok()).collect())
        .unwrap_or_default();
    let [reps, ticks, empty_ticks] = numbers[..] else {
        return Err(Failure::new(format!(
            "{}: no trace-check line",
            listing.display()
        )));
    };
    let timer = (ticks - empty_ticks) * INSTRUCTIONS_PER_TICK / reps;
    let lengths = call_lengths(&trace)?;
    let _ = std::fs::remove_file(&trace); // tens of megabytes
    let mode = |calls: &BTreeMap<u64, usize>| {
        calls
            .iter()
            .max_by_key(|(_, n)| **n)
            .map(|(length, _)| *length)
    };
    let (Some(call), Some(empty)) = (mode(&lengths.0), mode(&lengths.1)) else {
        return Err(Failure::new("the instruction trace shows no measured call"));
    };
    let check = TraceCheck { timer, call, empty };
    println!(
        "xtask bench: trace check: timer {timer:.2} instructions, trace {call} - {empty} = {}",
        call - empty
    );
    if (timer - (call - empty) as f64).abs() > CALIBRATION_TOLERANCE {
        return Err(Failure::new(format!(
            "trace check failed: the timer counts {timer:.2} instructions per prediction, \
             the instruction trace {call} - {empty} = {}",
            call - empty
        )));
    }
    Ok(check)
}

/// Lengths of the calls that `count::ticks` makes, from a `-d exec` trace of one
/// instruction per block: (measured function, empty function), length -> calls.
fn call_lengths(trace: &Path) -> Result<(BTreeMap<u64, usize>, BTreeMap<u64, usize>)> {
    use std::io::BufRead as _;
    let file =
        File::open(trace).map_err(|e| Failure::new(format!("opening {}: {e}", trace.display())))?;
    let (mut calls, mut empties) = (BTreeMap::new(), BTreeMap::new());
    // Inside a call of the measured (true) or the empty (false) function, and its length.
    let mut inside: Option<(bool, u64)> = None;
    for line in std::io::BufReader::new(file).lines() {
        let line = line.map_err(|e| Failure::new(format!("{}: {e}", trace.display())))?;
        let Some((_, symbol)) = line.rsplit_once("] ") else {
            continue;
        };
        // Legacy and v0 manglings both contain the path segments `5count5ticks`.
        if symbol.contains("5count5ticks") {
            if let Some((measured, length)) = inside.take() {
                *(if measured { &mut calls } else { &mut empties })
                    .entry(length)
                    .or_insert(0) += 1;
            }
            continue;
        }
        match &mut inside {
            Some((_, length)) => *length += 1,
            None if symbol.trim() == "bench_trace_root" => inside = Some((true, 1)),
            None if symbol.contains("5count5empty") => inside = Some((false, 1)),
            None => {}
        }
    }
    Ok((calls, empties))
}

/// Parses the `calibration` and `count` lines of a run, checks the calibration and
/// that the listing is complete.
fn parse(build: &'static Build, listing: PathBuf) -> Result<Run> {
    let text = std::fs::read_to_string(&listing)
        .map_err(|e| Failure::new(format!("reading {}: {e}", listing.display())))?;
    let at = |n: usize| format!("{}:{}", listing.display(), n + 1);
    let number = |s: &str, n: usize| -> Result<f64> {
        s.parse::<f64>()
            .map_err(|_| Failure::new(format!("{}: bad number {s:?}", at(n))))
    };
    let mut calibration = Vec::new();
    let mut counts: Vec<((String, String), Vec<f64>)> = Vec::new();
    let mut index: BTreeMap<(String, String), usize> = BTreeMap::new();
    let mut ended = false;
    for (n, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line.split(' ').collect();
        match fields[0] {
            "calibration" if fields.len() >= 6 => {
                let (expected, reps) = (number(fields[1], n)?, number(fields[2], n)?);
                let (block, empty) = (number(fields[3], n)?, number(fields[4], n)?);
                calibration.push(Calibration {
                    name: fields[5..].join(" "),
                    expected,
                    measured: (block - empty) * INSTRUCTIONS_PER_TICK / reps,
                });
            }
            "count" if fields.len() == 7 => {
                let key = (fields[1].to_string(), fields[2].to_string());
                let (reps, ticks, empty) = (
                    number(fields[4], n)?,
                    number(fields[5], n)?,
                    number(fields[6], n)?,
                );
                let slot = *index.entry(key.clone()).or_insert_with(|| {
                    counts.push((key, Vec::new()));
                    counts.len() - 1
                });
                counts[slot]
                    .1
                    .push((ticks - empty) * INSTRUCTIONS_PER_TICK / reps);
            }
            "end" => ended = true,
            _ => {}
        }
    }
    if !ended {
        return Err(Failure::new(format!(
            "{}: the bench firmware's output ends early (no `end` line)",
            listing.display()
        )));
    }
    if calibration.is_empty() || counts.is_empty() {
        return Err(Failure::new(format!(
            "{}: no calibration or count lines",
            listing.display()
        )));
    }
    for c in &calibration {
        if (c.measured - c.expected).abs() > CALIBRATION_TOLERANCE {
            return Err(Failure::new(format!(
                "calibration failed ({}, {} {}): '{}' should take {} instructions, measured {:.2}; \
                 QEMU is not counting one instruction per virtual nanosecond",
                listing.display(),
                build.backend,
                build.profile,
                c.name,
                c.expected,
                c.measured
            )));
        }
    }
    Ok(Run {
        build,
        listing,
        calibration,
        counts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn qemu_version_picks_the_option() {
        let old = "QEMU emulator version 7.2.22 (Debian 1:7.2+dfsg-7+deb12u18+b3)\nCopyright";
        assert_eq!(insn_option(old), ["-singlestep"]);
        let new = "QEMU emulator version 8.2.2 (Debian 1:8.2.2+ds-0ubuntu1)";
        assert_eq!(insn_option(new), ["-accel", "tcg,one-insn-per-tb=on"]);
        assert_eq!(
            insn_option("QEMU emulator version 10.0.0"),
            ["-accel", "tcg,one-insn-per-tb=on"]
        );
    }
}
