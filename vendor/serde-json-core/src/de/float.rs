//! cuesight patch: a panic-free decimal → float parser, replacing `f32::from_str` /
//! `f64::from_str` (core's `dec2flt` keeps bounds-checked slice indexing and bignum
//! arithmetic that the optimiser cannot prove in range, so a firmware using them cannot
//! be proved panic-free at link time).
//!
//! Accepts `[+-]? digits [. digits]? ([eE] [+-]? digits)?` (at least one digit in the
//! mantissa), the number syntax of JSON plus a leading `+` and an empty integer or
//! fraction part, as `from_str` did for the characters this crate hands it.
//!
//! Accuracy: the first 19 significant digits are kept exactly (a `u64`). With at most
//! 15 of them and a decimal exponent within ±22, the f64 result is correctly rounded
//! (Clinger's fast path: one exact operand, one exact power of ten, one rounding); an
//! f32 is then rounded once more from that f64, which can differ from a correctly
//! rounded f32 only for decimal inputs within 2^-29 ulp of a tie. Outside that domain
//! the power of ten is applied in steps of 10^22 (a few f64 roundings: well within one
//! f32 ulp for normal results). Overflow gives ±inf, underflow ±0.

use core::convert::TryFrom;

/// Exact powers of ten in f64 (10^0 ..= 10^22).
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Types this parser produces.
pub(crate) trait FromDecimal: Sized {
    fn from_decimal(text: &[u8]) -> Option<Self>;
}

impl FromDecimal for f64 {
    fn from_decimal(text: &[u8]) -> Option<Self> {
        parse(text)
    }
}

impl FromDecimal for f32 {
    fn from_decimal(text: &[u8]) -> Option<Self> {
        parse_f32(text)
    }
}

/// 10^e for 0 <= e <= 22.
fn pow10(e: i32) -> f64 {
    usize::try_from(e)
        .ok()
        .and_then(|e| POW10.get(e))
        .copied()
        .unwrap_or(1.0)
}

/// Parses `text` as a whole; `None` if it is not a number.
pub(crate) fn parse(text: &[u8]) -> Option<f64> {
    let (negative, mantissa, exp10, _) = parts(text)?;
    let magnitude = scale(mantissa, exp10);
    Some(if negative { -magnitude } else { magnitude })
}

/// Parses `text` as a whole into an f32 with integer arithmetic only (no f64: on a
/// Cortex-M4F that is software floating point, several KB of flash). Correctly rounded
/// (ties to even; 300,000 random decimals agree bit for bit with `str::parse`) except
/// when the first 19 significant digits fall within about 10^-18 (relative) of a tie
/// between two floats and later digits decide it, where the result can be the other
/// neighbour; `None` if it is not a number.
pub(crate) fn parse_f32(text: &[u8]) -> Option<f32> {
    let (negative, mantissa, exp10, dropped) = parts(text)?;
    let magnitude = scale_f32(mantissa, exp10, dropped);
    Some(if negative { -magnitude } else { magnitude })
}

/// Sign, the first 19 significant digits as an integer, the decimal exponent of its
/// last digit, and whether a non-zero digit was dropped after those 19.
fn parts(text: &[u8]) -> Option<(bool, u64, i64, bool)> {
    let mut dropped = false;
    let mut bytes = text.iter().copied().peekable();
    let negative = match bytes.peek() {
        Some(b'-') => {
            bytes.next();
            true
        }
        Some(b'+') => {
            bytes.next();
            false
        }
        _ => false,
    };
    let mut mantissa: u64 = 0;
    let mut kept: u32 = 0; // significant digits in `mantissa`
    let mut exp10: i64 = 0; // decimal exponent of `mantissa`'s last digit
    let mut digits = 0u32;
    let mut in_fraction = false;
    while let Some(&c) = bytes.peek() {
        match c {
            b'0'..=b'9' => {
                bytes.next();
                digits = digits.saturating_add(1);
                let d = u64::from(c - b'0');
                if kept < 19 {
                    if mantissa != 0 || d != 0 {
                        mantissa = mantissa * 10 + d; // < 10^19 < 2^64
                        kept += 1;
                    }
                    if in_fraction {
                        exp10 -= 1;
                    }
                } else {
                    dropped |= d != 0;
                    if !in_fraction {
                        exp10 += 1; // a dropped integer digit
                    }
                }
            }
            b'.' if !in_fraction => {
                bytes.next();
                in_fraction = true;
            }
            _ => break,
        }
    }
    if digits == 0 {
        return None;
    }
    if let Some(b'e' | b'E') = bytes.peek() {
        bytes.next();
        let exp_negative = match bytes.peek() {
            Some(b'-') => {
                bytes.next();
                true
            }
            Some(b'+') => {
                bytes.next();
                false
            }
            _ => false,
        };
        let mut exp: i64 = 0;
        let mut exp_digits = 0u32;
        while let Some(&c) = bytes.peek() {
            if !c.is_ascii_digit() {
                break;
            }
            bytes.next();
            exp_digits += 1;
            exp = (exp * 10 + i64::from(c - b'0')).min(100_000);
        }
        if exp_digits == 0 {
            return None;
        }
        exp10 += if exp_negative { -exp } else { exp };
    }
    if bytes.next().is_some() {
        return None; // trailing characters
    }
    Some((negative, mantissa, exp10, dropped))
}

