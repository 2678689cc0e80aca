//! The shot-guidance probe (`bench-firmware/src/bin/guidance_probe.rs`): instructions
//! and peak stack of one forward shot (`shot::play`) and of an inverse aim
//! (`aim::solve_aim`) on the Cortex-M4F, for `KimGrip` and `Auto { 1e-3 }`, counted as
//! the bench counts (QEMU `-icount shift=0`, the scene's construction subtracted), the
//! stack by painting. Recorded as `bench-guidance-*` figures for `docs/shot.md` by
//! `cargo xtask test`'s bench-firmware step (about 3 s beside its builds), by `cargo
//! xtask bench` and by `cargo xtask bench --guidance-only`.

use std::time::Duration;

use super::firmware::{record_figure, run_probe};
use crate::cmd::{Failure, Result};
use crate::format::thousands;

const PROBE: &str = "guidance-probe";

/// One line of the probe: `guidance WHAT MODEL INSTRUCTIONS STACK (scene construction
/// BASE excluded)`.
#[derive(Debug, PartialEq)]
struct Probe {
    what: String,
    model: String,
    instructions: u64,
    stack: u64,
    construction: u64,
}

fn parse_line(line: &str) -> Option<Probe> {
    let mut words = line.strip_prefix("guidance ")?.split_whitespace();
    let what = words.next()?.to_owned();
    let model = words.next()?.to_owned();
    let instructions = words.next()?.parse().ok()?;
    let stack = words.next()?.parse().ok()?;
    let construction = line
        .split("scene construction ")
        .nth(1)?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    Some(Probe {
        what,
        model,
        instructions,
        stack,
        construction,
    })
}

/// A model's name as a figure key takes it: `auto(1e-3)` → `auto-1e-3`.
fn key_part(model: &str) -> String {
    model
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect::<String>()
        .trim_matches('-')
        .to_owned()
}

/// Builds and runs the probe, prints and records its figures.
pub fn run(timeout: Duration) -> Result {
    let text = run_probe(PROBE, timeout)?;
    let probes: Vec<Probe> = text.lines().filter_map(parse_line).collect();
    if probes.len() != 4 {
        return Err(Failure::new(format!(
            "{PROBE}: expected 4 `guidance` lines (forward and inverse-aim × KimGrip and Auto), found {}",
            probes.len()
        )));
    }
    let record = |key: String, value: String| record_figure(&key, &value);
    for probe in &probes {
        println!(
            "xtask bench: guidance {} {}: {} instructions, peak stack {} B (scene construction {} excluded)",
            probe.what, probe.model, probe.instructions, probe.stack, probe.construction
        );
        let key = format!("bench-guidance-{}-{}", probe.what, key_part(&probe.model));
        record(format!("{key}-instructions"), thousands(probe.instructions))?;
        record(format!("{key}-stack"), thousands(probe.stack))?;
    }
    record(
        "bench-guidance-scene-construction".into(),
        thousands(probes[0].construction),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_probe_line() {
        let line = "guidance inverse-aim auto(1e-3) 31995 3132 (scene construction 809 excluded)";
        assert_eq!(
            parse_line(line),
            Some(Probe {
                what: "inverse-aim".into(),
                model: "auto(1e-3)".into(),
                instructions: 31995,
                stack: 3132,
                construction: 809,
            })
        );
        assert_eq!(key_part("auto(1e-3)"), "auto-1e-3");
        assert_eq!(parse_line("kimgrip-count 129000"), None);
    }
}
