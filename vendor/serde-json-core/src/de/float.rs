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
        parse(text).map(|v| v as f32)
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
                } else if !in_fraction {
                    exp10 += 1; // a dropped integer digit
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
    let magnitude = scale(mantissa, exp10);
    Some(if negative { -magnitude } else { magnitude })
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
    use super::parse;

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
        }
        for bad in ["", "-", "e5", "1e", "1e+", "1.2.3", "--1", "1-", "."] {
            assert_eq!(parse(bad.as_bytes()), None, "{bad}");
        }
    }
}
