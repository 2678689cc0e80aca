//! Assembles `target/bench/tradeoff.json` from the measurements, and renders it as
//! `docs/tradeoff.md` and as a console table. The documents are generated from the
//! JSON alone, so they always show the same numbers.

use std::collections::BTreeSet;
use std::process::Command;

use serde_json::{json, Value};

use super::disasm;
use super::firmware::{Run, TraceCheck, BUILDS, INSTRUCTIONS_PER_TICK, QEMU_ARGS};
use super::host::Timings;
use super::regression::Shot;
use crate::cmd::{probe, Failure, Result};

/// Everything measured by one `cargo xtask bench`.
pub struct Bench<'a> {
    pub seed: u64,
    pub scenes: usize,
    pub counted: usize,
    pub runs: &'a [Run],
    pub trace_check: &'a TraceCheck,
    /// `kimgrip-count`'s shots: one per branch of `KimGrip`'s fast path, and three the
    /// general path takes.
    pub branches: &'a [Shot],
    pub errors: &'a Value,
    pub timings: Option<&'a Timings>,
}

/// Targets of issue 4.
const KIM_GRIP_TARGET: f64 = 150.0;
const EXACT_TARGET: f64 = 20_000.0;
const EXACT_ACCURACY_TARGET: f64 = 2e-4;
const REFERENCE_RATIO_TARGET: f64 = 1000.0;

fn stats(values: &[f64]) -> Value {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    json!({
        "scenes": n,
        "mean": values.iter().sum::<f64>() / n as f64,
        "median": median,
        "min": sorted[0],
        "max": sorted[n - 1],
    })
}

