//! `docs/tradeoff.{json,md,svg}`: the speed/accuracy trade of `cargo xtask bench`.
//!
//! The JSON holds the measurements; the report and the plot are rendered from it alone
//! (`crate::bench::render_report`). So:
//!
//! * `cargo xtask docs` adopts a bench run's measurements (`target/bench/tradeoff.json`,
//!   when it is newer than the tracked JSON) and writes the report and the plot;
//! * `--check` fails when the report or the plot is not what the tracked JSON gives, when
//!   a KimGrip branch count of the JSON differs from the one the CI gate measured in the
//!   same run (`bench-kimgrip-LABEL`, recorded by `cargo xtask test`'s bench-firmware
//!   step, `crate::bench::regression`), and when a bench run's measurements differ from
//!   the tracked ones in anything but host timings and provenance (the instruction counts
//!   are QEMU's virtual time and the errors are computed: both repeat exactly).

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use serde_json::Value;

use crate::bench;
use crate::cmd::{self, Failure, Result};

/// What the check found.
pub struct Outcome {
    /// One message per stale file or figure.
    pub stale: Vec<String>,
    /// Files and figures compared.
    pub compared: usize,
}

fn docs_file(name: &str) -> PathBuf {
    cmd::root().join("docs").join(name)
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("reading {}: {e}", path.display())))
}

