//! Puts the board's `memory.x` (at the repository root) where cortex-m-rt's `link.x`
//! finds it, adds `link.x` to the binaries, and bakes the scene set into the image.
//!
//! The scenes are a binary file written by `cargo xtask bench` from the seeded grid
//! (`cuesight_host::grid::scenes`); its path comes in `CUESIGHT_BENCH_SCENES`, falling
//! back to `../target/bench/scenes.bin`. Without either, an empty set is baked and the
//! bench binary reports that instead of measuring (the probe binary needs no scenes).
//!
//! Likewise the sample stream of the streaming estimator's bench (`stream-count`),
//! written by `cargo xtask bench` from the sensors crate's kinematic stroke model
//! (`sensors/tests/streaming.rs`, `the_bench_stream_gives_its_strokes_and_faults`): its
//! path comes in `CUESIGHT_BENCH_STREAM`, falling back to `../target/bench/stream.bin`.

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

    bake(&manifest, &out, "CUESIGHT_BENCH_SCENES", "scenes.bin");
    bake(&manifest, &out, "CUESIGHT_BENCH_STREAM", "stream.bin");
}

/// Copies the file named by `variable` (default `../target/bench/<name>`) into
/// `OUT_DIR/<name>`, or writes an empty one there.
fn bake(manifest: &std::path::Path, out: &std::path::Path, variable: &str, name: &str) {
    println!("cargo:rerun-if-env-changed={variable}");
    let source = env::var_os(variable)
        .map(PathBuf::from)
        .unwrap_or_else(|| manifest.join("..").join("target").join("bench").join(name));
    println!("cargo:rerun-if-changed={}", source.display());
    let baked = out.join(name);
    if source.is_file() {
        fs::copy(&source, &baked)
            .unwrap_or_else(|e| panic!("copying {} into OUT_DIR: {e}", source.display()));
    } else {
        fs::write(&baked, []).unwrap_or_else(|e| panic!("writing an empty {name}: {e}"));
    }
}