/// The JSON document (`target/bench/tradeoff.json`).
pub fn json(bench: &Bench) -> Result<Value> {
    let error_rows = bench.errors["rows"]
        .as_array()
        .ok_or_else(|| Failure::new("errors.json has no rows"))?;
    // Row order: models as the firmware lists them, then precision, then backend.
    let mut keys: Vec<(String, String, &str)> = Vec::new();
    for backend in ["libm", "micromath"] {
        for run in bench.runs.iter().filter(|r| r.build.backend == backend) {
            for ((label, precision), _) in &run.counts {
                let key = (label.clone(), precision.clone(), backend);
                if !keys.contains(&key) {
                    keys.push(key);
                }
            }
        }
    }
    let labels: Vec<String> = keys.iter().fold(Vec::new(), |mut v, k| {
        if !v.contains(&k.0) {
            v.push(k.0.clone());
        }
        v
    });
    keys.sort_by_key(|(label, precision, backend)| {
        (
            labels.iter().position(|l| l == label),
            precision.clone(),
            *backend,
        )
    });

    let mut rows = Vec::new();
    for (label, precision, backend) in &keys {
        let mut instructions = serde_json::Map::new();
        for run in bench.runs.iter().filter(|r| r.build.backend == *backend) {
            if let Some((_, values)) = run
                .counts
                .iter()
                .find(|((l, p), _)| l == label && p == precision)
            {
                instructions.insert(run.build.profile.to_string(), stats(values));
            }
        }
        let error = error_rows.iter().find(|r| {
            r["model"] == label.as_str()
                && r["precision"] == precision.as_str()
                && r["backend"] == *backend
        });
        let host_ns = bench.timings.filter(|_| *backend == "libm").and_then(|t| {
            t.predictions
                .get(&(label.clone(), precision.clone()))
                .copied()
        });
        rows.push(json!({
            "model": label,
            "precision": precision,
            "backend": backend,
            "instructions": instructions,
            "host_ns": host_ns,
            "error": error.map(|e| json!({
                "all": e["all"],
                "reference_sliding": e["reference_sliding"],
            })),
            "failures": error.map(|e| e["failures"].clone()),
            "host_bitwise": error.filter(|e| e["host_checked"].as_u64() > Some(0)).map(|e| json!({
                "checked": e["host_checked"],
                "mismatches": e["host_mismatches"],
            })),
            "libm_bitwise": error.filter(|e| e["libm_checked"].as_u64() > Some(0)).map(|e| json!({
                "checked": e["libm_checked"],
                "differences": e["libm_differences"],
            })),
        }));
    }

    let calibration: Vec<Value> = bench
        .runs
        .iter()
        .flat_map(|run| {
            run.calibration.iter().map(move |c| {
                json!({
                    "image": format!("{} {}", run.build.backend, run.build.profile),
                    "block": c.name,
                    "expected": c.expected,
                    "measured": c.measured,
                })
            })
        })
        .collect();

    let kim_grip_ns = bench
        .timings
        .and_then(|t| {
            t.predictions
                .get(&("kim-grip".to_string(), "f32".to_string()))
        })
        .copied();
    let host = bench.timings.map(|t| {
        json!({
            "cpu": t.cpu,
            "cpus": t.cpus,
            "load_average": t.load,
            "reference_ns": t.reference_ns,
            "kim_grip_f32_ns": kim_grip_ns,
            "reference_over_kim_grip": kim_grip_ns.map(|k| t.reference_ns / k),
        })
    });

    let precisions: BTreeSet<&str> = keys.iter().map(|k| k.1.as_str()).collect();
    let mut todo = Vec::new();
    if !precisions.contains("f64") {
        todo.push("f64 precision: no `collide_f64` row was measured".to_string());
    }
    if !keys.iter().any(|k| k.2 == "micromath" && k.1 == "f64") {
        todo.push(
            "f64 with micromath: `cuesight::collide_f64` needs the libm backend, so those rows do not exist"
                .to_string(),
        );
    }
    let disassembly = match disasm::check_kimgrip() {
        Ok(()) => json!({"passed": true}),
        Err(failure) => json!({"passed": false, "message": failure.message}),
    };

    Ok(json!({
        "generated_by": "cargo xtask bench",
        "grid": {"seed": bench.seed, "scenes": bench.scenes, "counted": bench.counted},
        "method": {
            "qemu": probe(Command::new("qemu-system-arm").arg("--version"))
                .and_then(|v| v.lines().next().map(str::to_string)),
            "qemu_args": QEMU_ARGS.join(" "),
            "instructions_per_tick": INSTRUCTIONS_PER_TICK,
            "rustc": probe(Command::new("rustc").arg("--version")).map(|v| v.trim().to_string()),
            // The tree measured: a `-dirty` suffix means uncommitted changes were included.
            "source": probe(
                Command::new("git")
                    .args(["describe", "--always", "--dirty"])
                    .current_dir(crate::cmd::root())
            )
            .map(|v| v.trim().to_string()),
            "profiles": {
                "release": "opt-level 3, fat LTO, codegen-units 1",
                "release-s": "opt-level \"s\", fat LTO, codegen-units 1 (what firmware/ ships)",
            },
            "images": BUILDS.iter().map(|b| format!("{} {}", b.backend, b.profile)).collect::<Vec<_>>(),
        },
        "calibration": calibration,
        "trace_check": {
            "timer": bench.trace_check.timer,
            "traced_call": bench.trace_check.call,
            "traced_empty_call": bench.trace_check.empty,
        },
        "kimgrip_branches": bench.branches.iter().map(|shot| json!({
            "label": shot.label,
            "path": shot.path,
            "instructions": shot.instructions,
        })).collect::<Vec<_>>(),
        "host": host,
        "disassembly_check": disassembly,
        "rows": rows,
        "todo": todo,
    }))
}

/// Instructions: one decimal below 1000, else whole with separators (`475.1`, `8,677`).
pub fn instructions(x: f64) -> String {
    if x < 1000.0 {
        format!("{x:.1}")
    } else {
        thousands(x)
    }
}

