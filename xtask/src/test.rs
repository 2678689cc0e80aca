//! `cargo xtask test`: every check, in order, each under a header; stops at the
//! first failure unless asked to keep going, and ends with a one-line summary.

use std::time::{Duration, Instant};

use crate::cmd::{self, Failure, Result};
use crate::{images, install, qemu, size, tools};

/// One check: a title and what it runs.
struct Step {
    title: &'static str,
    action: fn() -> Result,
}

fn cargo_at_root(args: &[&str]) -> Result {
    cmd::run(cmd::cargo().args(args))
}

fn cargo_in_firmware(args: &[&str]) -> Result {
    cmd::run(cmd::cargo().args(args).current_dir(cmd::firmware_dir()))
}

const STEPS: &[Step] = &[
    Step {
        title: "host: rustfmt",
        action: || cargo_at_root(&["fmt", "--all", "--", "--check"]),
    },
    Step {
        title: "host: tests, every target linted by clippy as it builds (tests, examples, benches; warnings denied)",
        action: crate::host_tests::run,
    },
    Step {
        title: "host: rustdoc, warnings denied",
        action: rustdoc,
    },
    Step {
        title: "core: KimGrip's speed-dependent fast path (feature speed-path, off in the default build): unit and property tests",
        action: || {
            cargo_at_root(&[
                "test",
                "-p",
                "cuesight",
                "--features",
                "speed-path",
                "--lib",
                "--test",
                "properties",
            ])
        },
    },
    Step {
        title: "python: rustfmt of the Python package (python/, its own workspace)",
        action: crate::python::lint,
    },
    Step {
        title: "python: pip install ./python into target/python/venv (its crate linted by clippy as it builds), pytest against the cuesight CLI",
        action: crate::python::tests,
    },
    Step {
        title: "core: build for thumbv7em-none-eabihf",
        action: || {
            cargo_at_root(&[
                "build",
                "-p",
                "cuesight",
                "--target",
                tools::TARGET,
                "--release",
            ])
        },
    },
    Step {
        title: "firmware: rustfmt",
        action: || cargo_in_firmware(&["fmt", "--all", "--", "--check"]),
    },
    Step {
        title: "firmware: clippy",
        action: || {
            cargo_in_firmware(&["clippy", "--release", "--all-targets", "--", "-D", "warnings"])
        },
    },
    Step {
        title: "firmware: release build",
        action: qemu::build_release,
    },
    Step {
        title: "tools: qemu-system-arm and defmt-print, installed beside the steps so far if missing (log: target/xtask/install.log)",
        action: install::ready,
    },
    Step {
        title: "firmware: on-target unit tests in QEMU (defmt-test, release profile)",
        action: on_target_tests,
    },
    Step {
        title: "firmware: release image size (shot request included), flash within issue 14's 44 KiB target (48 KiB budget) and static RAM within 16 KiB",
        action: || size::check_budgets(&qemu::elf_path()),
    },
    Step {
        title: "link: at most 1,500 lines of code in link/src (issue 14)",
        action: crate::lines::check_link,
    },
    Step {
        title: "firmware: no reachable panic (release profile, --features panic-never: links only if no panic path survives)",
        action: panic_never,
    },
    Step {
        title: "firmware: nrf52840 board: clippy, release builds (the link image and the live-cue image), flash within 48 KiB and static RAM within 16 KiB; not run: no hardware here",
        action: nrf52840,
    },
    Step {
        title: "firmware: demo session in QEMU, peak stack within 8 KB",
        action: demo_session,
    },
    Step {
        title: "firmware: end-to-end test in QEMU",
        action: end_to_end,
    },
    Step {
        title: "firmware: end-to-end shot test in QEMU (answers bit for bit the host session's, peak stack within 8 KiB)",
        action: end_to_end_shot,
    },
    Step {
        title: "firmware: live cue (issue 15): clippy and build of the `live` image, flash within 48 KiB and static RAM within 16 KiB, the shipped IMU traces through it in QEMU against their truth and the host's guidance, the 100-stroke acceptance stream, the sampling interrupt within 400 instructions",
        action: live_cue,
    },
    Step {
        title: "bench-firmware: fmt, clippy, KimGrip f32 disassembly (vsqrt.f32, no soft f64), instruction count within 5 % of the baseline, the shot-guidance probe's counts",
        action: crate::bench::check,
    },
    Step {
        title: "docs: the figures of the long runs: the low-speed sweep (cargo run -p cuesight-host --example low_speed_sweep) and the streaming estimator's instructions per sample in QEMU (cargo xtask bench --stream-only)",
        action: long_runs,
    },
    Step {
        title: "docs: every generated block of README.md and docs/ is current, the figures the tests above recorded included (cargo xtask docs --check)",
        action: || crate::docs::run(&crate::docs::Args::check()),
    },
    Step {
        title: "fuzz: every cargo-fuzz target for 60 s on its seed corpus (stable toolchain, RUSTC_BOOTSTRAP=1), no crash",
        action: crate::fuzz::check,
    },
];

