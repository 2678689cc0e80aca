//! The figures of `docs:value`, `docs:console` and `docs:figure` blocks: commands'
//! output, image sizes, the link's limits, the worked example, and what the tests
//! recorded (see the parent module).

use std::path::Path;
use std::process::Command;

use crate::cmd::{self, Failure, Result};
use crate::format::thousands;
use crate::{qemu, size};

/// Runs `line` (split at spaces) from the repository root; its stdout and stderr.
pub(super) fn output_of(line: &str) -> Result<String> {
    let mut words = line.split_whitespace();
    let program = words
        .next()
        .ok_or(Failure::new("an empty `docs:console` command"))?;
    // Through the linted host build, as the tests built the CLI: a plain `cargo run`
    // would compile the workspace's crates again.
    let program = if program == "cargo" {
        crate::tools::host_cargo()?
    } else {
        Command::new(program)
    };
    let mut command = program;
    command
        .args(words)
        .current_dir(cmd::root())
        .env("CARGO_TERM_COLOR", "never");
    let output = command
        .output()
        .map_err(|e| Failure::new(format!("running `{line}`: {e}")))?;
    let mut text = String::from_utf8_lossy(&output.stdout).into_owned();
    text.push_str(&String::from_utf8_lossy(&output.stderr));
    Ok(text)
}

pub(super) fn console(line: &str) -> Result<String> {
    Ok(format!("```console\n$ {line}\n{}```", output_of(line)?))
}

/// The JSON answer of a `cuesight ... --json` command.
fn json_of(line: &str) -> Result<serde_json::Value> {
    let text = output_of(line)?;
    serde_json::from_str(text.trim()).map_err(|e| {
        Failure::new(format!(
            "`{line}` did not print one JSON value ({e}): {text}"
        ))
    })
}

/// The release image's sizes. Always built, as [`nrf52840_sizes`].
fn firmware_sizes() -> Result<size::Sizes> {
    qemu::build_release()?;
    sizes_of(&qemu::elf_path())
}

/// The nrf52840 board's release image (without `shot`), as the CI step builds it.
/// Always built (cargo does nothing when it is current): an image left from an older
/// commit gave a stale figure that only `--check` in CI caught.
fn nrf52840_sizes() -> Result<size::Sizes> {
    sizes_of(&crate::images::NRF52840.build()?)
}

/// The live image (issue 15), always built, as the CI step builds it.
fn live_sizes() -> Result<size::Sizes> {
    sizes_of(&crate::images::LIVE.build()?)
}

fn sizes_of(elf: &Path) -> Result<size::Sizes> {
    let bytes =
        std::fs::read(elf).map_err(|e| Failure::new(format!("reading {}: {e}", elf.display())))?;
    size::sizes(&bytes).ok_or(Failure::new(format!(
        "{}: not an ELF32 image",
        elf.display()
    )))
}

/// The CLI, as README.md runs it: `--bin` without `-p` resolves the dependencies'
/// features over the whole workspace, as `cargo test --workspace` and `cargo xtask`
/// (with its feature unification) do, so after them it is a no-op. `-p cuesight-host`
/// resolved its own features and recompiled 25 crates, core, link, sensors, nalgebra
/// and cuesight-host among them (95 s of CPU on a CI build that had run the tests).
const CLI: &str = "cargo run -q --bin cuesight --";

/// The number at `path` of a JSON value (element `i` if it is an array).
fn number(value: &serde_json::Value, path: &[&str], i: usize) -> Result<f64> {
    let mut at = value;
    for key in path {
        at = &at[*key];
    }
    at.get(i)
        .unwrap_or(at)
        .as_f64()
        .ok_or(Failure::new(format!("no number at {path:?}[{i}]")))
}

/// A number of the worked example's `--json` answer (KimGrip).
fn worked_example(path: &[&str], i: usize) -> Result<f64> {
    number(&json_of(&format!("{CLI} {WORKED_EXAMPLE}"))?, path, i)
}

/// The peak stack of the last demo session (`cargo xtask run`'s log, "peak stack N of M
/// bytes"); plays the demo first if there is no log newer than the release ELF.
fn demo_peak_stack() -> Result<u64> {
    let log = qemu::log_file();
    let modified = |path: &Path| std::fs::metadata(path).and_then(|m| m.modified()).ok();
    let fresh = match (modified(&log), modified(&qemu::elf_path())) {
        (Some(log), Some(elf)) => log >= elf,
        _ => false,
    };
    if !fresh {
        crate::tools::ensure_for_qemu()?;
        qemu::build_release()?;
        let timeout = std::time::Duration::from_secs(qemu::DEFAULT_TIMEOUT_SECS);
        qemu::run_session(&qemu::elf_path(), &qemu::demo_session(), timeout)?;
    }
    let text = std::fs::read_to_string(&log)
        .map_err(|e| Failure::new(format!("reading {}: {e}", log.display())))?;
    text.lines()
        .find_map(|line| line.split("peak stack ").nth(1))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .ok_or(Failure::new(format!(
            "no 'peak stack N' line in {}",
            log.display()
        )))
}

