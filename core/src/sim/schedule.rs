//! The cached contact time of every pair of balls, and the earliest of them without
//! scanning all 120: each row (the pairs `(i, j)`, `j > i`) keeps its minimum, updated as
//! a time is written and rescanned only when its minimum grows.

use crate::table::MAX_BALLS;

/// Pairs of distinct balls.
const PAIRS: usize = MAX_BALLS * (MAX_BALLS - 1) / 2;

/// Index of the pair `{i, j}`, `i ≠ j`, in `0..PAIRS`.
fn index(i: usize, j: usize) -> usize {
    let (low, high) = if i < j { (i, j) } else { (j, i) };
    high * (high - 1) / 2 + low
}

/// Contact times (s, ∞ for none) and when each pair last collided.
pub(crate) struct Schedule {
    times: [f32; PAIRS],
    /// Per row `i`: the earliest time of the pairs `(i, j > i)` and its `j`.
    rows: [(f32, usize); MAX_BALLS],
    last: [f32; PAIRS],
}

impl Schedule {
    /// No contact for any pair; none collided.
    pub fn new() -> Self {
        Self {
            times: [f32::INFINITY; PAIRS],
            rows: [(f32::INFINITY, 0); MAX_BALLS],
            last: [f32::NEG_INFINITY; PAIRS],
        }
    }

    /// Sets the contact time of the pair `{i, j}` (`i ≠ j`, both below `MAX_BALLS`).
    pub fn set(&mut self, i: usize, j: usize, time: f32) {
        let (row, column) = if i < j { (i, j) } else { (j, i) };
        let Some(slot) = self.times.get_mut(index(row, column)) else {
            return;
        };
        *slot = time;
        let Some(&(earliest, at)) = self.rows.get(row) else {
            return;
        };
        if time < earliest {
            self.rows[row] = (time, column);
        } else if at == column && time > earliest {
            self.rescan(row);
        }
    }

    fn rescan(&mut self, row: usize) {
        let mut best = (f32::INFINITY, 0);
        for column in row + 1..MAX_BALLS {
            let time = self.times[index(row, column)];
            if time < best.0 {
                best = (time, column);
            }
        }
        self.rows[row] = best;
    }

    /// The earliest contact among the first `balls` balls: `(time, i, j)`, `i < j`.
    pub fn earliest(&self, balls: usize) -> Option<(f32, usize, usize)> {
        let mut best: Option<(f32, usize, usize)> = None;
        for (row, &(time, column)) in self.rows.iter().enumerate().take(balls) {
            if time < f32::INFINITY && best.is_none_or(|(t, ..)| time < t) {
                best = Some((time, row, column));
            }
        }
        best
    }

    /// When the pair `{i, j}` last collided (s; −∞ if never).
    pub fn last_collision(&self, i: usize, j: usize) -> f32 {
        self.last
            .get(index(i, j))
            .copied()
            .unwrap_or(f32::NEG_INFINITY)
    }

    /// Notes that the pair `{i, j}` collided at `time`.
    pub fn collided(&mut self, i: usize, j: usize, time: f32) {
        if let Some(slot) = self.last.get_mut(index(i, j)) {
            *slot = time;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The row minima always give what a scan of every pair gives, through writes that
    /// lower, raise and clear the current minimum.
    #[test]
    fn the_earliest_is_the_minimum_over_every_pair() {
        let mut schedule = Schedule::new();
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        for step in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let i = (state % 16) as usize;
            let j = ((state >> 8) % 16) as usize;
            if i == j {
                continue;
            }
            let time = if (state >> 20) % 4 == 0 {
                f32::INFINITY
            } else {
                ((state >> 24) % 1000) as f32 * 0.01
            };
            schedule.set(i, j, time);
            let mut expected: Option<(f32, usize, usize)> = None;
            for a in 0..16 {
                for b in a + 1..16 {
                    let t = schedule.times[index(a, b)];
                    if t < f32::INFINITY && expected.is_none_or(|(e, ..)| t < e) {
                        expected = Some((t, a, b));
                    }
                }
            }
            let got = schedule.earliest(16);
            assert_eq!(got.map(|g| g.0), expected.map(|e| e.0), "step {step}");
        }
    }
}
