//! Strict JSON syntax check (RFC 8259), run on every line before it is decoded.
//!
//! serde-json-core is lenient in places a protocol should not be (it reads `+1`, `.5`
//! and `1.` as numbers, and skips unknown scalars by scanning to the next delimiter), and
//! its errors say little about where a line went wrong. This single pass settles the
//! question "is this JSON at all?" with the byte offset and the reason, so that every
//! later error is about the *schema*, not the syntax. No allocation: nesting is tracked
//! in a bit stack, up to [`MAX_DEPTH`] levels.

use core::fmt;

use crate::text::{unsigned, Fmt, Sink};

/// Deepest nesting of arrays and objects accepted (a request needs four).
pub const MAX_DEPTH: u32 = 32;

/// Why a line is not JSON.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SyntaxReason {
    /// The line ends inside a value (truncated).
    UnexpectedEnd,
    /// A value (object, array, string, number, `true`, `false`, `null`) was expected.
    ExpectedValue,
    /// An object key must be a string.
    ExpectedKey,
    /// `:` expected after an object key.
    ExpectedColon,
    /// `,` or the closing bracket expected after a value.
    ExpectedCommaOrEnd,
    /// Misspelt `true`, `false` or `null` (this is where `NaN` and `Infinity` land).
    InvalidLiteral,
    /// A number that does not follow the JSON grammar.
    InvalidNumber,
    /// A backslash escape other than `\" \\ \/ \b \f \n \r \t \uXXXX`.
    InvalidEscape,
    /// A raw control character (below U+0020) inside a string.
    ControlCharacter,
    /// A string that is not valid UTF-8.
    InvalidUtf8,
    /// Arrays and objects nested deeper than [`MAX_DEPTH`].
    TooDeep,
    /// Something other than whitespace after the value.
    TrailingCharacters,
}

impl SyntaxReason {
    /// Short description, for error messages.
    pub const fn describe(self) -> &'static str {
        match self {
            Self::UnexpectedEnd => "unexpected end of line",
            Self::ExpectedValue => "expected a value",
            Self::ExpectedKey => "expected a string key",
            Self::ExpectedColon => "expected ':'",
            Self::ExpectedCommaOrEnd => "expected ',' or a closing bracket",
            Self::InvalidLiteral => "invalid literal (true, false and null are the only words)",
            Self::InvalidNumber => "invalid number",
            Self::InvalidEscape => "invalid escape in a string",
            Self::ControlCharacter => "raw control character in a string",
            Self::InvalidUtf8 => "invalid UTF-8 in a string",
            Self::TooDeep => "nested too deeply",
            Self::TrailingCharacters => "trailing characters after the value",
        }
    }
}

/// A syntax error and the byte offset where it was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Syntax {
    /// Byte offset in the line (0-based).
    pub at: usize,
    /// What is wrong there.
    pub reason: SyntaxReason,
}

impl fmt::Display for Syntax {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Fmt::write(f, |out| self.write_message(out))
    }
}

impl Syntax {
    /// `<reason> at byte <offset>`.
    pub(crate) fn write_message(&self, f: &mut dyn Sink) {
        f.put(self.reason.describe());
        f.put(" at byte ");
        unsigned(f, self.at);
    }
}

/// Checks that `input` is exactly one JSON value, optionally surrounded by whitespace.
pub fn check(input: &[u8]) -> Result<(), Syntax> {
    Scanner { s: input, i: 0 }.document()
}

struct Scanner<'a> {
    s: &'a [u8],
    i: usize,
}

/// Open containers, innermost in bit 0: 1 for an object, 0 for an array.
struct Stack {
    bits: u32,
    depth: u32,
}

impl Stack {
    fn push(&mut self, object: bool) -> bool {
        if self.depth >= MAX_DEPTH {
            return false;
        }
        self.bits = (self.bits << 1) | u32::from(object);
        self.depth += 1;
        true
    }

    fn pop(&mut self) {
        self.bits >>= 1;
        self.depth -= 1;
    }

