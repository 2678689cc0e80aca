//! `cargo xtask fuzz`: builds the cargo-fuzz targets of `fuzz/` (libFuzzer) and runs
//! each for a bounded time; any crash, panic, timeout or out-of-memory fails it. `cargo
//! xtask test` runs every target for [`DEFAULT_SECONDS`].
//!
//! * **Stable toolchain.** cargo-fuzz passes nightly-only flags to rustc
//!   (`-Zsanitizer=…`, `-Cllvm-args=-sanitizer-coverage-…` with `-Cpasses=sancov-module`)
//!   and CI has only the stable toolchain, so the build runs with `RUSTC_BOOTSTRAP=1`,
//!   which lets a stable rustc accept them. It is set for the cargo-fuzz process only.
//! * **No sanitizer** (`-s none`): the crates fuzzed deny `unsafe` code (core, link,
//!   device, sensors), so AddressSanitizer would find little, and the runs do about twice
//!   the executions without it. Debug assertions and overflow checks stay on (cargo-fuzz's default).
//! * **Corpora.** The committed seeds (`fuzz/corpus/<target>/`) are read only: libFuzzer
//!   writes what it finds into the first corpus directory it is given, a scratch one,
//!   `fuzz/corpus-run/<target>/` (git-ignored, kept between local runs), so a run never
//!   changes the tree. A crashing input goes to `fuzz/artifacts/<target>/` (git-ignored).
//! * **Output.** libFuzzer's full log goes to `fuzz/target/xtask-logs/<target>.log`; the
//!   console shows it without the per-input `NEW`/`REDUCE` lines, each line tagged with
//!   its target (two run at once), then a table of the executions per target.

use std::fs::{self, File};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// The fuzz targets, in the order they run (`fuzz/fuzz_targets/<name>.rs`).
pub const TARGETS: [&str; 4] = ["link_frame", "link_session", "shot_scene", "collide"];

/// Seconds each target runs for in `cargo xtask test`.
pub const DEFAULT_SECONDS: u64 = 60;

/// One input running longer than this (s) counts as a hang and fails the run.
const INPUT_TIMEOUT_SECS: u64 = 10;

/// Options of `cargo xtask fuzz`.
#[derive(clap::Args)]
pub struct Args {
    /// How long each target runs (s).
    #[arg(long, default_value_t = DEFAULT_SECONDS)]
    seconds: u64,
    /// Targets to run [default: all: link_frame, link_session, shot_scene, collide].
    #[arg(value_name = "TARGET")]
    targets: Vec<String>,
}

/// What one target's run reached.
struct Run {
    target: String,
    /// Inputs executed (libFuzzer's `stat::number_of_executed_units`).
    executions: Option<u64>,
    /// Wall-clock time of the run (s).
    seconds: f64,
    /// Executions per second (`exec/s:` of libFuzzer's last status line).
    rate: Option<u64>,
    /// Coverage counters hit (`cov:` of libFuzzer's last status line).
    coverage: Option<u64>,
    /// Inputs in the scratch corpus at the end (`corp:`).
    corpus: Option<u64>,
    /// Why it failed, if it did.
    failure: Option<Failure>,
}

/// `cargo xtask fuzz`: the chosen targets (all by default), each for `--seconds`.
pub fn run(args: &Args) -> Result {
    let targets: Vec<String> = if args.targets.is_empty() {
        TARGETS.iter().map(|t| t.to_string()).collect()
    } else {
        args.targets.clone()
    };
    if let Some(unknown) = targets.iter().find(|t| !TARGETS.contains(&t.as_str())) {
        return Err(Failure::new(format!(
            "unknown fuzz target {unknown:?}; the targets are {}",
            TARGETS.join(", ")
        )));
    }
    fuzz_targets(&targets, args.seconds)
}

/// The step of `cargo xtask test`: every target for [`DEFAULT_SECONDS`].
pub fn check() -> Result {
    let targets: Vec<String> = TARGETS.iter().map(|t| t.to_string()).collect();
    fuzz_targets(&targets, DEFAULT_SECONDS)
}

