//! `cargo xtask test`'s "host: tests": `cargo test --workspace --tests`, with the test
//! binaries run two at a time.
//!
//! `cargo test` runs its test binaries one after the other. Each runs its own tests on
//! every core, but a binary's last long test runs alone, and most binaries hold a few
//! tests of very different lengths. The host tests took 150 s of wall time for 206 s of
//! CPU on two cores. So the binaries are built by cargo (`--no-run`, the executables
//! read from its JSON messages) and run here by two workers, the longest known ones
//! first, each in its package's directory as cargo runs them. Each binary's output is
//! printed whole when it ends. The doctests follow through cargo.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::sync::Mutex;
use std::time::Instant;

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// Test binaries (target names) that took longest in CI, started first so the short
/// ones fill the end. A name not here only starts later.
const LONGEST_FIRST: &[&str] = &[
    "properties",
    "glitch",
    "invariants",
    "domain",
    "shot_properties",
    "follow_through",
    "calibrate",
    "properties_reference",
    "seed_exact",
    "streaming",
    "pictures",
    "synthetic_strokes",
];

/// Binaries run at once: the machine's two cores (each binary also runs its own tests
/// on every core, so more would only queue).
const WORKERS: usize = 2;

/// One test binary cargo built.
struct TestBinary {
    /// `lib`, `bin` or `test`, and the target's name.
    kind: String,
    name: String,
    executable: PathBuf,
    /// The package's directory: cargo runs a test binary there.
    package_dir: PathBuf,
}

/// The unit, binary and integration tests of the workspace, then its doctests; the
/// build compiles the examples and benches too (in the test profile, never run) and
/// lints every target with clippy as it compiles them ([`tools::host_cargo`]): this step
/// is the host workspace's `cargo clippy --all-targets -- -D warnings` as well.
pub fn run() -> Result {
    let mut binaries = build()?;
    // The figures the docs quote are recorded afresh by this run: one an older run left
    // would let `cargo xtask docs --check` pass on a test that no longer records it.
    let figures = cuesight_figures::dir();
    if figures.exists() {
        std::fs::remove_dir_all(&figures)
            .map_err(|e| Failure::new(format!("removing {}: {e}", figures.display())))?;
    }
    binaries.sort_by_key(|b| {
        LONGEST_FIRST
            .iter()
            .position(|&name| name == b.name)
            .unwrap_or(LONGEST_FIRST.len())
    });
    let count = binaries.len();
    let queue = Mutex::new(VecDeque::from(binaries));
    let failed: Mutex<Vec<String>> = Mutex::new(Vec::new());
    let started = Instant::now();
    std::thread::scope(|scope| {
        for _ in 0..WORKERS {
            scope.spawn(|| loop {
                let next = lock(&queue).pop_front();
                let Some(binary) = next else { break };
                if let Err(message) = run_one(&binary) {
                    lock(&failed).push(message);
                }
            });
        }
    });
    let failed = failed.into_inner().unwrap_or_else(|p| p.into_inner());
    println!(
        "xtask: {count} test binaries, {WORKERS} at a time, in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    if !failed.is_empty() {
        return Err(Failure::new(format!(
            "failed test binaries: {}",
            failed.join("; ")
        )));
    }
    cmd::run(tools::host_cargo()?.args(["test", "--workspace", "--doc"]))
}

fn lock<T>(mutex: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    mutex
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// `cargo test --workspace --tests --examples --benches --no-run`, linted, its test
/// executables read from its JSON messages (diagnostics still rendered on stderr).
fn build() -> Result<Vec<TestBinary>> {
    let mut command = tools::host_cargo()?;
    command
        .args([
            "test",
            "--workspace",
            "--tests",
            "--examples",
            "--benches",
            "--no-run",
        ])
        .args(["--message-format", "json-render-diagnostics"])
        .current_dir(cmd::root())
        .stderr(Stdio::inherit());
    let shown = cmd::display(&command);
    eprintln!("$ {shown}");
    let output = command
        .output()
        .map_err(|e| Failure::new(format!("cannot start `{shown}`: {e}")))?;
    cmd::check(&shown, output.status)?;
    let binaries: Vec<TestBinary> = String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter_map(|message| test_binary(&message))
        .collect();
    if binaries.is_empty() {
        return Err(Failure::new(format!("`{shown}` listed no test binary")));
    }
    Ok(binaries)
}

/// A `compiler-artifact` message of a test build with an executable, other than an
/// example's or a bench's (built to be linted, not run: the benches are `cargo xtask
/// bench`'s, the examples take their own arguments).
fn test_binary(message: &serde_json::Value) -> Option<TestBinary> {
    if message["reason"] != "compiler-artifact" || message["profile"]["test"] != true {
        return None;
    }
    if !matches!(
        message["target"]["kind"][0].as_str(),
        Some("lib" | "bin" | "test")
    ) {
        return None;
    }
    let executable = PathBuf::from(message["executable"].as_str()?);
    let package_dir = PathBuf::from(message["manifest_path"].as_str()?)
        .parent()?
        .to_path_buf();
    Some(TestBinary {
        kind: message["target"]["kind"][0].as_str()?.to_owned(),
        name: message["target"]["name"].as_str()?.to_owned(),
        executable,
        package_dir,
    })
}

/// Runs one binary, prints its output whole, and says why it failed if it did.
fn run_one(binary: &TestBinary) -> std::result::Result<(), String> {
    let started = Instant::now();
    let output = Command::new(&binary.executable)
        .current_dir(&binary.package_dir)
        .stdin(Stdio::null())
        .output();
    let seconds = started.elapsed().as_secs_f64();
    let title = format!(
        "{} {} ({})",
        binary.kind,
        binary.name,
        binary.executable.display()
    );
    match output {
        Ok(Output {
            status,
            stdout,
            stderr,
        }) => {
            // One block per binary: a worker's print cannot cut into another's.
            let block = format!(
                "     Running {title}, {seconds:.1} s\n{}{}",
                String::from_utf8_lossy(&stdout),
                String::from_utf8_lossy(&stderr)
            );
            println!("{block}");
            if status.success() {
                Ok(())
            } else {
                Err(format!("{title}: {status}"))
            }
        }
        Err(e) => Err(format!("{title}: cannot start: {e}")),
    }
}
