//! `cargo xtask bench`: the measured speed/accuracy trade of every model (issue 4),
//! and the disassembly check that `cargo xtask test` runs.
//!
//! For every model (`Model::ALL`, then `Auto` at three tolerances) × math backend
//! (`libm`, `micromath`) × evaluation precision (`f32`; `f64` with `libm`):
//!
//! 1. instructions per prediction on the Cortex-M4F, from `bench-firmware/` under QEMU
//!    `mps2-an386` with `-icount shift=0` (one instruction per virtual nanosecond,
//!    read from a CMSDK timer; loop and empty call subtracted; calibrated against
//!    blocks of known length), on the first scenes of the grid, for the release
//!    profile (opt-level 3) and the shipping one (opt-level "s");
//! 2. host time per prediction with criterion (`host-tests/benches/collide.rs`,
//!    `libm`), and the f64 reference solver's time on the same scenes;
//! 3. max and RMS error against the reference on the whole grid, of the outcomes the
//!    firmware itself printed (`host-tests/benches/tradeoff.rs`).
//!
//! Results: `target/bench/tradeoff.json`, and the report `tradeoff.md` with its plot
//! `tradeoff.svg` beside it in `target/bench/`; with `--update-docs` the measurements,
//! the report and the plot replace the tracked `docs/tradeoff.{json,md,svg}` instead.
//! The report and plot are functions of the JSON alone ([`render_report`]): `cargo xtask
//! docs` regenerates them from `docs/tradeoff.json`, adopts a newer bench run's JSON,
//! and `--check` holds all three to each other and to the KimGrip gate's counts
//! (`crate::docs`'s tradeoff module).
//!
//! Besides, the streaming stroke estimator (issue 15): instructions per sample on a
//! stroke stream and its code size, in the shipped firmware's build configuration
//! ([`stream`]; `target/bench/stream.json`, and `--stream-only` for just that); and the
//! shot-guidance probe ([`guidance`], `--guidance-only` for just that and the whole-table probe, [`table`]).

mod disasm;
mod firmware;
mod guidance;
mod host;
mod plot;
mod regression;
mod report;
mod stream;
mod table;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// Options of `cargo xtask bench`.
#[derive(clap::Args)]
pub struct Args {
    /// Seed of the scene grid (`cuesight_host::grid::scenes`).
    #[arg(long, default_value_t = 2024)]
    seed: u64,
    /// Scenes the errors are measured on.
    #[arg(long, default_value_t = 10_000)]
    scenes: usize,
    /// Leading scenes the instructions (and host times) are measured on.
    #[arg(long, default_value_t = host::COUNTED_SCENES)]
    counted: usize,
    /// Kill a QEMU run after this many seconds and fail.
    #[arg(long, default_value_t = 600)]
    timeout: u64,
    /// Skip the criterion timings (host ns and the reference ratio are left empty).
    #[arg(long)]
    no_host_timing: bool,
    /// Write the report and the plot over the tracked docs/tradeoff.md and
    /// docs/tradeoff.svg (without it they go to target/bench/, beside tradeoff.json).
    #[arg(long)]
    update_docs: bool,
    /// Only the streaming stroke estimator's figures (issue 15: instructions per
    /// sample and code size on the Cortex-M4F), written to target/bench/stream.json.
    #[arg(long)]
    stream_only: bool,
    /// Only the shot-guidance probe (a forward shot and an inverse aim on the
    /// Cortex-M4F: instructions and peak stack, recorded for docs/shot.md).
    #[arg(long)]
    guidance_only: bool,
}

/// Where the measurements go: `target/bench/` (honours `CARGO_TARGET_DIR`).
fn out_dir() -> PathBuf {
    host::target_dir().join("bench")
}

/// Where the report and its plot go: the tracked `docs/` only when asked
/// (`--update-docs`), otherwise `target/bench/` beside the JSON.
fn report_dir(update_docs: bool) -> PathBuf {
    if update_docs {
        cmd::root().join("docs")
    } else {
        out_dir()
    }
}

/// `--stream-only` with the default timeout: a step of `cargo xtask test`, so that the
/// per-sample table of `docs/sensors.md` (`bench-stream-*`) is recorded where CI's
/// `cargo xtask docs --check` compares it.
pub fn stream_figures() -> Result {
    tools::ensure_toolchain()?;
    tools::ensure_qemu()?;
    let dir = out_dir();
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure::new(format!("creating {}: {e}", dir.display())))?;
    stream::run(&dir, Duration::from_secs(600)).map(|_| ())
}