/// 10^0 ..= 10^9 (each below 2^30; division uses at most 10^4, below 2^14).
const POW10_U64: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// `mantissa · 10^exp10` rounded to f32 (ties to even). The value is carried as
/// `x · 2^binary` with `x` a u64 holding 64 significant bits (after the first step) and
/// `inexact` recording any non-zero bit dropped on the way (the sticky bit of the final
/// rounding); each step's truncation is below 2^-62 of the value.
fn scale_f32(mantissa: u64, exp10: i64, dropped: bool) -> f32 {
    if mantissa == 0 {
        return 0.0;
    }
    // mantissa < 10^19: beyond these the result is ±inf or 0 whatever the digits.
    if exp10 > 40 {
        return f32::INFINITY;
    }
    if exp10 < -70 {
        return 0.0;
    }
    let (mut x, mut binary, mut inexact) = (mantissa, 0i32, dropped);
    let mut e = exp10 as i32;
    while e > 0 {
        let step = e.min(9);
        let factor = POW10_U64.get(step as usize).copied().unwrap_or(1);
        // The exact product (< 2^94), cut back to its top 64 bits.
        let product = u128::from(x) * u128::from(factor);
        let shift = (128 - product.leading_zeros() as i32 - 64).max(0);
        inexact |= product & ((1u128 << shift) - 1) != 0;
        x = (product >> shift) as u64;
        binary += shift;
        e -= step;
    }
    while e < 0 {
        let step = (-e).min(4);
        let divisor = POW10_U64.get(step as usize).copied().unwrap_or(1) as u32;
        let normalize = x.leading_zeros(); // x ≥ 2^63 afterwards
        x <<= normalize;
        binary -= normalize as i32;
        // x / divisor to 64 significant bits: the integer quotient, then as many
        // fraction bits as it has leading zeros (at most 14: divisor < 2^14).
        let (quotient, remainder) = div_small(x, divisor);
        let shift = quotient.leading_zeros();
        let (fraction, rest) = div_small(u64::from(remainder) << shift, divisor);
        inexact |= rest != 0;
        x = (quotient << shift) | fraction;
        binary -= shift as i32;
        e += step;
    }
    round_to_f32(x, binary, inexact)
}

/// `(x / divisor, x % divisor)` for a divisor below 2^16, by long division in 16-bit
/// digits with the hardware's 32-bit divide (a u64 division is a library routine of
/// about 1 KB on the Cortex-M4).
fn div_small(x: u64, divisor: u32) -> (u64, u32) {
    let divisor = divisor.max(1);
    let (mut quotient, mut remainder) = (0u64, 0u32);
    for shift in [48u32, 32, 16, 0] {
        let current = (remainder << 16) | ((x >> shift) as u32 & 0xffff); // < 2^32
        quotient = (quotient << 16) | u64::from(current / divisor);
        remainder = current % divisor;
    }
    (quotient, remainder)
}

/// `x · 2^binary` (x > 0; `inexact`: the true value is a little more) to the nearest
/// f32, ties to even.
fn round_to_f32(x: u64, binary: i32, inexact: bool) -> f32 {
    let top = 63 - x.leading_zeros() as i32; // x in [2^top, 2^(top+1))
    let exponent = top + binary; // the value in [2^exponent, 2^(exponent+1))
    if exponent > 127 {
        return f32::INFINITY;
    }
    // Significant bits kept: 24 for a normal result, fewer for a subnormal one.
    let keep = if exponent >= -126 { 24 } else { exponent + 150 };
    if keep < 0 {
        return 0.0; // below half the smallest subnormal
    }
    let drop = top + 1 - keep;
    let mut m = if drop <= 0 {
        x << (-drop) // exact: fewer than 24 significant bits
    } else {
        let kept = x.checked_shr(drop as u32).unwrap_or(0);
        let rest = x & (1u64.checked_shl(drop as u32).unwrap_or(0).wrapping_sub(1));
        let half = 1u64 << (drop - 1);
        let up = rest > half || (rest == half && (inexact || kept & 1 == 1));
        kept + u64::from(up)
    };
    let bits = if exponent >= -126 {
        let mut biased = exponent + 127;
        if m == 1 << 24 {
            m >>= 1; // rounding carried into the next binade
            biased += 1;
        }
        if biased > 254 {
            return f32::INFINITY;
        }
        ((biased as u32) << 23) | (m as u32 & 0x007f_ffff)
    } else {
        // Subnormal: the field is m (a carry to 2^23 is the smallest normal, as wanted).
        m as u32
    };
    f32::from_bits(bits)
}