    fn in_object(&self) -> bool {
        self.bits & 1 == 1
    }
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.i).copied()
    }

    fn fail<T>(&self, reason: SyntaxReason) -> Result<T, Syntax> {
        Err(Syntax { at: self.i, reason })
    }

    fn skip_whitespace(&mut self) {
        while let Some(b' ' | b'\t' | b'\n' | b'\r') = self.peek() {
            self.i += 1;
        }
    }

    fn document(&mut self) -> Result<(), Syntax> {
        let mut stack = Stack { bits: 0, depth: 0 };
        'value: loop {
            self.skip_whitespace();
            match self.peek() {
                None => return self.fail(SyntaxReason::UnexpectedEnd),
                Some(open @ (b'{' | b'[')) => {
                    let object = open == b'{';
                    self.i += 1;
                    self.skip_whitespace();
                    let close = if object { b'}' } else { b']' };
                    if self.peek() == Some(close) {
                        self.i += 1;
                    } else {
                        if !stack.push(object) {
                            return self.fail(SyntaxReason::TooDeep);
                        }
                        if object {
                            self.key()?;
                        }
                        continue 'value;
                    }
                }
                Some(b'"') => self.string()?,
                Some(b't') => self.literal(b"true")?,
                Some(b'f') => self.literal(b"false")?,
                Some(b'n') => self.literal(b"null")?,
                Some(b'-' | b'0'..=b'9') => self.number()?,
                Some(_) => return self.fail(SyntaxReason::ExpectedValue),
            }
            // A value is complete: close containers or move to the next element.
            loop {
                self.skip_whitespace();
                if stack.depth == 0 {
                    return match self.peek() {
                        None => Ok(()),
                        Some(_) => self.fail(SyntaxReason::TrailingCharacters),
                    };
                }
                match self.peek() {
                    None => return self.fail(SyntaxReason::UnexpectedEnd),
                    Some(b',') => {
                        self.i += 1;
                        if stack.in_object() {
                            self.skip_whitespace();
                            self.key()?;
                        }
                        continue 'value;
                    }
                    Some(b'}') if stack.in_object() => {
                        self.i += 1;
                        stack.pop();
                    }
                    Some(b']') if !stack.in_object() => {
                        self.i += 1;
                        stack.pop();
                    }
                    Some(_) => return self.fail(SyntaxReason::ExpectedCommaOrEnd),
                }
            }
        }
    }

    /// `"key"` then `:` (leading whitespace already skipped).
    fn key(&mut self) -> Result<(), Syntax> {
        match self.peek() {
            Some(b'"') => self.string()?,
            None => return self.fail(SyntaxReason::UnexpectedEnd),
            Some(_) => return self.fail(SyntaxReason::ExpectedKey),
        }
        self.skip_whitespace();
        match self.peek() {
            Some(b':') => {
                self.i += 1;
                Ok(())
            }
            None => self.fail(SyntaxReason::UnexpectedEnd),
            Some(_) => self.fail(SyntaxReason::ExpectedColon),
        }
    }

    fn literal(&mut self, word: &[u8]) -> Result<(), Syntax> {
        for &expected in word {
            match self.peek() {
                Some(b) if b == expected => self.i += 1,
                None => return self.fail(SyntaxReason::UnexpectedEnd),
                Some(_) => return self.fail(SyntaxReason::InvalidLiteral),
            }
        }
        // `nullx` is not `null` followed by garbage but a bad word.
        match self.peek() {
            Some(b) if b.is_ascii_alphanumeric() => self.fail(SyntaxReason::InvalidLiteral),
            _ => Ok(()),
        }
    }

    fn digits(&mut self) -> usize {
        let start = self.i;
        while let Some(b'0'..=b'9') = self.peek() {
            self.i += 1;
        }
        self.i - start
    }

    /// `-? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?`
    fn number(&mut self) -> Result<(), Syntax> {
        if self.peek() == Some(b'-') {
            self.i += 1;
        }
        match self.peek() {
            Some(b'0') => self.i += 1,
            Some(b'1'..=b'9') => {
                self.digits();
            }
            None => return self.fail(SyntaxReason::UnexpectedEnd),
            Some(_) => return self.fail(SyntaxReason::InvalidNumber),
        }
        if self.peek() == Some(b'.') {
            self.i += 1;
            if self.digits() == 0 {
                return self.number_end_error();
            }
        }
        if let Some(b'e' | b'E') = self.peek() {
            self.i += 1;
            if let Some(b'+' | b'-') = self.peek() {
                self.i += 1;
            }
            if self.digits() == 0 {
                return self.number_end_error();
            }
        }
        // `01`, `1x`, `2.5.1`: the number runs into something that cannot follow it.
        match self.peek() {
            Some(b) if b.is_ascii_alphanumeric() || b == b'.' || b == b'-' || b == b'+' => {
                self.fail(SyntaxReason::InvalidNumber)
            }
            _ => Ok(()),
        }
    }

    fn number_end_error(&self) -> Result<(), Syntax> {
        match self.peek() {
            None => self.fail(SyntaxReason::UnexpectedEnd),
            Some(_) => self.fail(SyntaxReason::InvalidNumber),
        }
    }

    /// A string starting at the current `"`.
    fn string(&mut self) -> Result<(), Syntax> {
        self.i += 1;
        let start = self.i;
        loop {
            match self.peek() {
                None => return self.fail(SyntaxReason::UnexpectedEnd),
                Some(b'"') => break,
                Some(b'\\') => {
                    self.i += 1;
                    match self.peek() {
                        None => return self.fail(SyntaxReason::UnexpectedEnd),
                        Some(b'"' | b'\\' | b'/' | b'b' | b'f' | b'n' | b'r' | b't') => self.i += 1,
                        Some(b'u') => {
                            self.i += 1;
                            for _ in 0..4 {
                                match self.peek() {
                                    Some(h) if h.is_ascii_hexdigit() => self.i += 1,
                                    None => return self.fail(SyntaxReason::UnexpectedEnd),
                                    Some(_) => return self.fail(SyntaxReason::InvalidEscape),
                                }
                            }
                        }
                        Some(_) => return self.fail(SyntaxReason::InvalidEscape),
                    }
                }
                Some(b) if b < 0x20 => return self.fail(SyntaxReason::ControlCharacter),
                Some(_) => self.i += 1,
            }
        }
        // Escapes are ASCII, so the raw bytes must be UTF-8 exactly when the text is.
        let raw = self.s.get(start..self.i).unwrap_or_default();
        if let Err(e) = core::str::from_utf8(raw) {
            return Err(Syntax {
                at: start + e.valid_up_to(),
                reason: SyntaxReason::InvalidUtf8,
            });
        }
        self.i += 1; // closing quote
        Ok(())
    }
}

