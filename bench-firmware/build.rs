//! Puts the board's `memory.x` (at the repository root) where cortex-m-rt's `link.x`
//! finds it, adds `link.x` to the binaries, and bakes the scene set into the image.
//!
//! The scenes are a binary file written by `cargo xtask bench` from the seeded grid
//! (`cuesight_host::grid::scenes`); its path comes in `CUESIGHT_BENCH_SCENES`, falling
//! back to `../target/bench/scenes.bin`. Without either, an empty set is baked and the
//! bench binary reports that instead of measuring (the probe binary needs no scenes).

use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let manifest =
        PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    let memory_x = manifest.join("..").join("memory.x");
    fs::copy(&memory_x, out.join("memory.x"))
        .unwrap_or_else(|e| panic!("copying {} into OUT_DIR: {e}", memory_x.display()));
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory_x.display());
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-arg-bins=-Tlink.x");

    println!("cargo:rerun-if-env-changed=CUESIGHT_BENCH_SCENES");
    let scenes = env::var_os("CUESIGHT_BENCH_SCENES")
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            manifest
                .join("..")
                .join("target")
                .join("bench")
                .join("scenes.bin")
        });
    println!("cargo:rerun-if-changed={}", scenes.display());
    let baked = out.join("scenes.bin");
    if scenes.is_file() {
        fs::copy(&scenes, &baked)
            .unwrap_or_else(|e| panic!("copying {} into OUT_DIR: {e}", scenes.display()));
    } else {
        fs::write(&baked, []).expect("writing an empty scene set");
    }
}