/// Rounded to a whole number, with thousands separators: `264,340`.
pub fn thousands(x: f64) -> String {
    let digits = format!("{:.0}", x);
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Three significant digits, no exponent for the ranges errors take.
pub fn sig3(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

fn opt(value: &Value, f: impl Fn(f64) -> String) -> String {
    value.as_f64().map_or_else(|| "—".to_string(), f)
}

/// `docs/tradeoff.md`.
pub fn markdown(report: &Value) -> String {
    let mut md = String::new();
    let grid = &report["grid"];
    md.push_str("# The speed/accuracy trade, measured\n\n");
    md.push_str(
        "_Generated from the measurements in [`tradeoff.json`](tradeoff.json) by `cargo xtask \
         docs`, with the plot [`tradeoff.svg`](tradeoff.svg); `cargo xtask docs --check` (CI) \
         holds the three to each other and the JSON's KimGrip branch counts to the ones CI \
         measures. The measurements are `cargo xtask bench`'s (written to \
         `target/bench/tradeoff.json`, which `cargo xtask docs` then adopts; `cargo xtask \
         bench --update-docs` does both). Do not edit by hand._\n\n",
    );
    md.push_str(&format!(
        "Every model × evaluation precision × math backend of `cuesight`. **Instructions** are \
         per prediction on the Cortex-M4F (QEMU `mps2-an386`), mean over the first {} scenes \
         of the grid (min–max in brackets where they differ); they are instructions, not cycles. **Host** is \
         nanoseconds per prediction on the same scenes (criterion, `libm`). **Errors** are \
         against the f64 reference solver on the {}-scene grid (seed {}), of the outcomes the \
         Cortex-M4F itself computed, in % of the cue-ball speed U (`|Δv|/U`, worst ball) and \
         degrees of throw.\n\n",
        grid["counted"], grid["scenes"], grid["seed"]
    ));
    md.push_str(
        "| model | precision | backend | instructions, opt-level 3 | opt-level s | host ns | \
         max \\|Δv\\|/U % | RMS \\|Δv\\|/U % | max R\\|Δω\\|/U % | max throw ° | max \\|Δv\\|/U %, \
         reference sliding |\n",
    );
    md.push_str("|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n");
    let empty = Vec::new();
    let rows = report["rows"].as_array().unwrap_or(&empty);
    for row in rows {
        let i3 = &row["instructions"]["release"];
        let is = &row["instructions"]["release-s"];
        let err = &row["error"]["all"];
        let pct = |v: &Value| opt(v, |x| sig3(100.0 * x));
        let spread = match (i3["min"].as_f64(), i3["max"].as_f64()) {
            (Some(lo), Some(hi)) if hi - lo >= 0.5 => {
                format!(" ({}–{})", instructions(lo), instructions(hi))
            }
            _ => String::new(),
        };
        md.push_str(&format!(
            "| {} | {} | {} | {}{spread} | {} | {} | {} | {} | {} | {} | {} |\n",
            row["model"].as_str().unwrap_or("?"),
            row["precision"].as_str().unwrap_or("?"),
            row["backend"].as_str().unwrap_or("?"),
            opt(&i3["mean"], instructions),
            opt(&is["mean"], instructions),
            opt(&row["host_ns"], |x| format!("{x:.0}")),
            pct(&err["max"]["velocity"]),
            pct(&err["rms"]["velocity"]),
            pct(&err["max"]["spin"]),
            opt(&err["max"]["throw_deg"], sig3),
            pct(&row["error"]["reference_sliding"]["max"]["velocity"]),
        ));
    }
    md.push_str("\n![Pareto plot: max |Δv|/U against instructions per prediction, log–log](tradeoff.svg)\n\n");

    md.push_str("## Targets (issue 4)\n\n");
    md.push_str(&targets(report));

    md.push_str("\n## Method\n\n");
    md.push_str(&method(report));
    md
}

/// The per-branch counts of `kimgrip-count` and the verdict on the fast path's worst.
fn branch_table(report: &Value) -> String {
    let Some(shots) = report["kimgrip_branches"].as_array() else {
        return String::new();
    };
    let verdict = |ok: bool| if ok { "**met**" } else { "**not met**" };
    let fast_max = shots
        .iter()
        .filter(|s| s["path"] == "fast")
        .filter_map(|s| s["instructions"].as_f64())
        .fold(f64::NAN, f64::max);
    let mut md = format!(
        "- Every branch of `KimGrip`'s fast path (constant μ, μ_s ≤ 0.4, slip ≥ 1 pm/s: \
         every such scene but exact gearing) takes at most {} instructions: {} for every \
         collision. A branch has no loop, so one shot per branch covers them all \
         (`bench-firmware/src/bin/kimgrip_count.rs`; which branch each shot takes is \
         checked by the core's `gate_shots_take_their_branches`; `cargo xtask test` fails \
         above {KIM_GRIP_TARGET}). TP A.14's speed-dependent μ(v) has a fast path of its own \
         (`speed`, issue 16's target 200; `docs/physics.md` §4); the general path serves \
         everything else: no friction, exact gearing, the cue ball's table friction, \
         μ(v) past that path's range, and cloths of μ_s above 0.4 (`cloth-*`: a pressed \
         object ball's slide followed in pieces, `docs/physics.md` §4 item 7):\n\n\
         | shot | path | instructions |\n|---|---|---:|\n",
        instructions(fast_max),
        verdict(fast_max <= KIM_GRIP_TARGET),
    );
    for shot in shots {
        md.push_str(&format!(
            "| {} | {} | {} |\n",
            shot["label"].as_str().unwrap_or("?"),
            shot["path"].as_str().unwrap_or("?"),
            opt(&shot["instructions"], instructions),
        ));
    }
    md.push('\n');
    md
}

pub fn find<'a>(
    report: &'a Value,
    model: &str,
    precision: &str,
    backend: &str,
) -> Option<&'a Value> {
    report["rows"]
        .as_array()?
        .iter()
        .find(|r| r["model"] == model && r["precision"] == precision && r["backend"] == backend)
}

