//! `cargo xtask docs [--check]`: the figures of `README.md` and `docs/*.md` that come
//! from a command live in generated blocks, which this regenerates; `--check` (a CI
//! step) changes nothing and fails on any block that is not what its command gives
//! now, showing the first difference.
//!
//! Blocks are HTML comments, invisible in the rendered page:
//!
//! ```text
//! <!-- docs:console CMD -->
//! ...
//! <!-- /docs -->
//! ```
//!
//! is CMD's output (run from the repository root, without a shell: CMD is split at
//! spaces; stdout, then stderr) as a ```` ```console ```` block whose first line is
//! `$ CMD`, so the page names the command that produced it. And
//!
//! ```text
//! <!-- docs:value NAME -->...<!-- /docs -->
//! ```
//!
//! (inline, or on lines of its own) is a figure computed here: the values are listed in
//! [`value`] (firmware sizes from the release ELF, the link's limits from
//! `cuesight-link`, differences between two commands' JSON answers). And
//!
//! ```text
//! <!-- docs:figure KEY -->...<!-- /docs -->
//! ```
//!
//! is a figure a test measured and recorded (`cuesight_figures::record!`, under
//! `target/figures/`): `cargo xtask docs` writes what the last run of that test
//! recorded, and `--check` fails on a figure the tests did not record. `docs:figure
//! KEY by-hand` marks one recorded by a test CI does not run (`#[ignore]`d for its
//! time): checked when a recording exists, else listed as unchecked.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::cmd::{self, Failure, Result};
use crate::format::thousands;
use crate::{qemu, size};

/// `cargo xtask docs` arguments.
#[derive(clap::Args)]
pub struct Args {
    /// Change nothing; fail if any generated block differs from what it would be now.
    #[arg(long)]
    check: bool,
}

impl Args {
    /// `--check`.
    pub fn check() -> Self {
        Self { check: true }
    }
}

const OPEN: &str = "<!-- docs:";
const CLOSE: &str = "<!-- /docs -->";

/// One generated block of a file: `spec` is what follows `docs:` in its marker,
/// `content` the bytes between the markers.
#[derive(Debug)]
struct Block {
    spec: String,
    content: std::ops::Range<usize>,
}

pub fn run(args: &Args) -> Result {
    let mut stale = Vec::new();
    let mut unchecked = Vec::new();
    let mut blocks_seen = 0;
    for file in files()? {
        let text = std::fs::read_to_string(&file)
            .map_err(|e| Failure::new(format!("reading {}: {e}", file.display())))?;
        let shown = file
            .strip_prefix(cmd::root())
            .unwrap_or(&file)
            .display()
            .to_string();
        let blocks = parse(&text).map_err(|e| Failure::new(format!("{shown}: {e}")))?;
        let mut updated = String::with_capacity(text.len());
        let mut at = 0;
        for block in &blocks {
            blocks_seen += 1;
            let was = &text[block.content.clone()];
            let line = text[..block.content.start].lines().count();
            let now = match render(&block.spec, is_inline(&text, block)) {
                Ok(now) => now,
                Err(e) if e.message.starts_with(UNRECORDED) => {
                    unchecked.push(shown.clone());
                    was.to_string()
                }
                Err(e) => return Err(Failure::new(format!("{shown}:{line}: {}", e.message))),
            };
            if now != was && !within_layout_slack(&block.spec, was, &now) {
                stale.push(format!(
                    "{shown}:{line}: `{}` is stale\n{}",
                    block.spec,
                    first_difference(was, &now)
                ));
            }
            updated.push_str(&text[at..block.content.start]);
            updated.push_str(&now);
            at = block.content.end;
        }
        updated.push_str(&text[at..]);
        if !args.check && updated != text {
            std::fs::write(&file, updated)
                .map_err(|e| Failure::new(format!("writing {}: {e}", file.display())))?;
            println!("xtask docs: updated {shown}");
        }
    }
    if args.check && !stale.is_empty() {
        return Err(Failure::new(format!(
            "{} of {blocks_seen} generated blocks are stale (run `cargo xtask docs`):\n{}",
            stale.len(),
            stale.join("\n")
        )));
    }
    if !unchecked.is_empty() {
        let mut per_file: Vec<(String, usize)> = Vec::new();
        for file in &unchecked {
            match per_file.last_mut() {
                Some((last, n)) if last == file => *n += 1,
                _ => per_file.push((file.clone(), 1)),
            }
        }
        let listed: Vec<String> = per_file.iter().map(|(f, n)| format!("{f} {n}")).collect();
        println!(
            "xtask docs: {} by-hand figure(s) not recorded here, left as they are ({}): \
             the ignored tests, examples or `cargo xtask bench` runs that record them did \
             not run since the last `cargo xtask test`",
            unchecked.len(),
            listed.join(", ")
        );
    }
    println!(
        "xtask docs: {} generated blocks {}",
        blocks_seen - unchecked.len(),
        if args.check { "current" } else { "regenerated" }
    );
    Ok(())
}

