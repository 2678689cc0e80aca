//! The defmt global logger: frames over semihosting to the host's **stderr**.
//!
//! QEMU's Arm semihosting (`target=native`) implements `SH_EXT_STDOUT_STDERR`: `:tt`
//! opened for writing is its stdout, opened for appending its stderr. The protocol owns
//! stdout (`-serial stdio`), so the log takes stderr, where `cargo xtask` decodes it
//! with `defmt-print`. (`-semihosting-config chardev=` would only redirect the
//! one-character `SYS_WRITEC`/`SYS_WRITE0` calls, not `SYS_WRITE` to `:tt`.)
//!
//! Like `defmt-semihosting`, but for stderr and without panics: a re-entrant call (a
//! fault while a frame is being written) ends the program with failure instead.

use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicBool, Ordering};

use cortex_m_semihosting::hio::{self, HostStream};

#[defmt::global_logger]
struct Logger;

struct State {
    encoder: defmt::Encoder,
    stream: Option<HostStream>,
    restore: critical_section::RestoreState,
}

struct Shared {
    taken: AtomicBool,
    state: UnsafeCell<State>,
}

// SAFETY: `state` is only touched between `acquire` and `release`, inside a critical
// section, and `taken` refuses a second owner.
#[allow(unsafe_code)]
unsafe impl Sync for Shared {}

static SHARED: Shared = Shared {
    taken: AtomicBool::new(false),
    state: UnsafeCell::new(State {
        encoder: defmt::Encoder::new(),
        stream: None,
        restore: critical_section::RestoreState::invalid(),
    }),
};

#[inline(never)]
fn emit(stream: &mut Option<HostStream>, bytes: &[u8]) {
    if let Some(stream) = stream {
        // Nothing to do about a host that refuses the log.
        let _ = stream.write_all(bytes);
    }
}

// SAFETY: acquire/release bracket every frame in a critical section and `taken`
// makes the logger exclusive, as `defmt::Logger` requires.
#[allow(unsafe_code)]
unsafe impl defmt::Logger for Logger {
    fn acquire() {
        // SAFETY: released exactly once, in `release`.
        let restore = unsafe { critical_section::acquire() };
        if SHARED.taken.swap(true, Ordering::Relaxed) {
            // A fault inside the logger: nothing more can be logged.
            super::exit(false);
        }
        // SAFETY: exclusive (critical section + `taken`).
        let state = unsafe { &mut *SHARED.state.get() };
        state.restore = restore;
        if state.stream.is_none() {
            state.stream = hio::hstderr().ok();
        }
        let State {
            encoder, stream, ..
        } = state;
        encoder.start_frame(|bytes| emit(stream, bytes));
    }

    unsafe fn flush() {
        // Semihosting writes are synchronous: the host has every byte already.
    }

    unsafe fn release() {
        if !SHARED.taken.load(Ordering::Relaxed) {
            return;
        }
        // SAFETY: exclusive until `taken` is cleared below.
        let state = unsafe { &mut *SHARED.state.get() };
        let State {
            encoder, stream, ..
        } = state;
        encoder.end_frame(|bytes| emit(stream, bytes));
        let restore = state.restore;
        SHARED.taken.store(false, Ordering::Relaxed);
        // SAFETY: pairs with the `acquire` of this frame.
        unsafe { critical_section::release(restore) };
    }

    unsafe fn write(bytes: &[u8]) {
        if !SHARED.taken.load(Ordering::Relaxed) {
            return;
        }
        // SAFETY: exclusive (inside a frame).
        let state = unsafe { &mut *SHARED.state.get() };
        let State {
            encoder, stream, ..
        } = state;
        encoder.write(bytes, |out| emit(stream, out));
    }
}
