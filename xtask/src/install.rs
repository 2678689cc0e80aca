//! `cargo xtask test`'s install of what its QEMU steps need (`tools::ensure_for_qemu`:
//! QEMU by apt-get, defmt-print by `cargo install`), on a thread of its own beside the
//! host steps.

use std::fs::File;
use std::path::PathBuf;
use std::sync::Mutex;
use std::thread::JoinHandle;
use std::time::Instant;

use crate::cmd::{self, Failure, Result};
use crate::tools;

/// The install of what the QEMU steps need (`tools::ensure_for_qemu`: QEMU by apt-get,
/// defmt-print by `cargo install`), running on a thread of its own while the host steps
/// run; taken by [`ready`].
static INSTALLS: Mutex<Option<JoinHandle<Result>>> = Mutex::new(None);

/// Where the background install's commands write their output.
fn install_log() -> PathBuf {
    cmd::root().join("target").join("xtask").join("install.log")
}

/// Starts [`INSTALLS`]. On a bare machine defmt-print's build took 75 s before the
/// first step could start; beside the host steps, at the lowest CPU priority, it takes
/// what they leave idle. Nothing that needs QEMU or defmt-print runs before the step
/// [`ready`] has joined the install, so no step's deadline (the demo session's
/// 60 s) is spent on one.
pub fn start() -> Result {
    let path = install_log();
    let log = path
        .parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| File::create(&path))
        .map_err(|e| Failure::new(format!("cannot write {}: {e}", path.display())))?;
    let handle = std::thread::spawn(move || cmd::logging_to(log, tools::ensure_for_qemu));
    *INSTALLS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner()) = Some(handle);
    Ok(())
}

/// Waits for [`INSTALLS`] (or installs now, if no install was started) and shows the
/// install's log when it failed.
pub fn ready() -> Result {
    let pending = INSTALLS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .take();
    let Some(handle) = pending else {
        return tools::ensure_for_qemu();
    };
    let waited = Instant::now();
    let result = handle
        .join()
        .unwrap_or_else(|_| Err(Failure::new("the install thread panicked")));
    println!(
        "xtask: waited {:.1} s for the install",
        crate::test::secs(waited)
    );
    if result.is_err() {
        if let Ok(log) = std::fs::read_to_string(install_log()) {
            eprintln!("{log}");
        }
    }
    result
}

/// Waits for an install still running (after a failed step), ignoring its result.
pub fn finish() {
    let pending = INSTALLS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .take();
    if let Some(handle) = pending {
        let _ = handle.join();
    }
}
