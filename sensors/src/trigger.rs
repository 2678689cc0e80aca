//! Online impact trigger: tells the capture loop when the ring buffer holds the stroke.

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

impl ImpactTrigger {
    /// Trigger on a deceleration beyond `threshold` (m/s², positive; e.g. 8 g) and wait
    /// `post_samples` more samples.
    pub const fn new(threshold: f32, post_samples: usize) -> Self {
        Self {
            threshold,
            post_samples,
            remaining: None,
        }
    }

    /// Feed one sample; `true` when the capture is complete (and on every later call
    /// until [`ImpactTrigger::reset`]).
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
        let mut t = ImpactTrigger::new(8.0 * STANDARD_GRAVITY, 3);
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
        let mut immediate = ImpactTrigger::new(10.0, 0);
        assert!(immediate.push(-11.0));
    }
}
