//! Error-message text without `core::fmt`: the messages are built piece by piece into a
//! [`Sink`] — the answer's fixed-size message on the device, a `Formatter` for the
//! `Display` impls a host uses — so the firmware links none of `core::fmt`'s machinery
//! (`write!` and its padding and integer code cost it about 4 KB of flash, issue 6).
//! The text is exactly what the former `write!`s produced.

use core::fmt;

/// Where text goes.
pub(crate) trait Sink {
    /// Appends `text`.
    fn put(&mut self, text: &str);
}

/// Into a fixed string: as much of each piece as fits, never splitting a character (a
/// later, shorter piece may still fit).
impl<const N: usize> Sink for heapless::String<N> {
    fn put(&mut self, text: &str) {
        push_truncated(self, text);
    }
}

/// Appends the longest prefix of `text` that fits, at a character boundary.
pub(crate) fn push_truncated<const N: usize>(out: &mut heapless::String<N>, text: &str) {
    let mut end = text.len().min(N - out.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    // Fits, at a boundary: cannot fail.
    let _ = out.push_str(text.get(..end).unwrap_or_default());
}

/// Into a `Formatter` (the host's `Display`), keeping its first error.
pub(crate) struct Fmt<'a, 'b> {
    f: &'a mut fmt::Formatter<'b>,
    result: fmt::Result,
}

impl<'a, 'b> Fmt<'a, 'b> {
    /// Writes `build`'s text to `f`.
    pub(crate) fn write(
        f: &'a mut fmt::Formatter<'b>,
        build: impl FnOnce(&mut dyn Sink),
    ) -> fmt::Result {
        let mut sink = Self { f, result: Ok(()) };
        build(&mut sink);
        sink.result
    }
}

impl Sink for Fmt<'_, '_> {
    fn put(&mut self, text: &str) {
        if self.result.is_ok() {
            self.result = self.f.write_str(text);
        }
    }
}

/// An unsigned integer in decimal, as `{}` writes it.
pub(crate) fn unsigned(out: &mut dyn Sink, value: usize) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    let mut rest = value;
    loop {
        at = at.saturating_sub(1);
        if let Some(slot) = digits.get_mut(at) {
            *slot = b'0' + (rest % 10) as u8;
        }
        rest /= 10;
        if rest == 0 || at == 0 {
            break;
        }
    }
    out.put(ascii(digits.get(at..).unwrap_or_default()));
}

/// ASCII bytes as text.
pub(crate) fn ascii(bytes: &[u8]) -> &str {
    core::str::from_utf8(bytes).unwrap_or("?")
}

/// `a, b, c` (`separator` between two names, `last` before the last one).
pub(crate) fn list<'a>(
    out: &mut dyn Sink,
    names: impl Iterator<Item = &'a str> + Clone,
    last: &str,
) {
    let count = names.clone().count();
    for (i, name) in names.enumerate() {
        if i > 0 {
            out.put(if i + 1 == count { last } else { ", " });
        }
        out.put(name);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::format;
    use std::string::String;

    use super::*;

    #[test]
    fn integers_as_display_writes_them() {
        for value in [
            0usize,
            1,
            9,
            10,
            99,
            100,
            12_000,
            u32::MAX as usize,
            usize::MAX,
        ] {
            let mut out: heapless::String<32> = heapless::String::new();
            unsigned(&mut out, value);
            assert_eq!(out.as_str(), format!("{value}"));
        }
    }

    #[test]
    fn truncation_keeps_whole_characters() {
        let mut out: heapless::String<6> = heapless::String::new();
        out.put("abcé");
        assert_eq!(out.as_str(), "abcé");
        out.put("é");
        assert_eq!(out.as_str(), "abcé", "two bytes do not fit in one");
        out.put("xy");
        assert_eq!(out.as_str(), "abcéx", "a later, shorter piece does");
        let mut out: heapless::String<4> = heapless::String::new();
        out.put("😀😀");
        assert_eq!(out.as_str(), "😀");
        let text = String::from("ab😀cd");
        for n in 0..text.len() {
            let mut out: heapless::String<8> = heapless::String::new();
            out.put(&"x".repeat(8 - n));
            out.put(&text);
            let mut expected = "x".repeat(8 - n);
            for c in text.chars() {
                if expected.len() + c.len_utf8() > 8 {
                    break;
                }
                expected.push(c);
            }
            assert_eq!(out.as_str(), expected);
        }
    }
}
