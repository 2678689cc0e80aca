//! The firmware's other images: the live cue (`live`), the nrf52840 board and the
//! link-time no-panic proof (`panic-never`), beside the default (QEMU link) image of
//! [`crate::qemu::build_release`].
//!
//! Each is built in `firmware/`'s one target directory, where the default image's
//! dependencies, proc macros and build scripts already are: in a target directory of
//! its own each compiled them all again (the live image 35 s, the no-panic proof 28 s of
//! a bare-machine CI run). Cargo keeps every feature set's artifacts apart, but all
//! images are linked to the same path, `<target>/thumbv7em-none-eabihf/release/
//! cuesight-firmware`. So [`Variant::build`] copies the variant's ELF to
//! `firmware/target/<name>/thumbv7em-none-eabihf/release/cuesight-firmware` (the path its
//! own target directory gave it, which the docs name) and puts back the default image's
//! file at the shared path, so the QEMU steps, which read the default image there,
//! never find a variant.

use std::path::{Path, PathBuf};

use crate::cmd::{self, Failure, Result};
use crate::{qemu, tools};

/// A firmware image built with other features than the default.
pub struct Variant {
    /// Its directory under `firmware/target/`.
    name: &'static str,
    /// Its feature arguments to `cargo build --release`.
    features: &'static [&'static str],
    /// Whether `cargo clippy -- -D warnings` runs on it before the build.
    linted: bool,
}

/// The live cue: RTIC 2, the emulated IMU, the streaming estimator, guidance on impact;
/// no stroke upload.
pub const LIVE: Variant = Variant {
    name: "live",
    features: &["--no-default-features", "--features", "live"],
    linted: true,
};

/// The nrf52840 board. `--no-default-features` leaves the `shot` request out too (the
/// board's image with it is over the 44 KiB target the link images are held to, though
/// within the 48 KiB budget: [`NRF52840_SHOT`]), so this also builds and lints the
/// firmware without `shot`.
pub const NRF52840: Variant = Variant {
    name: "nrf52840",
    features: &["--no-default-features", "--features", "nrf52840"],
    linted: true,
};

/// The nrf52840 board with the `shot` request (README's "nRF52840": within the 48 KiB
/// budget, over the 44 KiB target; built only for `cargo xtask docs`' figure).
pub const NRF52840_SHOT: Variant = Variant {
    name: "nrf52840-shot",
    features: &["--no-default-features", "--features", "nrf52840,shot"],
    linted: false,
};

/// The live cue on the nrf52840 board (issue 15, item 5): RTIC 2, a real LSM6DSOX on
/// SPIM3 with its data-ready on GPIOTE, the streaming estimator, guidance on impact;
/// no stroke upload. Built and linted, not run (no hardware).
pub const NRF52840_LIVE: Variant = Variant {
    name: "nrf52840-live",
    features: &["--no-default-features", "--features", "nrf52840-live"],
    linted: true,
};

/// The default image with the panic handler replaced by a call to a symbol that exists
/// nowhere: it links only if no panic path survives optimisation (README, "No panic
/// path"). Not linted apart: its code is the default image's, which "firmware: clippy"
/// lints.
pub const PANIC_NEVER: Variant = Variant {
    name: "panic-never",
    features: &["--features", "panic-never"],
    linted: false,
};

impl Variant {
    /// Where [`Variant::build`] leaves the image's release ELF.
    pub fn elf(&self) -> PathBuf {
        cmd::firmware_dir()
            .join("target")
            .join(self.name)
            .join(tools::TARGET)
            .join("release")
            .join("cuesight-firmware")
    }

    /// `cargo build --release` with the variant's features in `firmware/`, its ELF copied
    /// to [`Variant::elf`]; the shared path holds what it held before.
    pub fn build(&self) -> Result<PathBuf> {
        let shared = qemu::elf_path();
        // Cargo hard-links the ELF it links to the shared path: the default image's
        // entry is moved aside (cargo's own artifact is left as it is) and back after.
        let parked = shared.with_extension("default");
        let had_default = shared.is_file();
        if had_default {
            rename(&shared, &parked)?;
        }
        let cargo = |subcommand: &str, trailing: &[&str]| {
            cmd::run(
                cmd::cargo()
                    .args([subcommand, "--release"])
                    .args(self.features)
                    .args(trailing)
                    .current_dir(cmd::firmware_dir()),
            )
        };
        // Linted in a run of its own: clippy-driver compiles with MIR optimisations
        // off, so an image it built would not be the one users build (the live image
        // came out 56 B smaller that way).
        let linted = if self.linted {
            cargo("clippy", &["--", "-D", "warnings"])
        } else {
            Ok(())
        };
        let built = linted
            .and_then(|()| cargo("build", &[]))
            .and_then(|()| copy(&shared, &self.elf()));
        // Even when the build failed: cargo may have linked the variant first.
        let restored = remove_if_present(&shared).and_then(|()| {
            if had_default {
                rename(&parked, &shared)
            } else {
                Ok(())
            }
        });
        built.and(restored).map(|()| self.elf())
    }
}

fn rename(from: &Path, to: &Path) -> Result {
    std::fs::rename(from, to).map_err(|e| {
        Failure::new(format!(
            "moving {} to {}: {e}",
            from.display(),
            to.display()
        ))
    })
}

/// Copies `from` to a new file at `to` (an old `to` may be a hard link into a target
/// directory, so it is removed, not written through).
fn copy(from: &Path, to: &Path) -> Result {
    let failed = |e: std::io::Error| {
        Failure::new(format!(
            "copying {} to {}: {e}",
            from.display(),
            to.display()
        ))
    };
    if let Some(dir) = to.parent() {
        std::fs::create_dir_all(dir).map_err(failed)?;
    }
    remove_if_present(to)?;
    std::fs::copy(from, to).map(drop).map_err(failed)
}

fn remove_if_present(path: &Path) -> Result {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            Err(Failure::new(format!("removing {}: {e}", path.display())))
        }
        _ => Ok(()),
    }
}
