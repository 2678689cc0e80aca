//! Glitches in a raw stroke window: a rail word or a single-sample spike before the tip
//! impact.
//!
//! A window uploaded in chunks can carry a corrupted word. One `−32768` in the forward
//! stroke shifts [`estimate_raw`](crate::estimate_raw)'s cue speed by tens of per cent
//! (its impact detector may even take it for the impact), and the estimator cannot
//! tell: [`find_glitch`] names the first such sample so that the window can be refused.
//!
//! # What is a glitch
//!
//! Words are read as forward-positive accelerations `a = word · scale` (m/s²); every
//! threshold below is in g and converted to words at the given scale. The tip impact
//! decelerates the cue by tens to hundreds of g for about a millisecond: rail words and
//! jumps of many g are physical *at* the impact and in the ringing after it. Before it,
//! a hand stroke is smooth: in the repo's kinematic model (`tests/synthetic_strokes.rs`)
//! the largest jerk is 2,770 m/s³ = 282 g/s (a 6 m/s stroke whose forward swing lasts
//! 0.114 s), 0.28 g per sample at 1 kHz and 0.04 g at 6.66 kHz, and the largest
//! deceleration 2.8 g (the backswing); sensor noise is 1–8 mg RMS. So:
//!
//! * **lone sample**: a sample that jumps by at least [`SPIKE_G`] (1 g) away from
//!   *both* neighbours in the same direction, while the two neighbours agree within
//!   `AGREE_G + 2 JERK_G_PER_S / rate` (0.25 g + two samples of the 300 g/s jerk: 0.85 g
//!   at 1 kHz, 0.43 g at 3.33 kHz, 0.34 g at 6.66 kHz; rates below 500 Hz use 500 Hz's
//!   1.45 g). A clean stroke changes by at most 0.28 g per sample at 1 kHz, so a 1 g jump
//!   on both sides is 3.5 times anything it does; a corrupted word does it by
//!   construction, and its neighbours still agree with each other.
//! * **impact-like sample**: a rail word in the deceleration direction, a deceleration
//!   beyond [`HOT_G`] (6.9 g: the estimator's 8 g impact threshold below the highest
//!   rest level, 1 g of gravity along a vertical cue plus 0.1 g of offset), or a drop of
//!   [`DROP_G`] (2 g) from the sample before (7 times the 0.28 g of the steepest
//!   stroke; it catches a contact that a 1 ms sample averages to less than 6.9 g).
//! * **the impact**: the last group of impact-like samples, consecutive members at most
//!   [`GAP_S`] (10 ms) apart so that the group holds the ringing (the model's 20–60 g
//!   ringing decays with 3 ms: to 2 g in 10 ms). Its first sample is the impact onset,
//!   except that leading lone samples are glitches before it: a real contact spans
//!   several samples, or is followed by its ringing, so its first sample is not lone.
//!
//!   Below 2.5 kHz ([`CONTACT_MIN_S`] · rate < 2: the shortest contact, 0.8 ms, need not
//!   cover two sample periods) a contact can fall into one sample that is lone by the
//!   test above (measured without the rule that follows: 3.9 % of the kinematic model's
//!   strokes at 1 kHz, 0.7 % at 1.67 kHz, none at 3.33 and 6.66 kHz). There a leading
//!   lone sample that is strictly deeper than every sample in the 10 ms after it is the
//!   impact (the ringing after a real impact is weaker than the impact).
//!
//! Before the onset, [`find_glitch`] reports the first sample that is a rail word in the
//! forward direction ([`GlitchKind::Rail`]: a hand stroke never reaches 16 g forward), a
//! lone sample ([`GlitchKind::Rail`] if it is a rail word, else [`GlitchKind::Spike`]),
//! or a forward jump of 1 g from a smooth left side followed by a drop of 1 g (a forward
//! spike right before the impact, whose right neighbour is already decelerating:
//! [`GlitchKind::Spike`]). An earlier group of impact-like samples that does not start
//! with a lone sample (a knock before the rest, which the estimator skips) is skipped
//! with 10 ms of ringing. Nothing after the onset is looked at: the estimator reads
//! nothing there.
//!
//! # What it cannot see
//!
//! * A deceleration glitch in the **one sample just before the onset** reads as the
//!   impact starting one sample earlier (the host generator's impact is a step to the
//!   rail: the two windows are identical). The estimator then leaves that sample out of
//!   its integral, an error of at most `|a| Δt` (one sample of the stroke's own
//!   acceleration), the resolution it has anyway.
//! * **Below 2.5 kHz**, a deceleration glitch within the 10 ms before an impact that it
//!   out-depths (a rail word before an impact that stays off the rail) reads as the
//!   impact. The demo and end-to-end strokes (host generator) reach the rail: a rail
//!   glitch ties and is found.
//! * Glitches after the onset, and within a skipped knock, are not looked for.
//! * A rate or scale that is not a finite number above zero (scale: non-zero) gives
//!   `None`: the estimator refuses such a window itself (`InvalidConfig`, `NotFinite`).
//!
//! # Measured (`sensors/tests/glitch.rs`)
//!
//! Measured with
//!
//! ```text
//! cargo test -p cuesight-sensors --release --test glitch -- --nocapture
//! ```
//!
//! (8–11 s on the 2-core machine). The windows: the kinematic model of
//! `tests/synthetic_strokes.rs` (replicated draw for draw: its sets of 250 strokes with
//! their seeds, 1, 3 and 8 mg of noise and the pendulum tilt, each at 1, 1.67, 3.33 and
//! 6.66 kHz, as the capture ring freezes them), the
//! host generator of `host-tests/src/strokes.rs` (the demo session's stroke, checked word
//! for word against `firmware/demo/session.jsonl`; the brief's 1 kHz demo stroke
//! `synthetic_stroke(7, 1000, 2.5)`; the end-to-end and its own test's strokes; 250
//! seeded strokes per rate) and 100 piecewise-constant strokes of `tests/common` per
//! rate.
//!
//! * **False positives: none** in 5,061 clean windows (1,354 at 1 kHz, 1,000 at
//!   1.67 kHz, 1,355 at 3.33 kHz, 1,352 at 6.66 kHz), each also with the words and the
//!   scale negated.
//! * **Detection** (index, kind and word exact) of a `−32768` (deceleration rail at a
//!   positive scale), a `+32767`, and a `+2 g` and `−2 g` spike (added to the word)
//!   injected before the onset (the generator's first contact sample), at random
//!   positions and at both ends of the covered range (every position but the one just
//!   before the onset for the deceleration direction): **100.00 %** of 2,288 injections
//!   per kind at 1 kHz (250 host and 322 kinematic windows, those the estimator takes),
//!   of 2,600 per kind at 3.33 kHz and at 6.66 kHz (250 + 400 windows). At 1 kHz, the
//!   kinematic model's `−32768` injections in the 10 samples before the covered range's
//!   end are tallied apart: 588 of 3,220 (18.3 %) found, the rest read as the impact
//!   (never another sample named). Every position of the 1 kHz demo stroke is also
//!   checked, all four kinds.
//! * **Smallest spike found at every sampled position** (0.05 g grid, one random
//!   position per window plus both ends, 572–650 windows): +1.35 / −1.25 g at 1 kHz,
//!   ±1.10 g at 3.33 kHz, ±1.05 g at 6.66 kHz (the 1 g threshold plus the stroke's own
//!   change over a sample).
//! * **The sample just before the onset**, deceleration direction: a `−32768` there is
//!   still reported in 3 of 572 windows at 1 kHz, 55 of 650 at 3.33 kHz, 58 of 650 at
//!   6.66 kHz (where the first contact sample is barely touched), a `−2 g` spike in 30,
//!   55 and 58; otherwise it reads as the impact.
//! * **Robustness**: 20,000 proptest cases (any words, rails weighted up, or a stroke
//!   with words overwritten; every special f32 as rate and scale): no panic, `Some`
//!   only for a valid rate and scale, naming a sample of the window with its word.
//!
//! For scale: one `−32768` in the middle of the 1 kHz demo stroke's forward swing makes
//! the estimator take it for the impact (`NotForward`, −0.07 m/s instead of 2.50 m/s);
//! a `+32767` there is refused as `Saturated`.
//!
//! Every operation is plain f32 arithmetic and comparison on `i32` word differences; no
//! heap, no panic path (`get` for every read), and nothing can become NaN (the word
//! thresholds are a finite number over a finite, non-zero scale).

