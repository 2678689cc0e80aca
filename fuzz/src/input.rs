//! The fuzzer's bytes as a fixed-layout stream of choices and numbers, and the
//! [`Writer`] that lays out seeds in the same form.
//!
//! A choice is one byte (taken modulo the number of options). A number is five bytes,
//! a tag and a little-endian word, so that every number keeps its place in the stream
//! whatever its form; the tag (modulo 16) picks the form:
//!
//! | tag | value |
//! |---|---|
//! | 0 | the word's raw `f32` bit pattern (NaN payloads, subnormals, anything) |
//! | 1 | one of [`SPECIAL`] (the word picks which) |
//! | 2, 3 | the low or the high end of the range |
//! | 4, 5 | one ulp outside the low or the high end |
//! | 6–15 | inside the range, `lo + (hi − lo) · word / (2³² − 1)` |
//!
//! So most numbers land in the range a caller calls reasonable (and a mutated word keeps
//! them there), while every bit pattern stays reachable. Past the end of the bytes every
//! read is zero: the first option, and the low end of a range.

/// Values worth trying anywhere: zeros, non-finite values, the extremes of `f32`.
pub const SPECIAL: [f32; 16] = [
    0.0,
    -0.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MIN_POSITIVE,
    1e-45, // the smallest subnormal
    -1e-45,
    f32::MAX,
    f32::MIN,
    f32::EPSILON,
    1.0,
    -1.0,
    1e-6,
    1e6,
    1e30,
];

/// The tag of a number inside its range (what [`Writer::real`] writes).
const IN_RANGE: u8 = 6;

/// Reads choices and numbers off the fuzzer's bytes (see the module docs).
#[derive(Clone, Debug)]
pub struct Input<'a> {
    bytes: &'a [u8],
}

impl<'a> Input<'a> {
    /// A reader at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    /// `true` once every byte has been read.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    fn byte(&mut self) -> u8 {
        match self.bytes.split_first() {
            Some((&first, rest)) => {
                self.bytes = rest;
                first
            }
            None => 0,
        }
    }

    fn word(&mut self) -> u32 {
        u32::from_le_bytes([self.byte(), self.byte(), self.byte(), self.byte()])
    }

    /// One of `options` choices, `0..options` (`options` ≥ 1).
    pub fn choice(&mut self, options: u8) -> u8 {
        self.byte() % options.max(1)
    }

    /// A yes/no choice.
    pub fn flag(&mut self) -> bool {
        self.choice(2) == 1
    }

    /// A number, mostly in `[lo, hi]` (see the module docs for the other forms).
    pub fn real(&mut self, lo: f32, hi: f32) -> f32 {
        if self.is_empty() {
            return lo;
        }
        let tag = self.byte() % 16;
        let word = self.word();
        match tag {
            0 => f32::from_bits(word),
            1 => SPECIAL[word as usize % SPECIAL.len()],
            2 => lo,
            3 => hi,
            4 => lo.next_down(),
            5 => hi.next_up(),
            _ => {
                let fraction = f64::from(word) / f64::from(u32::MAX);
                let value = (f64::from(lo) + (f64::from(hi) - f64::from(lo)) * fraction) as f32;
                // A caller's bound may itself come from the input (NaN, or below `lo`).
                if lo <= hi {
                    value.clamp(lo, hi)
                } else {
                    value
                }
            }
        }
    }

    /// Two numbers in the same range.
    pub fn pair(&mut self, lo: f32, hi: f32) -> [f32; 2] {
        [self.real(lo, hi), self.real(lo, hi)]
    }

    /// Three numbers in the same range.
    pub fn triple(&mut self, lo: f32, hi: f32) -> [f32; 3] {
        [self.real(lo, hi), self.real(lo, hi), self.real(lo, hi)]
    }
}

/// Writes seeds in the layout [`Input`] reads: each call matches one `Input` call.
#[derive(Clone, Debug, Default)]
pub struct Writer {
    bytes: Vec<u8>,
}

impl Writer {
    /// An empty seed.
    pub fn new() -> Self {
        Self::default()
    }

    /// Choice number `index`.
    pub fn choice(&mut self, index: u8) -> &mut Self {
        self.bytes.push(index);
        self
    }

    /// A yes/no choice.
    pub fn flag(&mut self, yes: bool) -> &mut Self {
        self.choice(u8::from(yes))
    }

    /// `value`, as a number inside `[lo, hi]` (read back to within `f32` rounding).
    pub fn real(&mut self, lo: f32, hi: f32, value: f32) -> &mut Self {
        let fraction = (f64::from(value) - f64::from(lo)) / (f64::from(hi) - f64::from(lo));
        let word = (fraction.clamp(0.0, 1.0) * f64::from(u32::MAX)).round() as u32;
        self.bytes.push(IN_RANGE);
        self.bytes.extend_from_slice(&word.to_le_bytes());
        self
    }

    /// Two numbers in the same range.
    pub fn pair(&mut self, lo: f32, hi: f32, values: [f32; 2]) -> &mut Self {
        self.real(lo, hi, values[0]).real(lo, hi, values[1])
    }

    /// Three numbers in the same range.
    pub fn triple(&mut self, lo: f32, hi: f32, values: [f32; 3]) -> &mut Self {
        self.real(lo, hi, values[0])
            .real(lo, hi, values[1])
            .real(lo, hi, values[2])
    }

    /// `value` exactly, as its raw bit pattern.
    pub fn raw(&mut self, value: f32) -> &mut Self {
        self.bytes.push(0);
        self.bytes.extend_from_slice(&value.to_bits().to_le_bytes());
        self
    }

    /// The seed's bytes.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_written_seed_reads_back() {
        let mut w = Writer::new();
        w.choice(3).flag(true).real(-2.0, 5.0, 1.25).raw(f32::NAN);
        let mut r = Input::new(w.bytes());
        assert_eq!(r.choice(4), 3);
        assert!(r.flag());
        assert!((r.real(-2.0, 5.0) - 1.25).abs() < 1e-6);
        assert!(r.real(0.0, 1.0).is_nan());
        assert!(r.is_empty());
        assert_eq!(r.real(0.5, 1.0), 0.5, "past the end: the low end");
    }

    #[test]
    fn every_form_is_reachable() {
        let read = |tag: u8, word: u32| {
            let mut bytes = vec![tag];
            bytes.extend_from_slice(&word.to_le_bytes());
            Input::new(&bytes).real(1.0, 2.0)
        };
        assert_eq!(read(0, 1.5f32.to_bits()), 1.5);
        assert!(read(1, 2).is_nan());
        assert_eq!((read(2, 0), read(3, 0)), (1.0, 2.0));
        assert!(read(4, 0) < 1.0 && read(5, 0) > 2.0);
        assert_eq!((read(6, 0), read(15, u32::MAX)), (1.0, 2.0));
    }
}
