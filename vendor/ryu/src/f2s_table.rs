//! cuesight patch: the powers of 5 that `f32` formatting needs, 64 bits each, read at
//! compile time from the `f64` tables (`d2s_full_table`, the upper halves of their
//! entries, as `f2s_intrinsics` used them): 31 + 48 entries, 632 bytes, in place of the
//! `small` feature's computation of every power from a few (about 1.5 KB of code and
//! tables on a Cortex-M4) or the full tables (about 10 KB). The C reference
//! implementation of Ryū has tables of this kind for `f32` (`FLOAT_POW5_INV_SPLIT`,
//! `FLOAT_POW5_SPLIT`).

use crate::d2s_full_table::{DOUBLE_POW5_INV_SPLIT, DOUBLE_POW5_SPLIT};

/// Entries `0..=30` of `DOUBLE_POW5_INV_SPLIT`'s upper halves: `q = log10_pow2(e2)` for
/// an `f32`'s `e2 <= 102`, and `q - 1`.
pub static FLOAT_POW5_INV_SPLIT: [u64; 31] = upper_halves(&DOUBLE_POW5_INV_SPLIT);

/// Entries `0..=47` of `DOUBLE_POW5_SPLIT`'s upper halves: `i = -e2 - log10_pow5(-e2)`
/// for an `f32`'s `-e2 <= 151`, and `i + 1`.
pub static FLOAT_POW5_SPLIT: [u64; 48] = upper_halves(&DOUBLE_POW5_SPLIT);

const fn upper_halves<const N: usize>(table: &[(u64, u64)]) -> [u64; N] {
    let mut halves = [0u64; N];
    let mut i = 0;
    while i < N {
        halves[i] = table[i].1;
        i += 1;
    }
    halves
}