/// A cursor over a line that [`check`] accepted, for the hand-written decoders
/// (`decode.rs`): it reads values the way serde-json-core's deserializer did, so every
/// request gets the answer it got when serde-json-core decoded it, down to the same
/// quirks (an integer field stops at a `.`, so `0.5` there leaves `.5` where a `,` or
/// `}` should follow). The syntax is known to be valid, so it only ever has to tell one
/// kind of value from another; nothing here can panic (`get`, never indexing).
pub(crate) struct Reader<'a> {
    scan: Scanner<'a>,
}

/// A value of the wrong kind for its field (the decoder names the field).
pub(crate) struct WrongKind;

impl<'a> Reader<'a> {
    /// At the start of `line`.
    pub(crate) const fn new(line: &'a [u8]) -> Self {
        Self {
            scan: Scanner { s: line, i: 0 },
        }
    }

    /// The next byte after any whitespace (not consumed).
    pub(crate) fn peek(&mut self) -> Option<u8> {
        self.scan.skip_whitespace();
        self.scan.peek()
    }

    fn bump(&mut self) {
        self.scan.i += 1;
    }

    /// Consumes `byte` if it comes next (after whitespace).
    pub(crate) fn eat(&mut self, byte: u8) -> bool {
        let found = self.peek() == Some(byte);
        if found {
            self.bump();
        }
        found
    }