fn fuzz_targets(targets: &[String], seconds: u64) -> Result {
    tools::ensure_cargo_fuzz()?;
    tools::ensure_cxx()?;
    let started = Instant::now();
    // All targets at once (they share the harness library): cargo fuzz builds one target
    // or, without one, every target.
    cmd::run(&mut cargo_fuzz("build"))?;
    let build_secs = started.elapsed().as_secs_f64();
    println!("xtask: fuzz targets built in {build_secs:.0} s");
    let runs = run_targets(targets, seconds);
    print_summary(&runs, build_secs);
    let failed: Vec<&Run> = runs.iter().filter(|r| r.failure.is_some()).collect();
    match failed.first() {
        None => Ok(()),
        Some(first) => {
            for run in &failed {
                if let Some(failure) = &run.failure {
                    eprintln!("xtask: fuzz target {}: {}", run.target, failure.message);
                }
            }
            Err(Failure {
                message: format!(
                    "fuzz target(s) failed: {}",
                    failed
                        .iter()
                        .map(|r| r.target.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                code: first.failure.as_ref().map_or(1, |f| f.code),
            })
        }
    }
}

/// Targets running at once. libFuzzer (one job, no `-fork`) keeps one core busy, and CI
/// has two: two targets side by side take half the wall time, each still its full
/// `seconds` on a core of its own.
const CONCURRENT: usize = 2;

/// Runs every target for `seconds`, [`CONCURRENT`] at a time; the runs in `targets`'
/// order.
fn run_targets(targets: &[String], seconds: u64) -> Vec<Run> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let done = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..CONCURRENT.min(targets.len()) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(target) = targets.get(i) else { break };
                let run = run_target(target, seconds);
                done.lock()
                    .unwrap_or_else(|e| e.into_inner())
                    .push((i, run));
            });
        }
    });
    let mut runs = done.into_inner().unwrap_or_else(|e| e.into_inner());
    runs.sort_by_key(|(i, _)| *i);
    runs.into_iter().map(|(_, run)| run).collect()
}

fn fuzz_dir() -> PathBuf {
    cmd::root().join("fuzz")
}

/// `cargo fuzz <subcommand>` with the flags every call shares: the stable-toolchain
/// switch, no sanitizer, and the fuzz workspace's own target directory (so a
/// `CARGO_TARGET_DIR` meant for the host workspace does not mix the two builds).
fn cargo_fuzz(subcommand: &str) -> Command {
    let mut command = cmd::cargo();
    command
        .args(["fuzz", subcommand, "--sanitizer", "none", "--target-dir"])
        .arg(fuzz_dir().join("target"))
        .env("RUSTC_BOOTSTRAP", "1")
        .current_dir(cmd::root());
    command
}

/// Runs one target for `seconds` on its seeds and scratch corpus.
fn run_target(target: &str, seconds: u64) -> Run {
    println!("\n--> fuzz target {target}, {seconds} s");
    let started = Instant::now();
    let mut run = Run {
        target: target.to_string(),
        executions: None,
        seconds: 0.0,
        rate: None,
        coverage: None,
        corpus: None,
        failure: None,
    };
    let scratch = fuzz_dir().join("corpus-run").join(target);
    let seeds = fuzz_dir().join("corpus").join(target);
    let logs = fuzz_dir().join("target").join("xtask-logs");
    for dir in [&scratch, &logs] {
        if let Err(e) = fs::create_dir_all(dir) {
            run.failure = Some(Failure::new(format!("creating {}: {e}", dir.display())));
            return run;
        }
    }
    let mut command = cargo_fuzz("run");
    command
        .arg(target)
        .arg(&scratch)
        .arg(&seeds)
        .arg("--")
        .arg(format!("-max_total_time={seconds}"))
        .arg(format!("-timeout={INPUT_TIMEOUT_SECS}"))
        .arg("-print_final_stats=1");
    // libFuzzer stops itself at -max_total_time; this only catches a wedged run.
    let limit = Duration::from_secs(2 * seconds + 300);
    let log = logs.join(format!("{target}.log"));
    let result = run_logged(&mut command, &log, limit, &mut run);
    run.seconds = started.elapsed().as_secs_f64();
    if let Err(mut failure) = result {
        failure.message = format!(
            "{}; full log {}; reproduce with `RUSTC_BOOTSTRAP=1 cargo fuzz run -s none {target} <artifact>`",
            failure.message,
            log.display()
        );
        run.failure = Some(failure);
    } else if run.executions.is_none() {
        run.failure = Some(Failure::new(format!(
            "no execution count in libFuzzer's output (see {})",
            log.display()
        )));
    }
    run
}

/// Runs `command` with its stderr (libFuzzer's output) copied to `log` and, without the
/// per-input lines, to the console; records the figures in `run`.
fn run_logged(command: &mut Command, log: &Path, limit: Duration, run: &mut Run) -> Result {
    let shown = cmd::display(command);
    println!("$ RUSTC_BOOTSTRAP=1 {shown}");
    let mut file =
        File::create(log).map_err(|e| Failure::new(format!("creating {}: {e}", log.display())))?;
    let mut child = command
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| Failure::new(format!("cannot start `{shown}`: {e}")))?;
    let stderr = child.stderr.take().expect("stderr is piped");
    // Read on a thread so the deadline below is kept even if the output stops.
    let target = run.target.clone();
    let reader = std::thread::spawn(move || {
        let mut lines = Vec::new();
        for line in BufReader::new(stderr).lines() {
            let Ok(line) = line else { break };
            if !is_progress(&line) {
                // Two targets run at once: each line says whose it is.
                eprintln!("[{target}] {line}");
            }
            lines.push(line);
        }
        lines
    });
    let deadline = Instant::now() + limit;
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break Some(status),
            Ok(None) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(100)),
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
        }
    };
    let lines = reader.join().unwrap_or_default();
    for line in &lines {
        let _ = writeln!(file, "{line}");
    }
    read_figures(&lines, run);
    let Some(status) = status else {
        return Err(Failure {
            message: format!("did not finish within {} s", limit.as_secs()),
            code: 124,
        });
    };
    cmd::check(&shown, status).map_err(|mut failure| {
        if let Some(artifact) = lines
            .iter()
            .find_map(|l| l.split("Test unit written to ").nth(1))
        {
            failure.message = format!("{}: crash input {artifact}", failure.message);
        }
        failure
    })
}