use crate::lsm6dsox::STANDARD_GRAVITY;

/// What is wrong with one raw sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum GlitchKind {
    /// The word is `i16::MIN` or `i16::MAX`, before the impact.
    Rail,
    /// The word jumps away from both neighbours (by at least [`SPIKE_G`]) before the
    /// impact.
    Spike,
}

/// One corrupted sample of a raw window.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Glitch {
    /// Index of the sample in the window.
    pub index: usize,
    /// What is wrong with it.
    pub kind: GlitchKind,
    /// Its raw word.
    pub value: i16,
}

/// Smallest jump of a lone sample away from each neighbour (g).
pub const SPIKE_G: f32 = 1.0;
/// Fixed part of the neighbours' agreement (g); two samples of [`JERK_G_PER_S`] are
/// added.
pub const AGREE_G: f32 = 0.25;
/// Largest jerk of a hand stroke (g/s): the kinematic model's steepest is 282 g/s.
pub const JERK_G_PER_S: f32 = 300.0;
/// Deceleration that makes a sample impact-like (g).
pub const HOT_G: f32 = 6.9;
/// Drop from the sample before that makes a sample impact-like (g).
pub const DROP_G: f32 = 2.0;
/// Largest spacing of impact-like samples within one event (s).
pub const GAP_S: f32 = 0.010;
/// Shortest tip contact (s).
pub const CONTACT_MIN_S: f32 = 0.8e-3;

