//! `docs/shot-cli.svg`, the example drawing of `docs/shot-cli.md`: what `cuesight shot
//! --scene cli/scenes/cut_to_corner.toml --svg FILE` draws. `cargo xtask docs` writes
//! it, `--check` fails when it differs (the drawing changed and the page's example did
//! not).

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
    let path = root.join("docs").join("shot-cli.svg");
    let was = std::fs::read_to_string(&path).unwrap_or_default();
    let mut stale = Vec::new();
    if was != now {
        stale.push(format!(
            "docs/shot-cli.svg is not what `{COMMAND} docs/shot-cli.svg` draws (`cargo xtask docs` writes it)"
        ));
        if !check {
            std::fs::write(&path, &now)
                .map_err(|e| Failure::new(format!("writing {}: {e}", path.display())))?;
            println!("xtask docs: updated docs/shot-cli.svg");
        }
    }
    Ok(Outcome { stale, compared: 1 })
}
