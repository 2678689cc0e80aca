//! `cuesight calibrate` (issue 19): recovery of known parameters from synthetic throw
//! (`recovery`), the fit on the shared calibration set (`shared`), every bad-input class
//! (`bad_input`), and the CLI (`--json`, `--params` round trips into `collide`; `cli`).
//!
//! Figures: `cargo test -p cuesight-cli --release --test calibrate -- --nocapture`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod bad_input;
mod cli;
mod recovery;
mod shared;

pub fn shared_set() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/data/measured_throw_calibration.json")
}

pub fn cuesight(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cuesight"))
        .args(args)
        .output()
        .expect("cuesight binary runs")
}

pub fn temp_file(name: &str, contents: &[u8]) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("calibrate");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, contents).unwrap();
    path
}