/// The worked example of README.md, as `cuesight collide` takes it.
const WORKED_EXAMPLE: &str = "collide --speed 2 --cut 30 --spin 0,40,0 --mu 0.06 --json";

/// The figures a `docs:value` block can hold.
pub(super) fn value(name: &str) -> Result<String> {
    Ok(match name {
        "firmware-flash" => thousands(firmware_sizes().map(|s| s.text + s.data)?),
        "firmware-static-ram" => thousands(firmware_sizes().map(|s| s.data + s.bss)?),
        "firmware-flash-under-target" => {
            let flash = firmware_sizes().map(|s| s.text + s.data)?;
            thousands(size::FLASH_TARGET.saturating_sub(flash))
        }
        "nrf52840-flash" => thousands(nrf52840_sizes().map(|s| s.text + s.data)?),
        "nrf52840-static-ram" => thousands(nrf52840_sizes().map(|s| s.data + s.bss)?),
        "nrf52840-shot-flash" => {
            thousands(sizes_of(&crate::images::NRF52840_SHOT.build()?).map(|s| s.text + s.data)?)
        }
        "live-flash" => thousands(live_sizes().map(|s| s.text + s.data)?),
        "nrf52840-live-flash" => {
            thousands(sizes_of(&crate::images::NRF52840_LIVE.build()?).map(|s| s.text + s.data)?)
        }
        "nrf52840-live-flash-under-budget" => {
            let flash =
                sizes_of(&crate::images::NRF52840_LIVE.build()?).map(|s| s.text + s.data)?;
            thousands(size::FLASH_BUDGET.saturating_sub(flash))
        }
        "nrf52840-live-static-ram" => {
            thousands(sizes_of(&crate::images::NRF52840_LIVE.build()?).map(|s| s.data + s.bss)?)
        }
        "live-static-ram" => thousands(live_sizes().map(|s| s.data + s.bss)?),
        "live-flash-under-budget" => {
            let flash = live_sizes().map(|s| s.text + s.data)?;
            thousands(size::FLASH_BUDGET.saturating_sub(flash))
        }
        "link-code-lines" => thousands(crate::lines::link_code_lines()? as u64),
        "max-frame" => thousands(cuesight_link::frame::MAX_FRAME as u64),
        "max-samples" => cuesight_link::MAX_SAMPLES.to_string(),
        "stroke-capacity" => thousands(cuesight_link::STROKE_CAPACITY as u64),
        "schema-hash" => format!("{:#010x}", cuesight_link::SCHEMA_HASH),
        "worked-example-throw" => format!("{:.2}", worked_example(&["throw_deg"], 0)?),
        "worked-example-deflection" => {
            format!("{:.1}", worked_example(&["cue_deflection_deg"], 0)?)
        }
        "worked-example-hop" => format!("{:.3}", worked_example(&["cue", "v"], 2)?),
        "worked-example-vs-reference" => {
            let model = json_of(&format!("{CLI} {WORKED_EXAMPLE}"))?;
            let reference = json_of(&format!("{CLI} {WORKED_EXAMPLE} --model reference"))?;
            let mut velocity = 0.0f64;
            for ball in ["cue", "object"] {
                for i in 0..3 {
                    let d = number(&model, &[ball, "v"], i)? - number(&reference, &[ball, "v"], i)?;
                    velocity = velocity.max(d.abs());
                }
            }
            let throw =
                (number(&model, &["throw_deg"], 0)? - number(&reference, &["throw_deg"], 0)?).abs();
            format!("at most {velocity:.1e} m/s in velocity and {throw:.3}° in throw")
        }
        "demo-peak-stack" => thousands(demo_peak_stack()?),
        _ => return Err(Failure::new(format!("unknown `docs:value {name}`"))),
    })
}

/// A figure recorded by the test that measures it (`cuesight_figures::record!`).
pub(super) fn figure(key: &str) -> Result<String> {
    if key.contains(' ') {
        return Err(Failure::new(format!(
            "`docs:figure {key}`: expected a key alone (figures CI does not record, once marked `by-hand`, are no longer accepted: record it in a test or a step `cargo xtask test` runs)"
        )));
    }
    if !cuesight_figures::valid_key(key) {
        return Err(Failure::new(format!(
            "`docs:figure {key}`: not a figure key"
        )));
    }
    let path = cuesight_figures::dir().join(key);
    match std::fs::read_to_string(&path) {
        Ok(text) => Ok(text.lines().next().unwrap_or_default().to_string()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(Failure::new(format!(
            "figure `{key}` is not recorded ({}): run the tests first (`cargo xtask test`, \
             or the test that records it: `grep -rn '\"{key}\"' --include=*.rs .`)",
            path.display()
        ))),
        Err(e) => Err(Failure::new(format!("reading {}: {e}", path.display()))),
    }
}