fn targets(report: &Value) -> String {
    let mut md = String::new();
    let verdict = |ok: bool| if ok { "**met**" } else { "**not met**" };
    if let Some(row) = find(report, "kim-grip", "f32", "libm") {
        let i3 = &row["instructions"]["release"];
        let is = &row["instructions"]["release-s"];
        if let (Some(mean), Some(max)) = (i3["mean"].as_f64(), i3["max"].as_f64()) {
            md.push_str(&format!(
                "- `KimGrip` f32 ≤ {KIM_GRIP_TARGET} instructions per collision: {} \
                 instructions on average and {} at most over the {} counted grid scenes \
                 (opt-level 3; {} on average at opt-level s). For scale, `Ideal` (no \
                 friction at all, only the outcome bookkeeping and the finiteness guard) \
                 takes {}. Where the instructions go: \
                 [`physics.md` §4, Cost](physics.md#4-kimgrip).\n",
                instructions(mean),
                instructions(max),
                report["grid"]["counted"].as_u64().unwrap_or(0),
                opt(&is["mean"], instructions),
                find(report, "ideal", "f32", "libm").map_or("—".into(), |r| opt(
                    &r["instructions"]["release"]["mean"],
                    instructions
                )),
            ));
        }
    }
    md.push_str(&branch_table(report));
    let check = &report["disassembly_check"];
    md.push_str(&format!(
        "- No software-f64 call and a hardware `vsqrt.f32` in the f32 `KimGrip` hot path, from \
         the disassembly (`cargo xtask test`, step \"bench-firmware\"): {}.\n",
        if check["passed"].as_bool() == Some(true) {
            "**passes**".to_string()
        } else {
            format!(
                "**fails**: {}",
                check["message"].as_str().unwrap_or("not run")
            )
        }
    ));
    if let Some(row) = find(report, "exact", "f32", "libm") {
        let max = row["instructions"]["release"]["max"].as_f64();
        let sliding = row["error"]["reference_sliding"]["max"]["velocity"].as_f64();
        if let (Some(max), Some(sliding)) = (max, sliding) {
            md.push_str(&format!(
                "- `Exact` ≤ {} instructions: {} at most, {} on average — {}; max |Δv|/U ≤ 0.02 % \
                 where the reference slides: {} % — {}.\n",
                instructions(EXACT_TARGET),
                instructions(max),
                opt(&row["instructions"]["release"]["mean"], instructions),
                verdict(max <= EXACT_TARGET),
                sig3(100.0 * sliding),
                verdict(sliding <= EXACT_ACCURACY_TARGET),
            ));
        }
    }
    if let Some(row) = find(report, "seed-exact", "f32", "libm") {
        let max = row["instructions"]["release"]["max"].as_f64();
        let worst = row["error"]["all"]["max"]["velocity"].as_f64();
        if let (Some(max), Some(worst)) = (max, worst) {
            md.push_str(&format!(
                "- `SeedExact` (the seed's closed sliding solution, eqs. (24)–(41) with \
                 erratum E1, and a stick branch) ≤ {} instructions: {} at most, {} on \
                 average — {}. Against this (vector) reference it is off by up to {} % of U: \
                 the seed's eq. (7) points the object ball's table friction along −x, which \
                 the tier keeps; against the reference solving that same physics it agrees to \
                 its quadrature and rounding (`host-tests/tests/seed_exact.rs`, \
                 `docs/physics.md` §7).\n",
                instructions(EXACT_TARGET),
                instructions(max),
                opt(&row["instructions"]["release"]["mean"], instructions),
                verdict(max <= EXACT_TARGET),
                sig3(100.0 * worst),
            ));
        }
    }
    let host = &report["host"];
    if let Some(ratio) = host["reference_over_kim_grip"].as_f64() {
        md.push_str(&format!(
            "- Reference solver ≥ {REFERENCE_RATIO_TARGET}× slower than `KimGrip` on the host: \
             {:.0} ns per solve against {:.1} ns, **{:.0}×** — {} ({}).\n",
            host["reference_ns"].as_f64().unwrap_or(f64::NAN),
            host["kim_grip_f32_ns"].as_f64().unwrap_or(f64::NAN),
            ratio,
            verdict(ratio >= REFERENCE_RATIO_TARGET),
            host["cpu"].as_str().unwrap_or("?"),
        ));
    } else {
        md.push_str("- Reference/`KimGrip` host ratio: not measured (`--no-host-timing`).\n");
    }
    md
}

