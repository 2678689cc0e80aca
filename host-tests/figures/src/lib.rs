//! The figures `README.md` and `docs/` quote, recorded by the tests that measure them.
//!
//! A test that measures a figure the docs quote records it, formatted as the docs
//! print it:
//!
//! ```no_run
//! let worst_error_pct = 0.7412_f64;
//! cuesight_figures::record!("sensors-speed-error-max", "{worst_error_pct:.2}");
//! ```
//!
//! and the docs hold it in a generated block,
//! `<!-- docs:figure sensors-speed-error-max -->0.74<!-- /docs -->`. `cargo xtask docs`
//! writes the recorded value there; `cargo xtask docs --check` (a CI step, after every
//! step that runs tests) fails when the docs and the recording differ. So a figure
//! cannot drift from the code that measures it: a change that moves it fails CI until
//! the docs are regenerated.
//!
//! Each figure is a file `target/figures/KEY` (or under `$CUESIGHT_FIGURES_DIR`): the
//! value on its first line, the command that records it on its second (`cargo test -p
//! PACKAGE --test TARGET -- TEST --exact`, or an example's or binary's `cargo run`
//! command line). Keys are lowercase ASCII letters, digits and `-`.
//!
//! Only figures that the same code gives on every machine belong here: counts, errors
//! against a reference, sizes, instruction counts. A wall time or a rate is a
//! measurement of the machine and stays prose naming its command.

use std::fmt::Display;
use std::path::PathBuf;

/// `format!` for [`record!`], reachable from crates without `std` in scope (the core's
/// `no_std` unit tests).
#[doc(hidden)]
pub use std::format as __format;

/// Records a figure: `record!(KEY, FORMAT, ARGS...)` formats as `format!` does.
/// The caller's package and test target name the command that records it.
#[macro_export]
macro_rules! record {
    ($key:expr, $($format:tt)+) => {
        $crate::record_from(
            env!("CARGO_PKG_NAME"),
            env!("CARGO_CRATE_NAME"),
            option_env!("CARGO_BIN_NAME").is_some(),
            $key,
            &$crate::__format!($($format)+),
        )
    };
}

/// An integer with a comma every three digits, as the docs print counts: `136,679`.
pub fn thousands(n: impl Display) -> String {
    let text = n.to_string();
    let (sign, digits) = match text.strip_prefix('-') {
        Some(digits) => ("\u{2212}", digits),
        None => ("", text.as_str()),
    };
    let mut out = String::from(sign);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// `x` to `decimals` places with the minus sign (U+2212) the docs print: `−0.036`.
pub fn signed(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}").replace('-', "\u{2212}")
}

/// Where figures are kept: `$CUESIGHT_FIGURES_DIR`, else `target/figures` at the
/// workspace root.
pub fn dir() -> PathBuf {
    match std::env::var_os("CUESIGHT_FIGURES_DIR") {
        Some(dir) => PathBuf::from(dir),
        None => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/figures"),
    }
}

/// Whether `key` is a valid figure name (lowercase ASCII letters, digits, `-`).
pub fn valid_key(key: &str) -> bool {
    !key.is_empty()
        && key
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-')
}

/// [`record!`]'s body. Panics (it runs in tests) on an invalid key, a value with a line
/// break, or a file it cannot write: a figure that silently went unrecorded would let
/// `--check` compare against an old one.
///
/// `runnable` is a binary or an example (`cargo run`): the command is then its own
/// command line, arguments included; otherwise a test's, from its thread's name.
pub fn record_from(package: &str, target: &str, runnable: bool, key: &str, value: &dyn Display) {
    let thread = std::thread::current();
    let test = thread.name().unwrap_or("main");
    // An `#[ignore]`d test (run by `cargo xtask test` with `--ignored`) says so.
    let ignored = if std::env::args().any(|a| a == "--ignored" || a == "--include-ignored") {
        " --ignored"
    } else {
        ""
    };
    let command = if runnable {
        let exe = std::env::current_exe().unwrap_or_default();
        let kind = if exe.components().any(|c| c.as_os_str() == "examples") {
            "--example"
        } else {
            "--bin"
        };
        let args: Vec<String> = std::env::args().skip(1).collect();
        format!(
            "cargo run --release -p {package} {kind} {target} -- {}",
            args.join(" ")
        )
    } else if target == package.replace('-', "_") {
        format!("cargo test -p {package} --lib -- {test} --exact{ignored}")
    } else {
        format!("cargo test -p {package} --test {target} -- {test} --exact{ignored}")
    };
    if let Err(e) = record_with(key, value, &command) {
        panic!("figure {key}: writing {}: {e}", dir().display());
    }
}

/// Records a figure measured by a command that is not a test (`cargo xtask`'s steps),
/// named by `command`. Panics on an invalid key or a value that is not one line (a
/// programming error), returns the error of a file it cannot write.
pub fn record_with(key: &str, value: &dyn Display, command: &str) -> std::io::Result<()> {
    assert!(valid_key(key), "figure key {key:?}: use a-z, 0-9 and -");
    let value = value.to_string();
    assert!(
        !value.contains('\n') && !value.is_empty(),
        "figure {key}: {value:?} must be one non-empty line"
    );
    let dir = dir();
    std::fs::create_dir_all(&dir).and_then(|()| {
        // Written whole then renamed: two test threads never leave a torn file.
        static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let write = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let temporary = dir.join(format!(".{key}.{}.{write}", std::process::id()));
        std::fs::write(&temporary, format!("{value}\n{command}\n"))?;
        std::fs::rename(&temporary, dir.join(key))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats() {
        assert_eq!(thousands(0u32), "0");
        assert_eq!(thousands(999usize), "999");
        assert_eq!(thousands(1000u64), "1,000");
        assert_eq!(thousands(136_679usize), "136,679");
        assert_eq!(thousands(-16_394i32), "\u{2212}16,394");
        assert_eq!(signed(-0.0364, 3), "\u{2212}0.036");
        assert_eq!(signed(2.5, 2), "2.50");
    }

    #[test]
    fn keys() {
        assert!(valid_key("sensors-speed-error-max"));
        assert!(valid_key("e2e-frames-2"));
        assert!(!valid_key(""));
        assert!(!valid_key("Speed"));
        assert!(!valid_key("a/b"));
        assert!(!valid_key("a b"));
    }
}