/// Thresholds in words for one window.
struct Plan<'a> {
    raw: &'a [i16],
    /// +1 when a positive word is a forward acceleration, −1 otherwise.
    sign: i32,
    spike: f32,
    agree: f32,
    hot: f32,
    drop: f32,
    gap: usize,
    /// A tip contact can fall into one sample period.
    one_sample_impacts: bool,
}

fn abs(x: i32) -> i32 {
    if x < 0 {
        -x
    } else {
        x
    }
}

impl Plan<'_> {
    /// Forward-positive word (0 out of range; callers stay in range).
    fn s(&self, i: usize) -> i32 {
        self.raw.get(i).map_or(0, |&w| i32::from(w) * self.sign)
    }

    fn is_rail(&self, i: usize) -> bool {
        matches!(self.raw.get(i), Some(&i16::MIN) | Some(&i16::MAX))
    }

    fn impact_like(&self, i: usize) -> bool {
        if i >= self.raw.len() {
            return false;
        }
        let x = self.s(i);
        (self.is_rail(i) && x < 0)
            || (x as f32) <= -self.hot
            || (i > 0 && ((x - self.s(i - 1)) as f32) <= -self.drop)
    }

    /// A sample that jumps by `spike` away from both neighbours, which agree. At an end
    /// of the window the next-but-one sample stands in for the missing neighbour.
    fn lone(&self, i: usize) -> bool {
        let n = self.raw.len();
        if n < 3 || i >= n {
            return false;
        }
        let (l, r) = if i == 0 {
            (2, 1)
        } else if i + 1 == n {
            (i - 1, i - 2)
        } else {
            (i - 1, i + 1)
        };
        let (x, a, b) = (self.s(i), self.s(l), self.s(r));
        let t = self.spike;
        let up = ((x - a) as f32) >= t && ((x - b) as f32) >= t;
        let down = ((a - x) as f32) >= t && ((b - x) as f32) >= t;
        (up || down) && (abs(a - b) as f32) <= self.agree
    }

    /// A forward jump of `spike` from a smooth left side, and a drop of as much after it
    /// (a forward spike whose right neighbour is already the impact).
    fn forward_spike(&self, i: usize) -> bool {
        if i == 0 || i + 1 >= self.raw.len() {
            return false;
        }
        let (x, a) = (self.s(i), self.s(i - 1));
        let smooth = i < 2 || (abs(a - self.s(i - 2)) as f32) <= self.agree;
        smooth && ((x - a) as f32) >= self.spike && ((x - self.s(i + 1)) as f32) >= self.spike
    }

    /// Last impact-like sample of the group that starts at `start`.
    fn group_end(&self, start: usize) -> usize {
        let mut last = start;
        let mut j = start.saturating_add(1);
        while j < self.raw.len() && j - last <= self.gap {
            if self.impact_like(j) {
                last = j;
            }
            j += 1;
        }
        last
    }

    /// First sample of the tip impact (the window's length if there is none).
    fn impact_start(&self) -> usize {
        let n = self.raw.len();
        let Some(last) = (0..n).rev().find(|&i| self.impact_like(i)) else {
            return n;
        };
        let mut start = last;
        let mut j = last;
        while j > 0 && start - (j - 1) <= self.gap {
            j -= 1;
            if self.impact_like(j) {
                start = j;
            }
        }
        // Leading lone samples are glitches, unless (below 2.5 kHz) strictly deeper than
        // every later sample of the group within the gap: a one-sample contact.
        while start < last && self.lone(start) {
            let Some(next) = (start + 1..=last).find(|&k| self.impact_like(k)) else {
                break;
            };
            let x = self.s(start);
            let reach = last.min(start.saturating_add(self.gap));
            if self.one_sample_impacts && (start + 1..=reach).all(|k| self.s(k) > x) {
                break;
            }
            start = next;
        }
        start
    }
}

