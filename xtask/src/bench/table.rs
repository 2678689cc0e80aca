//! The whole-table probe (`bench-firmware/src/bin/table_probe.rs`): instructions of the
//! table simulation on the Cortex-M4F for a three-cushion carom shot, a 16-ball shot and
//! a 9-ball break (`KimGrip`, f32, the scene's construction subtracted), with their event
//! counts. Recorded as `bench-table-*` figures for `docs/table.md` by `cargo xtask
//! test`'s bench-firmware step, by `cargo xtask bench` and by `cargo xtask bench
//! --guidance-only`.

use std::time::Duration;

use super::firmware::{record_figure, run_probe};
use crate::cmd::{Failure, Result};
use crate::format::thousands;

const PROBE: &str = "table-probe";

/// One line of the probe: `table SHOT INSTRUCTIONS EVENTS COLLISIONS CUSHIONS POCKETS
/// (scene construction BASE excluded)`.
#[derive(Debug, PartialEq)]
struct Probe {
    shot: String,
    instructions: u64,
    events: u64,
    collisions: u64,
    cushions: u64,
    pockets: u64,
}

fn parse_line(line: &str) -> Option<Probe> {
    let mut words = line.strip_prefix("table ")?.split_whitespace();
    let shot = words.next()?.to_owned();
    let mut number = || words.next()?.parse().ok();
    Some(Probe {
        shot,
        instructions: number()?,
        events: number()?,
        collisions: number()?,
        cushions: number()?,
        pockets: number()?,
    })
}

/// Builds and runs the probe, prints and records its figures.
pub fn run(timeout: Duration) -> Result {
    let text = run_probe(PROBE, timeout)?;
    let probes: Vec<Probe> = text.lines().filter_map(parse_line).collect();
    if probes.len() != 3 {
        return Err(Failure::new(format!(
            "{PROBE}: expected 3 `table` lines (three-cushion, sixteen-balls, nine-ball-break), found {}",
            probes.len()
        )));
    }
    let record = |key: String, value: String| record_figure(&key, &value);
    // Host and device bit-identical: the device's digest of each shot's result against
    // the host's, from the same core (`cuesight::sim::shots`).
    let mut identical = 0;
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("table-digest ") else {
            continue;
        };
        let mut words = rest.split_whitespace();
        let (Some(name), Some(device)) = (words.next(), words.next()) else {
            continue;
        };
        let Some((_, make)) = cuesight::sim::shots::ALL.iter().find(|(n, _)| *n == name) else {
            return Err(Failure::new(format!("{PROBE}: unknown shot {name}")));
        };
        let host = make()
            .and_then(|shot| cuesight::sim::shots::digest(&shot))
            .map_err(|e| Failure::new(format!("{PROBE}: {name} on the host: {e}")))?;
        if format!("{host:08x}") != device {
            return Err(Failure::new(format!(
                "{PROBE}: {name}: the device's result digest {device} is not the host's {host:08x}: host and device differ"
            )));
        }
        println!("xtask bench: table {name}: host and device bit-identical (digest {device})");
        identical += 1;
    }
    if identical != probes.len() {
        return Err(Failure::new(format!(
            "{PROBE}: {identical} digests for {} shots",
            probes.len()
        )));
    }
    record(
        "bench-table-bit-identical".into(),
        format!("{identical} of {}", probes.len()),
    )?;
    for p in &probes {
        let per_event = p.instructions / p.events.max(1);
        println!(
            "xtask bench: table {}: {} instructions, {} events ({} collisions, {} cushions, {} pockets), {} per event",
            p.shot, p.instructions, p.events, p.collisions, p.cushions, p.pockets, per_event
        );
        let key = format!("bench-table-{}", p.shot);
        record(format!("{key}-instructions"), thousands(p.instructions))?;
        record(format!("{key}-events"), p.events.to_string())?;
        record(format!("{key}-collisions"), p.collisions.to_string())?;
        record(format!("{key}-cushions"), p.cushions.to_string())?;
        record(format!("{key}-pockets"), p.pockets.to_string())?;
        record(format!("{key}-per-event"), thousands(per_event))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_probe_line() {
        let line = "table nine-ball-break 739110 48 18 20 1 (scene construction 2900 excluded)";
        assert_eq!(
            parse_line(line),
            Some(Probe {
                shot: "nine-ball-break".into(),
                instructions: 739_110,
                events: 48,
                collisions: 18,
                cushions: 20,
                pockets: 1,
            })
        );
        assert_eq!(parse_line("guidance forward kim-grip 3655 2664"), None);
    }
}
