//! Puts the board's `memory.x` (kept at the repository root, shared by every
//! board-level crate) where cortex-m-rt's `link.x` finds it, and adds the linker
//! scripts of cortex-m-rt and defmt to the firmware binary and the on-target tests.

use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let memory_x =
        PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"))
            .join("..")
            .join("memory.x");
    fs::copy(&memory_x, out.join("memory.x"))
        .unwrap_or_else(|e| panic!("copying {} into OUT_DIR: {e}", memory_x.display()));
    // The QEMU board has its own interrupt vectors (src/board/qemu/vectors.rs), so
    // cortex-m-rt's `device` feature is on, and its link.x includes a `device.x`: here
    // it provides `DefaultHandler` for each named line a build leaves without a handler
    // (as an svd2rust crate's does). (The nrf52840 board's comes with nrf52840-pac.)
    if env::var_os("CARGO_FEATURE_QEMU").is_some() {
        let lines = ["UART0RX", "UART1RX", "UART2RX", "TIMER1", "DUALTIMER"];
        let provide: String = lines
            .iter()
            .map(|line| format!("PROVIDE({line} = DefaultHandler);\n"))
            .collect();
        fs::write(out.join("device.x"), provide)
            .unwrap_or_else(|e| panic!("writing device.x into OUT_DIR: {e}"));
    }
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed={}", memory_x.display());
    println!("cargo:rerun-if-changed=build.rs");
    for kind in ["bins", "tests"] {
        println!("cargo:rustc-link-arg-{kind}=-Tlink.x");
        println!("cargo:rustc-link-arg-{kind}=-Tdefmt.x");
    }
}
