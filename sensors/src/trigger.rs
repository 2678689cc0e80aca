//! Online impact trigger: tells the capture loop when the ring buffer holds the stroke.

use core::fmt;

/// Online impact trigger for the capture loop: feed every sample (m/s², forward
/// positive); it reports `true` once `post_samples` samples have followed the first one
/// below `−threshold`, which is when the ring buffer holds the stroke and can be frozen.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ImpactTrigger {
    threshold: f32,
    post_samples: usize,
    remaining: Option<usize>,
}

/// [`ImpactTrigger::new`] refused its threshold: not a finite number above zero.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct InvalidThreshold {
    /// The rejected threshold (m/s²), NaN included.
    pub threshold: f32,
}

impl fmt::Display for InvalidThreshold {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "impact trigger threshold = {} m/s^2 must be a finite number > 0",
            self.threshold
        )
    }
}

impl core::error::Error for InvalidThreshold {}

impl ImpactTrigger {
    /// Trigger on a deceleration beyond `threshold` (m/s², a finite number > 0; e.g.
    /// 8 g) and wait `post_samples` more samples (any count; 0 completes on the impact
    /// sample itself). A NaN, infinite, zero or negative threshold is refused: it would
    /// never fire, or fire at rest.
    pub const fn new(threshold: f32, post_samples: usize) -> Result<Self, InvalidThreshold> {
        // NaN-safe: NaN, ±∞, ±0 and negative values all fail one of the two comparisons.
        if threshold > 0.0 && threshold < f32::INFINITY {
            Ok(Self {
                threshold,
                post_samples,
                remaining: None,
            })
        } else {
            Err(InvalidThreshold { threshold })
        }
    }

    /// Feed one sample; `true` when the capture is complete (and on every later call
    /// until [`ImpactTrigger::reset`]). The impact is the first sample strictly below
    /// `−threshold`: a sample equal to it does not trigger, `−∞` does, NaN and `+∞`
    /// never do (the estimator refuses a window holding them, `StrokeError::NotFinite`).
    pub fn push(&mut self, accel: f32) -> bool {
        match self.remaining {
            Some(0) => true,
            Some(ref mut left) => {
                *left -= 1;
                *left == 0
            }
            None if accel < -self.threshold => {
                self.remaining = Some(self.post_samples);
                self.post_samples == 0
            }
            None => false,
        }
    }

    /// `true` once the impact has been seen.
    pub const fn is_triggered(&self) -> bool {
        self.remaining.is_some()
    }

    /// The threshold (m/s²) given to [`ImpactTrigger::new`].
    pub const fn threshold(&self) -> f32 {
        self.threshold
    }

    /// Re-arm for the next stroke.
    pub fn reset(&mut self) {
        self.remaining = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lsm6dsox::STANDARD_GRAVITY;

    #[test]
    fn trigger_fires_after_the_post_samples() {
        let mut t = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, 3).unwrap();
        assert!(!t.push(5.0));
        assert!(!t.push(-50.0)); // −5 g: not an impact
        assert!(!t.is_triggered());
        assert!(!t.push(-100.0)); // −10 g: impact
        assert!(t.is_triggered());
        assert!(!t.push(0.0));
        assert!(!t.push(0.0));
        assert!(t.push(0.0));
        assert!(t.push(0.0));
        t.reset();
        assert!(!t.is_triggered());
        assert!(!t.push(f32::NAN));
        let mut immediate = ImpactTrigger::new(10.0, 0).unwrap();
        assert!(immediate.push(-11.0));
    }
}