fn method(report: &Value) -> String {
    let m = &report["method"];
    let mut md = String::new();
    md.push_str(&format!(
        "- **Instructions.** `bench-firmware/` runs under `qemu-system-arm {}` ({}). With \
         `-icount shift=0` QEMU advances its virtual clock by exactly 1 ns per guest \
         instruction, and the CMSDK APB timer 0 of `mps2-an386` counts that clock at 25 MHz: \
         one tick is {} instructions. With interrupts off, each scene is predicted once to warm \
         up, then `reps` times through a function pointer (`reps` so that a run is ≈ 500,000 \
         instructions, ≥ 8), and the same loop calling an empty function of the same signature \
         is subtracted: the figure is the instructions of the call beyond an empty call. \
         Calibration blocks of known length (measured / expected): {}. Cross-check on real \
         code (`bench-firmware/src/bin/trace_check.rs`, one `KimGrip` f32 prediction, QEMU \
         logging every executed instruction): the timer gives {} instructions, the trace {} for \
         the call and {} for the empty call.\n",
        m["qemu_args"].as_str().unwrap_or("?"),
        m["qemu"].as_str().unwrap_or("?"),
        m["instructions_per_tick"],
        calibration_summary(report),
        opt(&report["trace_check"]["timer"], |x| format!("{x:.2}")),
        report["trace_check"]["traced_call"],
        report["trace_check"]["traced_empty_call"],
    ));
    md.push_str(&format!(
        "- **Builds.** Source `{}`; {} for `thumbv7em-none-eabihf`; `release` is {} and \
         `release-s` {}. `micromath` has no f64 rows: `cuesight::collide_f64` needs `libm`.\n",
        m["source"].as_str().unwrap_or("?"),
        m["rustc"].as_str().unwrap_or("rustc"),
        m["profiles"]["release"].as_str().unwrap_or("?"),
        m["profiles"]["release-s"].as_str().unwrap_or("?"),
    ));
    let host = &report["host"];
    md.push_str(&format!(
        "- **Host time.** `host-tests/benches/collide.rs` (criterion, short runs), all counted \
         scenes per iteration; the reference is `cuesight_host::compare::reference` on the same \
         scenes. {}, {} logical CPUs, 1-minute load average {} after the run: other work on the \
         machine inflates these times (the instruction counts are virtual time and immune).\n",
        host["cpu"].as_str().unwrap_or("unknown CPU"),
        host["cpus"],
        opt(&host["load_average"], |l| format!("{l:.1}")),
    ));
    let mut agreement = Vec::new();
    let mut differences = Vec::new();
    for row in report["rows"].as_array().into_iter().flatten() {
        if let Some(mismatches) = row["host_bitwise"]["mismatches"].as_u64() {
            agreement.push(mismatches);
        }
        if let Some(d) = row["libm_bitwise"]["differences"].as_u64() {
            if d > 0 {
                differences.push(format!(
                    "{} {} in {d} scenes",
                    row["model"].as_str().unwrap_or("?"),
                    row["precision"].as_str().unwrap_or("?")
                ));
            }
        }
    }
    md.push_str(&format!(
        "- **Errors.** The firmware prints every outcome on the grid (bit patterns); \
         `host-tests/benches/tradeoff.rs` scores them with `cuesight_host::compare`. The `libm` \
         image's outcomes are also recomputed on the host: {} of the rows agree bit for bit in \
         every scene. `micromath` against `libm` on the target: {}.\n",
        if agreement.iter().all(|&m| m == 0) {
            format!("all {}", agreement.len())
        } else {
            format!(
                "{} of {}",
                agreement.iter().filter(|&&m| m == 0).count(),
                agreement.len()
            )
        },
        if differences.is_empty() {
            "identical outcomes in every scene (the f32 hot path's only function is the \
             hardware `vsqrt.f32`, whatever the backend)"
                .to_string()
        } else {
            format!("differ for {}", differences.join(", "))
        }
    ));
    for todo in report["todo"].as_array().into_iter().flatten() {
        md.push_str(&format!(
            "- Not measured: {}.\n",
            todo.as_str().unwrap_or("?")
        ));
    }
    md
}

