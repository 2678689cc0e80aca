//! `cargo xtask test`'s Python steps: the `cuesight` package of `python/` (PyO3 +
//! maturin, a workspace of its own like `firmware/`, so the host workspace's fmt and
//! clippy do not see it) linted, installed with pip into a virtual environment under
//! the target directory, and its pytest suite run against the `cuesight` CLI, the
//! reference of identity (`python/tests/conftest.py`).
//!
//! pip builds the extension into `<target>/python/cargo` (`CARGO_TARGET_DIR`), so
//! nothing is written inside `python/` and a second run reuses the first's build, and
//! clippy lints the package's crate in that build (`tools::lint_while_building`). The extension
//! depends on `cuesight-cli` (the CLI's code: `shot`, `calibrate`, and through it the
//! reference solver of `cuesight-host`), so that build includes both crates and their
//! dependencies: about 165 s
//! cold, 34 s warm on 2 shared cores. The calibration tests read the shared
//! measured-throw set from `../shared` beside the repository (skipped, saying so,
//! without it).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::cmd::{self, probe, Failure, Result};

/// The package's directory.
fn package_dir() -> PathBuf {
    cmd::root().join("python")
}

/// The host workspace's target directory (honours `CARGO_TARGET_DIR`).
fn host_target_dir() -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) => cmd::root().join(dir),
        None => cmd::root().join("target"),
    }
}

/// Where the package's cargo builds and its virtual environment go.
fn python_target_dir() -> PathBuf {
    host_target_dir().join("python")
}

/// `cargo` in `python/`, building into [`python_target_dir`].
fn cargo_in_package(args: &[&str]) -> Result {
    cmd::run(
        cmd::cargo()
            .args(args)
            .current_dir(package_dir())
            .env("CARGO_TARGET_DIR", python_target_dir().join("cargo")),
    )
}

/// `cargo fmt --check` on the package's Rust crate (its own workspace). Clippy lints it
/// in [`tests`], while pip builds it.
pub fn lint() -> Result {
    // Not `--all`: that would format the path dependencies too (core, link, sensors),
    // which "host: rustfmt" checks already.
    cargo_in_package(&["fmt", "--", "--check"])
}

/// A Python 3.9 or newer to make the virtual environment with: `python3`, else `python`.
fn system_python() -> Result<PathBuf> {
    let check = "import sys; assert sys.version_info >= (3, 9); print(sys.executable)";
    ["python3", "python"]
        .into_iter()
        .find_map(|name| probe(Command::new(name).args(["-c", check])))
        .map(|exe| PathBuf::from(exe.trim()))
        .ok_or_else(|| {
            Failure::new(
                "no Python 3.9 or newer on PATH (python3 or python) for the Python package",
            )
        })
}

/// The virtual environment's interpreter, the environment made first if missing.
fn venv_python() -> Result<PathBuf> {
    let venv = python_target_dir().join("venv");
    let python = venv.join("bin").join("python");
    if !python.is_file() {
        cmd::run(
            Command::new(system_python()?)
                .args(["-m", "venv"])
                .arg(&venv),
        )?;
    }
    Ok(python)
}

/// The `cuesight` CLI the tests compare with, built if it is not (the debug profile, as
/// "host: tests" leaves it). `--workspace`, not `-p cuesight-cli`: the features are
/// then the ones "host: tests" built the binary with, so after that step this is a
/// no-op, where `-p` resolved other features (no `schema` on core, link and sensors)
/// and rebuilt core, link, sensors and the CLI (57 s of a bare-machine CI run).
fn cli() -> Result<PathBuf> {
    cmd::run(crate::tools::host_cargo()?.args(["build", "--workspace", "--bin", "cuesight"]))?;
    Ok(host_target_dir().join("debug").join("cuesight"))
}

/// `pip install ./python pytest numpy` into the virtual environment (pip fetches
/// maturin, the build backend, and builds the extension in release), then pytest on
/// `python/tests` with `CUESIGHT_CLI` set, so no test is skipped for want of the CLI.
pub fn tests() -> Result {
    let python = venv_python()?;
    let mut pip = Command::new(&python);
    pip.args(["-m", "pip", "--disable-pip-version-check", "install", "-q"])
        .args(["./python", "pytest", "numpy"])
        .env("CARGO_TARGET_DIR", python_target_dir().join("cargo"))
        // The CI build need not be the fastest extension (fat LTO and one codegen unit
        // are for the throughput benchmark): a thin, parallel release build halves the
        // step's cold time. Optimisation does not change an f32 result (no fast-math),
        // so the identity tests hold.
        .env("CARGO_PROFILE_RELEASE_LTO", "false")
        .env("CARGO_PROFILE_RELEASE_CODEGEN_UNITS", "16");
    // pip's build backend (maturin) runs cargo with this environment, so the package's
    // crate is linted as `cargo clippy -- -D warnings` would, in the one build.
    cmd::run(crate::tools::lint_while_building(&mut pip)?)?;
    let cli = cli()?;
    // From the repository root: `import cuesight` is then the installed package, not
    // python/cuesight/ (the sources, without the compiled extension).
    cmd::run(
        Command::new(&python)
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(Path::new("python").join("tests"))
            .env("CUESIGHT_CLI", &cli),
    )
}
