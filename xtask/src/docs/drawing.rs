//! The drawings of `docs/`: `docs/shot-cli.svg`, the example drawing of
//! `docs/shot-cli.md` (what `cuesight shot --scene cli/scenes/cut_to_corner.toml --svg
//! FILE` draws, run here), and `docs/low-speed-limit.svg`, which the low-speed sweep
//! draws into `target/docs/` (`cargo run -p cuesight-host --example low_speed_sweep`, a
//! step of `cargo xtask test`). `cargo xtask docs` writes them, `--check` fails when
//! one differs (the drawing changed and the page did not).

use crate::cmd::{self, Failure, Result};

use super::tradeoff::Outcome;
use super::values::output_of;

/// The command, less the file it writes.
const COMMAND: &str =
    "cargo run -q --bin cuesight -- shot --scene cli/scenes/cut_to_corner.toml --svg";

/// Draws the example and compares it with (or, unless `check`, writes it to)
/// `docs/shot-cli.svg`.
pub fn run(check: bool) -> Result<Outcome> {
    let root = cmd::root();
    let scratch = root.join("target").join("docs");
    std::fs::create_dir_all(&scratch)
        .map_err(|e| Failure::new(format!("creating {}: {e}", scratch.display())))?;
    let drawn = scratch.join("shot-cli.svg");
    let line = format!("{COMMAND} {}", drawn.display());
    let output = output_of(&line)?;
    let now = std::fs::read_to_string(&drawn)
        .map_err(|e| Failure::new(format!("`{line}` wrote no drawing ({e}): {output}")))?;
    let mut stale = Vec::new();
    compare(
        "shot-cli.svg",
        &now,
        &format!("`{COMMAND} docs/shot-cli.svg`"),
        check,
        &mut stale,
    )?;
    let swept = scratch.join("low-speed-limit.svg");
    match std::fs::read_to_string(&swept) {
        Ok(now) => compare(
            "low-speed-limit.svg",
            &now,
            &format!("`{SWEEP}`"),
            check,
            &mut stale,
        )?,
        Err(e) => stale.push(format!(
            "docs/low-speed-limit.svg: {} not drawn ({e}): run `{SWEEP}` (a step of `cargo xtask test`)",
            swept.display()
        )),
    }
    Ok(Outcome { stale, compared: 2 })
}

/// The command that draws `target/docs/low-speed-limit.svg`.
pub const SWEEP: &str = "cargo run -p cuesight-host --example low_speed_sweep";

/// Compares `docs/NAME` with the drawing `now` (made by `by`), writing it unless
/// `check`; a difference goes to `stale`.
fn compare(name: &str, now: &str, by: &str, check: bool, stale: &mut Vec<String>) -> Result {
    let path = cmd::root().join("docs").join(name);
    let was = std::fs::read_to_string(&path).unwrap_or_default();
    if was != now {
        stale.push(format!(
            "docs/{name} is not what {by} draws (`cargo xtask docs` writes it)"
        ));
        if !check {
            std::fs::write(&path, now)
                .map_err(|e| Failure::new(format!("writing {}: {e}", path.display())))?;
            println!("xtask docs: updated docs/{name}");
        }
    }
    Ok(())
}