fn calibration_summary(report: &Value) -> String {
    let mut seen: Vec<(String, f64, f64)> = Vec::new();
    for c in report["calibration"].as_array().into_iter().flatten() {
        let name = c["block"].as_str().unwrap_or("?").to_string();
        let expected = c["expected"].as_f64().unwrap_or(f64::NAN);
        let measured = c["measured"].as_f64().unwrap_or(f64::NAN);
        match seen.iter_mut().find(|(n, _, _)| *n == name) {
            // Keep the worst image per block.
            Some(entry) if (measured - expected).abs() > (entry.2 - entry.1).abs() => {
                entry.2 = measured;
            }
            Some(_) => {}
            None => seen.push((name, expected, measured)),
        }
    }
    seen.iter()
        .map(|(name, expected, measured)| format!("{name} {measured:.2} / {expected}"))
        .collect::<Vec<_>>()
        .join("; ")
}

/// A short table for the terminal.
pub fn console(report: &Value) -> String {
    let mut out = format!(
        "\n{:<12} {:<4} {:<9} {:>12} {:>12} {:>9} {:>12} {:>12}\n",
        "model",
        "prec",
        "backend",
        "instr (O3)",
        "instr (Os)",
        "host ns",
        "max dv/U %",
        "rms dv/U %"
    );
    for row in report["rows"].as_array().into_iter().flatten() {
        let err = &row["error"]["all"];
        out.push_str(&format!(
            "{:<12} {:<4} {:<9} {:>12} {:>12} {:>9} {:>12} {:>12}\n",
            row["model"].as_str().unwrap_or("?"),
            row["precision"].as_str().unwrap_or("?"),
            row["backend"].as_str().unwrap_or("?"),
            opt(&row["instructions"]["release"]["mean"], instructions),
            opt(&row["instructions"]["release-s"]["mean"], instructions),
            opt(&row["host_ns"], |x| format!("{x:.1}")),
            opt(&err["max"]["velocity"], |x| sig3(100.0 * x)),
            opt(&err["rms"]["velocity"], |x| sig3(100.0 * x)),
        ));
    }
    if let Some(ratio) = report["host"]["reference_over_kim_grip"].as_f64() {
        out.push_str(&format!(
            "reference / KimGrip f32 on the host: {ratio:.0}x\n"
        ));
    }
    out
}
