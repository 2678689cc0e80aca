//! The host side, run through `cargo bench -p cuesight-host` (optimised builds): the
//! scene set and error scoring (`benches/tradeoff.rs`), and the criterion timings
//! (`benches/collide.rs`), whose results are read back from `target/criterion/`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::cmd::{self, Failure, Result};

/// Scenes the instructions and host times are measured on (the criterion bench's
/// `SCENES`: the first 64 of the grid).
pub const COUNTED_SCENES: usize = 64;

/// The host workspace's target directory (honours `CARGO_TARGET_DIR`).
pub fn target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => cmd::root().join(dir),
        None => cmd::root().join("target"),
    }
}

fn cargo_bench(bench: &str, args: &[String]) -> Result {
    cmd::run(
        cmd::cargo()
            .args(["bench", "-p", "cuesight-host", "--bench", bench, "--"])
            .args(args),
    )
}

fn absolute(path: &Path) -> String {
    // cargo runs bench targets from the package directory.
    std::path::absolute(path)
        .unwrap_or_else(|_| path.to_path_buf())
        .display()
        .to_string()
}

/// Writes the grid's first `count` scenes as the firmware's scene set.
pub fn write_scenes(seed: u64, count: usize, counted: usize, out: &Path) -> Result {
    cargo_bench(
        "tradeoff",
        &[
            "scenes".into(),
            format!("--seed={seed}"),
            format!("--count={count}"),
            format!("--counted={counted}"),
            format!("--out={}", absolute(out)),
        ],
    )
}

/// Scores the firmware listings against the reference; returns the JSON it wrote.
pub fn score(seed: u64, count: usize, listings: &[PathBuf], json: &Path) -> Result<Value> {
    let mut args = vec![
        "errors".into(),
        format!("--seed={seed}"),
        format!("--count={count}"),
        format!("--json={}", absolute(json)),
    ];
    args.extend(listings.iter().map(|l| absolute(l)));
    cargo_bench("tradeoff", &args)?;
    read_json(json)
}

fn read_json(path: &Path) -> Result<Value> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("reading {}: {e}", path.display())))?;
    serde_json::from_str(&text).map_err(|e| Failure::new(format!("{}: {e}", path.display())))
}

/// Host time per prediction (ns) by (model label, precision), and per reference solve.
pub struct Timings {
    pub predictions: BTreeMap<(String, String), f64>,
    pub reference_ns: f64,
    pub cpu: String,
    /// Logical CPUs and the 1-minute load average after the run: other work on the
    /// machine slows these timings down (instruction counts are immune).
    pub cpus: usize,
    pub load: Option<f64>,
}

/// Runs the criterion bench and reads its estimates (time per iteration divided by
/// the elements of its throughput: one iteration evaluates every counted scene).
pub fn criterion() -> Result<Timings> {
    let root = target_dir().join("criterion");
    for group in ["collide", "reference"] {
        // Stale results of models that no longer exist must not be read back.
        let _ = std::fs::remove_dir_all(root.join(group));
    }
    cargo_bench("collide", &["--noplot".into()])?;
    let mut predictions = BTreeMap::new();
    let mut reference_ns = None;
    let mut found = Vec::new();
    find_benchmarks(&root, &mut found);
    for dir in found {
        let id = read_json(&dir.join("benchmark.json"))?;
        let estimates = read_json(&dir.join("estimates.json"))?;
        let per_iteration = ["slope", "mean"]
            .iter()
            .find_map(|k| estimates[k]["point_estimate"].as_f64())
            .ok_or_else(|| Failure::new(format!("{}: no estimate", dir.display())))?;
        let elements = id["throughput"]["Elements"].as_f64().unwrap_or(1.0);
        let ns = per_iteration / elements;
        let group = id["group_id"].as_str().unwrap_or_default();
        let function = id["function_id"].as_str().unwrap_or_default().to_string();
        let value = id["value_str"].as_str().unwrap_or_default().to_string();
        match group {
            "collide" => {
                predictions.insert((function, value), ns);
            }
            "reference" => reference_ns = Some(ns),
            _ => {}
        }
    }
    let reference_ns = reference_ns
        .ok_or_else(|| Failure::new(format!("no reference timing under {}", root.display())))?;
    if predictions.is_empty() {
        return Err(Failure::new(format!(
            "no prediction timings under {}",
            root.display()
        )));
    }
    Ok(Timings {
        predictions,
        reference_ns,
        cpu: host_cpu(),
        cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
        load: std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|l| l.split_whitespace().next()?.parse().ok()),
    })
}

/// Directories holding a fresh criterion result (`…/new/benchmark.json`).
fn find_benchmarks(dir: &Path, found: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if !path.is_dir() {
            continue;
        }
        if path.file_name().is_some_and(|n| n == "new") && path.join("benchmark.json").is_file() {
            found.push(path);
        } else {
            find_benchmarks(&path, found);
        }
    }
}

fn host_cpu() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into())
}