fn parse(path: &Path) -> Result<Value> {
    serde_json::from_str(&read(path)?)
        .map_err(|e| Failure::new(format!("{}: not the bench's JSON: {e}", path.display())))
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The tracked measurements, `docs/tradeoff.json`.
pub fn tracked() -> Result<Value> {
    parse(&docs_file("tradeoff.json"))
}

/// `docs:value tradeoff MODEL PRECISION BACKEND PROFILE STAT`: an instruction count of
/// the tracked measurements (`crate::bench::instructions_of`), e.g. `tradeoff seed-exact
/// f32 libm release mean`.
pub fn value(spec: &str) -> Result<String> {
    let words: Vec<&str> = spec.split_whitespace().collect();
    let query: [&str; 5] = words.as_slice().try_into().map_err(|_| {
        Failure::new(format!(
            "`docs:value tradeoff {spec}`: expected MODEL PRECISION BACKEND PROFILE STAT"
        ))
    })?;
    bench::instructions_of(&tracked()?, query).ok_or(Failure::new(format!(
        "`docs:value tradeoff {spec}`: no such count in docs/tradeoff.json"
    )))
}

/// A bench run newer than the tracked measurements, if there is one.
fn newer_bench_run() -> Option<PathBuf> {
    let run = bench::measured_json();
    match (modified(&run), modified(&docs_file("tradeoff.json"))) {
        (Some(run_time), Some(tracked)) if run_time > tracked => Some(run),
        (Some(_), None) => Some(run),
        _ => None,
    }
}

/// Regenerates (or, with `check`, compares) the three files.
pub fn run(check: bool) -> Result<Outcome> {
    let json_path = docs_file("tradeoff.json");
    let mut stale = Vec::new();
    let mut compared = 0;
    let mut tracked = if json_path.exists() {
        Some(parse(&json_path)?)
    } else {
        None
    };
    if let Some(run) = newer_bench_run() {
        let measured = parse(&run)?;
        compared += 1;
        let difference = match &tracked {
            Some(tracked) => {
                first_difference(&deterministic(tracked), &deterministic(&measured), "")
            }
            None => Some("all: docs/tradeoff.json is missing".into()),
        };
        if let Some(difference) = difference {
            stale.push(format!(
                "docs/tradeoff.json differs from the bench run {} at {difference} \
                 (`cargo xtask docs` adopts the run)",
                run.display()
            ));
        }
        if !check {
            write(&json_path, &bench::json_text(&measured))?;
            tracked = Some(measured);
        }
    }
    let tracked = tracked.ok_or(Failure::new(
        "docs/tradeoff.json is missing: `cargo xtask bench --update-docs` measures it",
    ))?;
    let (md, svg) = bench::render_report(&tracked)?;
    for (name, now) in [("tradeoff.md", md), ("tradeoff.svg", svg)] {
        let path = docs_file(name);
        compared += 1;
        let was = std::fs::read_to_string(&path).unwrap_or_default();
        if was != now {
            stale.push(format!(
                "docs/{name} is not what docs/tradeoff.json gives (`cargo xtask docs` renders it)"
            ));
            if !check {
                write(&path, &now)?;
            }
        }
    }
    let (gate_compared, gate_stale) = against_gate(&tracked)?;
    compared += gate_compared;
    stale.extend(gate_stale);
    Ok(Outcome { stale, compared })
}

fn write(path: &Path, text: &str) -> Result {
    std::fs::write(path, text)
        .map_err(|e| Failure::new(format!("writing {}: {e}", path.display())))?;
    println!(
        "xtask docs: updated {}",
        path.strip_prefix(cmd::root()).unwrap_or(path).display()
    );
    Ok(())
}

/// The JSON's KimGrip branch counts against the CI gate's recordings (rounded to whole
/// instructions, as the gate records them). A branch the gate did not record (no
/// `cargo xtask test` run here) is not compared.
fn against_gate(tracked: &Value) -> Result<(usize, Vec<String>)> {
    let branches = tracked["kimgrip_branches"].as_array().ok_or(Failure::new(
        "docs/tradeoff.json: no `kimgrip_branches` array",
    ))?;
    let mut compared = 0;
    let mut stale = Vec::new();
    for branch in branches {
        let (Some(label), Some(instructions)) =
            (branch["label"].as_str(), branch["instructions"].as_f64())
        else {
            return Err(Failure::new(format!(
                "docs/tradeoff.json: a KimGrip branch without label or instructions: {branch}"
            )));
        };
        let key = format!("bench-kimgrip-{label}");
        let Ok(recorded) = std::fs::read_to_string(cuesight_figures::dir().join(&key)) else {
            continue;
        };
        compared += 1;
        let recorded = recorded.lines().next().unwrap_or_default().trim();
        let documented = format!("{instructions:.0}");
        if recorded != documented {
            stale.push(format!(
                "docs/tradeoff.json: KimGrip branch {label} has {documented} instructions, the \
                 gate measured {recorded} (`cargo xtask bench`, then `cargo xtask docs`)"
            ));
        }
    }
    Ok((compared, stale))
}

/// The measurements without what differs between two runs of one commit: host timings
/// (`host`, each row's `host_ns`) and the source commit.
fn deterministic(report: &Value) -> Value {
    let mut copy = report.clone();
    if let Some(object) = copy.as_object_mut() {
        object.remove("host");
    }
    if let Some(method) = copy["method"].as_object_mut() {
        method.remove("source");
    }
    if let Some(rows) = copy["rows"].as_array_mut() {
        for row in rows.iter_mut().filter_map(Value::as_object_mut) {
            row.remove("host_ns");
        }
    }
    copy
}

/// The path of the first place `a` and `b` differ, with both values.
fn first_difference(a: &Value, b: &Value, at: &str) -> Option<String> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            keys.into_iter().find_map(|key| {
                first_difference(
                    x.get(key).unwrap_or(&Value::Null),
                    y.get(key).unwrap_or(&Value::Null),
                    &format!("{at}.{key}"),
                )
            })
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .find_map(|(i, (p, q))| first_difference(p, q, &format!("{at}[{i}]"))),
        _ if a == b => None,
        _ => Some(format!("`{at}`: {a} there, {b} here")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn host_timings_and_source_are_not_measurements() {
        let a = json!({"host": {"cpus": 2}, "method": {"source": "abc", "qemu": "7.2"},
                       "rows": [{"host_ns": 61.5, "instructions": 129.0}]});
        let b = json!({"host": {"cpus": 8}, "method": {"source": "def", "qemu": "7.2"},
                       "rows": [{"host_ns": 40.0, "instructions": 129.0}]});
        assert_eq!(
            first_difference(&deterministic(&a), &deterministic(&b), ""),
            None
        );
        let c = json!({"host": {}, "method": {"source": "def", "qemu": "7.2"},
                       "rows": [{"host_ns": 40.0, "instructions": 130.0}]});
        assert_eq!(
            first_difference(&deterministic(&a), &deterministic(&c), "").as_deref(),
            Some("`.rows[0].instructions`: 129.0 there, 130.0 here")
        );
    }
}