/// libFuzzer's per-input lines: `#1234<TAB>NEW    cov: …` (also `REDUCE`, `RELOAD`)
/// and the `NEW_FUNC[…]` / `NEW_PC` lines that follow a new input.
fn is_progress(line: &str) -> bool {
    let mut words = line.split_whitespace();
    match (words.next(), words.next()) {
        (Some(first), Some(kind)) if first.starts_with('#') => {
            matches!(kind, "NEW" | "REDUCE" | "RELOAD")
        }
        (Some(first), _) => first.starts_with("NEW_FUNC") || first.starts_with("NEW_PC"),
        _ => false,
    }
}

/// The execution count and rate, the coverage and the corpus size from libFuzzer's
/// output.
fn read_figures(lines: &[String], run: &mut Run) {
    let number_after = |line: &str, key: &str| -> Option<u64> {
        let rest = line.split(key).nth(1)?;
        let digits: String = rest
            .trim_start()
            .chars()
            .take_while(|c| c.is_ascii_digit())
            .collect();
        digits.parse().ok()
    };
    for line in lines {
        if let Some(n) = number_after(line, "stat::number_of_executed_units:") {
            run.executions = Some(n);
        }
        if line.starts_with('#') {
            if let Some(n) = number_after(line, "exec/s:") {
                run.rate = Some(n);
            }
            if let Some(n) = number_after(line, "cov:") {
                run.coverage = Some(n);
            }
            if let Some(n) = number_after(line, "corp:") {
                run.corpus = Some(n);
            }
        }
    }
}

fn print_summary(runs: &[Run], build_secs: f64) {
    println!("\nxtask fuzz: build {build_secs:.0} s");
    println!(
        "{:<14} {:>12} {:>9} {:>8} {:>8} {:>7}  result",
        "target", "executions", "exec/s", "coverage", "corpus", "time s"
    );
    let show = |n: Option<u64>| n.map_or_else(|| "-".to_string(), crate::format::thousands);
    for run in runs {
        println!(
            "{:<14} {:>12} {:>9} {:>8} {:>8} {:>7.0}  {}",
            run.target,
            show(run.executions),
            show(run.rate),
            show(run.coverage),
            show(run.corpus),
            run.seconds,
            if run.failure.is_some() {
                "FAILED"
            } else {
                "ok"
            }
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn per_input_lines_are_progress_and_the_rest_is_not() {
        for line in [
            "#31\tNEW    cov: 1324 ft: 3078 corp: 29/22Kb lim: 6819 exec/s: 0 rss: 31Mb",
            "#26277\tREDUCE cov: 2383 ft: 12752 corp: 729/2202Kb",
            "\tNEW_FUNC[1/1]: 0x5637e7085821",
        ] {
            assert!(is_progress(line), "{line}");
        }
        for line in [
            "#30\tINITED cov: 1323 ft: 3075 corp: 28/22Kb exec/s: 0 rss: 31Mb",
            "#1048576\tpulse  cov: 1208 ft: 3266 corp: 1078/178Kb",
            "==1234== ERROR: libFuzzer: deadly signal",
            "thread '<unnamed>' panicked at src/collide.rs:76:21:",
            "",
        ] {
            assert!(!is_progress(line), "{line}");
        }
    }

    #[test]
    fn figures_come_from_the_last_status_line_and_the_final_stats() {
        let lines: Vec<String> = [
            "#30\tINITED cov: 1323 ft: 3075 corp: 28/22Kb exec/s: 0 rss: 31Mb",
            "#1925760\tDONE   cov: 1208 ft: 3266 corp: 1078/178Kb lim: 4096 exec/s: 31569 rss: 32Mb",
            "Done 1925760 runs in 61 second(s)",
            "stat::number_of_executed_units: 1925760",
        ]
        .iter()
        .map(|l| l.to_string())
        .collect();
        let mut run = Run {
            target: "t".into(),
            executions: None,
            seconds: 0.0,
            rate: None,
            coverage: None,
            corpus: None,
            failure: None,
        };
        read_figures(&lines, &mut run);
        assert_eq!(run.executions, Some(1_925_760));
        assert_eq!(run.rate, Some(31_569));
        assert_eq!(run.coverage, Some(1208));
        assert_eq!(run.corpus, Some(1078));
        assert_eq!(crate::format::thousands(1_925_760), "1,925,760");
        assert_eq!(crate::format::thousands(999), "999");
    }
}
