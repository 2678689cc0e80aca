//! The `KimGrip` instruction-count regression gate (reliability issue: a regression of
//! more than 5 % fails CI). `bench-firmware`'s `kimgrip-count` image prints the f32
//! `KimGrip` mean instructions per prediction (QEMU `-icount shift=0` is deterministic)
//! and this compares it with the committed `bench-firmware/kimgrip-baseline.txt`.

use std::path::Path;
use std::time::Duration;

use super::firmware::{bench_firmware_dir, run_qemu_with, target_dir};
use crate::cmd::{self, Failure, Result};
use crate::tools;

const PROBE: &str = "kimgrip-count";
/// Allowed growth over the baseline.
const ALLOWED: f64 = 1.05;

/// Builds and runs the counting image; fails above the baseline + 5 %.
pub fn check_kimgrip_count() -> Result {
    tools::ensure_qemu()?;
    cmd::run(
        cmd::cargo()
            .args(["build", "--release", "--bin", PROBE])
            .current_dir(bench_firmware_dir()),
    )?;
    let elf = target_dir().join(tools::TARGET).join("release").join(PROBE);
    let listing = target_dir().join("kimgrip-count.txt");
    run_qemu_with(&[], &elf, &listing, Duration::from_secs(120))?;
    let measured = read_count(&listing)?;
    let baseline = read_baseline(&bench_firmware_dir().join("kimgrip-baseline.txt"))?;
    let (measured, baseline) = (measured as f64 / 1000.0, baseline as f64 / 1000.0);
    println!(
        "xtask: KimGrip f32 {measured:.3} instructions per prediction (baseline {baseline:.3}, limit {:.3})",
        baseline * ALLOWED
    );
    if measured > baseline * ALLOWED {
        return Err(Failure::new(format!(
            "KimGrip f32 instruction count {measured:.3} is more than 5 % above the baseline {baseline:.3} (bench-firmware/kimgrip-baseline.txt)"
        )));
    }
    Ok(())
}

fn read_count(listing: &Path) -> Result<u64> {
    let text = std::fs::read_to_string(listing)
        .map_err(|e| Failure::new(format!("reading {}: {e}", listing.display())))?;
    text.lines()
        .find_map(|line| line.strip_prefix("kimgrip-count ")?.trim().parse().ok())
        .ok_or_else(|| Failure::new(format!("no `kimgrip-count` line in {}", listing.display())))
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