/// The first sample of a raw accelerometer window (i16 words along the cue, as
/// [`estimate_raw`](crate::estimate_raw) takes them, `scale` m/s² per word with the
/// sign that makes forward positive; `rate_hz` the sample rate) that is a rail value
/// (`i16::MIN` or `i16::MAX`) or a single-sample spike, outside the tip impact; `None`
/// if there is none. The criteria, their numbers and what they cannot see are in the
/// [module documentation](self).
pub fn find_glitch(raw: &[i16], rate_hz: f32, scale: f32) -> Option<Glitch> {
    let finite = cuesight::math::is_finite;
    if !(finite(rate_hz) && rate_hz > 0.0 && finite(scale) && scale != 0.0) {
        return None;
    }
    let per_word = if scale > 0.0 { scale } else { -scale };
    // Finite over finite and non-zero: a number, possibly +∞ (then never reached).
    let words = |g: f32| g * STANDARD_GRAVITY / per_word;
    let rate = if rate_hz < 500.0 { 500.0 } else { rate_hz };
    let plan = Plan {
        raw,
        sign: if scale > 0.0 { 1 } else { -1 },
        spike: words(SPIKE_G),
        agree: words(AGREE_G + 2.0 * JERK_G_PER_S / rate),
        hot: words(HOT_G),
        drop: words(DROP_G),
        // Saturating cast; at least two samples.
        gap: ((GAP_S * rate_hz) as usize).max(2),
        one_sample_impacts: CONTACT_MIN_S * rate_hz < 2.0,
    };
    let onset = plan.impact_start();
    let mut skip_until: Option<usize> = None;
    for (i, &value) in raw.iter().enumerate().take(onset) {
        if skip_until.is_some_and(|u| i <= u) {
            continue;
        }
        let rail = value == i16::MIN || value == i16::MAX;
        if rail && plan.s(i) > 0 {
            return Some(Glitch {
                index: i,
                kind: GlitchKind::Rail,
                value,
            });
        }
        if plan.lone(i) || plan.forward_spike(i) {
            let kind = if rail {
                GlitchKind::Rail
            } else {
                GlitchKind::Spike
            };
            return Some(Glitch {
                index: i,
                kind,
                value,
            });
        }
        if plan.impact_like(i) {
            // An earlier event that does not start with a lone sample (a knock before the
            // rest): skip it and its ringing.
            skip_until = Some(plan.group_end(i).saturating_add(plan.gap));
        }
    }
    None
}
