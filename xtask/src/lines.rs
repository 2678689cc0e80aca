//! Issue 14's size limit on the link crate: at most 1,500 lines of code in `link/src`
//! (no tests live there), a line of code being one that is neither blank nor a comment
//! (`//`, `///`, `//!`). The same count as
//! `cat link/src/*.rs | grep -v '^\s*$' | grep -v '^\s*//' | wc -l`.

use std::fs;

use crate::cmd::{self, Failure, Result};

/// Issue 14: "The link crate ≤ 1,500 lines without tests".
pub const LINK_CODE_LINES_LIMIT: usize = 1_500;

/// Lines of code in `link/src/*.rs`.
pub fn link_code_lines() -> Result<usize> {
    let dir = cmd::root().join("link").join("src");
    let entries =
        fs::read_dir(&dir).map_err(|e| Failure::new(format!("{}: {e}", dir.display())))?;
    let mut lines = 0;
    for entry in entries {
        let path = entry
            .map_err(|e| Failure::new(format!("{}: {e}", dir.display())))?
            .path();
        if path.extension().is_some_and(|ext| ext == "rs") {
            let text = fs::read_to_string(&path)
                .map_err(|e| Failure::new(format!("{}: {e}", path.display())))?;
            lines += code_lines(&text);
        }
    }
    Ok(lines)
}

fn code_lines(text: &str) -> usize {
    text.lines()
        .map(str::trim_start)
        .filter(|line| !line.is_empty() && !line.starts_with("//"))
        .count()
}

/// The step of `cargo xtask test`: fails above [`LINK_CODE_LINES_LIMIT`].
pub fn check_link() -> Result {
    let lines = link_code_lines()?;
    println!("link/src: {lines} lines of code (limit {LINK_CODE_LINES_LIMIT})");
    if lines > LINK_CODE_LINES_LIMIT {
        return Err(Failure::new(format!(
            "link/src has {lines} lines of code, over issue 14's {LINK_CODE_LINES_LIMIT}"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::code_lines;

    #[test]
    fn blank_and_comment_lines_are_not_code() {
        let text = "//! crate\n\n/// doc\n  // note\nfn f() {\n    1 // trailing\n}\n";
        assert_eq!(code_lines(text), 3);
    }
}