/// The runs that record the figures no test records: the low-speed sweep
/// (`docs/low-speed-limit.md` and its plot; about 20 s on two cores) and the streaming
/// estimator's instruction counts (`docs/sensors.md` §11; about 30 s).
fn long_runs() -> Result {
    let sweep: Vec<&str> = crate::docs::SWEEP.split(' ').skip(1).collect();
    cmd::run(tools::host_cargo()?.args(&sweep))?;
    crate::bench::stream_figures()
}

/// `cargo doc --no-deps --workspace` with every rustdoc warning an error (broken
/// intra-doc links, bad code-block attributes, ...). The doctests themselves run in
/// "host: tests".
fn rustdoc() -> Result {
    cmd::run(
        cmd::cargo()
            .args(["doc", "--no-deps", "--workspace"])
            .env("RUSTDOCFLAGS", "-D warnings"),
    )
}

/// The link-time no-panic proof: the shipped configuration (release profile: opt-level
/// "z", LLVM inline threshold 50, fat LTO, one codegen unit; default features: the QEMU
/// board and the `shot` request) whose panic handler calls a symbol defined nowhere, in
/// its own target directory so the release ELF the QEMU steps run is left alone.
/// `cargo test --release` in `firmware/`: the defmt-test binaries of `firmware/tests/`,
/// each booted in QEMU by the runner (`firmware/qemu-run`), which decodes the log with
/// the defmt-print found or installed here and exits with the tests' verdict.
fn on_target_tests() -> Result {
    let defmt_print = tools::defmt_print()?;
    cmd::run(
        cmd::cargo()
            .args(["test", "--release"])
            .env("DEFMT_PRINT", defmt_print)
            .current_dir(cmd::firmware_dir()),
    )
}

fn panic_never() -> Result {
    images::PANIC_NEVER.build().map(drop)
}

/// The nrf52840 board's link image and live-cue image, linted and built, their flash
/// and static RAM held to the budgets (the link image's flash to issue 14's target
/// too). Flash either with `probe-rs run --chip nRF52840_xxAA <elf>` (README).
fn nrf52840() -> Result {
    size::check_budgets(&images::NRF52840.build()?)?;
    size::check_live_budgets(&images::NRF52840_LIVE.build()?)
}

/// Issue 6's stack budget: the painted peak the firmware logs at `shutdown`.
const STACK_BUDGET: u32 = 8 * 1024;

fn demo_session() -> Result {
    tools::ensure_qemu()?;
    qemu::run_session(
        &qemu::elf_path(),
        &qemu::demo_session(),
        Duration::from_secs(qemu::DEFAULT_TIMEOUT_SECS),
    )?;
    check_stack_budget()
}

/// Fails when the demo session's peak stack (the `peak stack N of M bytes` log line)
/// exceeds [`STACK_BUDGET`], or when the line is missing.
fn check_stack_budget() -> Result {
    let path = qemu::log_file();
    let log = std::fs::read_to_string(&path)
        .map_err(|e| Failure::new(format!("reading {}: {e}", path.display())))?;
    let peak = log.lines().find_map(|line| {
        let rest = line.split("peak stack ").nth(1)?;
        rest.split_whitespace().next()?.parse::<u32>().ok()
    });
    match peak {
        Some(peak) if peak <= STACK_BUDGET => {
            println!("xtask: peak stack {peak} bytes, within the budget of {STACK_BUDGET}");
            Ok(())
        }
        Some(peak) => Err(Failure::new(format!(
            "peak stack {peak} bytes exceeds the budget of {STACK_BUDGET}"
        ))),
        None => Err(Failure::new(format!(
            "no 'peak stack' line in {}",
            path.display()
        ))),
    }
}

/// `cargo test` of one `#[ignore]`d end-to-end test of `host-tests/tests/`, with
/// `--workspace` rather than `-p cuesight-host`: the features are then those of "host:
/// tests" (which already compiled this binary), where `-p` resolves others (no
/// `schema` on core, link and sensors) and rebuilt cuesight-host, its dependents and
/// the test first (150 s of CPU on a fresh clone). Same test, same binary source.
fn e2e_test(name: &str) -> Result<std::process::Command> {
    let mut test = tools::host_cargo()?;
    test.args(["test", "--workspace", "--test", name, "--"]);
    Ok(test)
}