/// `mantissa * 10^exp10` in f64.
fn scale(mantissa: u64, exp10: i64) -> f64 {
    if mantissa == 0 {
        return 0.0;
    }
    // Far outside f64's range either way (mantissa < 10^19): saturate.
    if exp10 > 330 {
        return f64::INFINITY;
    }
    if exp10 < -360 {
        return 0.0;
    }
    let mut e = exp10 as i32;
    let mut value = mantissa as f64; // exact up to 2^53
    if e >= 0 {
        while e > 22 {
            value *= 1e22;
            e -= 22;
        }
        value * pow10(e)
    } else {
        // Keep the intermediate away from the subnormal range as long as possible:
        // divide by the exact powers (one rounding each).
        while e < -22 {
            value /= 1e22;
            e += 22;
        }
        value / pow10(-e)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::format;
    use std::string::String;

    use super::{parse, parse_f32};

    /// A small deterministic generator (xorshift64*), to keep the crate's dev-dependencies
    /// as upstream's.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
        }
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }

    #[test]
    fn f32_agrees_with_core_on_random_decimals() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let mut text = String::new();
        for _ in 0..300_000 {
            text.clear();
            if rng.below(2) == 0 {
                text.push('-');
            }
            let digits = 1 + rng.below(24);
            let point = rng.below(digits + 1);
            for i in 0..digits {
                if i == point && i > 0 {
                    text.push('.');
                }
                text.push(char::from(b'0' + rng.below(10) as u8));
            }
            if rng.below(3) > 0 {
                let exp = rng.below(100) as i64 - 60;
                text.push_str(&format!("e{exp}"));
            }
            let ours = parse_f32(text.as_bytes());
            let core: Option<f32> = text.parse().ok();
            assert_eq!(
                ours.map(f32::to_bits),
                core.map(f32::to_bits),
                "{text}: {ours:?} vs {core:?}"
            );
        }
    }

    #[test]
    fn f32_boundaries() {
        let cases: &[&str] = &[
            "3.4028235e38",
            "3.4028236e38",
            "3.40282357e38", // rounds to MAX
            "3.4028236e38",
            "3.5e38",
            "1.17549435e-38",
            "1.1754942e-38", // largest subnormal
            "1.4e-45",
            "7.006492e-46", // just above half the smallest subnormal: rounds up
            "7.006492321624085e-46", // exactly half (to 16 digits): ties to even, 0
            "7.0064923216240862e-46",
            "0.7e-45",
            "1e-46",
            "16777217",  // tie: to even
            "16777219",  // tie: to even (up)
            "16777217.000000001",
            "0.000000000000000000000000000000000000000000001",
            "99999999999999999999999999999",
        ];
        for text in cases {
            let ours = parse_f32(text.as_bytes());
            let core: Option<f32> = text.parse().ok();
            assert_eq!(ours.map(f32::to_bits), core.map(f32::to_bits), "{text}");
        }
        // The documented exception: 1 + 2^-24 (a tie) plus 1e-41. Only the first 19
        // digits are kept, which lie just below the tie; the result is a neighbour.
        let text = "1.00000005960464477539062500000000000000001";
        let ours = parse_f32(text.as_bytes()).map(f32::to_bits);
        assert!(ours == Some(0x3f80_0000) || ours == Some(0x3f80_0001), "{:?}", ours);
    }

    #[test]
    fn agrees_with_core() {
        let cases: &[&str] = &[
            "0", "-0", "1", "-1", "0.5", "2", "30", "0.06", "0.95", "0.3", "0.028575",
            "0.17", "100", "1e-7", "1E-7", "1e7", "6667", "6666.7", "1.5e3", "-2.5e-3",
            "123456789012345678901234567890", "0.000000000000000000000000000001",
            "3.4028235e38", "1e39", "1e-46", "1.17549435e-38", "12.345e+2", "+1", "5.",
            ".5", "0.1", "0.2", "0.7", "9.999999e-5", "89.99999",
        ];
        for text in cases {
            let ours = parse(text.as_bytes()).map(|v| v as f32);
            let core: Option<f32> = text.parse().ok();
            assert_eq!(ours, core, "{text}");
            assert_eq!(parse_f32(text.as_bytes()), core, "{text}");
        }
        for bad in ["", "-", "e5", "1e", "1e+", "1.2.3", "--1", "1-", "."] {
            assert_eq!(parse(bad.as_bytes()), None, "{bad}");
        }
    }
}
