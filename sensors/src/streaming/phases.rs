//! The stroke's phases, for the metrics a smart cue reports (`docs/sensors.md` §11,
//! "Stroke metrics"): backswing length, the time back, the pause at the back and the
//! forward time, from the cue's velocity and position integrated from the rest end.
//!
//! Per sample, with `a` the acceleration and `q` the bias-free pitch rate in counts:
//!
//! ```text
//! velocity += (a − bias) + tilt_gain · A          counts·samples  (× scale · Δt = m/s)
//! position += velocity                            counts·samples² (× scale · Δt² = m)
//! ```
//!
//! `A = T + q/2` is the mid-sample elevation change of the speed's gyro aid (step 5 of
//! the module docs), to first order: `tilt_gain = g cos θ₀ · pitch_scale · Δt / scale`
//! (so a cue tilting back by 2° adds no 0.34 m/s² of apparent acceleration to the phases).
//! f32 sums: for a 6 m/s, 60 s stroke at 6.66 kHz the velocity is below 2²⁴ ulps of its
//! size and the position within 1e-5 of its size; these are metrics, the speed keeps
//! its exact integer sums.
//!
//! The back of the backswing is the cue's deepest position, `min position`. The pause is
//! the run of samples, around that point, where `|velocity| < slow` ([`super::integral`]'s
//! `REST_SPEED`, 0.02 m/s). Without a pause it is the reversal's own slow passage
//! (`2 · 0.02 / |a|`, 20 ms at 2 m/s²).

/// The phase tracker of one stroke (counts and sample indices).
#[derive(Clone, Copy, Debug)]
pub(super) struct Phases {
    /// The rest end the stroke started from (kept when a pause at the back re-anchors
    /// the speed's integration).
    origin: u32,
    velocity: f32,
    position: f32,
    /// The deepest position so far, and its sample.
    deepest: f32,
    deepest_at: u32,
    /// First sample of the current run with `|velocity| < slow`.
    slow_from: Option<u32>,
    /// The slow run holding the deepest point: `[pause_start, pause_end)`.
    pause_start: u32,
    pause_end: u32,
    /// The phases up to a later rest that became the speed's origin within the stroke.
    previous: Option<PhaseReport>,
}

/// The phases at the impact (counts·samples² and sample indices).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PhaseReport {
    /// `−min position`, 0 if the cue never went back.
    pub depth: f32,
    pub origin: u32,
    pub pause_start: u32,
    pub pause_end: u32,
}

impl Phases {
    /// No stroke.
    pub const fn new() -> Self {
        Self {
            origin: 0,
            velocity: 0.0,
            position: 0.0,
            deepest: 0.0,
            deepest_at: 0,
            slow_from: None,
            pause_start: 0,
            pause_end: 0,
            previous: None,
        }
    }

    /// A stroke starts at `rest_end`, integrated through sample `n` (`velocity` counts
    /// there, reached over `span` samples): the position is taken for a velocity growing
    /// linearly over the span (12 ms at most), and the cue was still until `rest_end`.
    ///
    /// `within_stroke`: a rest within a stroke in progress (whether or not it becomes
    /// the speed's origin). That rest is either the address after a settling move (the
    /// backswing is still to come) or a long pause at the back (it is over); the phases
    /// so far are kept, and [`Self::report`] decides by what follows. The velocity
    /// starts again from the rest (the cue is still there, whatever the integral says).
    pub fn start(&mut self, rest_end: u32, n: u32, velocity: f32, span: f32, within_stroke: bool) {
        self.previous = if within_stroke {
            Some(self.report())
        } else {
            None
        };
        // Field by field: a struct literal is built on the stack and copied.
        let position = 0.5 * velocity * span;
        let back = position < 0.0;
        self.origin = rest_end;
        self.velocity = velocity;
        self.position = position;
        self.deepest = if back { position } else { 0.0 };
        self.deepest_at = if back { n } else { rest_end };
        self.slow_from = Some(rest_end);
        self.pause_start = rest_end;
        self.pause_end = rest_end;
    }

    /// Sample `n`: `delta` counts of bias-free acceleration, `tilt` the mid-sample tilt
    /// times `tilt_gain` (velocity counts); `slow` the pause threshold in velocity counts.
    #[inline(always)]
    pub fn step(&mut self, n: u32, delta: f32, tilt: f32, slow: f32) {
        self.velocity += delta + tilt;
        self.position += self.velocity;
        if self.position < self.deepest {
            self.deepest = self.position;
            self.deepest_at = n;
            // A new deepest point: the pause is the slow run holding it (if any).
            let start = self.slow_from.unwrap_or(n);
            self.pause_start = start;
            self.pause_end = n.wrapping_add(1);
        }
        let slow_now = -slow < self.velocity && self.velocity < slow;
        match (slow_now, self.slow_from) {
            (true, None) => self.slow_from = Some(n),
            (false, Some(start)) => {
                // The slow run ends: it is the pause if it holds the deepest point.
                if self.deepest_at.wrapping_sub(start) as i32 >= 0 {
                    self.pause_end = n;
                }
                self.slow_from = None;
            }
            _ => {}
        }
    }

    /// The phases at the impact onset. If the cue never went back after the latest rest
    /// (its slow run at the deepest point starts at that rest's end), that rest was the
    /// pause at the back: the backswing is the one before it, and the pause lasts until
    /// the cue left that rest.
    pub fn report(&self) -> PhaseReport {
        match self.previous {
            Some(before) if self.pause_start == self.origin => PhaseReport {
                pause_end: self.pause_end,
                ..before
            },
            _ => PhaseReport {
                depth: -self.deepest,
                origin: self.origin,
                pause_start: self.pause_start,
                pause_end: self.pause_end,
            },
        }
    }
}
