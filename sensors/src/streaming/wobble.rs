//! Side-to-side wobble of a stroke: the spread of the gyro's yaw rate (`gz`, about the
//! axis perpendicular to the cue in its vertical plane, `z` up) while the cue moves. A
//! stroke straight along the cue's line turns the cue about no vertical axis: its yaw
//! rate stays at the sensor's bias plus noise (0.29 °/s RMS in the synthetic model,
//! `docs/sensors.md` §5); a cue that swings sideways turns. O(1): a count and two `f32`
//! sums of raw counts (a few instructions a sample on the Cortex-M4F's FPU; over a 10 s
//! stroke at 6.66 kHz the sum of squares stays exact to 1e-5 of itself, far below the
//! noise's share of it).

/// Running yaw-rate statistics (raw counts) over one stroke.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wobble {
    samples: u32,
    sum: f32,
    sum_sq: f32,
}

impl Wobble {
    /// No samples.
    pub const fn new() -> Self {
        Self {
            samples: 0,
            sum: 0.0,
            sum_sq: 0.0,
        }
    }

    /// Forgets every sample (a new stroke starts).
    pub fn restart(&mut self) {
        *self = Self::new();
    }

    /// Takes one yaw-rate word.
    #[inline(always)]
    pub fn push(&mut self, yaw_rate: i16) {
        let x = f32::from(yaw_rate);
        self.samples = self.samples.saturating_add(1);
        self.sum += x;
        self.sum_sq += x * x;
    }

    /// The root-mean-square deviation of the yaw rate from its mean (the bias drops
    /// out), in the unit of `per_count` per count (e.g. °/s with 0.07 °/s per count at
    /// ±2000 dps); 0 with fewer than two samples.
    pub fn rms(&self, per_count: f32) -> f32 {
        if self.samples < 2 {
            return 0.0;
        }
        let n = self.samples as f32;
        let mean = self.sum / n;
        let variance = (self.sum_sq / n - mean * mean).max(0.0);
        cuesight::math::sqrt(variance) * per_count.abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_rate_has_no_wobble_and_a_swing_has_its_amplitude() {
        let mut still = Wobble::new();
        for _ in 0..1000 {
            still.push(-14);
        }
        assert_eq!(still.rms(0.07), 0.0);
        // ±100 counts alternating about a bias of 20: RMS 100 counts = 7 °/s.
        let mut swing = Wobble::new();
        for i in 0..1000 {
            swing.push(20 + if i % 2 == 0 { 100 } else { -100 });
        }
        assert!((swing.rms(0.07) - 7.0).abs() < 1e-4, "{}", swing.rms(0.07));
        swing.restart();
        assert_eq!(swing, Wobble::new());
    }
}