    /// A string's raw text, escapes kept as written (serde-json-core was given no
    /// unescape buffer, so `"sp\u0065ed"` is not `speed`), the reader past its closing
    /// quote; `None`, nothing consumed, if the next value is not a string.
    pub(crate) fn string(&mut self) -> Option<&'a str> {
        if !self.eat(b'"') {
            return None;
        }
        let start = self.scan.i;
        let mut escaped = false;
        while let Some(b) = self.scan.peek() {
            self.bump();
            match b {
                b'\\' => escaped = !escaped,
                b'"' if !escaped => break,
                _ => escaped = false,
            }
        }
        let raw = self
            .scan
            .s
            .get(start..self.scan.i.saturating_sub(1))
            .unwrap_or_default();
        // Checked UTF-8 by `check`.
        Some(core::str::from_utf8(raw).unwrap_or_default())
    }

    /// The next key of an object whose `{` (or previous value) was just read, and its
    /// `:`; `Ok(None)` at the closing `}` (consumed). `Err` when something else follows
    /// the previous value: only after an integer that stopped early (`0.5`), which
    /// serde-json-core answered with a bare error that named no field.
    pub(crate) fn key(&mut self) -> Result<Option<&'a str>, WrongKind> {
        if self.eat(b'}') {
            return Ok(None);
        }
        self.eat(b',');
        let key = self.string().ok_or(WrongKind)?;
        if !self.eat(b':') {
            return Err(WrongKind);
        }
        Ok(Some(key))
    }

    /// The text of a number, `-`, digits, `.`, `e` and signs: what serde-json-core
    /// handed its float parser.
    fn number_text(&mut self) -> &'a [u8] {
        self.scan.skip_whitespace();
        let start = self.scan.i;
        while let Some(b'0'..=b'9' | b'+' | b'-' | b'.' | b'e' | b'E') = self.scan.peek() {
            self.bump();
        }
        self.scan.s.get(start..self.scan.i).unwrap_or_default()
    }

    /// An `f32`: a number, as serde-json-core parses it (beyond the f32 range ±inf,
    /// below it ±0), or `null`, read as NaN.
    pub(crate) fn f32(&mut self) -> Result<f32, WrongKind> {
        if self.peek() == Some(b'n') {
            self.scan.i += 4; // `null`: checked
            return Ok(f32::NAN);
        }
        serde_json_core::de::parse_f32(self.number_text()).ok_or(WrongKind)
    }

    /// `true` or `false`.
    pub(crate) fn bool(&mut self) -> Result<bool, WrongKind> {
        let (value, length) = match self.peek() {
            Some(b't') => (true, 4),
            Some(b'f') => (false, 5),
            _ => return Err(WrongKind),
        };
        self.scan.i += length; // checked
        Ok(value)
    }

    /// An `i16` as serde-json-core reads one: an optional `-`, then `0` or digits (so
    /// `1.5` reads 1 and leaves `.5`, which the array then refuses); `Err` for anything
    /// else or beyond the `i16` range.
    pub(crate) fn i16(&mut self) -> Result<i16, WrongKind> {
        let negative = self.eat(b'-');
        match self.scan.peek() {
            Some(b'0') => {
                self.bump();
                return Ok(0);
            }
            Some(b'1'..=b'9') => {}
            _ => return Err(WrongKind),
        }
        let mut value: i16 = 0;
        while let Some(digit @ b'0'..=b'9') = self.scan.peek() {
            self.bump();
            let digit = i16::from(digit - b'0');
            value = value
                .checked_mul(10)
                .and_then(|v| {
                    if negative {
                        v.checked_sub(digit)
                    } else {
                        v.checked_add(digit)
                    }
                })
                .ok_or(WrongKind)?;
        }
        Ok(value)
    }

    /// A `u32` as serde-json-core reads one: digits without a sign, stopping at the
    /// first non-digit (so `0.5` reads 0 and leaves `.5`); `Err` for anything else or
    /// beyond `u32::MAX`.
    #[cfg(feature = "shot")]
    pub(crate) fn u32(&mut self) -> Result<u32, WrongKind> {
        match self.peek() {
            Some(b'0') => {
                self.bump();
                return Ok(0);
            }
            Some(b'1'..=b'9') => {}
            _ => return Err(WrongKind),
        }
        let mut value: u32 = 0;
        while let Some(digit @ b'0'..=b'9') = self.scan.peek() {
            self.bump();
            value = value
                .checked_mul(10)
                .and_then(|v| v.checked_add(u32::from(digit - b'0')))
                .ok_or(WrongKind)?;
        }
        Ok(value)
    }

    /// `[x0, x1, ...]`: exactly `N` [`Reader::f32`]s.
    pub(crate) fn f32s<const N: usize>(&mut self) -> Result<[f32; N], WrongKind> {
        if !self.eat(b'[') {
            return Err(WrongKind);
        }
        let mut values = [0.0; N];
        for (i, slot) in values.iter_mut().enumerate() {
            if i > 0 && !self.eat(b',') {
                return Err(WrongKind); // `]`: too few
            }
            *slot = self.f32()?;
        }
        if self.eat(b']') {
            Ok(values)
        } else {
            Err(WrongKind) // too many
        }
    }

    /// Steps into an array: `true` if one starts here (its `[` consumed).
    pub(crate) fn open_array(&mut self) -> bool {
        self.eat(b'[')
    }

    /// Before the next element of an array whose `[` or previous element was just read:
    /// `false` at its `]` (consumed).
    pub(crate) fn next_element(&mut self) -> bool {
        if self.eat(b']') {
            return false;
        }
        self.eat(b',');
        true
    }

    /// Steps into an object: `true` if one starts here (its `{` consumed).
    pub(crate) fn open_object(&mut self) -> bool {
        self.eat(b'{')
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::String;

    use super::*;

    fn reason(text: &[u8]) -> Option<SyntaxReason> {
        check(text).err().map(|e| e.reason)
    }

    #[test]
    fn accepts_json() {
        for text in [
            &b"{}"[..],
            b" [ ] ",
            b"0",
            b"-0.5e-3",
            b"1E+2",
            b"\"a\\u00e9\\n\"",
            b"{\"a\":[1,{\"b\":null},true,false,\"\xc3\xa9\"]}",
            b"[[[[]]]]",
        ] {
            assert_eq!(check(text), Ok(()), "{}", String::from_utf8_lossy(text));
        }
    }

    #[test]
    fn names_each_reason() {
        use SyntaxReason::*;
        let cases: &[(&[u8], SyntaxReason)] = &[
            (b"", UnexpectedEnd),
            (b"{\"a\":1", UnexpectedEnd),
            (b"{\"a\":", UnexpectedEnd),
            (b"\"abc", UnexpectedEnd),
            (b"1.", UnexpectedEnd),
            (b"{,}", ExpectedKey),
            (b"{1:2}", ExpectedKey),
            (b"{\"a\" 1}", ExpectedColon),
            (b"[1 2]", ExpectedCommaOrEnd),
            (b"{\"a\":1]", ExpectedCommaOrEnd),
            (b"[1,]", ExpectedValue),
            (b"NaN", ExpectedValue),
            (b"nan", InvalidLiteral),
            (b"[Infinity]", ExpectedValue),
            (b"tru", UnexpectedEnd),
            (b"trux", InvalidLiteral),
            (b"nullx", InvalidLiteral),
            (b"+1", ExpectedValue),
            (b".5", ExpectedValue),
            (b"01", InvalidNumber),
            (b"1.e5", InvalidNumber),
            (b"1e", UnexpectedEnd),
            (b"-", UnexpectedEnd),
            (b"-x", InvalidNumber),
            (b"2.5.1", InvalidNumber),
            (b"\"\\x\"", InvalidEscape),
            (b"\"\\u12g4\"", InvalidEscape),
            (b"\"a\tb\"", ControlCharacter),
            (b"\"\xff\"", InvalidUtf8),
            (b"{} {}", TrailingCharacters),
            (b"1 2", TrailingCharacters),
        ];
        for (text, expected) in cases {
            assert_eq!(
                reason(text),
                Some(*expected),
                "{}",
                String::from_utf8_lossy(text)
            );
        }
    }

    #[test]
    fn depth_is_bounded() {
        let mut deep = [b'['; 40];
        deep[39] = b']';
        assert_eq!(reason(&deep), Some(SyntaxReason::TooDeep));
        let ok = b"[[[[[[[[[[]]]]]]]]]]";
        assert_eq!(check(ok), Ok(()));
    }

    #[test]
    fn reports_the_offset() {
        assert_eq!(
            check(b"{\"a\":tru}"),
            Err(Syntax {
                at: 8,
                reason: SyntaxReason::InvalidLiteral
            })
        );
    }
}
