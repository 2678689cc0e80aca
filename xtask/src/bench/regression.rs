//! The `KimGrip` instruction-count gate. `bench-firmware`'s `kimgrip-count` image counts
//! the f32 `KimGrip` prediction on one shot per branch of its fast path (QEMU
//! `-icount shift=0` is deterministic) and prints their mean and maximum; this fails
//! when the mean is more than 5 % above the committed
//! `bench-firmware/kimgrip-baseline.txt` (reliability issue), when any branch takes
//! more than [`FAST_PATH_TARGET`] instructions (issue 4) or any branch of the
//! speed-dependent μ(v) fast path more than [`SPEED_PATH_TARGET`] (issue 16, item 6).

use std::path::Path;
use std::time::Duration;

use super::firmware::{bench_firmware_dir, run_probe};
use crate::cmd::{Failure, Result};

const PROBE: &str = "kimgrip-count";
/// Allowed growth over the baseline.
const ALLOWED: f64 = 1.05;
/// Issue 4's target: `KimGrip` f32 ≤ 150 instructions per collision.
pub const FAST_PATH_TARGET: f64 = 150.0;
/// Issue 16 item 6's target: TP A.14's speed-dependent μ(v) on a fast path, ≤ 200
/// instructions per collision.
pub const SPEED_PATH_TARGET: f64 = 200.0;

/// One shot of the counting image: its label, the path of `KimGrip` that takes it
/// (`fast`: constant μ; `speed`: the speed-dependent μ(v) fast path; `general`), and
/// its instructions per prediction.
#[derive(Clone, Debug)]
pub struct Shot {
    pub label: String,
    pub path: String,
    pub instructions: f64,
}

/// Builds and runs the counting image: every shot's count, and the mean over the
/// fast-path shots as the image prints it (instructions).
pub fn count_branches() -> Result<(Vec<Shot>, f64)> {
    let text = run_probe(PROBE, Duration::from_secs(120))?;
    let shots: Vec<Shot> = text
        .lines()
        .filter_map(|line| {
            let mut fields = line.strip_prefix("kimgrip-shot ")?.split_whitespace();
            let (label, path, milli) = (fields.next()?, fields.next()?, fields.next()?);
            Some(Shot {
                label: label.to_owned(),
                path: path.to_owned(),
                instructions: milli.parse::<u64>().ok()? as f64 / 1000.0,
            })
        })
        .collect();
    let mean = text
        .lines()
        .find_map(|line| {
            line.strip_prefix("kimgrip-count ")?
                .trim()
                .parse::<u64>()
                .ok()
        })
        .ok_or_else(|| Failure::new(format!("no `kimgrip-count` line in {PROBE}'s output")))?;
    Ok((shots, mean as f64 / 1000.0))
}

/// The fast-path shot with the most instructions.
pub fn worst_fast(shots: &[Shot]) -> Option<&Shot> {
    worst_on(shots, "fast")
}

/// The shot of `path` with the most instructions.
fn worst_on<'a>(shots: &'a [Shot], path: &str) -> Option<&'a Shot> {
    shots
        .iter()
        .filter(|shot| shot.path == path)
        .max_by(|a, b| a.instructions.total_cmp(&b.instructions))
}

/// Runs the counting image; fails above the baseline + 5 % or above the target.
pub fn check_kimgrip_count() -> Result {
    let (shots, measured) = count_branches()?;
    let worst = worst_fast(&shots)
        .ok_or_else(|| Failure::new("the counting image printed no fast-path shot"))?;
    let baseline =
        read_baseline(&bench_firmware_dir().join("kimgrip-baseline.txt"))? as f64 / 1000.0;
    println!(
        "xtask: KimGrip f32 {measured:.3} instructions per prediction (baseline {baseline:.3}, limit {:.3})",
        baseline * ALLOWED
    );
    println!(
        "xtask: KimGrip f32 fast path at most {:.3} instructions ({}; target {FAST_PATH_TARGET})",
        worst.instructions, worst.label
    );
    let worst_speed = worst_on(&shots, "speed")
        .ok_or_else(|| Failure::new("the counting image printed no speed-path shot"))?;
    let speed_baseline =
        read_baseline(&bench_firmware_dir().join("kimgrip-speed-baseline.txt"))? as f64;
    println!(
        "xtask: KimGrip f32 speed-dependent fast path at most {:.3} instructions ({}; baseline {speed_baseline}, limit {:.3}; issue 16's target {SPEED_PATH_TARGET}: {})",
        worst_speed.instructions,
        worst_speed.label,
        speed_baseline * ALLOWED,
        if whole(worst_speed) <= SPEED_PATH_TARGET { "met" } else { "not met" }
    );
    record_counts(&shots, measured)?;
    if worst_speed.instructions > speed_baseline * ALLOWED {
        return Err(Failure::new(format!(
            "KimGrip f32 speed-dependent fast path takes {:.3} instructions on {}, more than 5 % above its baseline {speed_baseline} (bench-firmware/kimgrip-speed-baseline.txt)",
            worst_speed.instructions, worst_speed.label
        )));
    }
    // A branch is straight-line code: its count is a whole number, and the measurement's
    // fraction (±0.01, the timer's sampling) is noise, so the target holds the rounded
    // count.
    if whole(worst) > FAST_PATH_TARGET {
        return Err(Failure::new(format!(
            "KimGrip f32 fast path takes {:.3} instructions on {}, above the target of {FAST_PATH_TARGET}",
            worst.instructions, worst.label
        )));
    }
    if measured > baseline * ALLOWED {
        return Err(Failure::new(format!(
            "KimGrip f32 instruction count {measured:.3} is more than 5 % above the baseline {baseline:.3} (bench-firmware/kimgrip-baseline.txt)"
        )));
    }
    Ok(())
}

/// A shot's count as the whole number of instructions its straight-line branch takes.
fn whole(shot: &Shot) -> f64 {
    shot.instructions.round()
}

/// Records the counts docs/physics.md §4 and docs/reliability.md quote
/// (`bench-kimgrip-SHOT`, whole instructions; `bench-kimgrip-mean` and `-max` as the
/// gate prints them), for `cargo xtask docs --check`, which runs after this step.
fn record_counts(shots: &[Shot], mean: f64) -> Result {
    let record = super::firmware::record_figure;
    for shot in shots {
        let key = format!("bench-kimgrip-{}", shot.label);
        record(&key, &format!("{:.0}", shot.instructions))?;
    }
    if let Some(worst) = worst_fast(shots) {
        record("bench-kimgrip-max", &format!("{:.3}", worst.instructions))?;
    }
    if let Some(worst) = worst_on(shots, "speed") {
        record(
            "bench-kimgrip-speed-max",
            &format!("{:.3}", worst.instructions),
        )?;
    }
    record("bench-kimgrip-mean", &format!("{mean:.3}"))
}

fn read_baseline(path: &Path) -> Result<u64> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("reading {}: {e}", path.display())))?;
    text.lines()
        .map(str::trim)
        .find(|line| !line.is_empty() && !line.starts_with('#'))
        .and_then(|line| line.parse().ok())
        .ok_or_else(|| Failure::new(format!("no number in {}", path.display())))
}
