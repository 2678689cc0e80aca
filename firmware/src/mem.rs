//! Size-first memory routines: the ARM EABI's `__aeabi_memcpy{,4,8}` and
//! `__aeabi_memclr{,4,8}`, the only ones the images call (checked with `llvm-objdump`),
//! in place of `compiler_builtins`' speed-first ones.
//!
//! `compiler_builtins` copies with unrolled word loads and shifts for every alignment
//! case: 1,280 B of flash for these routines (730 B of them its `memcpy`), 2.8 % of the
//! image. Here each is a plain loop, 4 bytes at a time where both pointers are 4-byte
//! aligned (always, for the `4` forms: the EABI's promise), else one byte at a time:
//! 146 B in all. The image is 1,132 B smaller; the on-target tests execute 1.8 % more
//! instructions (560,897 → 571,176, the copies of frames, answers and scenes; docs/
//! reliability.md, "Flash target", gives the command). That flash is most of what lets
//! the image meet issue 14's 44 KiB target (`cargo xtask test`, step "release image
//! size").
//!
//! The `8` forms (8-byte aligned pointers) are the `4` forms: the live image calls them
//! for its structs with `u64` fields, and `compiler_builtins`' `8` forms brought its
//! `memcpy` back in (1,060 B of flash for the three).
//!
//! The loads and stores are volatile so that LLVM does not recognise the loops as a
//! `memcpy`/`memset` idiom and compile them into a call to themselves. With these
//! defined, the linker takes them and leaves `compiler_builtins`' out (`llvm-nm` of the
//! image lists only these). `tests/on_target.rs` checks them at every alignment.
#![allow(unsafe_code)]

use core::ptr::{read_volatile, write_volatile};

/// Copies `n` bytes from `src` to `dest` (regions do not overlap): as
/// [`__aeabi_memcpy4`] when both are 4-byte aligned, else one byte at a time.
///
/// # Safety
/// As C's `memcpy`: `src` readable and `dest` writable for `n` bytes, no overlap.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memcpy(dest: *mut u8, src: *const u8, n: usize) {
    if (dest as usize | src as usize) % 4 == 0 {
        // SAFETY: the caller's contract, and both pointers are 4-byte aligned.
        return unsafe { __aeabi_memcpy4(dest, src, n) };
    }
    // SAFETY: the caller's contract.
    unsafe { copy_bytes(dest, src, n) }
}

/// The byte loop of [`__aeabi_memcpy`].
///
/// # Safety
/// As [`__aeabi_memcpy`].
unsafe fn copy_bytes(dest: *mut u8, src: *const u8, n: usize) {
    let mut at = 0;
    while at < n {
        // SAFETY: `at < n`, within both regions by the caller's contract.
        unsafe { write_volatile(dest.add(at), read_volatile(src.add(at))) };
        at += 1;
    }
}

/// [`__aeabi_memcpy`] with `dest` and `src` 4-byte aligned (the EABI's promise): words,
/// then the 0–3 bytes left.
///
/// # Safety
/// As [`__aeabi_memcpy`], both pointers 4-byte aligned.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memcpy4(dest: *mut u8, src: *const u8, n: usize) {
    let words = n / 4;
    let mut at = 0;
    while at < words {
        // SAFETY: aligned by the EABI's contract, `4 * at + 4 <= n`.
        unsafe {
            let word = read_volatile(src.cast::<u32>().add(at));
            write_volatile(dest.cast::<u32>().add(at), word);
        }
        at += 1;
    }
    // SAFETY: the rest of the same regions.
    unsafe { copy_bytes(dest.add(words * 4), src.add(words * 4), n % 4) }
}

/// [`__aeabi_memcpy4`]: 8-byte aligned pointers (the EABI's promise) are 4-byte aligned.
///
/// # Safety
/// As [`__aeabi_memcpy`], both pointers 8-byte aligned.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memcpy8(dest: *mut u8, src: *const u8, n: usize) {
    // SAFETY: the caller's contract; 8-byte aligned is 4-byte aligned.
    unsafe { __aeabi_memcpy4(dest, src, n) }
}

/// Sets `n` bytes at `dest` to zero, one byte at a time.
///
/// # Safety
/// As C's `memset(dest, 0, n)`: `dest` writable for `n` bytes.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memclr(dest: *mut u8, n: usize) {
    let mut at = 0;
    while at < n {
        // SAFETY: `at < n`, within the region by the caller's contract.
        unsafe { write_volatile(dest.add(at), 0) };
        at += 1;
    }
}

/// [`__aeabi_memclr`] with `dest` 4-byte aligned: words, then the 0–3 bytes left.
///
/// # Safety
/// As [`__aeabi_memclr`], `dest` 4-byte aligned.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memclr4(dest: *mut u8, n: usize) {
    let words = n / 4;
    let mut at = 0;
    while at < words {
        // SAFETY: aligned by the EABI's contract, `4 * at + 4 <= n`.
        unsafe { write_volatile(dest.cast::<u32>().add(at), 0) };
        at += 1;
    }
    // SAFETY: the rest of the same region.
    unsafe { __aeabi_memclr(dest.add(words * 4), n % 4) }
}

/// [`__aeabi_memclr4`]: an 8-byte aligned `dest` (the EABI's promise) is 4-byte aligned.
///
/// # Safety
/// As [`__aeabi_memclr`], `dest` 8-byte aligned.
#[no_mangle]
pub unsafe extern "aapcs" fn __aeabi_memclr8(dest: *mut u8, n: usize) {
    // SAFETY: the caller's contract; 8-byte aligned is 4-byte aligned.
    unsafe { __aeabi_memclr4(dest, n) }
}