/// `README.md` and every `docs/*.md`, sorted.
fn files() -> Result<Vec<PathBuf>> {
    let docs = cmd::root().join("docs");
    let listing = std::fs::read_dir(&docs)
        .map_err(|e| Failure::new(format!("reading {}: {e}", docs.display())))?;
    let mut files: Vec<PathBuf> = listing
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| path.extension().is_some_and(|ext| ext == "md"))
        .collect();
    files.sort();
    files.insert(0, cmd::root().join("README.md"));
    Ok(files)
}

/// The generated blocks of `text`, in order; an unclosed or nested block is an error.
fn parse(text: &str) -> std::result::Result<Vec<Block>, String> {
    let mut blocks = Vec::new();
    let mut from = 0;
    while let Some(found) = text[from..].find(OPEN) {
        let open = from + found;
        let line = text[..open].lines().count().max(1);
        let marker_end = text[open..]
            .find("-->")
            .map(|end| open + end + 3)
            .ok_or(format!("line {line}: a `{OPEN}` marker without its `-->`"))?;
        let spec = text[open + OPEN.len()..marker_end - 3].trim().to_string();
        let close = text[marker_end..]
            .find(CLOSE)
            .map(|end| marker_end + end)
            .ok_or(format!("line {line}: `{spec}` has no `{CLOSE}`"))?;
        if text[marker_end..close].contains(OPEN) {
            return Err(format!("line {line}: `{spec}` holds another block"));
        }
        blocks.push(Block {
            spec,
            content: marker_end..close,
        });
        from = close + CLOSE.len();
    }
    Ok(blocks)
}

/// A block whose markers share a line renders without line breaks around it.
fn is_inline(text: &str, block: &Block) -> bool {
    !text[block.content.clone()].contains('\n')
}

fn render(spec: &str, inline: bool) -> Result<String> {
    let (kind, rest) = spec.split_once(' ').unwrap_or((spec, ""));
    let body = match kind {
        "console" => console(rest.trim())?,
        "value" => value(rest.trim())?,
        "figure" => figure(rest.trim())?,
        _ => {
            return Err(Failure::new(format!(
                "unknown generated block `docs:{kind}`"
            )))
        }
    };
    Ok(if inline {
        body.trim_end().to_string()
    } else {
        format!("\n{}\n", body.trim_end())
    })
}