/// `host-tests/tests/e2e.rs`, `#[ignore]`d in plain `cargo test` because it needs the
/// firmware just built; QEMU is wrapped in the test's own deadlines, and the whole
/// test in a 10-minute limit here.
fn end_to_end() -> Result {
    tools::ensure_qemu()?;
    let defmt_print = tools::defmt_print()?;
    let mut test = e2e_test("e2e")?;
    test.args(["--ignored", "--nocapture"])
        .env("CUESIGHT_FIRMWARE_ELF", qemu::elf_path())
        .env("DEFMT_PRINT", defmt_print);
    cmd::run_with_timeout(&mut test, Duration::from_secs(600))
}

/// `host-tests/tests/e2e_shot.rs` against the release image, which has the protocol's
/// `shot` request (a default feature): seeded `shot` requests answered byte for byte as
/// the host session answers them, the peak stack within 8 KiB. `#[ignore]`d in plain
/// `cargo test`, like [`end_to_end`].
fn end_to_end_shot() -> Result {
    tools::ensure_qemu()?;
    let defmt_print = tools::defmt_print()?;
    let mut test = e2e_test("e2e_shot")?;
    test.args(["--ignored", "--nocapture"])
        .env("CUESIGHT_FIRMWARE_ELF", qemu::elf_path())
        .env("DEFMT_PRINT", defmt_print);
    cmd::run_with_timeout(&mut test, Duration::from_secs(600))
}

/// The `live` image (RTIC 2, the emulated IMU, the streaming estimator, guidance on
/// impact; no stroke upload): linted, built, held to the flash and static RAM budgets,
/// and `host-tests/tests/e2e_live.rs` run on it.
fn live_cue() -> Result {
    let elf = images::LIVE.build()?;
    size::check_live_budgets(&elf)?;
    tools::ensure_qemu()?;
    let defmt_print = tools::defmt_print()?;
    let mut test = e2e_test("e2e_live")?;
    // The 100-stroke acceptance stream included (about a minute: two QEMUs at once).
    test.args(["--ignored", "--nocapture"])
        .env("CUESIGHT_LIVE_ELF", &elf)
        .env("DEFMT_PRINT", defmt_print);
    cmd::run_with_timeout(&mut test, Duration::from_secs(600))
}

/// Runs every step (see [`STEPS`]), or those whose title contains `only`.
pub fn run_all(keep_going: bool, only: Option<&str>) -> Result {
    let started = Instant::now();
    let total = STEPS.len();
    tools::ensure_toolchain()?;
    install::start()?;
    let mut failed: Vec<&str> = Vec::new();
    let mut first_failure: Option<Failure> = None;
    let mut ran = 0;
    for (i, step) in STEPS.iter().enumerate() {
        if only.is_some_and(|text| !step.title.contains(text)) {
            continue;
        }
        println!("\n==> [{}/{total}] {}", i + 1, step.title);
        let step_start = Instant::now();
        let result = (step.action)();
        ran += 1;
        match result {
            Ok(()) => println!(
                "<== [{}/{total}] {}: ok ({:.1} s)",
                i + 1,
                step.title,
                secs(step_start)
            ),
            Err(failure) => {
                println!(
                    "<== [{}/{total}] {}: FAILED: {}",
                    i + 1,
                    step.title,
                    failure.message
                );
                failed.push(step.title);
                first_failure.get_or_insert(failure);
                if !keep_going {
                    break;
                }
            }
        }
    }
    // After a failure the install may still run: let it finish rather than leave an
    // apt-get or a cargo install behind this process.
    install::finish();
    let passed = ran - failed.len();
    let skipped = total - ran;
    println!();
    if !failed.is_empty() {
        println!("xtask test: failed step(s): {}", failed.join("; "));
    }
    println!("xtask test: {total} steps in {:.0} s", secs(started));
    // Alone on its line, in the 'N passed, N failed' form CI summaries look for.
    println!(
        "summary: {passed} passed, {} failed, {skipped} skipped",
        failed.len()
    );
    match first_failure {
        None => Ok(()),
        Some(failure) => Err(Failure {
            message: "xtask test failed".into(),
            code: failure.code,
        }),
    }
}

pub fn secs(since: Instant) -> f64 {
    since.elapsed().as_secs_f64()
}
