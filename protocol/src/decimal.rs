//! `f32` in the decimal form of Rust's `{}` (shortest round-trip digits, no exponent:
//! `-1`, `0.0000001`, `100000000000000000000`) without core's float formatting, whose
//! `flt2dec` keeps panic paths the optimiser cannot remove: the digits come from `ryu`
//! (the same shortest digits; also what serde-json-core serializes numbers with), laid
//! out here with no indexing that can panic, into a [`Sink`] (no `core::fmt`). The
//! firmware's error messages go through this, so its image can be proved panic-free at
//! link time.

#[cfg(test)]
use core::fmt;

#[cfg(test)]
use crate::text::Fmt;
use crate::text::{ascii, Sink};

/// Displays the wrapped `f32` exactly as `{}` would (see [`plain`]; for the tests).
#[cfg(test)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plain(pub f32);

#[cfg(test)]
impl fmt::Display for Plain {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Fmt::write(f, |out| plain(out, self.0))
    }
}

/// `value` as `{}` writes it.
pub(crate) fn plain(f: &mut dyn Sink, value: f32) {
    if value.is_nan() {
        return f.put("NaN");
    }
    if value.is_infinite() {
        return f.put(if value < 0.0 { "-inf" } else { "inf" });
    }
    if value.is_sign_negative() {
        f.put("-");
    }
    if value == 0.0 {
        return f.put("0");
    }
    let mut buffer = ryu::Buffer::new();
    // "d.ddd", "d.dddeX", "0.000ddd" or "deX" (finite, non-zero, positive).
    let text = buffer.format_finite(value.abs()).as_bytes();
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(at) => (
            text.get(..at).unwrap_or_default(),
            parse_exponent(text.get(at + 1..).unwrap_or_default()),
        ),
        None => (text, 0),
    };
    // Digits of the mantissa and where its point is.
    let point = mantissa
        .iter()
        .position(|&c| c == b'.')
        .unwrap_or(mantissa.len());
    let mut digits = [0u8; 24];
    let mut count = 0usize;
    for &c in mantissa.iter().filter(|c| c.is_ascii_digit()) {
        if let Some(slot) = digits.get_mut(count) {
            *slot = c;
            count += 1;
        }
    }
    let digits = digits.get(..count).unwrap_or_default();
    // Drop leading zeros (each moves the point left) and trailing zeros.
    let leading = digits.iter().take_while(|&&c| c == b'0').count();
    let digits = digits.get(leading..).unwrap_or_default();
    let trailing = digits.iter().rev().take_while(|&&c| c == b'0').count();
    let digits = digits
        .get(..digits.len().saturating_sub(trailing))
        .unwrap_or_default();
    // value = 0.DIGITS × 10^point
    let point = point as i32 - leading as i32 + exponent;
    let len = digits.len() as i32;
    if point <= 0 {
        f.put("0.");
        zeros(f, -point);
        f.put(ascii(digits));
    } else if point >= len {
        f.put(ascii(digits));
        zeros(f, point - len);
    } else {
        let (int, frac) = digits.split_at(point as usize);
        f.put(ascii(int));
        f.put(".");
        f.put(ascii(frac));
    }
}

fn parse_exponent(text: &[u8]) -> i32 {
    let (negative, digits) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    let magnitude = digits.iter().fold(0i32, |e, &c| {
        e.saturating_mul(10)
            .saturating_add(i32::from(c.wrapping_sub(b'0')) % 10)
    });
    if negative {
        -magnitude
    } else {
        magnitude
    }
}

fn zeros(f: &mut dyn Sink, count: i32) {
    for _ in 0..count {
        f.put("0");
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::format;

    use super::Plain;

    #[test]
    fn matches_display_of_f32() {
        let special = [
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            0.5,
            100.0,
            1e-7,
            1e20,
            1e-45,
            f32::MAX,
            f32::MIN_POSITIVE,
            0.028575,
            0.17,
            0.3,
            0.95,
            0.06,
            123456.79,
            1e16,
            1e15,
            1e-5,
            1e-4,
            12.5,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            89.99999,
            1.0e7,
            16777216.0,
        ];
        for v in special {
            assert_eq!(format!("{}", Plain(v)), format!("{v}"), "{v:e}");
        }
        // A deterministic sweep over bit patterns (every exponent, varied mantissas):
        // the same form and length, and the same value read back. (The digits differ
        // only when two shortest forms are equally close, e.g. 2827637.25: ryu rounds
        // the tie to even, `{}` up.)
        let mut bits = 0x1234_5678u32;
        for _ in 0..200_000 {
            bits = bits.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let v = f32::from_bits(bits);
            let (ours, core) = (format!("{}", Plain(v)), format!("{v}"));
            if v.is_nan() {
                assert_eq!(ours, core);
                continue;
            }
            assert_eq!(ours.len(), core.len(), "{ours} vs {core}");
            assert_eq!(
                ours.parse::<f32>().map(f32::to_bits),
                Ok(bits),
                "{ours} vs {core}"
            );
        }
    }
}