/// Runs the whole benchmark and writes the report (over the documents with
/// `--update-docs`).
pub fn run(args: &Args) -> Result {
    let started = Instant::now();
    if args.counted == 0 || args.counted > args.scenes {
        return Err(Failure::new("--counted must be between 1 and --scenes"));
    }
    if args.counted != host::COUNTED_SCENES && !args.no_host_timing {
        println!(
            "xtask bench: note: the criterion bench always uses the first {} scenes",
            host::COUNTED_SCENES
        );
    }
    tools::ensure_toolchain()?;
    tools::ensure_qemu()?;
    let dir = out_dir();
    std::fs::create_dir_all(&dir)
        .map_err(|e| Failure::new(format!("creating {}: {e}", dir.display())))?;
    let timeout = Duration::from_secs(args.timeout);
    if args.stream_only {
        section("streaming estimator under QEMU (-icount shift=0, instruction trace)");
        stream::run(&dir, timeout)?;
        println!(
            "xtask bench: streaming estimator done in {:.0} s",
            started.elapsed().as_secs_f64()
        );
        return Ok(());
    }

    if args.guidance_only {
        section("shot-guidance probe under QEMU (-icount shift=0)");
        guidance::run(timeout)?;
        section("whole-table probe under QEMU (-icount shift=0)");
        return table::run(timeout);
    }

    section("scene set");
    let scenes = dir.join("scenes.bin");
    host::write_scenes(args.seed, args.scenes, args.counted, &scenes)?;

    section("bench firmware under QEMU (-icount shift=0)");
    let runs = firmware::measure(&scenes, &dir, timeout)?;
    let trace_check = firmware::trace_check(&scenes, &dir, timeout)?;
    let (branches, _) = regression::count_branches()?;

    section("streaming estimator under QEMU (-icount shift=0, instruction trace)");
    stream::run(&dir, timeout)?;

    section("shot-guidance probe under QEMU (-icount shift=0)");
    guidance::run(timeout)?;
    section("whole-table probe under QEMU (-icount shift=0)");
    table::run(timeout)?;

    section("errors against the reference");
    let listings: Vec<PathBuf> = runs
        .iter()
        .filter(|r| r.build.outcomes)
        .map(|r| r.listing.clone())
        .collect();
    let errors = host::score(args.seed, args.scenes, &listings, &dir.join("errors.json"))?;

    let timings = if args.no_host_timing {
        None
    } else {
        section("host time per prediction (criterion)");
        Some(host::criterion()?)
    };

    section("report");
    let bench = report::Bench {
        seed: args.seed,
        scenes: args.scenes,
        counted: args.counted,
        runs: &runs,
        trace_check: &trace_check,
        branches: &branches,
        errors: &errors,
        timings: timings.as_ref(),
    };
    let json = report::json(&bench)?;
    write(&measured_json(), &json_text(&json))?;
    let reports = report_dir(args.update_docs);
    if args.update_docs {
        write(&reports.join("tradeoff.json"), &json_text(&json))?;
    }
    let (md_path, svg_path) = (reports.join("tradeoff.md"), reports.join("tradeoff.svg"));
    let (md, svg) = render_report(&json)?;
    write(&md_path, &md)?;
    write(&svg_path, &svg)?;
    println!("{}", report::console(&json));
    println!(
        "xtask bench: wrote {}, {}, {} in {:.0} s",
        measured_json().display(),
        md_path.display(),
        svg_path.display(),
        started.elapsed().as_secs_f64()
    );
    if !args.update_docs {
        println!(
            "xtask bench: docs/ left as it is (`cargo xtask docs` adopts this run into \
             docs/tradeoff.{{json,md,svg}}; --update-docs writes them at once)"
        );
    }
    Ok(())
}

/// Where a bench run writes its measurements: `target/bench/tradeoff.json`.
pub fn measured_json() -> PathBuf {
    out_dir().join("tradeoff.json")
}

/// The measurements as they are written: pretty JSON, a final newline.
pub fn json_text(json: &serde_json::Value) -> String {
    let mut text = serde_json::to_string_pretty(json).expect("JSON values serialise");
    text.push('\n');
    text
}

/// One instruction count of the measurements, as `tradeoff.md` prints it: `stat`
/// (`mean`, `min`, `max`, `median`) of `model`'s row at `precision` and `backend`,
/// built with `profile` (`release`: opt-level 3, `release-s`).
pub fn instructions_of(
    json: &serde_json::Value,
    [model, precision, backend, profile, stat]: [&str; 5],
) -> Option<String> {
    let row = report::find(json, model, precision, backend)?;
    let count = row["instructions"][profile][stat].as_f64()?;
    Some(report::instructions(count))
}

/// `tradeoff.md` and `tradeoff.svg`, both rendered from the measurements alone (so
/// `cargo xtask docs` regenerates them from the tracked `docs/tradeoff.json`).
pub fn render_report(json: &serde_json::Value) -> Result<(String, String)> {
    Ok((report::markdown(json), plot::svg(json)?))
}

/// The `cargo xtask test` step: fmt and clippy of `bench-firmware/`, the disassembly
/// check of the f32 `KimGrip` hot path for each backend, the KimGrip instruction-count
/// gate, and the shot-guidance probe (its figures recorded for docs/shot.md).
pub fn check() -> Result {
    let in_firmware = |args: &[&str]| {
        cmd::run(
            cmd::cargo()
                .args(args)
                .current_dir(firmware::bench_firmware_dir()),
        )
    };
    // Not `--all`: that would also check the core (a path dependency), which the host
    // steps already do.
    in_firmware(&["fmt", "--", "--check"])?;
    in_firmware(&[
        "clippy",
        "--release",
        "--all-targets",
        "--",
        "-D",
        "warnings",
    ])?;
    disasm::check_kimgrip()?;
    regression::check_kimgrip_count()?;
    guidance::run(Duration::from_secs(120))?;
    table::run(Duration::from_secs(120))
}

fn section(title: &str) {
    println!("\n==> bench: {title}");
}

fn write(path: &std::path::Path, text: &str) -> Result {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)
            .map_err(|e| Failure::new(format!("creating {}: {e}", parent.display())))?;
    }
    std::fs::write(path, text).map_err(|e| Failure::new(format!("writing {}: {e}", path.display())))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 18: a plain `cargo xtask bench` leaves the tracked documents alone.
    #[test]
    fn the_report_goes_to_docs_only_when_asked() {
        assert_eq!(report_dir(false), out_dir());
        assert!(report_dir(false).ends_with("bench"));
        assert_eq!(report_dir(true), cmd::root().join("docs"));
        assert!(report_dir(true).join("tradeoff.md").is_file());
    }
}