/// Runs `line` (split at spaces) from the repository root; its stdout and stderr.
fn output_of(line: &str) -> Result<String> {
    let mut words = line.split_whitespace();
    let program = words
        .next()
        .ok_or(Failure::new("an empty `docs:console` command"))?;
    let program = if program == "cargo" {
        cmd::cargo()
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

fn console(line: &str) -> Result<String> {
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
fn value(name: &str) -> Result<String> {
    Ok(match name {
        "firmware-flash" => thousands(firmware_sizes().map(|s| s.text + s.data)?),
        "firmware-static-ram" => thousands(firmware_sizes().map(|s| s.data + s.bss)?),
        "firmware-flash-under-target" => {
            let flash = firmware_sizes().map(|s| s.text + s.data)?;
            thousands(size::FLASH_TARGET.saturating_sub(flash))
        }
        "nrf52840-flash" => thousands(nrf52840_sizes().map(|s| s.text + s.data)?),
        "nrf52840-static-ram" => thousands(nrf52840_sizes().map(|s| s.data + s.bss)?),
        "live-flash" => thousands(live_sizes().map(|s| s.text + s.data)?),
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
/// `KEY by-hand` (an ignored test's figure) renders as what the docs hold when it is
/// not recorded: [`run`] counts those as unchecked.
fn figure(spec: &str) -> Result<String> {
    let (key, by_hand) = match spec.split_once(' ') {
        Some((key, "by-hand")) => (key, true),
        None => (spec, false),
        Some(_) => {
            return Err(Failure::new(format!(
                "`docs:figure {spec}`: expected `KEY` or `KEY by-hand`"
            )))
        }
    };
    if !cuesight_figures::valid_key(key) {
        return Err(Failure::new(format!(
            "`docs:figure {key}`: not a figure key"
        )));
    }
    let path = cuesight_figures::dir().join(key);
    match std::fs::read_to_string(&path) {
        Ok(text) => Ok(text.lines().next().unwrap_or_default().to_string()),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && by_hand => {
            Err(Failure::new(format!("{UNRECORDED}{key}")))
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(Failure::new(format!(
            "figure `{key}` is not recorded ({}): run the tests first (`cargo xtask test`, \
             or the test that records it: `grep -rn '\"{key}\"' --include=*.rs .`)",
            path.display()
        ))),
        Err(e) => Err(Failure::new(format!("reading {}: {e}", path.display()))),
    }
}

/// The start of [`figure`]'s error for a by-hand figure not recorded.
const UNRECORDED: &str = "unrecorded by-hand figure ";

/// Bytes an image's size may differ between two checkouts of one commit. Cargo hashes
/// a path dependency's location into its crates' metadata, so the symbols' names and
/// the order fat LTO emits the functions in change with the checkout's path, and with
/// them the alignment padding between functions (the functions' own sizes do not
/// change): measured 4 B on the link image between /work/main and /work/ci-clone.
const LAYOUT_SLACK: u64 = 32;

/// Whether a stale image-size value (`firmware-flash`, `nrf52840-flash`, `live-flash`
/// and their spares) differs from the documented one by no more than [`LAYOUT_SLACK`]:
/// then `--check` lets it stand (regenerating writes the current one).
fn within_layout_slack(spec: &str, was: &str, now: &str) -> bool {
    let sized = [
        "value firmware-flash",
        "value firmware-flash-under-target",
        "value nrf52840-flash",
        "value live-flash",
        "value live-flash-under-budget",
    ];
    let number = |s: &str| s.replace(',', "").trim().parse::<u64>().ok();
    sized.contains(&spec.trim())
        && matches!((number(was), number(now)), (Some(a), Some(b)) if a.abs_diff(b) <= LAYOUT_SLACK)
}

/// The first line where `was` and `now` differ, both versions.
fn first_difference(was: &str, now: &str) -> String {
    let (was_lines, now_lines): (Vec<&str>, Vec<&str>) =
        (was.lines().collect(), now.lines().collect());
    let n = was_lines.len().max(now_lines.len());
    for i in 0..n {
        let (a, b) = (was_lines.get(i), now_lines.get(i));
        if a != b {
            return format!(
                "    doc:  {}\n    now:  {}",
                a.unwrap_or(&"(nothing)"),
                b.unwrap_or(&"(nothing)")
            );
        }
    }
    "    (line breaks differ)".into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_inline_and_multiline_blocks() {
        let text = "a <!-- docs:value max-frame -->9<!-- /docs --> b\n\
                    <!-- docs:console echo hi -->\nold\n<!-- /docs -->\n";
        let blocks = parse(text).unwrap();
        assert_eq!(blocks.len(), 2);
        assert_eq!(blocks[0].spec, "value max-frame");
        assert_eq!(&text[blocks[0].content.clone()], "9");
        assert!(is_inline(text, &blocks[0]));
        assert_eq!(blocks[1].spec, "console echo hi");
        assert_eq!(&text[blocks[1].content.clone()], "\nold\n");
        assert!(!is_inline(text, &blocks[1]));
    }

    #[test]
    fn refuses_unclosed_and_nested_blocks() {
        assert!(parse("<!-- docs:value x -->")
            .unwrap_err()
            .contains("no `<!-- /docs -->`"));
        let nested = "<!-- docs:value a --><!-- docs:value b --><!-- /docs --><!-- /docs -->";
        assert!(parse(nested).unwrap_err().contains("holds another block"));
    }

    #[test]
    fn console_block_names_its_command() {
        let rendered = render("console echo 42", false).unwrap();
        assert_eq!(rendered, "\n```console\n$ echo 42\n42\n```\n");
    }
}
