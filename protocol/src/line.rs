//! Splitting a byte stream into request lines with a fixed buffer.
//!
//! A line ends at `\n` (a `\r` before it is dropped, so CRLF terminals work). A line
//! longer than the buffer is not cut into pieces: the rest of it is skipped up to its
//! newline, and the newline yields one [`Event::Overlong`], so every line sent gets
//! exactly one answer and the stream is back in step at the next line.

/// What a byte completed.
#[derive(Debug, PartialEq, Eq)]
pub enum Event<'a> {
    /// A complete line, without its terminator.
    Line(&'a [u8]),
    /// A line that did not fit: `length` bytes before its newline.
    Overlong {
        /// Bytes received before the newline (`\r` included).
        length: usize,
    },
}

/// Collects bytes into lines of at most `N` bytes.
pub struct LineReader<const N: usize> {
    buf: [u8; N],
    len: usize,
    /// Bytes of the current line, counted past the buffer when it overflowed.
    seen: usize,
}

impl<const N: usize> Default for LineReader<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> LineReader<N> {
    /// An empty reader.
    pub const fn new() -> Self {
        Self {
            buf: [0; N],
            len: 0,
            seen: 0,
        }
    }

    /// Takes one byte; returns the event it completes, if any.
    pub fn push(&mut self, byte: u8) -> Option<Event<'_>> {
        if byte != b'\n' {
            if let Some(slot) = self.buf.get_mut(self.len) {
                *slot = byte;
                self.len += 1;
            }
            self.seen = self.seen.saturating_add(1);
            return None;
        }
        let (len, seen) = (self.len, self.seen);
        self.len = 0;
        self.seen = 0;
        if seen > len {
            return Some(Event::Overlong { length: seen });
        }
        let line = self.buf.get(..len).unwrap_or_default();
        Some(Event::Line(line.strip_suffix(b"\r").unwrap_or(line)))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::{format, string::String, vec::Vec};

    use super::*;

    fn feed<const N: usize>(reader: &mut LineReader<N>, bytes: &[u8]) -> Vec<String> {
        let mut events = Vec::new();
        for &b in bytes {
            match reader.push(b) {
                Some(Event::Line(line)) => {
                    events.push(format!("line {}", String::from_utf8_lossy(line)))
                }
                Some(Event::Overlong { length }) => events.push(format!("overlong {length}")),
                None => {}
            }
        }
        events
    }

    #[test]
    fn splits_lines_and_drops_cr() {
        let mut r = LineReader::<8>::new();
        assert_eq!(
            feed(&mut r, b"ab\ncd\r\n\n"),
            ["line ab", "line cd", "line "]
        );
    }

    #[test]
    fn a_line_of_exactly_the_capacity_fits() {
        let mut r = LineReader::<4>::new();
        assert_eq!(feed(&mut r, b"abcd\n"), ["line abcd"]);
        assert_eq!(feed(&mut r, b"abcde\n"), ["overlong 5"]);
    }

    #[test]
    fn overlong_lines_give_one_event_and_resync() {
        let mut r = LineReader::<4>::new();
        assert_eq!(
            feed(&mut r, b"0123456789\nok\nabcdefgh"),
            ["overlong 10", "line ok"]
        );
        // The unfinished overlong line is still being skipped.
        assert_eq!(feed(&mut r, b"ij\nxy\n"), ["overlong 10", "line xy"]);
    }
}
